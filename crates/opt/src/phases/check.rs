//! The code check of the recommended design: its responses at the check fidelity, at
//! every property case, against every suite's acceptance limits — one line per
//! criterion with its limit, demand, ratio, verdict and the study key the limit comes
//! from — with the suites' code scaling beside it, written as `code-check.csv`,
//! `code-check.md` and `code-check.json` (only for a study with limits or bounds).

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::check::{
    CaseName, DesignCheck, LimitMetric, PropertyCase, check_csv, md_text, short,
};
use crate::model::fidelity::Fidelity;
use crate::model::study::{CodeScaling, Study};
use crate::phases::compliance::{self, ComplianceRow};
use crate::phases::nonstructural::{self, DriftFlag};
use crate::phases::refinement::OptimizeReport;
use crate::phases::strength::FrameStrength;
use crate::store::folder::StudyFolder;
use serde::Serialize;
use std::fmt::Write as _;

/// A suite as the check names it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckedSuite {
    /// Name.
    pub name: String,
    /// Its records.
    pub records: usize,
    /// How it was scaled to a code spectrum, when it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code_scaling: Option<CodeScaling>,
    /// How its pairs ran, when the study said (`pairs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pair_run: Option<String>,
}

/// The code check of one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CodeCheck {
    /// The study.
    pub study: String,
    /// Floors (from 1) of the dampers.
    pub damper_floors: Vec<usize>,
    /// The design's slip loads, kN per damper (nominal).
    #[serde(rename = "slip_loads_kN")]
    pub slip_loads_kn: Vec<f64>,
    /// How the design was chosen.
    pub chosen_as: String,
    /// The objective's label, and which property case it reads.
    pub objective: String,
    /// Its value at the check fidelity.
    pub objective_value: f64,
    /// The fidelity of the responses checked.
    pub fidelity: String,
    /// The property cases.
    pub cases: Vec<PropertyCase>,
    /// How the bounds were built from their parts, where the study gave them
    /// (`property_bounds.*.derivation`), one line each bound and each source.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub derivations: Vec<String>,
    /// The widest specification tolerance the design affords, where the bounds are built
    /// from their parts and the design passes ([`crate::phases::tolerance`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<crate::phases::tolerance::Tolerance>,
    /// The suites.
    pub suites: Vec<CheckedSuite>,
    /// Every criterion at every suite and case.
    pub check: DesignCheck,
    /// Whether every criterion passes.
    pub passes: bool,
    /// The verdict with its governing criterion.
    pub verdict: String,
    /// The margin of the governing criterion, 1 − ratio.
    pub margin: f64,
    /// What the model cannot show that the check counts ([`Study::model_limits`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub model_limits: Vec<String>,
    /// The devices' stroke capacity each way, mm, when the study states it: a run past it
    /// is counted as an unacceptable response.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_capacity_mm: Option<f64>,
    /// The compliance matrix: each requirement's clause, value, limit and status
    /// ([`crate::phases::compliance`]).
    pub compliance: Vec<ComplianceRow>,
    /// Per suite with a limit on a statistic of the residual drift: the runs whose
    /// residual drift alone exceeds that limit (record and case, value).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub residual_tails: Vec<ResidualTail>,
    /// Per suite, the drift flag for deformation-sensitive nonstructural components,
    /// when the study names `nonstructural`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub nonstructural: Vec<DriftFlag>,
    /// The frame's strength without dampers, where the study asks for it
    /// (`frame_strength`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frame_strength: Option<FrameStrength>,
}

/// The runs of one suite whose residual drift alone exceeds its limit on a statistic of
/// the residual drift: the records that make the tail of the statistic.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualTail {
    /// The suite.
    pub suite: String,
    /// The limit (a residual drift ratio).
    pub limit: f64,
    /// Seconds of rest after each record before the residual is read (0: at the record's
    /// end).
    pub free_vibration_s: f64,
    /// The runs past it: the run's name (record, and case for a bound) and its residual.
    pub runs: Vec<(String, f64)>,
}

