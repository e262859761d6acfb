//! Design families: the optimum of a study over a grid of period scales × intensity
//! scales — a table an engineer reads off for a similar building or another hazard level.
//!
//! A period scale p multiplies every period of the building: frame and brace stiffnesses
//! are divided by p² and the frame and brace damping by p (so every modal damping ratio is
//! kept), masses and storey heights unchanged. An intensity scale multiplies every record.
//! The design space (kN) stays the study's.

use crate::base::collapse::{objective_text, reduction, reduction_text};
use crate::base::error::OptError;
use crate::eval::evaluate::{DesignLoads, run_designs};
use crate::model::config::RefineMethod;
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::refinement::optimize;
use crate::phases::sweep::Manifest;
use crate::store::folder::StudyFolder;
use serde::{Deserialize, Serialize};
use slipload_sim::modes::Modes;
use std::fmt::Write as _;
use std::sync::Arc;

/// The optimum for one (period scale, intensity scale).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FamilyCell {
    /// Period scale.
    pub period_scale: f64,
    /// Intensity scale.
    pub intensity_scale: f64,
    /// Fundamental period of the bare frame, s.
    pub t1_s: f64,
    /// Optimal slip loads, kN per dissipator.
    pub slip_loads_kn: Vec<f64>,
    /// Objective of the optimum (sweep fidelity).
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub objective: f64,
    /// Objective of the bare frame (`"collapsed"` when it collapses on a record).
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub bare_objective: f64,
    /// Designs evaluated (sweep + refinement).
    pub designs: usize,
}

/// The study with its building's periods scaled by `period_scale` and its records by
/// `intensity_scale`.
pub fn scaled_study(
    study: &Study,
    period_scale: f64,
    intensity_scale: f64,
) -> Result<Study, OptError> {
    for (what, v) in [
        ("period scale", period_scale),
        ("intensity scale", intensity_scale),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(OptError::Missing(format!(
                "{what} must be finite and > 0, got {v}"
            )));
        }
    }
    let mut s = study.clone();
    let k = 1.0 / (period_scale * period_scale);
    let c = 1.0 / period_scale;
    s.building.stiffness *= k;
    s.building.damping *= c;
    for d in s.building.dissipators.iter_mut().flatten() {
        d.brace_stiffness *= k;
        d.brace_damping *= c;
    }
    s.building.modes = Modes::compute(&s.building.mass, &s.building.stiffness)
        .ok_or_else(|| OptError::Missing("scaled stiffness is not positive definite".into()))?;
    s.records = study
        .records
        .iter()
        .map(|r| r.try_scaled(intensity_scale).map(Arc::new))
        .collect::<Result<_, _>>()?;
    Ok(s)
}

/// Sweeps and refines the study at every (period scale, intensity scale).
pub fn family(
    study: &Study,
    period_scales: &[f64],
    intensity_scales: &[f64],
    method: RefineMethod,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<FamilyCell>, OptError> {
    let mut out = Vec::new();
    for &p in period_scales {
        for &a in intensity_scales {
            // a cell that cannot be built names its scales (the cause names the record)
            let at = |e: OptError| {
                e.context(format!(
                    "family table at period scale {p}, intensity scale {a}"
                ))
            };
            let s = scaled_study(study, p, a).map_err(at)?;
            let m = Manifest::of(&s);
            // the building file's design as written (its friction law, when it has one)
            let designs: Vec<DesignLoads> = m
                .designs
                .iter()
                .map(|d| DesignLoads {
                    slip_loads_n: d.slip_loads_n.clone(),
                    friction_n: d.friction_n.clone(),
                })
                .collect();
            let rows: Vec<_> = run_designs(&s, &designs, &Fidelity::sweep(&s), tick)
                .map_err(at)?
                .into_iter()
                .flatten()
                .collect();
            let r = optimize(&s, &m, &rows, method, None, None, tick).map_err(at)?;
            out.push(FamilyCell {
                period_scale: p,
                intensity_scale: a,
                t1_s: s.building.t1(),
                slip_loads_kn: r.optimum_loads.iter().map(|v| v / 1e3).collect(),
                objective: r.optimum.f,
                bare_objective: r.bare_objective,
                designs: r.sweep_designs + r.log.len(),
            });
        }
    }
    Ok(out)
}

/// CSV of a family.
pub fn to_csv(cells: &[FamilyCell], damper_floors: &[usize]) -> String {
    let mut s = String::from("period_scale,intensity_scale,t1_s");
    for f in damper_floors {
        let _ = write!(s, ",slip_load_kN_{f}");
    }
    s.push_str(",objective,bare_objective,designs\n");
    for c in cells {
        let _ = write!(s, "{},{},{}", c.period_scale, c.intensity_scale, c.t1_s);
        for v in &c.slip_loads_kn {
            let _ = write!(s, ",{v}");
        }
        let _ = writeln!(
            s,
            ",{},{},{}",
            objective_text(c.objective, None),
            objective_text(c.bare_objective, None),
            c.designs
        );
    }
    s
}

/// Markdown of a family.
pub fn to_markdown(cells: &[FamilyCell], damper_floors: &[usize], objective: &str) -> String {
    let floors: Vec<String> = damper_floors.iter().map(|f| f.to_string()).collect();
    let mut s = format!(
        "Optimal slip loads (kN, floors {}) by period scale × intensity scale; objective: {objective}.\n\n| period × | T₁ (s) | intensity × | slip loads (kN) | objective | bare frame | reduction |\n|---:|---:|---:|---|---:|---:|---:|\n",
        floors.join(" / ")
    );
    for c in cells {
        let loads: Vec<String> = c.slip_loads_kn.iter().map(|v| format!("{v:.1}")).collect();
        let _ = writeln!(
            s,
            "| {} | {:.3} | {} | {} | {} | {} | {} |",
            c.period_scale,
            c.t1_s,
            c.intensity_scale,
            loads.join(" / "),
            objective_text(c.objective, Some(5)),
            objective_text(c.bare_objective, Some(5)),
            reduction_text(reduction(c.objective, c.bare_objective), Some(1))
        );
    }
    s
}

/// A study's optimum over period scale × intensity scale ([`crate::pipeline::family_study`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyReport {
    /// The study's name.
    pub study: String,
    /// Its objective, as a label.
    pub objective: String,
    /// Floors (from 1) of the dissipators.
    pub damper_floors: Vec<usize>,
    /// One cell per (period scale, intensity scale), period scales outer.
    pub cells: Vec<FamilyCell>,
}

