//! What accuracy costs: every method × time step against the `exact` integrator.
//!
//! For one scene, each (method, Δt) is run and compared with `exact` on the same output
//! grid (exact does not depend on its grid, so this is "the coarser grid" of the pair):
//! - peak drift: max over storeys of |d − d_exact| / d_exact, with d_exact the continuous
//!   peak of `exact` (storeys whose exact peak is 0 are skipped);
//! - friction energy: |E_f − E_f,exact| / |E_f,exact| (over the input energy when the exact
//!   friction energy is 0);
//! - roof history: RMS over the grid of x_roof − x_roof,exact, over max |x_roof,exact|.
//!
//! CPU time is the median of `repeats` runs after one warm-up run (the plan is compiled
//! once per entry, outside the timing). A method that returns an error (beyond its
//! stability limit, a work cap) is recorded with its message; the study goes on. The
//! observed order of each metric is the least-squares slope of log(error) on log(Δt) over
//! the entries where the error is above 1e-13 (round-off).
//!
//! The method list is any slice of [`MethodName`]: new methods take part without change.

use crate::error::SimError;
use crate::plan::Plan;
use crate::response::Outcome;
use crate::scene::{MethodName, Scene};
use crate::simulate::run_plan;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// A time step: seconds, or a fraction of the bare frame's fundamental period.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DtSpec {
    /// Δt in seconds.
    Seconds(f64),
    /// Δt = T₁ / k.
    PeriodOver(f64),
}

impl DtSpec {
    /// Δt in seconds for a frame of fundamental period `t1` (s).
    pub fn seconds(self, t1: f64) -> f64 {
        match self {
            DtSpec::Seconds(s) => s,
            DtSpec::PeriodOver(k) => t1 / k,
        }
    }

    /// The spec as written (`T1/200` or seconds).
    pub fn label(self) -> String {
        match self {
            DtSpec::Seconds(s) => format!("{s}"),
            DtSpec::PeriodOver(k) => format!("T1/{k}"),
        }
    }
}

impl std::str::FromStr for DtSpec {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let t = s.trim();
        let bad = || {
            format!(
                "time step {t:?}: expected seconds (0.005) or T1/k (T1/200) with a positive finite value"
            )
        };
        let (v, period) = match t.strip_prefix("T1/").or_else(|| t.strip_prefix("t1/")) {
            Some(k) => (k.parse::<f64>().map_err(|_| bad())?, true),
            None => (t.parse::<f64>().map_err(|_| bad())?, false),
        };
        if !(v.is_finite() && v > 0.0) {
            return Err(bad());
        }
        Ok(if period {
            DtSpec::PeriodOver(v)
        } else {
            DtSpec::Seconds(v)
        })
    }
}

/// The default steps: T₁/25 … T₁/3200, halving.
pub fn default_dts() -> Vec<DtSpec> {
    [25.0, 50.0, 100.0, 200.0, 400.0, 800.0, 1600.0, 3200.0]
        .into_iter()
        .map(DtSpec::PeriodOver)
        .collect()
}

/// The default methods (every method but the reference itself is compared with it).
pub fn default_methods() -> Vec<MethodName> {
    vec![
        MethodName::Newmark,
        MethodName::Hht,
        MethodName::Bilinear,
        MethodName::Exact,
    ]
}

/// HHT α used for a method in the study (−0.05 for hht, 0 otherwise).
pub fn study_alpha(name: MethodName) -> f64 {
    if name == MethodName::Hht { -0.05 } else { 0.0 }
}

/// Settings of a study.
#[derive(Debug, Clone)]
pub struct StudySettings {
    /// Methods compared.
    pub methods: Vec<MethodName>,
    /// Time steps.
    pub dts: Vec<DtSpec>,
    /// Timed repeats per entry (median taken), default 5, at least 1.
    pub repeats: usize,
}

impl Default for StudySettings {
    fn default() -> Self {
        StudySettings {
            methods: default_methods(),
            dts: default_dts(),
            repeats: 5,
        }
    }
}

