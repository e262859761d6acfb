//! A study in plan, loaded and validated before any run ([`PlanStudy::load`]): the
//! building and its accidental-torsion cases, the suites' pairs read and scaled, the
//! design space over the plan's dampers. Errors name the study file and the field.

use super::config::{Placement, PlanMetric, PlanStudyConfig};
use crate::base::error::OptError;
use crate::model::space::{DesignSpace, Shape};
use nalgebra::DMatrix;
use slipload_motion::Record;
use slipload_sim::floorplan::{FloorPlan, FloorPlanRef};
use slipload_sim::scene::MethodName;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Most pairs × orientations × cases a study runs per design.
const MAX_RUNS_PER_DESIGN: usize = 2_000;

/// A damper of the building in plan: its line and storey (from 0), in the order the
/// compiled plan lists them (line after line, storeys up).
#[derive(Debug, Clone, PartialEq)]
pub struct DamperSite {
    /// Index of its line.
    pub line: usize,
    /// Storey, from 0.
    pub storey: usize,
    /// "A/3".
    pub name: String,
    /// The building file's slip load, N (`None`: locked or asymmetric bounds).
    pub file_slip_load: Option<f64>,
}

/// One property case: the building with its centres of mass where the case puts them,
/// and the factors on its dampers' slip loads and brace stiffnesses.
#[derive(Debug, Clone)]
pub struct PlanCase {
    /// "nominal", "centre of mass +5 % x", "lower bound", "upper bound, centre of mass
    /// -5 % y", …
    pub name: String,
    /// The building of the case.
    pub building: Arc<FloorPlan>,
    /// Factor on every damper's slip load (1, λ_min or λ_max).
    pub slip_factor: f64,
    /// Factor on every damper's brace stiffness.
    pub brace_factor: f64,
    /// Whether the objective reads the case (the limits read every case).
    pub objective: bool,
}

/// A pair of horizontal components, scaled.
#[derive(Debug, Clone)]
pub struct PlanPair {
    /// "NWH090+NWH360".
    pub name: String,
    /// The first component, m/s².
    pub first: Arc<Record>,
    /// The second component (at +90° to the first), m/s².
    pub second: Arc<Record>,
}

/// A suite of pairs, loaded.
#[derive(Debug, Clone)]
pub struct PlanSuite {
    /// Name.
    pub name: String,
    /// Its pairs.
    pub pairs: Vec<PlanPair>,
    /// Orientations of the first component from the plan's x axis, degrees.
    pub angles_deg: Vec<f64>,
    /// The scale factor on both components (a code-scaled suite's: its scaling's).
    pub factor: f64,
    /// How the suite was scaled to a code spectrum, when it was.
    pub code: Option<crate::model::code_scaling::CodeScaling>,
    /// Simulated time of each run, s (`None`: the longer component's).
    pub duration_s: Option<f64>,
}

/// A validated study in plan.
#[derive(Debug, Clone)]
pub struct PlanStudy {
    /// Name.
    pub name: String,
    /// The study file.
    pub path: PathBuf,
    /// The config as written.
    pub config: PlanStudyConfig,
    /// The nominal building (the file's slip loads).
    pub building: Arc<FloorPlan>,
    /// The property cases: the nominal first, then the accidental-torsion cases.
    pub cases: Vec<PlanCase>,
    /// The suites.
    pub suites: Vec<PlanSuite>,
    /// Every damper of the building.
    pub dampers: Vec<DamperSite>,
    /// The design space; its `dampers` index [`PlanStudy::dampers`].
    pub space: DesignSpace,
    /// The runs' method.
    pub method: MethodName,
}

impl PlanStudy {
    /// Reads and validates the study at `path` (building and records relative to it).
    pub fn load(path: &Path) -> Result<PlanStudy, OptError> {
        let text = crate::model::study::read_text(path)?;
        let cfg: PlanStudyConfig =
            serde_json::from_str(&text).map_err(|source| OptError::Json {
                path: path.to_path_buf(),
                source,
            })?;
        PlanStudy::from_config(cfg, path)
    }

