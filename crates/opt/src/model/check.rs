//! What a design must pass: the property bounds its dampers are checked at and the
//! acceptance limits of each suite — the study keys `property_bounds` and
//! `suites[i].limits` — and the check of one design's responses against them.
//!
//! A study that names neither runs as before: one property case (nominal), no limits,
//! and every file it writes keeps its bytes.
//!
//! **Property cases.** Slip loads vary over a device's life and between units (bolt
//! tension, friction coefficient), so a design is analysed at its nominal properties and
//! at its lower- and upper-bound properties (ASCE 7-16 Ch. 18, damping-device design
//! properties with λ_min and λ_max; EN 15129 §4 on the variation of a device's
//! properties): every slip load × λ_min (and the brace stiffness × its own λ_min, when
//! the study names one) is the lower-bound case, × λ_max the upper-bound case. The runs of
//! a study are its property cases × its records, nominal first ([`Checks::cases`]).
//!
//! **Acceptance limits.** Per suite, statistics of per-record responses against limits
//! (e.g. the mean of the peak storey drift ratios, ASCE 7-16 §16.4.1.2), and a count of
//! unacceptable responses (ASCE 7-16 §16.4.1.1: a record on which the run collapsed, or
//! on which a per-record limit is exceeded), each checked at every property case.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::objective::{Metric, Objective, Statistic};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;

pub use super::bounds::{Derivation, Factors, Part};

/// Which property case the objective reads.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BoundReading {
    /// The nominal properties (the default).
    #[default]
    Nominal,
    /// The worst (largest) objective of the nominal, lower- and upper-bound cases.
    Worst,
}

impl BoundReading {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            BoundReading::Nominal => "nominal",
            BoundReading::Worst => "worst",
        }
    }
}

/// The study key `property_bounds`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PropertyBoundsConfig {
    /// λ_min and λ_max of every slip load.
    pub slip_load: Factors,
    /// λ_min and λ_max of every brace stiffness (default: the brace as given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brace_stiffness: Option<Factors>,
    /// Which case the objective reads (default `nominal`).
    #[serde(default)]
    pub objective_reads: BoundReading,
}

/// A property case's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CaseName {
    /// Nominal properties.
    Nominal,
    /// Lower-bound properties (× λ_min).
    Lower,
    /// Upper-bound properties (× λ_max).
    Upper,
}

impl CaseName {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            CaseName::Nominal => "nominal",
            CaseName::Lower => "lower",
            CaseName::Upper => "upper",
        }
    }
}

/// One property case: the factors every damper's slip load and brace stiffness take.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PropertyCase {
    /// Which case.
    pub name: CaseName,
    /// Factor on every slip load.
    pub slip_load: f64,
    /// Factor on every brace stiffness.
    pub brace_stiffness: f64,
}

impl PropertyCase {
    /// The nominal case (factors 1).
    pub const NOMINAL: PropertyCase = PropertyCase {
        name: CaseName::Nominal,
        slip_load: 1.0,
        brace_stiffness: 1.0,
    };

    /// Whether the case changes nothing.
    pub fn is_nominal(&self) -> bool {
        self.name == CaseName::Nominal
    }
}

/// A per-record response a limit may read: responses a code limits (the objective's
/// ratios and indices — energy ratio, RPI, friction share, hysteretic energy — are no
/// acceptance criteria).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitMetric {
    /// Peak interstorey drift ratio, max over the storeys.
    PeakDriftRatio,
    /// Residual drift ratio, max over the storeys.
    ResidualDriftRatio,
    /// Peak absolute floor acceleration, max over the floors, m/s².
    PeakFloorAcceleration,
    /// Peak base shear, N.
    BaseShear,
    /// Peak storey ductility, max over the yielding storeys.
    PeakDuctility,
}

impl LimitMetric {
    /// The objective's metric of the same response.
    pub fn metric(self) -> Metric {
        match self {
            LimitMetric::PeakDriftRatio => Metric::PeakDriftRatio,
            LimitMetric::ResidualDriftRatio => Metric::ResidualDriftRatio,
            LimitMetric::PeakFloorAcceleration => Metric::PeakFloorAcceleration,
            LimitMetric::BaseShear => Metric::BaseShear,
            LimitMetric::PeakDuctility => Metric::PeakDuctility,
        }
    }