/// Errors of one (method, Δt) against `exact` (relative, see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Errors {
    /// Max relative error of the peak drifts over storeys.
    pub peak_drift: f64,
    /// Relative error of the friction energy.
    pub friction_energy: f64,
    /// RMS roof-displacement error over the peak roof displacement.
    pub roof_history: f64,
}

/// One (method, Δt) of a study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    /// Method name.
    pub method: String,
    /// Δt as asked (`T1/200` or seconds).
    pub dt_label: String,
    /// Δt, s.
    pub dt: f64,
    /// Errors, or `None` when the method failed.
    pub errors: Option<Errors>,
    /// Median CPU seconds per simulation with energies and histories, as compared here
    /// (`None` when it failed).
    pub cpu_seconds: Option<f64>,
    /// Median CPU seconds per simulation of the same run asking for peaks only, as a
    /// sweep runs it (`None` when it failed).
    #[serde(default)]
    pub cpu_seconds_peaks_only: Option<f64>,
    /// The method's error message when it failed.
    pub failure: Option<String>,
    /// Events located (`exact`), 0 otherwise.
    pub events: u64,
}

/// Observed convergence orders of one method (least-squares slopes, `None` with < 2 points).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Orders {
    /// Method name.
    pub method: String,
    /// Order of the peak-drift error.
    pub peak_drift: Option<f64>,
    /// Order of the friction-energy error.
    pub friction_energy: Option<f64>,
    /// Order of the roof-history error.
    pub roof_history: Option<f64>,
}

/// A study of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyReport {
    /// Scene (and record) name.
    pub scene: String,
    /// Bare-frame T₁, s.
    pub t1: f64,
    /// Simulated duration, s.
    pub duration: f64,
    /// `exact`'s continuous peak drifts, m.
    pub reference_peak_drift: Vec<f64>,
    /// `exact`'s friction energy, J.
    pub reference_friction_energy: f64,
    /// All entries, methods in the given order, Δt in the given order.
    pub entries: Vec<Entry>,
    /// Observed orders per method.
    pub orders: Vec<Orders>,
}

/// `scene` run by `name` at `dt`, with energies and histories when `outputs` (the runs
/// compared here), peaks only otherwise (as a sweep runs it).
fn with_method(scene: &Scene, name: MethodName, dt: f64, outputs: bool) -> Scene {
    let mut s = scene.clone();
    s.method.name = name;
    s.method.dt = dt;
    s.method.alpha = study_alpha(name);
    s.outputs.energies = outputs;
    s.outputs.histories = outputs;
    s
}

/// Compiles and runs `scene` with `name` at `dt` (with energies and histories): the
/// outcome, the median CPU seconds of `repeats` timed runs after one warm-up, and the
/// same for the run that asks for peaks only.
fn timed(
    scene: &Scene,
    name: MethodName,
    dt: f64,
    repeats: usize,
) -> Result<(Outcome, f64, f64), SimError> {
    let mut out = None;
    let mut cpu = [0.0; 2];
    for (c, outputs) in cpu.iter_mut().zip([true, false]) {
        let plan = Plan::compile(&with_method(scene, name, dt, outputs))?;
        let first = run_plan(&plan)?; // warm-up, and (with outputs) the outcome compared
        let mut times = Vec::with_capacity(repeats);
        for _ in 0..repeats.max(1) {
            let start = std::time::Instant::now();
            let o = run_plan(&plan)?;
            times.push(start.elapsed().as_secs_f64());
            std::hint::black_box(o);
        }
        *c = median(&mut times);
        out.get_or_insert(first);
    }
    let out = out.expect("the run with outputs ran first");
    Ok((out, cpu[0], cpu[1]))
}