    /// Validates `cfg`; `path` names it in errors and anchors relative paths.
    pub fn from_config(cfg: PlanStudyConfig, path: &Path) -> Result<PlanStudy, OptError> {
        let base = path.parent().unwrap_or(Path::new("."));
        let invalid = |field: &str, message: String| OptError::invalid(path, field, message);
        if cfg.name.trim().is_empty() {
            return Err(invalid("name", "must not be empty".into()));
        }
        let building = match &cfg.building {
            FloorPlanRef::Path(p) => FloorPlan::load(&base.join(p))?,
            FloorPlanRef::Inline(b) => FloorPlan::from_config(b, path)?,
        };
        let building = Arc::new(building);
        let dampers = damper_sites(&building);
        if dampers.is_empty() {
            return Err(invalid(
                "building",
                "the building in plan has no dampers: there are no slip loads to choose (give the lines `dissipators`)".into(),
            ));
        }
        check_metric_needs(&cfg, &building, path)?;
        if let Some(t) = cfg.devices.and_then(|d| d.test_protocol) {
            t.validate(path)?;
        }
        let cases = property_cases(&cfg, &building, path)?;
        let suites = load_suites(&cfg, &building, base, path)?;
        let space = plan_space(&cfg, &building, &dampers, path)?;
        let method = cfg.fidelity.method.unwrap_or(MethodName::Newmark);
        if !matches!(method, MethodName::Newmark | MethodName::Exact) {
            return Err(invalid(
                "fidelity.method",
                format!(
                    "{} does not run a building in plan in a study: newmark (default) or exact",
                    method.as_str()
                ),
            ));
        }
        if let Some(dt) = cfg.fidelity.dt_s
            && !(dt.is_finite() && dt > 0.0)
        {
            return Err(invalid(
                "fidelity.dt_s",
                format!("a positive time step in s, got {dt}"),
            ));
        }
        if let Some(f) = cfg.fidelity.check_dt_factor
            && !(f.is_finite() && f > 0.0 && f <= 1.0)
        {
            return Err(invalid(
                "fidelity.check_dt_factor",
                format!("a factor in (0, 1] on the time step, got {f}"),
            ));
        }
        if cfg.sweep.points == 0 || cfg.sweep.points > 10_000 {
            return Err(invalid(
                "sweep.points",
                format!("between 1 and 10000 designs, got {}", cfg.sweep.points),
            ));
        }
        if cfg.refine.max_evaluations > 10_000 {
            return Err(invalid(
                "refine.max_evaluations",
                format!("at most 10000, got {}", cfg.refine.max_evaluations),
            ));
        }
        let tol = cfg.refine.tolerance;
        if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
            return Err(invalid(
                "refine.tolerance",
                format!("a step in scaled variables in (0, 1), got {tol}"),
            ));
        }
        let runs: usize = suites
            .iter()
            .map(|s| s.pairs.len() * s.angles_deg.len())
            .sum::<usize>()
            * cases.len();
        if runs > MAX_RUNS_PER_DESIGN {
            return Err(invalid(
                "suites",
                format!(
                    "{runs} runs per design (pairs x orientations x property cases): at most {MAX_RUNS_PER_DESIGN}"
                ),
            ));
        }
        Ok(PlanStudy {
            name: cfg.name.clone(),
            path: path.to_path_buf(),
            config: cfg,
            building,
            cases,
            suites,
            dampers,
            space,
            method,
        })
    }

    /// Runs per design: every pair at every orientation in every case.
    pub fn runs_per_design(&self) -> usize {
        self.suites
            .iter()
            .map(|s| s.pairs.len() * s.angles_deg.len())
            .sum::<usize>()
            * self.cases.len()
    }

    /// The slip loads of every damper (N) with the space's at `z`, the others the
    /// file's (0 where the file locks a damper or gives bounds: those keep theirs).
    pub fn all_slip_loads(&self, z: &[f64]) -> Vec<Option<f64>> {
        let mut out: Vec<Option<f64>> = self.dampers.iter().map(|d| d.file_slip_load).collect();
        for (k, s) in self.space.slip_loads(z).into_iter().enumerate() {
            out[self.space.dampers[k]] = Some(s);
        }
        out
    }

    /// The building of `case` with the slip loads `loads` (N, per damper; `None` keeps
    /// the file's bounds).
    ///
    /// The case's factors multiply every damper's slip load (or the file's bounds) and
    /// brace stiffness; a locked damper stays locked.
    pub fn with_slip_loads(&self, case: usize, loads: &[Option<f64>]) -> FloorPlan {
        let c = &self.cases[case];
        let mut b = (*c.building).clone();
        for (site, load) in self.dampers.iter().zip(loads) {
            let Some(d) = b.lines[site.line].dissipators[site.storey].as_mut() else {
                continue;
            };
            if let Some(f) = load {
                d.lower = -f;
                d.upper = *f;
            }
            if c.slip_factor != 1.0 && !d.is_locked() {
                d.lower *= c.slip_factor;
                d.upper *= c.slip_factor;
            }
            if c.brace_factor != 1.0 {
                d.brace_stiffness *= c.brace_factor;
            }
        }
        b
    }
}

