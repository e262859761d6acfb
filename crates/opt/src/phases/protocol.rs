//! The device tests of the recommended design (`devices.test_protocol`): per damper the
//! prototype test's amplitude, frequency and velocity, the forces and loop energies a
//! test unit should show, and the production test of each unit.
//!
//! ASCE 7-16 §18.6.2 tests each damper type at the maximum damper displacement (the MCE_R
//! displacement) at the frequency 1/T_1M, T_1M the effective period at MCE_R, a number of
//! fully reversed cycles, with acceptance bands on each cycle, and a wind-cycle test at
//! the frame's first frequency unless the design wind does not slip the dampers. The
//! counts and bands are the study's (`devices.test_protocol`: the project states no
//! number of the clause it cannot verify); what the response history gives is computed:
//!
//! - **Amplitude**: the design stroke at MCE_R, the mean over the MCE_R suite's records
//!   of the larger slip each way at the property case where that mean is largest (as the
//!   device table's per-suite column), times the study's `displacement_factor`.
//! - **T_1M**: the first period of the frame with every storey at its secant stiffness at
//!   its design drift (the mean peak drift over the same records at the lower-bound case,
//!   the bound that governs displacement): a yielding storey's bilinear secant, and a
//!   damper in series with its brace as F/δ once it slips (its brace stiffness k′ while
//!   it does not). Damper masses are left out (they do not set a frame period).
//! - **Velocity**: the sinusoid's peak 2π f A, beside the largest slip velocity of the
//!   response histories (the device table's).
//! - **Forces and loop energy**: a friction damper's force at zero displacement is its
//!   slip load, between the bounds λ_min F and λ_max F; its loop at amplitude A
//!   dissipates 4 F A per cycle.

use crate::base::metrics::RecordMetrics;
use crate::model::check::{CaseName, md_text, short};
use crate::model::config::{Hazard, TestProtocolConfig};
use crate::model::study::Study;
use serde::Serialize;
use slipload_sim::Building;
use std::fmt::Write as _;

/// One damper's test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviceTest {
    /// Floor (from 1).
    pub floor: usize,
    /// Its amplitude, velocity, forces and loop energies.
    #[serde(flatten)]
    pub figures: TestFigures,
}

/// What one damper's test runs at and should show (a chain's damper or a plan's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TestFigures {
    /// Test amplitude each way, mm.
    pub amplitude_mm: f64,
    /// The sinusoid's peak velocity 2π A / T_1M, mm/s (with T_1M).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity_mm_s: Option<f64>,
    /// The force at zero displacement: nominal slip load and its bounds, kN.
    pub force_kn: [f64; 3],
    /// Loop energy per cycle 4 F A at the nominal slip load and at the bounds, kJ.
    pub loop_energy_kj: [f64; 3],
}

impl TestFigures {
    /// A friction damper of slip load `f_kn` (kN) tested at amplitude `a_mm` (mm) at the
    /// period `t1m_s` (s), its slip load between the factors `lo` and `hi`: its force at
    /// zero displacement is F (λ_min F to λ_max F), its loop dissipates 4 F A a cycle.
    pub fn of(f_kn: f64, a_mm: f64, t1m_s: Option<f64>, lo: f64, hi: f64) -> TestFigures {
        let force_kn = [f_kn, lo * f_kn, hi * f_kn];
        TestFigures {
            amplitude_mm: a_mm,
            velocity_mm_s: t1m_s.map(|t| 2.0 * std::f64::consts::PI * a_mm / t),
            force_kn,
            loop_energy_kj: force_kn.map(|f| 4.0 * f * a_mm / 1e3),
        }
    }

    /// The columns of its row after the damper's name: A, velocity, force and its
    /// range, loop energy and its range.
    pub fn cells(&self) -> String {
        let (force, energy) = (self.force_kn, self.loop_energy_kj);
        format!(
            "{:.1} | {} | {:.1} | {:.1}–{:.1} | {} | {}–{} |",
            self.amplitude_mm,
            self.velocity_mm_s
                .map_or_else(|| "—".to_string(), |v| format!("{v:.0}")),
            force[0],
            force[1],
            force[2],
            short(energy[0]),
            short(energy[1]),
            short(energy[2])
        )
    }
}