impl FamilyReport {
    /// The files [`FamilyReport::write_files`] writes.
    pub const FILES: [&str; 2] = ["family.csv", "family.md"];

    /// `family.csv`.
    pub fn to_csv(&self) -> String {
        to_csv(&self.cells, &self.damper_floors)
    }

    /// `family.md`.
    pub fn to_markdown(&self) -> String {
        to_markdown(&self.cells, &self.damper_floors, &self.objective)
    }

    /// Writes `family.csv` and `family.md` into `out`.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("family.csv", self.to_csv().as_bytes())?;
        folder.write("family.md", self.to_markdown().as_bytes())
    }
}

/// Checks the scales of a family table before anything runs: each list holds one scale
/// or more (an empty list is a table of nothing, refused here so that every front says
/// the same), every period scale keeps the frame's periods within the physical band,
/// every intensity scale keeps the records' PGA within the study's band, and no scale is
/// given twice.
pub fn check_scales(
    study: &Study,
    period_scales: &[f64],
    intensity_scales: &[f64],
) -> Result<(), OptError> {
    for (name, scales) in [
        ("--period-scales", period_scales),
        ("--intensity-scales", intensity_scales),
    ] {
        if scales.is_empty() {
            return Err(OptError::Argument(format!(
                "{name}: an empty list; give one scale or more (each is a row or column of the table)"
            )));
        }
    }
    // every scaled frame must stay a building: its periods within the physical band
    let (lo, hi) = slipload_sim::building::PERIOD_BAND_S;
    let periods = study.building.modes.periods();
    let (t_long, t_short) = (periods[0], periods[periods.len() - 1]);
    for &p in period_scales {
        if !(p.is_finite() && p > 0.0 && t_short * p >= lo && t_long * p <= hi) {
            return Err(OptError::Argument(format!(
                "--period-scales {p:e}: must be positive and keep the frame's periods ({t_short:.3} … {t_long:.3} s) within {lo:e} … {hi:e} s"
            )));
        }
    }
    // every scaled record must stay a ground motion: its PGA within the study's band
    let pgas = study.records.iter().map(|r| r.pga() / slipload_motion::G);
    let (pga_lo, pga_hi) = pgas.fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    let (min_g, max_g) = (
        crate::model::config::MIN_STUDY_PGA_G,
        slipload_motion::MAX_ABS_ACCEL_G,
    );
    for &i in intensity_scales {
        if !(i.is_finite() && i > 0.0 && pga_lo * i >= min_g && pga_hi * i <= max_g) {
            return Err(OptError::Argument(format!(
                "--intensity-scales {i:e}: must be positive and keep the records' PGA ({pga_lo:.3} … {pga_hi:.3} g) within {min_g} … {max_g} g (below, no dissipator slips; beyond, no ground has shaken)"
            )));
        }
    }
    for (name, scales) in [
        ("--period-scales", period_scales),
        ("--intensity-scales", intensity_scales),
    ] {
        if let Some((k, v)) = scales
            .iter()
            .enumerate()
            .find(|(k, v)| scales[..*k].contains(v))
        {
            return Err(OptError::Argument(format!(
                "{name}: {v} is given twice (values {} and {}): each scale is one row of the table; give each once",
                scales.iter().position(|x| x == v).map_or(0, |p| p + 1),
                k + 1
            )));
        }
    }
    Ok(())
}
