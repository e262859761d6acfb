//! A study in plan as its JSON file writes it ([`PlanStudyConfig`]): the building in plan,
//! suites of two-component ground motions run at orientations to the plan's axes, the
//! design space by line, the objective and limits on edge drifts and torsion, accidental
//! torsion as property cases, and how finely to sweep and refine. Validation and loading
//! are [`super::study`]'s.

use crate::model::space::Shape;
use serde::{Deserialize, Serialize};
use slipload_sim::floorplan::FloorPlanRef;
use slipload_sim::scene::MethodName;
use std::path::PathBuf;

/// A study in plan, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanStudyConfig {
    /// Short name.
    pub name: String,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The building in plan: a file (relative to the study) or an inline object.
    pub building: FloorPlanRef,
    /// The ground-motion suites (each a list of two-component pairs).
    pub suites: Vec<PlanSuiteConfig>,
    /// Which slip loads the study chooses, and their bounds.
    pub space: PlanSpaceConfig,
    /// What the study minimises.
    #[serde(default)]
    pub objective: PlanObjectiveConfig,
    /// Acceptance limits (none: every design is acceptable unless it collapses).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<PlanLimitsConfig>,
    /// Accidental torsion: each floor's centre of mass moved by this fraction of the plan
    /// dimension across each direction, ± (four property cases beside the nominal one;
    /// ASCE 7-16 §12.8.4.2 takes 0.05). The objective and limits read the worst case.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accidental_torsion: Option<f64>,
    /// The dampers' property bounds, as a chain study's `property_bounds`: every case
    /// runs again with every slip load × λ_min and × λ_max (and brace stiffness, when
    /// given), the accidental-torsion cases included. The limits read every case; the
    /// objective the nominal properties (`objective_reads`: `nominal`) or every case
    /// (`worst`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub property_bounds: Option<crate::model::check::PropertyBoundsConfig>,
    /// The devices: the prototype and production test protocol `plan-devices.md` writes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub devices: Option<PlanDevicesConfig>,
    /// The runs' method and step.
    #[serde(default)]
    pub fidelity: PlanFidelityConfig,
    /// The sweep's sample.
    #[serde(default)]
    pub sweep: PlanSweepConfig,
    /// The refinement.
    #[serde(default)]
    pub refine: PlanRefineConfig,
}

/// The devices of a study in plan.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanDevicesConfig {
    /// The device tests (as a chain study's `devices.test_protocol`): the counts and bands
    /// the specification uses; amplitudes, frequencies and velocities come from the runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub test_protocol: Option<crate::model::config::TestProtocolConfig>,
}

/// One suite of two-component ground motions.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSuiteConfig {
    /// Name (tables, figures).
    pub name: String,
    /// The pairs: `[first, second]` record files (relative to the study), the two
    /// horizontal components of one event, the second at 90° to the first.
    pub pairs: Vec<[PathBuf; 2]>,
    /// One scale factor on both components of every pair (default 1). Exclusive with
    /// `code_spectrum`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factor: Option<f64>,
    /// Scale the pairs to a code spectrum by their maximum-direction (RotD100) spectra,
    /// as a chain study's `scale.code_spectrum` scales pairs (ASCE 7-16 §16.2.3: the
    /// pairs' mean at or above 90 % of the target over the period range, here built from
    /// the plan's first-mode periods along x and y). Exclusive with `factor`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub code_spectrum: Option<crate::model::config::CodeSpectrumConfig>,
    /// The orientations the pairs run at: the first component's angle from the plan's x
    /// axis, degrees (the second at +90°); default `[0, 90]`. Each pair's responses are
    /// the largest over its orientations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angles_deg: Option<Vec<f64>>,
    /// Simulated time of each run, s (default: the longer component's duration).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
}

/// How the study places slip loads on the plan's dampers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// One variable per line: the line's slip loads are its first storey's times the
    /// shape, each line free of the others (the split between a direction's lines, stiff
    /// edge or flexible edge, is part of the design).
    Lines,
    /// One variable per direction: a storey's slip load along a direction is split
    /// between that direction's lines in proportion to their storey stiffness — what a
    /// planar study, which lumps a storey's lines into one, implies.
    Directions,
    /// One variable per damper.
    Free,
}

impl Placement {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            Placement::Lines => "lines",
            Placement::Directions => "directions",
            Placement::Free => "free",
        }
    }
}