/// The device tests of one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TestProtocol {
    /// The counts and bands the study gives.
    pub config: TestProtocolConfig,
    /// The suite the amplitudes come from.
    pub suite: String,
    /// Whether that suite is at MCE_R (else: the suite of the largest strokes).
    pub at_mce_r: bool,
    /// The bare frame's first period, s (the wind test's frequency is its inverse).
    pub t1_s: f64,
    /// T_1M, s (`None`: the secant frame has no positive mode).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t1m_s: Option<f64>,
    /// One test per damper, bottom to top.
    pub dampers: Vec<DeviceTest>,
    /// With the study's `wind`: the least ratio of a damper's lower-bound slip load to its
    /// storey's design wind shear, and that damper's floor (the wind test's exemption).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wind_margin: Option<(f64, usize)>,
}

/// The secant first period of `building` with storey `i` at drift `drift[i]` (m; `None`:
/// its initial stiffness) and the damper of storey `i` at slip load `force[i]` (N): the
/// frame's stiffness matrix plus, across each storey (floor i − 1 to floor i, the ground
/// for i = 0), the damper's secant in series with its brace and, for a yielding storey,
/// its secant less its initial stiffness. `None` when the matrix has no positive mode.
pub fn secant_period(building: &Building, drift: &[Option<f64>], force: &[f64]) -> Option<f64> {
    let mut k = building.stiffness.clone();
    let n = k.nrows();
    for i in 0..n {
        let Some(d) = drift.get(i).copied().flatten().filter(|d| *d > 0.0) else {
            continue;
        };
        let mut add = 0.0;
        if let Some(Some(y)) = building.storey_yield.get(i)
            && d > y.yield_drift()
        {
            let secant =
                (y.yield_shear + y.post_yield_ratio * y.stiffness * (d - y.yield_drift())) / d;
            add -= y.stiffness - secant;
        }
        if let Some(Some(b)) = building.dissipators.get(i) {
            let f = force.get(i).copied().unwrap_or(0.0);
            add += if d * b.brace_stiffness > f {
                f / d
            } else {
                b.brace_stiffness
            };
        }
        k[(i, i)] += add;
        if i > 0 {
            k[(i - 1, i - 1)] += add;
            k[(i, i - 1)] -= add;
            k[(i - 1, i)] -= add;
        }
    }
    let modes = slipload_sim::modes::Modes::compute(&building.mass, &k)?;
    let w = *modes.omega.iter().next()?;
    (w > 0.0 && w.is_finite()).then(|| 2.0 * std::f64::consts::PI / w)
}

/// The prototype test's acceptance, as the protocols state it.
pub(crate) fn acceptance(band: f64) -> String {
    format!(
        "Accepted when, in every cycle, the largest and the smallest force at zero displacement and the loop energy are within ±{band} % of their averages over the test, and those averages within the ranges below (the property bounds)."
    )
}