/// Every damper of `b`, in the compiled plan's order.
fn damper_sites(b: &FloorPlan) -> Vec<DamperSite> {
    let mut out = Vec::new();
    for (l, line) in b.lines.iter().enumerate() {
        for (f, d) in line.dissipators.iter().enumerate() {
            if let Some(d) = d {
                let symmetric = d.upper.is_finite() && d.lower == -d.upper;
                out.push(DamperSite {
                    line: l,
                    storey: f,
                    name: format!("{}/{}", line.name, f + 1),
                    file_slip_load: symmetric.then_some(d.upper),
                });
            }
        }
    }
    out
}

/// The metric and limits read what the building gives: drift ratios need storey
/// heights, edges and torsion need the plan's size.
fn check_metric_needs(cfg: &PlanStudyConfig, b: &FloorPlan, path: &Path) -> Result<(), OptError> {
    let needs_heights = |field: &str| -> Result<(), OptError> {
        if b.storey_heights.is_none() {
            return Err(OptError::invalid(
                path,
                field,
                "reads drift ratios: the building in plan must give `storey_heights`",
            ));
        }
        Ok(())
    };
    let needs_size = |field: &str| -> Result<(), OptError> {
        if b.plan_size.is_none() {
            return Err(OptError::invalid(
                path,
                field,
                "reads the plan's edges: the building in plan must give `plan_size`",
            ));
        }
        Ok(())
    };
    match cfg.objective.metric {
        PlanMetric::EdgeDriftRatio => {
            needs_heights("objective.metric")?;
            needs_size("objective.metric")?;
        }
        PlanMetric::LineDriftRatio => needs_heights("objective.metric")?,
        PlanMetric::TorsionalRatio => needs_size("objective.metric")?,
        PlanMetric::Rotation | PlanMetric::TotalSlipLoad => {}
    }
    if let Some(l) = &cfg.limits {
        if let Some(v) = l.edge_drift_ratio {
            if !(v.is_finite() && v > 0.0 && v < 1.0) {
                return Err(OptError::invalid(
                    path,
                    "limits.edge_drift_ratio",
                    format!("a drift ratio in (0, 1) (0.02 is 2 %), got {v}"),
                ));
            }
            needs_heights("limits.edge_drift_ratio")?;
            needs_size("limits.edge_drift_ratio")?;
        }
        if let Some(v) = l.torsional_ratio {
            if !(v.is_finite() && v >= 1.0) {
                return Err(OptError::invalid(
                    path,
                    "limits.torsional_ratio",
                    format!(
                        "a ratio of the larger edge drift to the edges' mean, >= 1 (1.2, 1.4), got {v}"
                    ),
                ));
            }
            needs_size("limits.torsional_ratio")?;
        }
        if l.edge_drift_ratio.is_none() && l.torsional_ratio.is_none() {
            return Err(OptError::invalid(
                path,
                "limits",
                "names no limit: give edge_drift_ratio or torsional_ratio, or leave `limits` out",
            ));
        }
    }
    if cfg.objective.metric == PlanMetric::TotalSlipLoad && cfg.limits.is_none() {
        return Err(OptError::invalid(
            path,
            "objective.metric",
            "total_slip_load is minimised subject to limits: give `limits` (without them the least slip load is none)",
        ));
    }
    Ok(())
}