    /// Name as written.
    pub fn as_str(self) -> &'static str {
        self.metric().as_str()
    }

    /// Its value on one record.
    pub fn value(self, m: &RecordMetrics) -> Result<f64, OptError> {
        self.metric().value(m, None)
    }
}

/// One limit on a statistic of a suite's per-record responses (`suites[i].limits.criteria[j]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Criterion {
    /// The per-record response.
    pub metric: LimitMetric,
    /// The statistic over the suite's records.
    pub statistic: Statistic,
    /// The largest acceptable value, in the metric's unit (drift ratios dimensionless,
    /// accelerations m/s², forces N).
    pub max: f64,
}

/// A per-record limit whose exceedance makes a response unacceptable.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordLimit {
    /// The per-record response.
    pub metric: LimitMetric,
    /// The largest acceptable value on one record.
    pub max: f64,
}

/// The count of unacceptable responses a suite allows (`suites[i].limits.unacceptable`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Unacceptable {
    /// How many records may respond unacceptably: as given, or (absent) what the study's
    /// `risk_category` allows (ASCE 7-16 §16.4.1.1: 1 for Risk Category I and II with at
    /// least 11 ground motions, else 0), 1 without a risk category. A loaded study holds
    /// it resolved ([`Unacceptable::resolve`]); [`Unacceptable::allowed`] reads it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_count: Option<usize>,
    /// Per-record limits: a record exceeding any of them responds unacceptably (a run
    /// that collapses always does).
    #[serde(default)]
    pub record_limits: Vec<RecordLimit>,
    /// Whether the study wrote the key (its absence allows the default count): only a
    /// count the study asks for is one it is told cannot happen ([`crate::Study::model_limits`]).
    #[serde(skip, default = "written")]
    pub written: bool,
}

fn written() -> bool {
    true
}

impl Unacceptable {
    /// The count allowed: the resolved or given `max_count`, else 1.
    pub fn allowed(&self) -> usize {
        self.max_count.unwrap_or(1)
    }

    /// Sets the count allowed for a suite of `motions` ground motions in a study of risk
    /// category `rc` (none: 1 where the study gives no count); a given count above what
    /// the category allows is refused with the allowance (`Err`).
    pub fn resolve(&mut self, rc: Option<RiskCategory>, motions: usize) -> Result<(), usize> {
        let allowance = rc.map(|rc| rc.allowance(motions));
        match (self.max_count, allowance) {
            (Some(n), Some(a)) if n > a => return Err(a),
            (None, a) => self.max_count = Some(a.unwrap_or(1)),
            _ => {}
        }
        Ok(())
    }
}

/// A Risk Category (ASCE 7-16 Table 1.5-1), as a study names it (`risk_category`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RiskCategory {
    /// Risk Category I.
    I,
    /// Risk Category II.
    II,
    /// Risk Category III.
    III,
    /// Risk Category IV.
    IV,
}

impl RiskCategory {
    /// As written.
    pub fn as_str(self) -> &'static str {
        match self {
            RiskCategory::I => "I",
            RiskCategory::II => "II",
            RiskCategory::III => "III",
            RiskCategory::IV => "IV",
        }
    }

    /// The unacceptable responses a suite of `motions` ground motions may have (ASCE 7-16
    /// §16.4.1.1: one for Risk Category I and II where the suite has at least 11, none
    /// otherwise).
    pub fn allowance(self, motions: usize) -> usize {
        match self {
            RiskCategory::I | RiskCategory::II if motions >= 11 => 1,
            _ => 0,
        }
    }
}

/// The acceptance limits of one suite (`suites[i].limits`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteLimits {
    /// Limits on statistics over the suite.
    #[serde(default)]
    pub criteria: Vec<Criterion>,
    /// The count of unacceptable responses (default: at most 1, collapses counted).
    #[serde(default)]
    pub unacceptable: Unacceptable,
}