/// Median of a slice (sorted in place with `total_cmp`); NaN for an empty slice.
pub fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// Errors of `out` against `reference` (same output grid).
pub fn compare(out: &Outcome, reference: &Outcome) -> Errors {
    let r = &reference.response;
    let o = &out.response;
    let peak_drift = o
        .peak_drift
        .iter()
        .zip(&r.peak_drift)
        .filter(|(_, e)| **e > 0.0)
        .map(|(d, e)| (d - e).abs() / e)
        .fold(0.0, f64::max);
    let (ef, er) = (
        o.energy.map_or(f64::NAN, |e| e.friction),
        r.energy.map_or(f64::NAN, |e| e.friction),
    );
    let scale = if er.abs() > 0.0 {
        er.abs()
    } else {
        r.energy.map_or(f64::NAN, |e| e.input.abs())
    };
    let friction_energy = if scale > 0.0 {
        (ef - er).abs() / scale
    } else {
        0.0
    };
    let roof_history = match (&out.history, &reference.history) {
        (Some(h), Some(hr)) => {
            let roof = format!("x{}_m", r.peak_drift.len());
            match (h.column(&roof), hr.column(&roof)) {
                (Some(a), Some(b)) => {
                    let len = a.len().min(b.len());
                    let peak = b[..len].iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    let ss: f64 = a[..len]
                        .iter()
                        .zip(&b[..len])
                        .map(|(x, y)| (x - y) * (x - y))
                        .sum();
                    if peak > 0.0 && len > 0 {
                        (ss / len as f64).sqrt() / peak
                    } else {
                        0.0
                    }
                }
                _ => f64::NAN,
            }
        }
        _ => f64::NAN,
    };
    Errors {
        peak_drift,
        friction_energy,
        roof_history,
    }
}