/// The residual tails of `runs` (every run of `study`).
fn residual_tails(study: &Study, runs: &[RecordMetrics]) -> Result<Vec<ResidualTail>, OptError> {
    let n = study.records.len();
    let cases = study.checks.cases().len();
    let mut out = Vec::new();
    for (i, suite) in study.suites.iter().enumerate() {
        let Some(Some(lim)) = study.checks.limits.get(i) else {
            continue;
        };
        for crit in &lim.criteria {
            if crit.metric != LimitMetric::ResidualDriftRatio {
                continue;
            }
            let mut past = Vec::new();
            for c in 0..cases {
                for r in suite.range.clone() {
                    let run = c * n + r;
                    let v = crit.metric.value(&runs[run])?;
                    if v > crit.max {
                        past.push((study.run_name(run), v));
                    }
                }
            }
            out.push(ResidualTail {
                suite: suite.name.clone(),
                limit: crit.max,
                free_vibration_s: suite.free_vibration_s,
                runs: past,
            });
        }
    }
    Ok(out)
}

impl CodeCheck {
    /// The files [`CodeCheck::write_files`] writes.
    pub const FILES: [&str; 3] = ["code-check.csv", "code-check.md", "code-check.json"];

    /// The check of the recommended design of `refined` (its runs at the check fidelity;
    /// `None` when the study has no limits).
    pub fn of(study: &Study, refined: &OptimizeReport) -> Result<Option<CodeCheck>, OptError> {
        let Some((runs, bare)) = &refined.recommended_runs else {
            return Ok(None);
        };
        let Some(first) = refined.finalists.first() else {
            return Ok(None);
        };
        Ok(Some(Self::of_runs(
            study,
            &first.slip_loads_n,
            runs,
            bare,
            if first.passes() {
                format!(
                    "the best of {} finalists that meets every limit, at the check fidelity",
                    refined.finalists.len()
                )
            } else {
                format!(
                    "no evaluated design meets every limit: the closest of {} finalists (the smallest sum of exceedances)",
                    refined.finalists.len()
                )
            },
        )?))
    }

    /// The check of the design `slip_loads_n` from its runs at the check fidelity.
    pub fn of_runs(
        study: &Study,
        slip_loads_n: &[f64],
        runs: &[RecordMetrics],
        bare: &[RecordMetrics],
        chosen_as: String,
    ) -> Result<CodeCheck, OptError> {
        let check = study.check_design(runs)?;
        let flags = nonstructural::drift_flags(study, runs);
        let fid = Fidelity::check(study);
        let reading = study.checks.reading();
        Ok(CodeCheck {
            study: study.name.clone(),
            damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
            slip_loads_kn: slip_loads_n.iter().map(|v| v / 1e3).collect(),
            chosen_as,
            objective: format!(
                "{} (at the {} properties)",
                study.objective.label(),
                reading.as_str()
            ),
            objective_value: study.objective_value(runs, bare, slip_loads_n)?,
            fidelity: format!(
                "{} at {} x the sweep time step",
                fid.method.as_str(),
                fid.dt_factor
            ),
            cases: study.checks.cases(),
            derivations: study.checks.derivations(),
            tolerance: None,
            suites: study
                .suites
                .iter()
                .map(|s| CheckedSuite {
                    name: s.name.clone(),
                    records: s.range.len(),
                    code_scaling: s.code_scaling.clone(),
                    pair_run: s.pair_run.clone(),
                })
                .collect(),
            passes: check.passes(),
            verdict: check.verdict(),
            margin: check.margin(),
            model_limits: study.model_limits(),
            stroke_capacity_mm: study
                .config
                .devices
                .as_ref()
                .and_then(|d| d.stroke_capacity_mm),
            compliance: {
                let mut rows = compliance::matrix(study, &check, slip_loads_n);
                nonstructural::into_matrix(&mut rows, &flags);
                rows
            },
            nonstructural: flags,
            residual_tails: residual_tails(study, runs)?,
            frame_strength: FrameStrength::of(study),
            check,
        })
    }

