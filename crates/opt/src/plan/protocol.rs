//! The device tests of a study in plan's optimum (`devices.test_protocol`), as a chain
//! study's (crate::phases::protocol) with the plan's own numbers: per damper the
//! prototype test's amplitude, frequency and velocity, the forces and loop energies a test
//! unit should show, and the production test.
//!
//! - **Amplitude** A: the damper's stroke (the larger slip either way) in the MCE_R suite
//!   (a suite scaled to a code spectrum at `mce_r`), else in the suite of the largest
//!   strokes — the suite's statistic over its pairs, at the property case where it is
//!   largest — times the study's `displacement_factor`.
//! - **T_1M** along x and along y: the first-mode periods of each direction (the mode with
//!   the largest effective mass along it) of the plan with every line's storey at its
//!   secant stiffness at its design drift ([`FloorPlan::secant_periods`]): the drift is
//!   the suite's statistic at the property cases of the least slip loads (the lower bound,
//!   which governs displacement; the nominal without bounds), the largest of those cases,
//!   and a damper's slip load is the design's at that bound. A damper is tested at the
//!   frequency of the direction its line is closer to.
//! - **Forces and loop energy**: a friction damper's force at zero displacement is its slip
//!   load F, between λ_min F and λ_max F; its loop at amplitude A dissipates 4 F A a cycle.
//!
//! [`FloorPlan::secant_periods`]: slipload_sim::floorplan::FloorPlan::secant_periods

use super::report::PlanRow;
use super::study::PlanStudy;
use crate::model::check::{md_text, short};
use crate::model::config::{Hazard, TestProtocolConfig};
use crate::phases::protocol::{TestFigures, acceptance};
use serde::Serialize;
use std::fmt::Write as _;

/// One damper's test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanDeviceTest {
    /// "D/3".
    pub damper: String,
    /// The direction whose T_1M it is tested at: 0 x, 1 y.
    pub direction: usize,
    /// Its amplitude, velocity, forces and loop energies.
    #[serde(flatten)]
    pub figures: TestFigures,
}

/// The device tests of a study in plan's optimum.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanTestProtocol {
    /// The counts and bands the study gives.
    pub config: TestProtocolConfig,
    /// The suite the amplitudes come from.
    pub suite: String,
    /// Whether that suite is at MCE_R (else: the suite of the largest strokes).
    pub at_mce_r: bool,
    /// The bare plan's first-mode periods along x and y, s.
    pub t1_s: [f64; 2],
    /// T_1M along x and y, s (`None`: the secant plan has no positive mode).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t1m_s: Option<[f64; 2]>,
    /// One test per damper, in the plan's order.
    pub dampers: Vec<PlanDeviceTest>,
}

impl PlanTestProtocol {
    /// The tests of `row` (the optimum, evaluated with per-damper demands).
    pub fn of(study: &PlanStudy, config: TestProtocolConfig, row: &PlanRow) -> PlanTestProtocol {
        let b = &study.building;
        let n = b.storeys();
        let cells = &row.eval.cells;
        let stroke = |suite: usize, k: usize| {
            cells
                .iter()
                .filter(|c| c.suite == suite)
                .map(|c| c.peaks.devices.stroke.get(k).copied().unwrap_or(0.0))
                .fold(0.0, f64::max)
        };
        let mce = study
            .suites
            .iter()
            .position(|s| s.code.as_ref().is_some_and(|c| c.hazard == Hazard::MceR));
        let total = |s: usize| (0..study.dampers.len()).map(|k| stroke(s, k)).sum::<f64>();
        let suite = mce.unwrap_or_else(|| {
            (0..study.suites.len())
                .max_by(|&a, &c| total(a).total_cmp(&total(c)))
                .unwrap_or(0)
        });
        let lo = study
            .cases
            .iter()
            .map(|c| c.slip_factor)
            .fold(f64::INFINITY, f64::min);
        let hi = study
            .cases
            .iter()
            .map(|c| c.slip_factor)
            .fold(f64::NEG_INFINITY, f64::max);
        // the design drifts (m along each line) at the cases of the least slip loads
        let heights = b.storey_heights.as_ref();
        let mut drift: Vec<Vec<Option<f64>>> = vec![vec![None; n]; b.lines.len()];
        for c in cells
            .iter()
            .filter(|c| c.suite == suite && study.cases[c.case].slip_factor == lo)
        {
            for (l, per) in drift.iter_mut().enumerate() {
                for (f, d) in per.iter_mut().enumerate() {
                    let v = c.peaks.line_drift.get(l * n + f).copied().unwrap_or(0.0);
                    // a drift ratio where the storey heights are given, else metres
                    let m = heights.map_or(v, |h| v * h[f]);
                    *d = Some(d.map_or(m, |x: f64| x.max(m)));
                }
            }
        }
        // each damper's nominal slip load, N (the file's upper bound where the design keeps it)
        let nominal: Vec<f64> = study
            .dampers
            .iter()
            .zip(&row.eval.loads)
            .map(|(site, load)| {
                load.unwrap_or_else(|| {
                    b.lines[site.line].dissipators[site.storey].map_or(0.0, |d| d.upper)
                })
            })
            .collect();
        let mut force = vec![vec![0.0; n]; b.lines.len()];
        for (site, f) in study.dampers.iter().zip(&nominal) {
            force[site.line][site.storey] = lo * f;
        }
        let t1m = b.secant_periods(&drift, &force);
        let t1 = b.secant_periods(&vec![vec![None; n]; b.lines.len()], &force);
        let factor = config.displacement_factor.unwrap_or(1.0);
        let dampers = study
            .dampers
            .iter()
            .enumerate()
            .map(|(k, site)| {
                let (c, s) = b.lines[site.line].direction();
                let direction = usize::from(s.abs() > c.abs());
                let a = factor * stroke(suite, k) * 1e3;
                let f = nominal[k] / 1e3;
                PlanDeviceTest {
                    damper: site.name.clone(),
                    direction,
                    figures: TestFigures::of(f, a, t1m.map(|t| t[direction]), lo, hi),
                }
            })
            .collect();
        PlanTestProtocol {
            config,
            suite: study.suites[suite].name.clone(),
            at_mce_r: mce.is_some(),
            t1_s: t1.unwrap_or([f64::NAN; 2]),
            t1m_s: t1m,
            dampers,
        }
    }