/// Least-squares slope of log(err) on log(dt) over the points with err > 1e-13.
pub fn observed_order(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(dt, e)| *dt > 0.0 && e.is_finite() && *e > 1e-13)
        .map(|(dt, e)| (dt.ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Runs the study on one scene. Errors only if the `exact` reference itself fails.
pub fn run_study(scene: &Scene, settings: &StudySettings) -> Result<StudyReport, SimError> {
    let t1 = scene.building.t1();
    let dts: Vec<(DtSpec, f64)> = settings.dts.iter().map(|d| (*d, d.seconds(t1))).collect();
    let mut entries = Vec::new();
    let mut references = Vec::with_capacity(dts.len());
    for &(_, dt) in &dts {
        let plan = Plan::compile(&with_method(scene, MethodName::Exact, dt, true))?;
        references.push(run_plan(&plan)?);
    }
    for &method in &settings.methods {
        for (k, &(spec, dt)) in dts.iter().enumerate() {
            let entry = match timed(scene, method, dt, settings.repeats) {
                Ok((out, cpu, cpu_peaks)) => Entry {
                    method: method.as_str().into(),
                    dt_label: spec.label(),
                    dt,
                    errors: Some(compare(&out, &references[k])),
                    cpu_seconds: Some(cpu),
                    cpu_seconds_peaks_only: Some(cpu_peaks),
                    failure: None,
                    events: out.diagnostics.events,
                },
                Err(e) => Entry {
                    method: method.as_str().into(),
                    dt_label: spec.label(),
                    dt,
                    errors: None,
                    cpu_seconds: None,
                    cpu_seconds_peaks_only: None,
                    failure: Some(e.to_string()),
                    events: 0,
                },
            };
            entries.push(entry);
        }
    }
    let orders = orders_of(&settings.methods, &entries);
    let reference = &references[0].response;
    Ok(StudyReport {
        scene: scene.name.clone(),
        t1,
        duration: scene.duration,
        reference_peak_drift: reference.peak_drift.clone(),
        reference_friction_energy: reference.energy.map_or(0.0, |e| e.friction),
        entries,
        orders,
    })
}

fn orders_of(methods: &[MethodName], entries: &[Entry]) -> Vec<Orders> {
    methods
        .iter()
        .map(|m| {
            let mine: Vec<&Entry> = entries.iter().filter(|e| e.method == m.as_str()).collect();
            let pts = |f: fn(&Errors) -> f64| -> Vec<(f64, f64)> {
                mine.iter()
                    .filter_map(|e| e.errors.as_ref().map(|er| (e.dt, f(er))))
                    .collect()
            };
            Orders {
                method: m.as_str().into(),
                peak_drift: observed_order(&pts(|e| e.peak_drift)),
                friction_energy: observed_order(&pts(|e| e.friction_energy)),
                roof_history: observed_order(&pts(|e| e.roof_history)),
            }
        })
        .collect()
}

/// The median over several reports of the same methods and steps (per entry: median of
/// each error and CPU time over the reports where it succeeded; a failure in any report
/// is kept as the entry's failure message, prefixed by the count).
pub fn median_report(name: &str, reports: &[StudyReport], methods: &[MethodName]) -> StudyReport {
    let first = &reports[0];
    let mut entries = Vec::new();
    for (k, e0) in first.entries.iter().enumerate() {
        let all: Vec<&Entry> = reports.iter().map(|r| &r.entries[k]).collect();
        let ok: Vec<&Errors> = all.iter().filter_map(|e| e.errors.as_ref()).collect();
        let failed: Vec<&String> = all.iter().filter_map(|e| e.failure.as_ref()).collect();
        let med = |f: fn(&Errors) -> f64| median(&mut ok.iter().map(|e| f(e)).collect::<Vec<_>>());
        let mut cpu: Vec<f64> = all.iter().filter_map(|e| e.cpu_seconds).collect();
        let mut cpu_peaks: Vec<f64> = all
            .iter()
            .filter_map(|e| e.cpu_seconds_peaks_only)
            .collect();
        entries.push(Entry {
            method: e0.method.clone(),
            dt_label: e0.dt_label.clone(),
            dt: e0.dt,
            errors: (!ok.is_empty()).then(|| Errors {
                peak_drift: med(|e| e.peak_drift),
                friction_energy: med(|e| e.friction_energy),
                roof_history: med(|e| e.roof_history),
            }),
            cpu_seconds: (!cpu.is_empty()).then(|| median(&mut cpu)),
            cpu_seconds_peaks_only: (!cpu_peaks.is_empty()).then(|| median(&mut cpu_peaks)),
            failure: failed
                .first()
                .map(|f| format!("failed on {} of {} records: {f}", failed.len(), all.len())),
            events: {
                let mut ev: Vec<f64> = all.iter().map(|e| e.events as f64).collect();
                median(&mut ev) as u64
            },
        });
    }
    let orders = orders_of(methods, &entries);
    let mut pd: Vec<Vec<f64>> = reports
        .iter()
        .map(|r| r.reference_peak_drift.clone())
        .collect();
    let storeys = pd[0].len();
    let reference_peak_drift = (0..storeys)
        .map(|i| median(&mut pd.iter_mut().map(|v| v[i]).collect::<Vec<_>>()))
        .collect();
    StudyReport {
        scene: name.into(),
        t1: first.t1,
        duration: first.duration,
        reference_peak_drift,
        reference_friction_energy: median(
            &mut reports
                .iter()
                .map(|r| r.reference_friction_energy)
                .collect::<Vec<_>>(),
        ),
        entries,
        orders,
    }
}

impl StudyReport {
    /// The largest Δt of `method` such that it and every finer Δt succeed with a
    /// peak-drift error ≤ 1 % (so a lucky coarse step does not count).
    pub fn one_percent(&self, method: &str) -> Option<&Entry> {
        let mut mine: Vec<&Entry> = self.entries.iter().filter(|e| e.method == method).collect();
        mine.sort_by(|a, b| b.dt.total_cmp(&a.dt));
        let ok = |e: &Entry| e.errors.is_some_and(|x| x.peak_drift <= 0.01);
        (0..mine.len())
            .find(|&i| mine[i..].iter().all(|e| ok(e)))
            .map(|i| mine[i])
    }

    /// CSV, one line per entry.
    pub fn to_csv(&self) -> String {
        let mut s = String::from(
            "scene,method,dt_label,dt_s,peak_drift_error,friction_energy_error,roof_history_error,cpu_seconds,cpu_seconds_peaks_only,events,failure\n",
        );
        for e in &self.entries {
            let (a, b, c) = e
                .errors
                .map_or((String::new(), String::new(), String::new()), |x| {
                    (
                        format!("{:.6e}", x.peak_drift),
                        format!("{:.6e}", x.friction_energy),
                        format!("{:.6e}", x.roof_history),
                    )
                });
            let cpu = e.cpu_seconds.map_or(String::new(), |c| format!("{c:.6e}"));
            let cpu_peaks = e
                .cpu_seconds_peaks_only
                .map_or(String::new(), |c| format!("{c:.6e}"));
            // Scene names hold commas ("benchmark, synthetic 0"): quoted, as RFC 4180 says.
            let fail = e.failure.as_deref().unwrap_or("").replace('"', "'");
            let _ = writeln!(
                s,
                "\"{}\",{},{},{:.9e},{a},{b},{c},{cpu},{cpu_peaks},{},\"{fail}\"",
                self.scene.replace('"', "\"\""),
                e.method,
                e.dt_label,
                e.dt,
                e.events
            );
        }
        s
    }

    /// Markdown summary: the table, the observed orders, and the cheapest entry reaching
    /// 1 % on peak drift per method.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "### {}\n\nT1 = {:.4} s, duration {:.2} s; reference: `exact` (peak drifts {:?} m, friction energy {:.6e} J).\n",
            self.scene,
            self.t1,
            self.duration,
            self.reference_peak_drift
                .iter()
                .map(|d| format!("{d:.6}"))
                .collect::<Vec<_>>(),
            self.reference_friction_energy
        );
        s.push_str("| method | dt | dt (s) | peak drift err | friction E err | roof RMS err | CPU (s) | CPU, peaks only (s) | events |\n");
        s.push_str("|---|---|---|---|---|---|---|---|---|\n");
        for e in &self.entries {
            match (&e.errors, &e.failure) {
                (Some(x), _) => {
                    let _ = writeln!(
                        s,
                        "| {} | {} | {:.3e} | {:.2e} | {:.2e} | {:.2e} | {:.3e} | {:.3e} | {} |",
                        e.method,
                        e.dt_label,
                        e.dt,
                        x.peak_drift,
                        x.friction_energy,
                        x.roof_history,
                        e.cpu_seconds.unwrap_or(f64::NAN),
                        e.cpu_seconds_peaks_only.unwrap_or(f64::NAN),
                        e.events
                    );
                }
                (None, f) => {
                    let _ = writeln!(
                        s,
                        "| {} | {} | {:.3e} | failed: {} | | | | | |",
                        e.method,
                        e.dt_label,
                        e.dt,
                        f.as_deref().unwrap_or("?")
                    );
                }
            }
        }
        s.push_str("\nObserved orders (least-squares slope of log error on log dt):\n\n| method | peak drift | friction E | roof history |\n|---|---|---|---|\n");
        let fmt = |o: Option<f64>| o.map_or("-".to_string(), |v| format!("{v:.2}"));
        for o in &self.orders {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} |",
                o.method,
                fmt(o.peak_drift),
                fmt(o.friction_energy),
                fmt(o.roof_history)
            );
        }
        s.push_str("\nLargest step from which every finer step stays within 1 % on every peak drift, per method:\n\n");
        for o in &self.orders {
            match self.one_percent(&o.method) {
                Some(e) => {
                    let _ = writeln!(
                        s,
                        "- {}: dt = {} ({:.3e} s), peak-drift error {:.2e}, {:.3e} s CPU",
                        o.method,
                        e.dt_label,
                        e.dt,
                        e.errors.map_or(f64::NAN, |x| x.peak_drift),
                        e.cpu_seconds.unwrap_or(f64::NAN)
                    );
                }
                None => {
                    let _ = writeln!(s, "- {}: none of the steps tried", o.method);
                }
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dt_specs_parse_seconds_and_period_fractions() {
        assert_eq!("T1/200".parse::<DtSpec>(), Ok(DtSpec::PeriodOver(200.0)));
        assert_eq!("0.005".parse::<DtSpec>(), Ok(DtSpec::Seconds(0.005)));
        assert!("T1/0".parse::<DtSpec>().is_err());
        assert!("-1".parse::<DtSpec>().is_err());
        assert!("fast".parse::<DtSpec>().is_err());
        assert_eq!(DtSpec::PeriodOver(4.0).seconds(2.0), 0.5);
    }

    #[test]
    fn order_is_the_least_squares_slope() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&h: &f64| (h, 3.0 * h * h))
            .collect();
        let p = observed_order(&pts).unwrap();
        assert!((p - 2.0).abs() < 1e-12, "{p}");
        assert_eq!(observed_order(&pts[..1]), None);
    }

    #[test]
    fn median_of_even_and_odd() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