/// The nominal case, with `accidental_torsion` the four cases with every floor's centre
/// of mass moved by ± that fraction of the plan's size along x and along y, and with
/// `property_bounds` each of these again at the lower and at the upper bound.
fn property_cases(
    cfg: &PlanStudyConfig,
    b: &Arc<FloorPlan>,
    path: &Path,
) -> Result<Vec<PlanCase>, OptError> {
    let mut cases = vec![PlanCase {
        name: "nominal".into(),
        building: b.clone(),
        slip_factor: 1.0,
        brace_factor: 1.0,
        objective: true,
    }];
    add_torsion_cases(cfg, b, path, &mut cases)?;
    let Some(bounds) = &cfg.property_bounds else {
        return Ok(cases);
    };
    bounds.validate(path)?;
    let checks = crate::model::check::Checks::of(Some(bounds.clone()), Vec::new());
    let worst = bounds.objective_reads == crate::model::check::BoundReading::Worst;
    let nominal = cases.clone();
    for bound in checks.cases().into_iter().filter(|c| !c.is_nominal()) {
        for c in &nominal {
            let name = format!("{} bound", bound.name.as_str());
            cases.push(PlanCase {
                name: if c.name == "nominal" {
                    name
                } else {
                    format!("{name}, {}", c.name)
                },
                building: c.building.clone(),
                slip_factor: bound.slip_load,
                brace_factor: bound.brace_stiffness,
                objective: worst,
            });
        }
    }
    Ok(cases)
}

/// The four accidental-torsion cases `accidental_torsion` asks for, after the nominal.
fn add_torsion_cases(
    cfg: &PlanStudyConfig,
    b: &Arc<FloorPlan>,
    path: &Path,
    cases: &mut Vec<PlanCase>,
) -> Result<(), OptError> {
    let Some(e) = cfg.accidental_torsion else {
        return Ok(());
    };
    if !(e.is_finite() && e > 0.0 && e <= 0.25) {
        return Err(OptError::invalid(
            path,
            "accidental_torsion",
            format!(
                "a fraction of the plan dimension in (0, 0.25] (0.05 is the standard's 5 %), got {e}"
            ),
        ));
    }
    let Some([lx, ly]) = b.plan_size else {
        return Err(OptError::invalid(
            path,
            "accidental_torsion",
            "moves the centres of mass by a fraction of the plan's size: the building in plan must give `plan_size`",
        ));
    };
    for (axis, size) in [("x", lx), ("y", ly)] {
        for sign in [1.0, -1.0] {
            let d = sign * e * size;
            let shift = if axis == "x" { [d, 0.0] } else { [0.0, d] };
            cases.push(PlanCase {
                name: format!(
                    "centre of mass {}{} % {axis}",
                    if sign > 0.0 { "+" } else { "-" },
                    super::config::trim(e * 100.0)
                ),
                building: Arc::new(b.with_centre_shift(shift)),
                slip_factor: 1.0,
                brace_factor: 1.0,
                objective: true,
            });
        }
    }
    Ok(())
}