    /// `code-check.csv`: one line per criterion.
    pub fn to_csv(&self) -> String {
        check_csv(&self.check)
    }

    /// `code-check.json`.
    pub fn to_json(&self) -> Result<String, OptError> {
        let mut s = serde_json::to_string_pretty(self).map_err(|source| OptError::Json {
            path: "code-check.json".into(),
            source,
        })?;
        s.push('\n');
        Ok(s)
    }

    /// `code-check.md`: the design, the cases, the suites' scaling, one table per suite
    /// (criteria × cases), the verdict and the compliance matrix.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# Code check: {}\n", self.study);
        let _ = writeln!(s, "**Verdict: {}**\n", self.verdict);
        let loads = self
            .damper_floors
            .iter()
            .zip(&self.slip_loads_kn)
            .map(|(f, v)| format!("floor {f}: {v:.1}"))
            .collect::<Vec<_>>()
            .join(", ");
        let _ = writeln!(s, "Design (nominal slip loads, kN): {loads}.\n");
        let _ = writeln!(s, "Chosen as {}.\n", self.chosen_as);
        if let Some(c) = self.stroke_capacity_mm {
            let _ = writeln!(
                s,
                "Unacceptable responses count the runs that collapse, pass a suite's per-record limits, or in which a damper travels past the devices' stroke capacity of {} mm each way (`devices.stroke_capacity_mm`).\n",
                short(c)
            );
        }
        for w in &self.model_limits {
            let _ = writeln!(s, "**What the model cannot show:** {w}.\n");
        }
        let _ = writeln!(
            s,
            "Objective: {} = {}. Responses: {}.\n",
            self.objective,
            short(self.objective_value),
            self.fidelity
        );
        s.push_str(
            "| property case | slip-load factor | brace-stiffness factor |\n|---|---:|---:|\n",
        );
        for c in &self.cases {
            let _ = writeln!(
                s,
                "| {} | {} | {} |",
                c.name.as_str(),
                c.slip_load,
                c.brace_stiffness
            );
        }
        s.push('\n');
        if !self.derivations.is_empty() {
            s.push_str("The bounds as built from their parts (λ_test, λ_ae of which a share counts, λ_spec; ASCE 7-16 Eq. 17.2-1 and 17.2-2, which Ch. 18 follows for damping devices; a bound the study sets on them is the study's number):\n\n");
            for l in &self.derivations {
                let _ = writeln!(s, "- {l}");
            }
            s.push('\n');
        }
        if let Some(t) = &self.tolerance {
            let _ = writeln!(s, "**Specification tolerance:** {}.\n", t.text());
        }
        for suite in &self.suites {
            let _ = writeln!(s, "## {} ({} records)\n", suite.name, suite.records);
            if let Some(run) = &suite.pair_run
                && suite
                    .code_scaling
                    .as_ref()
                    .is_none_or(|c| c.pairs.is_none())
            {
                let _ = writeln!(s, "The planar model runs {run}.\n");
            }
            if let Some(c) = &suite.code_scaling {
                let _ = writeln!(
                    s,
                    "Scaled to the {} spectrum ({}): factor {:.4} over [{:.3}, {:.3}] s, controlled at {:.3} s.\n",
                    c.hazard.as_str(),
                    c.target_text(),
                    c.factor,
                    c.range_s[0],
                    c.range_s[1],
                    c.controlling_period_s
                );
                if let (Some(lo), Some(hi)) = (
                    c.record_factors.iter().copied().reduce(f64::min),
                    c.record_factors.iter().copied().reduce(f64::max),
                ) {
                    let _ = writeln!(
                        s,
                        "Each record (pair) was first fitted to the target by its own factor (the geometric mean of target / spectrum over the range), then the suite by {:.4}: record factors from {lo:.4} to {hi:.4} (`code_scaling.record_factors` of code-check.json, in the suite's order).\n",
                        c.factor
                    );
                }
                if let Some(n) = c.pairs {
                    let _ = writeln!(
                        s,
                        "The suite is {n} pairs of horizontal components, scaled by their mean maximum-direction (RotD100) spectrum (ASCE 7-22 §16.2.3.2); the planar model runs {}.\n",
                        suite
                            .pair_run
                            .as_deref()
                            .unwrap_or("each component of a pair as its own record")
                    );
                }
                if let Some(z) = &c.zero_period {
                    let motions = c.pairs.unwrap_or(suite.records);
                    let _ = writeln!(
                        s,
                        "EN 1998-1 §3.2.3.1.2(4): {motions} accelerograms (at least 3); the scaled suite's mean PGA is {:.4} g against a_g·S = {:.4} g ({}); the mean spectrum is at least 90 % of the target over the range. {}\n",
                        z.mean_pga_g,
                        z.ag_s_g,
                        if z.binds {
                            "this condition set the factor"
                        } else {
                            "the spectral condition set the factor"
                        },
                        if motions >= crate::model::code_spectrum::EN1998_MEAN_FROM {
                            "With at least 7 accelerograms the design value is the mean response (EN 1998-1 §4.3.3.4.3(3))."
                        } else {
                            "With fewer than 7 accelerograms the design value is the most unfavourable response (EN 1998-1 §4.3.3.4.3(3)): every criterion of this suite is a maximum."
                        }
                    );
                }
                if let (Some(stuck), Some(m90)) = (c.stuck_period_s, c.mass_90_period_s) {
                    let _ = writeln!(
                        s,
                        "The range runs from the lesser of 0.2 × the first period with the dampers stuck ({stuck:.3} s) and the period of the last mode for 90 % of the mass ({m90:.3} s), to 2 × the bare frame's first period ({:.3} s; ASCE 7-16 §16.2.3.1).\n",
                        c.period_s
                    );
                }
            }
            let lines: Vec<_> = self
                .check
                .lines
                .iter()
                .filter(|l| l.suite == suite.name)
                .collect();
            if lines.is_empty() {
                s.push_str("No limits on this suite.\n\n");
                continue;
            }
            s.push_str("| case | criterion | limit | demand | ratio | verdict | source |\n");
            s.push_str("|---|---|---:|---:|---:|---|---|\n");
            for l in lines {
                // a count is a whole number; a drift ratio in percent, as every drift a
                // person reads
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {:.3} | {} | `{}` |",
                    l.case.as_str(),
                    l.criterion,
                    l.value_text(l.limit),
                    l.value_text(l.demand),
                    l.ratio,
                    if l.pass { "pass" } else { "**FAIL**" },
                    l.source
                );
            }
            s.push('\n');
            for t in self.residual_tails.iter().filter(|t| t.suite == suite.name) {
                let when = if t.free_vibration_s > 0.0 {
                    format!("after {} s of free vibration", t.free_vibration_s)
                } else {
                    "at the record's end".to_string()
                };
                let runs = if t.runs.is_empty() {
                    "none".to_string()
                } else {
                    t.runs
                        .iter()
                        .map(|(name, v)| format!("{} ({} %)", md_text(name), short(100.0 * v)))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                let _ = writeln!(
                    s,
                    "Residual drift (the largest storey drift ratio left when the run ends) read {when}; runs whose residual alone exceeds {} %: {runs}.\n",
                    short(100.0 * t.limit)
                );
            }
        }
        if let Some(f) = &self.frame_strength {
            s.push_str(&f.to_markdown());
        }
        s.push_str(&nonstructural::to_markdown(&self.nonstructural));
        s.push_str(&compliance::to_markdown(&self.compliance));
        s
    }

    /// Writes `code-check.{csv,md,json}` into the study folder.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("code-check.csv", self.to_csv().as_bytes())?;
        folder.write("code-check.md", self.to_markdown().as_bytes())?;
        folder.write("code-check.json", self.to_json()?.as_bytes())?;
        Ok(())
    }

    /// The lines of one property case.
    pub fn case_lines(
        &self,
        case: CaseName,
    ) -> impl Iterator<Item = &crate::model::check::CheckLine> {
        self.check.lines.iter().filter(move |l| l.case == case)
    }
}