impl TestProtocol {
    /// The tests of the design `slip_loads_n` (N per damper) from its runs (every run of
    /// `study`); `strokes_mm[k]`: damper k's mean stroke in each suite (the device table's
    /// per-suite column, largest over the cases).
    pub fn of(
        study: &Study,
        config: TestProtocolConfig,
        slip_loads_n: &[f64],
        runs: &[RecordMetrics],
        strokes_mm: &[Vec<f64>],
    ) -> TestProtocol {
        let cases = study.checks.cases();
        let n = study.records.len();
        // the MCE_R suite, else the suite of the largest strokes
        let mce = study.suites.iter().position(|s| {
            s.code_scaling
                .as_ref()
                .is_some_and(|c| c.hazard == Hazard::MceR)
        });
        let total = |i: usize| strokes_mm.iter().map(|s| s[i]).sum::<f64>();
        let suite = mce.unwrap_or_else(|| {
            (0..study.suites.len())
                .max_by(|&a, &b| total(a).total_cmp(&total(b)))
                .unwrap_or(0)
        });
        let (lo, hi) = study.checks.slip_load_range();
        let lower = cases
            .iter()
            .position(|c| c.name == CaseName::Lower)
            .unwrap_or(0);
        let floors = study.building.floors();
        let heights = study.building.storey_heights.as_ref();
        let range = study.suites[suite].range.clone();
        let count = range.len().max(1) as f64;
        let factor = config.displacement_factor.unwrap_or(1.0);
        // the storeys' design drifts (m) and slip loads (N) at the lower bound
        let mut force = vec![0.0; floors];
        let mut drift: Vec<Option<f64>> = vec![None; floors];
        for (k, &floor) in study.space.dampers.iter().enumerate() {
            force[floor] = lo * slip_loads_n[k];
        }
        // the mean peak drift: its ratio times the storey height (a study's building has
        // storey heights: checked when it loads)
        for (i, d) in drift.iter_mut().enumerate() {
            let ratio = range
                .clone()
                .map(|r| {
                    runs[lower * n + r]
                        .drift_ratio
                        .get(i)
                        .copied()
                        .unwrap_or(0.0)
                })
                .sum::<f64>()
                / count;
            *d = heights.and_then(|h| h.get(i)).map(|h| ratio * h);
        }
        let t1m = secant_period(&study.building, &drift, &force);
        let dampers = study
            .space
            .dampers
            .iter()
            .enumerate()
            .map(|(k, &floor)| {
                let a = factor * strokes_mm[k][suite];
                DeviceTest {
                    floor: floor + 1,
                    figures: TestFigures::of(slip_loads_n[k] / 1e3, a, t1m, lo, hi),
                }
            })
            .collect();
        TestProtocol {
            config,
            suite: study.suites[suite].name.clone(),
            at_mce_r: mce.is_some(),
            t1_s: study.building.t1(),
            t1m_s: t1m,
            dampers,
            wind_margin: crate::phases::compliance::wind_margin(study, slip_loads_n),
        }
    }