    /// The protocol as a section of `plan-devices.md`.
    pub fn to_markdown(&self) -> String {
        let c = &self.config;
        let mut s = String::from("\n## Test protocol\n\n");
        let periods = |t: [f64; 2]| format!("{:.3} s along x, {:.3} s along y", t[0], t[1]);
        let _ = writeln!(
            s,
            "The counts and bands are the study's (`devices.test_protocol`); amplitudes, frequencies and velocities come from the runs. Amplitude A: the damper's stroke in suite {}{} at the property case where it is largest{}. T_1M = {}: the first-mode periods of each direction of the plan with every line's storey at its secant stiffness at its design drift in that suite at the least slip loads (a damper F/δ once it slips); each damper is tested at the frequency of the direction its line is closer to. Bare plan: {}.\n",
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
                || "not computed (the secant plan has no positive mode)".to_string(),
                periods
            ),
            periods(self.t1_s)
        );
        let freq = |d: usize| {
            self.t1m_s
                .map_or_else(|| "1/T_1M".to_string(), |t| format!("{:.3} Hz", 1.0 / t[d]))
        };
        let _ = writeln!(
            s,
            "- **Prototype test**, each damper type: {} fully reversed sinusoidal cycles at amplitude ±A at 1/T_1M of its direction ({} along x, {} along y). {}",
            c.cycles,
            freq(0),
            freq(1),
            acceptance(c.band_percent)
        );
        let _ = writeln!(
            s,
            "- **Wind test**: {}",
            match c.wind_cycles {
                Some(w) => format!(
                    "{w} fully reversed cycles at the design wind's damper force and displacement, at 1/T1 of the damper's direction ({:.3} Hz along x, {:.3} Hz along y).",
                    1.0 / self.t1_s[0],
                    1.0 / self.t1_s[1]
                ),
                None => "not made: the study claims the exemption of dampers that do not slip in the design wind — show that each storey's design wind shear on a line is below its dampers' lower-bound slip load (the range below).".to_string(),
            }
        );
        if let Some(p) = c.production_cycles {
            let _ = writeln!(
                s,
                "- **Production test**, every unit: {p} cycles at ±A at its prototype's frequency; accepted when its average force at zero displacement and loop energy are within the ranges below."
            );
        }
        s.push_str("\n| damper | direction | A (mm) | velocity 2πA/T_1M (mm/s) | force at zero displacement (kN) | range (kN) | loop energy 4FA (kJ) | range (kJ) |\n|---|---|---:|---:|---:|---:|---:|---:|\n");
        for d in &self.dampers {
            let _ = writeln!(
                s,
                "| {} | {} | {}",
                md_text(&d.damper),
                ["x", "y"][d.direction],
                d.figures.cells()
            );
        }
        s
    }
}