/// The design space of a study in plan (slip loads in kN).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSpaceConfig {
    /// `lines`, `directions` or `free`.
    pub placement: Placement,
    /// The shape over the storeys (`lines`, `directions`; default `storey_shear`):
    /// `uniform`, `storey_shear` (the shear of a triangular load pattern) or `stiffness`
    /// (the line's own storey stiffness; for `directions` the direction's total).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<Shape>,
    /// [lower, upper] of each variable, kN: a line's first-storey slip load (`lines`),
    /// a direction's first-storey total (`directions`), a damper's slip load (`free`).
    pub slip_load_kn: [f64; 2],
    /// The lines whose dampers the study sizes (default: every line with dampers); the
    /// others keep the building file's slip loads.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lines: Option<Vec<String>>,
    /// Σ slip loads over the sized dampers ≤ this, kN.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub budget_kn: Option<f64>,
}

/// What a study in plan measures of a design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum PlanMetric {
    /// The largest peak drift ratio at the plan's edges over the storeys (the drift a
    /// code checks at the edge; needs `plan_size` and `storey_heights`).
    #[default]
    EdgeDriftRatio,
    /// The largest peak drift ratio of any line over the storeys (needs
    /// `storey_heights`).
    LineDriftRatio,
    /// The largest peak floor rotation, rad.
    Rotation,
    /// The largest torsional irregularity ratio over the storeys and directions (the
    /// larger edge drift over the edges' mean; needs `plan_size`).
    TorsionalRatio,
    /// The sum of the sized slip loads, N (with limits: the least slip load that passes).
    TotalSlipLoad,
}

impl PlanMetric {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            PlanMetric::EdgeDriftRatio => "edge_drift_ratio",
            PlanMetric::LineDriftRatio => "line_drift_ratio",
            PlanMetric::Rotation => "rotation",
            PlanMetric::TorsionalRatio => "torsional_ratio",
            PlanMetric::TotalSlipLoad => "total_slip_load",
        }
    }
}

/// How a suite's ground motions combine into one value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum PlanStatistic {
    /// The mean over the pairs (ASCE 7-16 §16.2.4 with seven pairs or more).
    #[default]
    Mean,
    /// The largest over the pairs.
    Max,
}

/// The objective of a study in plan.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanObjectiveConfig {
    /// The measure (default `edge_drift_ratio`).
    #[serde(default)]
    pub metric: PlanMetric,
    /// Over each suite's pairs (default `mean`); the objective is the worst suite at the
    /// worst property case.
    #[serde(default)]
    pub statistic: PlanStatistic,
}

/// Acceptance limits of a study in plan, each read as the objective's statistic at the
/// worst property case of every suite.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanLimitsConfig {
    /// The largest edge drift ratio allowed (e.g. 0.02: ASCE 7-16 Table 12.12-1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_drift_ratio: Option<f64>,
    /// The largest torsional irregularity ratio allowed (1.2: irregular past it; 1.4:
    /// extremely irregular, ASCE 7-16 Table 12.3-1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsional_ratio: Option<f64>,
}

/// The runs' fidelity.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanFidelityConfig {
    /// `newmark` (default) or `exact`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<MethodName>,
    /// Time step, s (default: the method's, T1/400 or a divisor of the records' step).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt_s: Option<f64>,
    /// The final table's designs run again at dt × this (default 0.25: a check of the
    /// sweep's accuracy on the designs reported).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check_dt_factor: Option<f64>,
}

/// The sweep of a study in plan: a shifted Halton sample of the space.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSweepConfig {
    /// Designs sampled (default 16).
    #[serde(default = "default_points")]
    pub points: usize,
    /// Seed of the sample's shift (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
}

impl Default for PlanSweepConfig {
    fn default() -> Self {
        PlanSweepConfig {
            points: default_points(),
            seed: default_seed(),
        }
    }
}

/// The refinement of a study in plan (the `model` refiner: profile line searches, then a
/// trust region on an interpolation model, the limits modelled as constraints).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanRefineConfig {
    /// Most new design evaluations (default 60).
    #[serde(default = "default_evaluations")]
    pub max_evaluations: usize,
    /// Stop when the trust radius falls below this, scaled variables (default 2e-3).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
}

impl Default for PlanRefineConfig {
    fn default() -> Self {
        PlanRefineConfig {
            max_evaluations: default_evaluations(),
            tolerance: default_tolerance(),
        }
    }
}

fn default_points() -> usize {
    16
}
fn default_seed() -> u64 {
    1
}
fn default_evaluations() -> usize {
    60
}
fn default_tolerance() -> f64 {
    2e-3
}

/// A number without trailing zeros (at most 6 decimals): 5, 2.5, 0.035.
pub fn trim(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}