impl PropertyBoundsConfig {
    /// Checks the factors ([`Factors::validate`]): numbers or a derivation, then
    /// 0 < λ_min ≤ 1 ≤ λ_max, finite.
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        self.slip_load.validate(path, "property_bounds.slip_load")?;
        if let Some(k) = &self.brace_stiffness {
            k.validate(path, "property_bounds.brace_stiffness")?;
        }
        Ok(())
    }
}

impl SuiteLimits {
    /// Checks the limits of `suites[suite]`: limitable metrics, finite positive limits.
    pub fn validate(&self, path: &Path, suite: usize) -> Result<(), OptError> {
        let field = |x: String| format!("suites[{suite}].limits.{x}");
        let value = |f: String, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(OptError::invalid(
                    path,
                    f,
                    format!("must be finite and > 0, got {v}"),
                ))
            }
        };
        if self.criteria.is_empty() && self.unacceptable.record_limits.is_empty() {
            return Err(OptError::invalid(
                path,
                field("criteria".into()),
                "the suite's limits name no criterion: give criteria (e.g. {\"metric\": \"peak_drift_ratio\", \"statistic\": \"mean\", \"max\": 0.02}) or unacceptable.record_limits",
            ));
        }
        for (j, c) in self.criteria.iter().enumerate() {
            value(field(format!("criteria[{j}].max")), c.max)?;
        }
        for (j, c) in self.unacceptable.record_limits.iter().enumerate() {
            value(field(format!("unacceptable.record_limits[{j}].max")), c.max)?;
        }
        Ok(())
    }
}

/// The checks of a study, resolved: its property bounds and each suite's limits (in the
/// order of the suites). Written into the sweep's manifest only when the study has some.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checks {
    /// The property bounds, when the study names them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub property_bounds: Option<PropertyBoundsConfig>,
    /// Each suite's limits (empty when no suite has any).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub limits: Vec<Option<SuiteLimits>>,
    /// The dampers' stroke capacity each way, m (`devices.stroke_capacity_mm`): a run
    /// past it responds unacceptably.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke_capacity_m: Option<f64>,
}

/// One line of a design's check: a criterion at one suite and property case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckLine {
    /// The suite.
    pub suite: String,
    /// The property case.
    pub case: CaseName,
    /// What is checked, e.g. `mean peak_drift_ratio`, `unacceptable responses`.
    pub criterion: String,
    /// The limit.
    pub limit: f64,
    /// The design's demand.
    pub demand: f64,
    /// demand / limit; for the count of unacceptable responses count / (allowed + ½), so
    /// that it is ≤ 1 exactly when the count is allowed (and 0 when no record responds
    /// unacceptably).
    pub ratio: f64,
    /// Whether the criterion is met.
    pub pass: bool,
    /// The study key of the limit, e.g. `suites[1].limits.criteria[0]`.
    pub source: String,
}

impl CheckLine {
    /// Whether the line counts unacceptable responses (its limit and demand are counts).
    pub fn is_count(&self) -> bool {
        self.source.ends_with("unacceptable")
    }

    /// Whether the line limits a drift ratio (peak or residual): its limit and demand are
    /// shown in percent of the storey height wherever a person reads them.
    pub fn is_drift(&self) -> bool {
        !self.is_count() && self.criterion.ends_with("drift_ratio")
    }

    /// A limit or demand of this line as a person reads it: a count as a whole number, a
    /// drift ratio in percent of the storey height (`0.4975 %`), any other response in
    /// the unit of its metric; 4 significant figures ([`short`]). The machine files keep
    /// the number itself.
    pub fn value_text(&self, v: f64) -> String {
        if self.is_count() {
            format!("{v:.0}")
        } else if self.is_drift() {
            format!("{} %", short(100.0 * v))
        } else {
            short(v)
        }
    }
}

/// A design's check against every limit at every property case.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DesignCheck {
    /// One line per (suite, case, criterion), suite after suite, case after case.
    pub lines: Vec<CheckLine>,
}

impl DesignCheck {
    /// Every line passes.
    pub fn passes(&self) -> bool {
        self.lines.iter().all(|l| l.pass)
    }

    /// The governing line: the largest ratio (the first of equals).
    pub fn governing(&self) -> Option<&CheckLine> {
        governing(&self.lines)
    }