/// Reads every suite's pairs and scales them.
fn load_suites(
    cfg: &PlanStudyConfig,
    building: &FloorPlan,
    base: &Path,
    path: &Path,
) -> Result<Vec<PlanSuite>, OptError> {
    if cfg.suites.is_empty() {
        return Err(OptError::invalid(
            path,
            "suites",
            "lists no suite: give at least one suite of pairs",
        ));
    }
    let mut out = Vec::with_capacity(cfg.suites.len());
    for (i, s) in cfg.suites.iter().enumerate() {
        let field = |f: &str| format!("suites[{i}].{f}");
        if s.name.trim().is_empty() {
            return Err(OptError::invalid(path, field("name"), "must not be empty"));
        }
        if out.iter().any(|o: &PlanSuite| o.name == s.name) {
            return Err(OptError::invalid(
                path,
                field("name"),
                format!(
                    "{:?} names another suite too: suite names tell their rows apart",
                    s.name
                ),
            ));
        }
        if s.pairs.is_empty() {
            return Err(OptError::invalid(
                path,
                field("pairs"),
                "lists no pair: give [first, second] record files",
            ));
        }
        if s.factor.is_some() && s.code_spectrum.is_some() {
            return Err(OptError::invalid(
                path,
                field("factor"),
                "give `factor` or `code_spectrum`, not both: a code-scaled suite's factor is the one that meets the spectrum",
            ));
        }
        let factor = s.factor.unwrap_or(1.0);
        if !(factor.is_finite() && factor > 0.0) {
            return Err(OptError::invalid(
                path,
                field("factor"),
                format!("a positive scale factor, got {factor}"),
            ));
        }
        let angles = s.angles_deg.clone().unwrap_or_else(|| vec![0.0, 90.0]);
        if angles.is_empty() || angles.iter().any(|a| !a.is_finite()) {
            return Err(OptError::invalid(
                path,
                field("angles_deg"),
                "at least one finite orientation, degrees from the plan's x axis",
            ));
        }
        if let Some(d) = s.duration_s
            && !(d.is_finite() && d > 0.0)
        {
            return Err(OptError::invalid(
                path,
                field("duration_s"),
                format!("a positive time in s, got {d}"),
            ));
        }
        let mut pairs = Vec::with_capacity(s.pairs.len());
        for (k, [a, b]) in s.pairs.iter().enumerate() {
            let read = |p: &PathBuf, c: usize| -> Result<Record, OptError> {
                let r = slipload_motion::read_record(&base.join(p), None, None).map_err(|e| {
                    OptError::invalid(path, format!("suites[{i}].pairs[{k}][{c}]"), e.to_string())
                })?;
                r.try_scaled(factor)
                    .map_err(|e| OptError::invalid(path, field("factor"), e.to_string()))
            };
            let first = read(a, 0)?;
            let second = read(b, 1)?;
            let stem = |p: &PathBuf| {
                p.file_stem().map_or_else(
                    || p.display().to_string(),
                    |s| s.to_string_lossy().into_owned(),
                )
            };
            let pair =
                slipload_motion::RecordPair::new(format!("{}+{}", stem(a), stem(b)), first, second)
                    .map_err(|e| {
                        OptError::invalid(path, format!("suites[{i}].pairs[{k}]"), e.to_string())
                    })?;
            pairs.push(pair);
        }
        let (pairs, factor, code) = match &s.code_spectrum {
            None => (pairs, factor, None),
            Some(c) => {
                let (pairs, scaling) = scale_pairs_to_code(cfg, building, &pairs, c, path, i)?;
                (pairs, scaling.factor, Some(scaling))
            }
        };
        out.push(PlanSuite {
            name: s.name.clone(),
            pairs: pairs
                .into_iter()
                .map(|p| PlanPair {
                    name: p.name().to_string(),
                    first: Arc::new(p.first().clone()),
                    second: Arc::new(p.second().clone()),
                })
                .collect(),
            angles_deg: angles,
            factor,
            code,
            duration_s: s.duration_s,
        });
    }
    Ok(out)
}

/// Suite `i`'s pairs scaled to the code spectrum `c` by their mean maximum-direction
/// spectrum, over the range built from the plan's principal-direction periods
/// ([`FloorPlan::scaling_periods`]); with the EN 1998-1 rule and fewer than 7 pairs the
/// objective must read the largest over them (§4.3.3.4.3(3)).
fn scale_pairs_to_code(
    cfg: &PlanStudyConfig,
    building: &FloorPlan,
    pairs: &[slipload_motion::RecordPair],
    c: &crate::model::config::CodeSpectrumConfig,
    path: &Path,
    i: usize,
) -> Result<
    (
        Vec<slipload_motion::RecordPair>,
        crate::model::code_scaling::CodeScaling,
    ),
    OptError,
> {
    use crate::model::code_scaling::{ScalingBasis, scale_to_code};
    use crate::model::code_spectrum::{EN1998_MEAN_FROM, ScalingRule};
    let periods = building.scaling_periods();
    let basis = ScalingBasis {
        t1_s: periods.map_or_else(|| building.t1(), |p| p.bare_t1_s),
        periods,
    };
    let (records, scaling) =
        scale_to_code(&[], pairs, c, None, &basis, path, i).map_err(|e| rename_field(e, i))?;
    if c.rule().ok() == Some(ScalingRule::En1998)
        && pairs.len() < EN1998_MEAN_FROM
        && cfg.objective.statistic == super::config::PlanStatistic::Mean
    {
        return Err(OptError::invalid(
            path,
            "objective.statistic",
            format!(
                "is \"mean\": with {} pairs (fewer than {EN1998_MEAN_FROM}) EN 1998-1 §4.3.3.4.3(3) takes the most unfavourable response; give \"max\", or at least {EN1998_MEAN_FROM} pairs",
                pairs.len()
            ),
        ));
    }
    let mut it = records.into_iter();
    let mut out = Vec::with_capacity(pairs.len());
    for (k, p) in pairs.iter().enumerate() {
        if let (Some(a), Some(b)) = (it.next(), it.next()) {
            out.push(
                slipload_motion::RecordPair::new(p.name(), a, b).map_err(|e| {
                    OptError::invalid(path, format!("suites[{i}].pairs[{k}]"), e.to_string())
                })?,
            );
        }
    }
    Ok((out, scaling))
}

