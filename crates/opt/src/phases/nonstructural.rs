//! The drift flag for deformation-sensitive nonstructural components (study key
//! `nonstructural`): per suite and storey, the mean over the suite's ground motions of the
//! peak storey drift ratio, at the property case where it is largest, against `factor`
//! (default 1.5) × the drift ratio the components are designed for; a storey past it is
//! flagged (docs/MODEL.md § The 150 % drift flag).
//!
//! The flag is a notice to the engineer, not an acceptance criterion: it does not change
//! the verdict. The clause (§16.1.2) and the 150 % are as the project's issue cites them;
//! the text of the clause was not available to check, so the factor is the study's to
//! give and the report says so.

use crate::base::metrics::RecordMetrics;
use crate::model::check::md_text;
use crate::model::study::Study;
use crate::phases::compliance::{ComplianceRow, Status};
use serde::Serialize;
use std::fmt::Write as _;

/// The flag's factor when the study gives none.
pub const DEFAULT_FACTOR: f64 = 1.5;

/// The clause the matrix names.
pub const CLAUSE: &str = "§16.1.2";

/// The drift flag of one suite.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DriftFlag {
    /// The suite.
    pub suite: String,
    /// The multiple of the designed-for drift that flags a storey.
    pub factor: f64,
    /// Per storey: the mean over the suite's ground motions of the peak drift ratio, at
    /// the property case where it is largest.
    pub mean_drift_ratio: Vec<f64>,
    /// Per storey: that case's name.
    pub case: Vec<String>,
    /// Per storey: the drift ratio the components are designed for.
    pub designed_drift_ratio: Vec<f64>,
    /// The flagged storeys, from 1.
    pub flagged: Vec<usize>,
}

impl DriftFlag {
    /// The largest ratio of the mean drift to `factor` × the designed-for drift, and its
    /// storey (from 1).
    pub fn worst(&self) -> (f64, usize) {
        let mut w = (f64::NEG_INFINITY, 0);
        for (s, (m, d)) in self
            .mean_drift_ratio
            .iter()
            .zip(&self.designed_drift_ratio)
            .enumerate()
        {
            let r = m / (self.factor * d);
            if r > w.0 {
                w = (r, s + 1);
            }
        }
        w
    }
}

/// The flag of every suite from the design's runs (every run of `study`); empty when the
/// study names no `nonstructural`.
pub fn drift_flags(study: &Study, runs: &[RecordMetrics]) -> Vec<DriftFlag> {
    let Some(c) = &study.config.nonstructural else {
        return Vec::new();
    };
    let storeys = study.building.floors();
    let designed = c.designed(storeys);
    let factor = c.factor.unwrap_or(DEFAULT_FACTOR);
    let n = study.records.len();
    let cases = study.checks.cases();
    study
        .suites
        .iter()
        .filter(|s| !s.range.is_empty())
        .map(|suite| {
            let mut mean = vec![f64::NEG_INFINITY; storeys];
            let mut case = vec![String::new(); storeys];
            for (ci, c) in cases.iter().enumerate() {
                for s in 0..storeys {
                    let sum: f64 = suite
                        .range
                        .clone()
                        .map(|r| runs[ci * n + r].drift_ratio[s])
                        .sum();
                    let m = sum / suite.range.len() as f64;
                    if m > mean[s] {
                        mean[s] = m;
                        case[s] = c.name.as_str().to_string();
                    }
                }
            }
            let flagged = (0..storeys)
                .filter(|&s| mean[s] > factor * designed[s])
                .map(|s| s + 1)
                .collect();
            DriftFlag {
                suite: suite.name.clone(),
                factor,
                mean_drift_ratio: mean,
                case,
                designed_drift_ratio: designed.clone(),
                flagged,
            }
        })
        .collect()
}

/// Puts the flags into the compliance matrix in place of its `not checked` row for the
/// clause (one row per suite); leaves the matrix as it is without flags.
pub fn into_matrix(rows: &mut Vec<ComplianceRow>, flags: &[DriftFlag]) {
    let Some(at) = rows.iter().position(|r| r.clause == CLAUSE) else {
        return;
    };
    if flags.is_empty() {
        return;
    }
    let new: Vec<ComplianceRow> = flags
        .iter()
        .map(|f| {
            let (ratio, storey) = f.worst();
            ComplianceRow {
                clause: format!("{CLAUSE} (as cited; factor the study's)"),
                requirement: format!(
                    "{}: drift of deformation-sensitive nonstructural components ({} % flag)",
                    md_text(&f.suite),
                    fmt_pct(f.factor * 100.0)
                ),
                value: if f.flagged.is_empty() {
                    format!("{ratio:.3} of the flag at its largest (storey {storey})")
                } else {
                    format!(
                        "storeys {} flagged; {ratio:.3} of the flag at storey {storey}",
                        f.flagged
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                },
                limit: format!(
                    "mean peak drift ≤ {} × the drift they are designed for",
                    short_factor(f.factor)
                ),
                status: if f.flagged.is_empty() {
                    Status::Pass
                } else {
                    Status::Flagged
                },
            }
        })
        .collect();
    rows.splice(at..=at, new);
}

fn fmt_pct(v: f64) -> String {
    format!("{}", (v * 1e6).round() / 1e6)
}

fn short_factor(v: f64) -> String {
    format!("{}", (v * 1e9).round() / 1e9)
}

/// The flags as a section of `code-check.md` (empty without flags).
pub fn to_markdown(flags: &[DriftFlag]) -> String {
    if flags.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "## Drift of deformation-sensitive nonstructural components\n\nPer storey, the mean over the suite's ground motions of the peak storey drift (percent of the storey height), at the property case where it is largest, against {} × the drift the components are designed for (the study's `nonstructural`). A flagged storey's components are to be reviewed for that drift; the flag does not change the verdict. The clause ({CLAUSE}) and its 150 % are as the project's issue cites them: the clause's text was not available to check, and the factor is the study's to give.\n\n",
        short_factor(flags[0].factor)
    );
    for f in flags {
        let _ = writeln!(
            s,
            "**{}**\n\n| storey | mean peak drift (%) | case | designed for (%) | flag at (%) | |\n|---|---|---|---|---|---|",
            md_text(&f.suite)
        );
        for (k, (m, d)) in f
            .mean_drift_ratio
            .iter()
            .zip(&f.designed_drift_ratio)
            .enumerate()
        {
            let _ = writeln!(
                s,
                "| {} | {:.3} | {} | {:.3} | {:.3} | {} |",
                k + 1,
                m * 100.0,
                f.case[k],
                d * 100.0,
                f.factor * d * 100.0,
                if f.flagged.contains(&(k + 1)) {
                    "**flagged**"
                } else {
                    ""
                }
            );
        }
        s.push('\n');
    }
    s
}