    /// The margin of the governing line, 1 − ratio (negative: the limit is exceeded).
    pub fn margin(&self) -> f64 {
        self.governing().map_or(f64::INFINITY, |l| 1.0 - l.ratio)
    }

    /// The sum of the exceedances over the study's limits, each at the property case
    /// where it is exceeded most: Σ over limits of maxᶜ max(0, ratio − 1). 0 exactly when
    /// the design passes; what the refiners minimise when no design of the sweep passes.
    /// (Summed over the cases too, bounds 1.0 / 1.0, three identical cases, would count
    /// every exceedance three times.)
    pub fn violation(&self) -> f64 {
        let mut worst: Vec<(&str, f64)> = Vec::new();
        for l in &self.lines {
            let e = (l.ratio - 1.0).max(0.0);
            match worst.iter_mut().find(|(s, _)| *s == l.source) {
                Some(w) => w.1 = w.1.max(e),
                None => worst.push((&l.source, e)),
            }
        }
        worst.iter().map(|(_, e)| e).sum()
    }

    /// The ratio of each criterion line (`suites[i].limits.criteria[j]` at each case), in
    /// order: the smooth functions of the design a refiner can model. The counts of
    /// unacceptable responses are left out (steps, not smooth functions).
    pub fn smooth_ratios(&self) -> Vec<f64> {
        self.lines
            .iter()
            .filter(|l| l.source.contains(".limits.criteria["))
            .map(|l| l.ratio)
            .collect()
    }

    /// A one-line verdict: `PASS (governing: …, ratio 0.93)` or `FAIL (…)`; a drift's
    /// demand and limit in percent of the storey height ([`CheckLine::value_text`]).
    pub fn verdict(&self) -> String {
        let head = if self.passes() { "PASS" } else { "FAIL" };
        match self.governing() {
            Some(g) => format!(
                "{head} (governing: {} of {} at {} properties, demand {} against limit {}, ratio {:.3}; {})",
                g.criterion,
                g.suite,
                g.case.as_str(),
                g.value_text(g.demand),
                g.value_text(g.limit),
                g.ratio,
                g.source
            ),
            None => format!("{head} (no limits)"),
        }
    }
}

/// The governing line of `lines`: the largest ratio (the first of equals).
pub fn governing<'a>(lines: impl IntoIterator<Item = &'a CheckLine>) -> Option<&'a CheckLine> {
    lines
        .into_iter()
        .fold(None, |best: Option<&CheckLine>, l| match best {
            Some(b) if b.ratio >= l.ratio => Some(b),
            _ => Some(l),
        })
}