    /// The protocol as a section of `device-table.md`.
    pub fn to_markdown(&self) -> String {
        let c = &self.config;
        let band = c.band_percent;
        let mut s = String::from("## Test protocol\n\n");
        let _ = writeln!(
            s,
            "The counts and bands are the study's (`devices.test_protocol`); amplitudes, frequencies and velocities come from the response histories. Amplitude A: the mean stroke over the records of suite {}{} at the property case where it is largest{}. T_1M = {}: the first period of the frame with each storey at its secant stiffness at its mean peak drift in that suite at the lower bound (a damper F/δ once it slips). Bare frame T1 = {} s.\n",
            md_text(&self.suite),
            if self.at_mce_r {
                " (MCE_R)"
            } else {
                " (no suite is at MCE_R: the suite of the largest strokes)"
            },
            match c.displacement_factor {
                Some(f) if f != 1.0 =>
                    format!(", times the study's displacement factor {}", short(f)),
                _ => String::new(),
            },
            self.t1m_s.map_or_else(
                || "not computed (the secant frame has no positive mode)".to_string(),
                |t| format!("{t:.3} s"),
            ),
            short(self.t1_s)
        );
        let freq = self.t1m_s.map_or_else(
            || "1/T_1M".to_string(),
            |t| format!("{:.3} Hz (1/T_1M)", 1.0 / t),
        );
        let _ = writeln!(
            s,
            "- **Prototype test**, each damper type: {} fully reversed sinusoidal cycles at amplitude ±A at {freq}. {}",
            c.cycles,
            acceptance(band)
        );
        let _ = writeln!(
            s,
            "- **Wind test**: {}",
            match c.wind_cycles {
                Some(w) => format!(
                    "{w} fully reversed cycles at the design wind's damper force and displacement, at {:.3} Hz (1/T1).",
                    1.0 / self.t1_s
                ),
                None => match self.wind_margin {
                    Some((r, floor)) => format!(
                        "not made: every damper's lower-bound slip load is at least {r:.2} × its storey's design wind shear (the least at floor {floor}; the study's `wind`), so no damper slips in the design wind — the exemption."
                    ),
                    None => "not made: the study claims the exemption of dampers that do not slip in the design wind — show that each storey's design wind shear is below its lower-bound slip load (the `range` of the device table), or give the study its `wind`.".to_string(),
                },
            }
        );
        if let Some(p) = c.production_cycles {
            let _ = writeln!(
                s,
                "- **Production test**, every unit: {p} cycles at ±A at {freq}; accepted when its average force at zero displacement and loop energy are within the ranges below."
            );
        }
        s.push_str("\n| floor | A (mm) | velocity 2πfA (mm/s) | force at zero displacement (kN) | range (kN) | loop energy 4FA (kJ) | range (kJ) |\n|---:|---:|---:|---:|---:|---:|---:|\n");
        for d in &self.dampers {
            let _ = writeln!(s, "| {} | {}", d.floor, d.figures.cells());
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// A one-storey frame of 100 t on a 100 MN/m storey with a massless damper on a
    /// 1000 MN/m brace; `yielding`: the storey yields at 10 mm drift, 10 % post-yield.
    fn one_storey(yielding: bool) -> Building {
        let y = if yielding {
            r#", "storey_heights": ["3 m"], "storey_yield": [ { "storey": 1, "yield_drift": "10 mm", "post_yield_ratio": 0.1 } ]"#
        } else {
            ""
        };
        let text = format!(
            r#"{{ "name": "one", "floor_masses": ["100 t"], "storey_stiffness": ["100 MN/m"],
                 "damping": {{ "modal": {{ "ratio": 0.02 }} }}{y},
                 "dissipators": [ {{ "floor": 1, "brace_stiffness": "1000 MN/m", "mass": 0,
                                     "brace_damping": 0, "slip_load": "1000 kN" }} ] }}"#
        );
        let cfg: slipload_sim::BuildingConfig = serde_json::from_str(&text).unwrap();
        Building::from_config(&cfg, Path::new("one.json")).unwrap()
    }

    fn period(m: f64, k: f64) -> f64 {
        2.0 * std::f64::consts::PI * (m / k).sqrt()
    }

    /// Closed forms of a one-storey frame: a slipping damper adds F/δ, a stuck one its
    /// brace, a yielding storey its bilinear secant; no drift keeps the initial storey
    /// alone (round-off of the eigen solve: 1e-12 relative).
    #[test]
    fn the_secant_period_of_one_storey_has_its_closed_form() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b;
        let b = one_storey(false);
        // 50 mm drift, 1 MN slip load: the brace would carry 50 MN, so it slips
        let t = secant_period(&b, &[Some(0.05)], &[1e6]).unwrap();
        assert!(close(t, period(1e5, 1e8 + 1e6 / 0.05)), "{t}");
        // a slip load above 50 MN: stuck, the brace in parallel with the storey
        let t = secant_period(&b, &[Some(0.05)], &[1e8]).unwrap();
        assert!(close(t, period(1e5, 1e8 + 1e9)), "{t}");
        let t = secant_period(&b, &[None], &[1e6]).unwrap();
        assert!(close(t, b.t1()) && close(t, period(1e5, 1e8)), "{t}");
        // yielding at 10 mm (1 MN), 10 % after: at 50 mm the storey carries 1.4 MN
        let y = one_storey(true);
        let t = secant_period(&y, &[Some(0.05)], &[1e6]).unwrap();
        assert!(close(t, period(1e5, 1.4e6 / 0.05 + 1e6 / 0.05)), "{t}");
    }
}