/// A chain suite's field names in an error of [`scale_to_code`] as a plan suite's:
/// `scale.code_spectrum` is `code_spectrum` here, `records` is `pairs`.
fn rename_field(e: OptError, i: usize) -> OptError {
    match e {
        OptError::Invalid {
            path,
            field,
            message,
        } => OptError::Invalid {
            path,
            field: field
                .replace(
                    &format!("suites[{i}].scale.code_spectrum"),
                    &format!("suites[{i}].code_spectrum"),
                )
                .replace(
                    &format!("suites[{i}].records"),
                    &format!("suites[{i}].pairs"),
                ),
            message: message.replace("scale.code_spectrum", "code_spectrum"),
        },
        other => other,
    }
}

/// The storey-shear shape of the plan (Σ_{j ≥ i} m_j h_j, first storey = 1).
fn storey_shear(b: &FloorPlan) -> Vec<f64> {
    let n = b.storeys();
    let heights = b.storey_heights.clone().unwrap_or_else(|| vec![1.0; n]);
    let mut elev = 0.0;
    let f: Vec<f64> = (0..n)
        .map(|i| {
            elev += heights[i];
            b.floors[i].mass * elev
        })
        .collect();
    let shear: Vec<f64> = (0..n).map(|i| f[i..].iter().sum()).collect();
    shear.iter().map(|v| v / shear[0]).collect()
}