/// A number in 4 significant figures.
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return v.to_string();
    }
    let mag = v.abs().log10().floor() as i32;
    if (-3..5).contains(&mag) {
        let decimals = (3 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

impl Checks {
    /// The checks a study file names.
    pub fn of(bounds: Option<PropertyBoundsConfig>, limits: Vec<Option<SuiteLimits>>) -> Checks {
        let limits = if limits.iter().any(Option::is_some) {
            limits
        } else {
            Vec::new()
        };
        Checks {
            property_bounds: bounds,
            limits,
            stroke_capacity_m: None,
        }
    }

    /// These checks with the dampers' stroke capacity (m; `None`: unlimited travel).
    pub fn with_stroke_capacity(mut self, capacity_m: Option<f64>) -> Checks {
        self.stroke_capacity_m = capacity_m;
        self
    }

    /// No bounds and no limits: the study runs as one without checks.
    pub fn is_empty(&self) -> bool {
        self.property_bounds.is_none() && self.limits.is_empty()
    }

    /// Whether any suite has limits.
    pub fn has_limits(&self) -> bool {
        !self.limits.is_empty()
    }

    /// The property cases, nominal first: `[nominal]`, or `[nominal, lower, upper]`.
    pub fn cases(&self) -> Vec<PropertyCase> {
        let mut out = vec![PropertyCase::NOMINAL];
        if let Some(b) = &self.property_bounds {
            let k = b
                .brace_stiffness
                .as_ref()
                .map_or((1.0, 1.0), Factors::bounds);
            let s = b.slip_load.bounds();
            out.push(PropertyCase {
                name: CaseName::Lower,
                slip_load: s.0,
                brace_stiffness: k.0,
            });
            out.push(PropertyCase {
                name: CaseName::Upper,
                slip_load: s.1,
                brace_stiffness: k.1,
            });
        }
        out
    }

    /// The least and the largest slip-load factor over the property cases (λ_min, λ_max;
    /// 1 and 1 without bounds).
    pub fn slip_load_range(&self) -> (f64, f64) {
        let cases = self.cases();
        (
            cases.iter().map(|c| c.slip_load).fold(1.0, f64::min),
            cases.iter().map(|c| c.slip_load).fold(1.0, f64::max),
        )
    }

    /// How the property bounds were built from their parts, for the report (empty where
    /// the study gave the factors as numbers).
    pub fn derivations(&self) -> Vec<String> {
        let Some(b) = &self.property_bounds else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (name, f) in [
            ("slip load", Some(&b.slip_load)),
            ("brace stiffness", b.brace_stiffness.as_ref()),
        ] {
            if let Some(d) = f.and_then(|f| f.derivation.as_ref()) {
                out.extend(d.lines(name));
            }
        }
        out
    }

    /// The property case an objective value is read at, as the summary and the report
    /// label it (`at the worst properties`, `at nominal properties`); `None` for a study
    /// without property bounds, whose one case needs no label.
    pub fn objective_case(&self) -> Option<&'static str> {
        self.property_bounds
            .as_ref()
            .map(|b| match b.objective_reads {
                BoundReading::Nominal => "at nominal properties",
                BoundReading::Worst => "at the worst properties",
            })
    }

    /// Which case the objective reads.
    pub fn reading(&self) -> BoundReading {
        self.property_bounds
            .as_ref()
            .map_or(BoundReading::Nominal, |b| b.objective_reads)
    }

    /// The case the objective reads for one design (`rows`: the cases × `records` runs,
    /// nominal first; `bare`: the bare frame's runs) and its objective there: the
    /// nominal case, or the case of the largest objective (the first of equals).
    fn read_case(
        &self,
        objective: &Objective,
        rows: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
        records: usize,
    ) -> Result<(usize, f64), OptError> {
        let value = |c: usize| {
            let span = c * records..(c + 1) * records;
            objective.value(&rows[span.clone()], bare.map(|b| &b[span]), suites)
        };
        let mut read = (0, value(0)?);
        if self.reading() == BoundReading::Worst {
            for c in 1..self.cases().len() {
                let f = value(c)?;
                if f > read.1 {
                    read = (c, f);
                }
            }
        }
        Ok(read)
    }

    /// The objective of one design (slip loads `loads_n`, N) over its runs (`rows`: the
    /// cases × `records` runs, nominal first; `bare`: the bare frame's runs): the nominal
    /// case's, or the worst of the cases', plus the design's cost (a cost objective).
    pub fn objective(
        &self,
        objective: &Objective,
        rows: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
        records: usize,
        loads_n: &[f64],
    ) -> Result<f64, OptError> {
        let response = self.read_case(objective, rows, bare, suites, records)?.1;
        Ok(response + objective.cost_value(loads_n))
    }

    /// The objective of each case the objective reads (the nominal case alone, or every
    /// case for the worst reading, whose objective is their largest), each with the
    /// design's cost: the pieces a refiner that knows the objective is a maximum models
    /// one by one.
    pub fn case_objectives(
        &self,
        objective: &Objective,
        rows: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
        records: usize,
        loads_n: &[f64],
    ) -> Result<Vec<f64>, OptError> {
        let cases = if self.reading() == BoundReading::Worst {
            self.cases().len()
        } else {
            1
        };
        let cost = objective.cost_value(loads_n);
        (0..cases)
            .map(|c| {
                let span = c * records..(c + 1) * records;
                Ok(objective.value(&rows[span.clone()], bare.map(|b| &b[span]), suites)? + cost)
            })
            .collect()
    }

    /// Each term's value at the case the objective reads (for the worst reading: at the
    /// case whose objective is the worst).
    pub fn terms(
        &self,
        objective: &Objective,
        rows: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
        records: usize,
    ) -> Result<Vec<f64>, OptError> {
        let (at, _) = self.read_case(objective, rows, bare, suites, records)?;
        let span = at * records..(at + 1) * records;
        objective
            .terms
            .iter()
            .map(|t| {
                Objective::term_value(
                    t,
                    &rows[span.clone()],
                    bare.map(|b| &b[span.clone()]),
                    suites,
                )
            })
            .collect()
    }

    /// The check of one design's runs (`rows`, cases × `records`, nominal first) against
    /// every suite's limits at every case. `suites`: (name, record range) per suite.
    pub fn check(
        &self,
        rows: &[RecordMetrics],
        suites: &[(&str, Range<usize>)],
        records: usize,
    ) -> Result<DesignCheck, OptError> {
        let mut lines = Vec::new();
        for (c, case) in self.cases().iter().enumerate() {
            let runs = &rows[c * records..(c + 1) * records];
            for (i, (name, range)) in suites.iter().enumerate() {
                let Some(Some(lim)) = self.limits.get(i) else {
                    continue;
                };
                for (j, crit) in lim.criteria.iter().enumerate() {
                    let vals = range
                        .clone()
                        .map(|r| crit.metric.value(&runs[r]))
                        .collect::<Result<Vec<f64>, _>>()?;
                    let demand = crit.statistic.of(&vals);
                    lines.push(CheckLine {
                        suite: name.to_string(),
                        case: case.name,
                        criterion: format!("{} {}", crit.statistic.as_str(), crit.metric.as_str()),
                        limit: crit.max,
                        demand,
                        ratio: demand / crit.max,
                        pass: demand <= crit.max,
                        source: format!("suites[{i}].limits.criteria[{j}]"),
                    });
                }
                let u = &lim.unacceptable;
                let mut count = 0usize;
                for r in range.clone() {
                    let m = &runs[r];
                    let mut bad = m.collapsed()
                        || self
                            .stroke_capacity_m
                            .is_some_and(|c| m.stroke.iter().any(|s| *s > c));
                    for rl in &u.record_limits {
                        bad |= rl.metric.value(m)? > rl.max;
                    }
                    count += usize::from(bad);
                }
                lines.push(CheckLine {
                    suite: name.to_string(),
                    case: case.name,
                    criterion: "unacceptable responses".into(),
                    limit: u.allowed() as f64,
                    demand: count as f64,
                    ratio: count as f64 / (u.allowed() as f64 + 0.5),
                    pass: count <= u.allowed(),
                    source: format!("suites[{i}].limits.unacceptable"),
                });
            }
        }
        Ok(DesignCheck { lines })
    }
}

/// The check as CSV: one line per criterion, with its source.
pub fn check_csv(check: &DesignCheck) -> String {
    let mut s = String::from("suite,case,criterion,limit,demand,ratio,pass,source\n");
    for l in &check.lines {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            l.suite,
            l.case.as_str(),
            l.criterion,
            l.limit,
            l.demand,
            l.ratio,
            if l.pass { "pass" } else { "FAIL" },
            l.source
        );
    }
    s
}

/// `text` (a name the user chose: a record's file name, a suite's) as Markdown text,
/// never markup:
/// every ASCII punctuation character backslash-escaped (CommonMark then shows it as
/// itself, `<` and `|` included), a control character shown as U+FFFD.
pub fn md_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.push('\u{fffd}');
        } else {
            if c.is_ascii_punctuation() {
                out.push('\\');
            }
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file name is text in Markdown: markup, table bars and HTML come out escaped, so
    /// CommonMark shows them as written; letters, digits and spaces stay.
    #[test]
    fn a_record_name_is_markdown_text_never_markup() {
        assert_eq!(md_text("RSN6 I-ELC180"), "RSN6 I\\-ELC180");
        assert_eq!(
            md_text("<img src=x onerror=alert(1)>|*b*"),
            "\\<img src\\=x onerror\\=alert\\(1\\)\\>\\|\\*b\\*"
        );
        assert_eq!(md_text("a\nb`c"), "a\u{fffd}b\\`c");
    }

    fn metrics(drift: f64, collapsed: bool) -> RecordMetrics {
        RecordMetrics {
            drift_ratio: vec![drift],
            residual_drift_ratio: vec![0.0],
            peak_floor_acceleration: 1.0,
            peak_base_shear: 1.0,
            peak_displacement: 0.01,
            stroke: vec![0.0],
            energy_input: None,
            energy_friction: None,
            strain_energy_area: None,
            ductility: None,
            energy_plastic: None,
            collapse: collapsed.then_some((1, 1.0)),
            dampers: None,
            tangent: None,
        }
    }

    fn checks(max_count: usize) -> Checks {
        Checks::of(
            Some(PropertyBoundsConfig {
                slip_load: Factors::numbers(0.8, 1.2),
                brace_stiffness: None,
                objective_reads: BoundReading::Worst,
            }),
            vec![Some(SuiteLimits {
                criteria: vec![Criterion {
                    metric: LimitMetric::PeakDriftRatio,
                    statistic: Statistic::Mean,
                    max: 0.02,
                }],
                unacceptable: Unacceptable {
                    max_count: Some(max_count),
                    record_limits: vec![RecordLimit {
                        metric: LimitMetric::PeakDriftRatio,
                        max: 0.03,
                    }],
                    written: true,
                },
            })],
        )
    }

    #[test]
    fn a_check_reads_every_case_and_counts_unacceptable_records() {
        // three cases × two records; the upper case has one record past the per-record limit
        let rows = vec![
            metrics(0.010, false),
            metrics(0.012, false),
            metrics(0.015, false),
            metrics(0.017, false),
            metrics(0.005, false),
            metrics(0.031, false),
        ];
        let suites = [("s", 0..2)];
        let c = checks(0).check(&rows, &suites, 2).unwrap();
        assert_eq!(c.lines.len(), 6);
        // the mean over the upper case: (0.005 + 0.031) / 2 = 0.018 ≤ 0.02
        assert!(c.lines[4].pass);
        assert!((c.lines[4].demand - 0.018).abs() < 1e-15);
        // one unacceptable response where none is allowed fails, and governs
        assert!(!c.lines[5].pass);
        assert_eq!(c.lines[5].ratio, 2.0);
        assert!(!c.passes());
        assert_eq!(
            c.governing().unwrap().source,
            "suites[0].limits.unacceptable"
        );
        assert!((c.violation() - 1.0).abs() < 1e-15);
        // none: ratio 0
        assert_eq!(c.lines[1].ratio, 0.0);
        // one allowed: it passes, below ratio 1; the upper case's mean drift governs
        let c = checks(1).check(&rows, &suites, 2).unwrap();
        assert!(c.passes());
        assert_eq!(c.violation(), 0.0);
        assert_eq!(c.lines[5].ratio, 1.0 / 1.5);
        assert_eq!(
            c.governing().unwrap().source,
            "suites[0].limits.criteria[0]"
        );
    }

    /// The sum of exceedances takes each limit once, at its worst case: with bounds
    /// 1.0 / 1.0 (three identical cases) it is the nominal case's, not three times it.
    #[test]
    fn the_sum_of_exceedances_counts_each_limit_once_at_its_worst_case() {
        let rows: Vec<RecordMetrics> = [0.03, 0.025, 0.03, 0.025, 0.03, 0.025]
            .iter()
            .map(|d| metrics(*d, false))
            .collect();
        let suites = [("s", 0..2)];
        let mut identical = checks(2);
        identical.property_bounds.as_mut().unwrap().slip_load = Factors::numbers(1.0, 1.0);
        let c = identical.check(&rows, &suites, 2).unwrap();
        let nominal = Checks::of(None, identical.limits.clone())
            .check(&rows[..2], &suites, 2)
            .unwrap();
        // mean drift 0.0275 against 0.02: 0.375 over, in every case alike
        assert!(
            (nominal.violation() - 0.375).abs() < 1e-12,
            "{}",
            nominal.violation()
        );
        assert_eq!(c.violation(), nominal.violation());
        // cases that differ: the worst case's exceedance of each limit
        let rows: Vec<RecordMetrics> = [0.03, 0.025, 0.02, 0.02, 0.04, 0.04]
            .iter()
            .map(|d| metrics(*d, false))
            .collect();
        let c = checks(2).check(&rows, &suites, 2).unwrap();
        // the drift limit at its worst (the upper case, 0.04: ratio 2), and the count of
        // responses past 0.03 (the upper case's two, against two allowed: passes)
        assert!((c.violation() - 1.0).abs() < 1e-12, "{}", c.violation());
    }

    /// A run in which a damper travels past the stated stroke capacity responds
    /// unacceptably, beside the collapses and the per-record limits; without a capacity
    /// the travel is unlimited.
    #[test]
    fn a_stroke_past_the_capacity_is_an_unacceptable_response() {
        let stroke = |s: f64| RecordMetrics {
            stroke: vec![0.001, s],
            ..metrics(0.01, false)
        };
        // nominal, lower, upper × two records: strokes 20 / 50 mm, 40 / 60 mm, 10 / 20 mm
        let rows: Vec<RecordMetrics> = [0.02, 0.05, 0.04, 0.06, 0.01, 0.02]
            .iter()
            .map(|s| stroke(*s))
            .collect();
        let suites = [("s", 0..2)];
        let count = |c: &DesignCheck| -> Vec<f64> {
            c.lines
                .iter()
                .filter(|l| l.criterion == "unacceptable responses")
                .map(|l| l.demand)
                .collect()
        };
        let unlimited = checks(1).check(&rows, &suites, 2).unwrap();
        assert_eq!(count(&unlimited), [0.0, 0.0, 0.0]);
        // 35 mm: one record past it at the nominal case, both at the lower, none at the
        // upper; one allowed, so the lower case fails
        let c = checks(1)
            .with_stroke_capacity(Some(0.035))
            .check(&rows, &suites, 2)
            .unwrap();
        assert_eq!(count(&c), [1.0, 2.0, 0.0]);
        assert!(!c.passes());
        assert_eq!(c.governing().unwrap().case, CaseName::Lower);
    }

    #[test]
    fn a_collapse_is_an_unacceptable_response_without_record_limits() {
        let mut ch = checks(0);
        ch.limits[0]
            .as_mut()
            .unwrap()
            .unacceptable
            .record_limits
            .clear();
        ch.property_bounds = None;
        let rows = vec![metrics(0.01, true), metrics(0.01, false)];
        let c = ch.check(&rows, &[("s", 0..2)], 2).unwrap();
        assert!(!c.lines[1].pass);
        assert_eq!(c.lines[1].demand, 1.0);
    }

    #[test]
    fn the_worst_reading_takes_the_largest_case_objective() {
        let one_suite = [std::ops::Range { start: 0, end: 1 }];
        let obj = Objective {
            terms: vec![crate::model::objective::Term {
                metric: Metric::PeakDriftRatio,
                statistic: Statistic::Mean,
                weight: 1.0,
            }],
            cost: None,
        };
        let rows = vec![
            metrics(0.010, false),
            metrics(0.030, false),
            metrics(0.005, false),
        ];
        let ch = checks(1);
        let f = ch.objective(&obj, &rows, None, &one_suite, 1, &[]).unwrap();
        assert_eq!(f, 0.030);
        assert_eq!(
            ch.terms(&obj, &rows, None, &one_suite, 1).unwrap(),
            vec![0.030]
        );
        let mut nominal = ch.clone();
        nominal.property_bounds.as_mut().unwrap().objective_reads = BoundReading::Nominal;
        assert_eq!(
            nominal
                .objective(&obj, &rows, None, &one_suite, 1, &[])
                .unwrap(),
            0.010
        );
    }

    #[test]
    fn factors_out_of_order_are_refused_by_field() {
        let b = PropertyBoundsConfig {
            slip_load: Factors::numbers(1.1, 1.2),
            brace_stiffness: None,
            objective_reads: BoundReading::Nominal,
        };
        let e = b.validate(Path::new("s.json")).unwrap_err().to_string();
        assert!(e.contains("property_bounds.slip_load.lower"), "{e}");
    }
}