/// The design space over the plan's dampers, as `space` places them.
fn plan_space(
    cfg: &PlanStudyConfig,
    b: &FloorPlan,
    dampers: &[DamperSite],
    path: &Path,
) -> Result<DesignSpace, OptError> {
    let sp = &cfg.space;
    let [lo, hi] = sp.slip_load_kn;
    if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
        return Err(OptError::invalid(
            path,
            "space.slip_load_kn",
            format!("[lower, upper] in kN with 0 <= lower < upper, got [{lo}, {hi}]"),
        ));
    }
    let (lo, hi) = (lo * 1e3, hi * 1e3);
    // the lines the study sizes
    let sized_lines: Vec<usize> = match &sp.lines {
        None => (0..b.lines.len())
            .filter(|&l| dampers.iter().any(|d| d.line == l))
            .collect(),
        Some(names) => {
            let mut v = Vec::new();
            for (k, n) in names.iter().enumerate() {
                let Some(l) = b.lines.iter().position(|line| &line.name == n) else {
                    return Err(OptError::invalid(
                        path,
                        format!("space.lines[{k}]"),
                        format!(
                            "{n:?} is not a line of the building (its lines: {})",
                            b.lines
                                .iter()
                                .map(|l| l.name.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ));
                };
                if !dampers.iter().any(|d| d.line == l) {
                    return Err(OptError::invalid(
                        path,
                        format!("space.lines[{k}]"),
                        format!("line {n:?} has no dampers in the building file: nothing to size"),
                    ));
                }
                if v.contains(&l) {
                    return Err(OptError::invalid(
                        path,
                        format!("space.lines[{k}]"),
                        format!("line {n:?} is named twice"),
                    ));
                }
                v.push(l);
            }
            v
        }
    };
    let sized: Vec<usize> = (0..dampers.len())
        .filter(|&k| sized_lines.contains(&dampers[k].line))
        .collect();
    let shape = sp.shape.unwrap_or(Shape::StoreyShear);
    if sp.placement == Placement::Free && sp.shape.is_some() {
        return Err(OptError::invalid(
            path,
            "space.shape",
            "a free space has one variable per damper: it takes no shape",
        ));
    }
    let shear = storey_shear(b);
    // each variable's group of sized dampers and each damper's weight in it
    let mut groups: Vec<(String, Vec<(usize, f64)>)> = Vec::new();
    match sp.placement {
        Placement::Free => {
            for (k, &d) in sized.iter().enumerate() {
                groups.push((format!("damper {}", dampers[d].name), vec![(k, 1.0)]));
            }
        }
        Placement::Lines => {
            for &l in &sized_lines {
                let line = &b.lines[l];
                let mine: Vec<(usize, &DamperSite)> = sized
                    .iter()
                    .enumerate()
                    .filter(|(_, d)| dampers[**d].line == l)
                    .map(|(k, d)| (k, &dampers[*d]))
                    .collect();
                let base = mine[0].1.storey;
                let w = |s: usize| match shape {
                    Shape::Uniform => 1.0,
                    Shape::StoreyShear => shear[s] / shear[base],
                    Shape::Stiffness => line.stiffness[s] / line.stiffness[base],
                };
                groups.push((
                    format!("line {}", line.name),
                    mine.iter().map(|(k, d)| (*k, w(d.storey))).collect(),
                ));
            }
        }
        Placement::Directions => {
            // lines grouped by direction (to 1e-9 rad, either sense)
            let mut dirs: Vec<(f64, Vec<usize>)> = Vec::new();
            for &l in &sized_lines {
                let a = b.lines[l].angle.rem_euclid(std::f64::consts::PI);
                match dirs.iter_mut().find(|(d, _)| {
                    let diff = (d - a).abs();
                    diff < 1e-9 || (std::f64::consts::PI - diff).abs() < 1e-9
                }) {
                    Some((_, v)) => v.push(l),
                    None => dirs.push((a, vec![l])),
                }
            }
            for (a, lines) in dirs {
                // the direction's total stiffness per storey over its sized lines
                let total = |s: usize| lines.iter().map(|&l| b.lines[l].stiffness[s]).sum::<f64>();
                let mine: Vec<(usize, &DamperSite)> = sized
                    .iter()
                    .enumerate()
                    .filter(|(_, d)| lines.contains(&dampers[**d].line))
                    .map(|(k, d)| (k, &dampers[*d]))
                    .collect();
                let base = mine.iter().map(|(_, d)| d.storey).min().unwrap_or(0);
                let w = |d: &DamperSite| {
                    let s = d.storey;
                    let share = b.lines[d.line].stiffness[s] / total(s);
                    share
                        * match shape {
                            Shape::Uniform => 1.0,
                            Shape::StoreyShear => shear[s] / shear[base],
                            Shape::Stiffness => total(s) / total(base),
                        }
                };
                let deg = super::config::trim(a.to_degrees());
                let names: Vec<&str> = lines.iter().map(|&l| b.lines[l].name.as_str()).collect();
                groups.push((
                    format!("direction {deg} deg ({})", names.join(", ")),
                    mine.iter().map(|(k, d)| (*k, w(d))).collect(),
                ));
            }
        }
    }
    let m = sized.len();
    let d = groups.len();
    let mut basis = DMatrix::zeros(m, d);
    let mut offset = vec![0.0; m];
    for (j, (_, members)) in groups.iter().enumerate() {
        for &(k, w) in members {
            basis[(k, j)] = (hi - lo) * w;
            offset[k] += lo * w;
        }
    }
    let (a, bvec) = match sp.budget_kn {
        None => (DMatrix::zeros(0, d), Vec::new()),
        Some(budget) => {
            if !(budget.is_finite() && budget > 0.0) {
                return Err(OptError::invalid(
                    path,
                    "space.budget_kn",
                    format!("a positive total slip load in kN, got {budget}"),
                ));
            }
            let least: f64 = offset.iter().sum();
            if least > budget * 1e3 * (1.0 + 1e-9) {
                return Err(OptError::invalid(
                    path,
                    "space.budget_kn",
                    format!(
                        "{budget} kN is below the space's least total slip load, {:.1} kN (every variable at its lower bound)",
                        least / 1e3
                    ),
                ));
            }
            let row = DMatrix::from_fn(1, d, |_, j| basis.column(j).sum());
            (row, vec![budget * 1e3 - least])
        }
    };
    let profile: Vec<f64> = sized.iter().map(|&k| shear[dampers[k].storey]).collect();
    Ok(DesignSpace {
        dampers: sized,
        offset,
        basis,
        a,
        b: bvec,
        names: groups.into_iter().map(|(n, _)| n).collect(),
        shape: None,
        profile,
    })
}
