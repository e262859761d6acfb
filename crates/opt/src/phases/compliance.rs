//! The compliance matrix of the code check: one row per requirement a reviewer reads a
//! submittal against — clause, requirement, value, limit, status — gathered from what the
//! check computed, and the requirements the study or the planar model cannot show named
//! as such (`not checked`: the study gives no data for it; `not covered`: a planar model of
//! one component cannot show it). Clauses are ASCE 7-16's, except the rows of a suite
//! scaled by the EN 1998-1 rule, which name EN 1998-1 §3.2.3.1.2; a criterion the study
//! sets itself is named as the study's.

use crate::model::check::{CheckLine, DesignCheck, md_text};
use crate::model::code_scaling::{MIN_CODE_PAIRS, MIN_CODE_RECORDS};
use crate::model::code_spectrum::{MIN_EN1998_ACCELEROGRAMS, ScalingRule};
use crate::model::config::{ScaleConfig, TestProtocolConfig};
use crate::model::study::Study;
use crate::phases::strength::FrameStrength;
use serde::Serialize;
use std::fmt::Write as _;

/// How a requirement stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Checked and met.
    Pass,
    /// Checked and not met.
    Fail,
    /// Documented by the study's own numbers (a derivation, a protocol).
    Stated,
    /// The study gives no data to check it.
    NotChecked,
    /// The planar model cannot show it.
    NotCovered,
    /// Past a flag the study set: to be reviewed, not a failure of the verdict.
    Flagged,
}

impl Status {
    /// As the matrix prints it.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Pass => "pass",
            Status::Fail => "**FAIL**",
            Status::Stated => "stated",
            Status::NotChecked => "not checked",
            Status::NotCovered => "not covered",
            Status::Flagged => "**flagged**",
        }
    }
}

/// One row of the matrix.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComplianceRow {
    /// The clause (ASCE 7-16, or EN 1998-1 where it says so), or whose requirement it is.
    pub clause: String,
    /// What it requires.
    pub requirement: String,
    /// What the design or the study has.
    pub value: String,
    /// What it is held to.
    pub limit: String,
    /// How it stands.
    pub status: Status,
}

fn row(
    clause: &str,
    requirement: String,
    value: String,
    limit: String,
    status: Status,
) -> ComplianceRow {
    ComplianceRow {
        clause: clause.to_string(),
        requirement,
        value,
        limit,
        status,
    }
}

/// The worst line (largest ratio; the first of equals, the nominal case before the
/// bounds) among `lines`.
fn worst<'a>(lines: impl Iterator<Item = &'a CheckLine>) -> Option<&'a CheckLine> {
    lines.fold(None, |w: Option<&CheckLine>, l| match w {
        Some(w) if w.ratio >= l.ratio => Some(w),
        _ => Some(l),
    })
}

/// The least ratio, over the dampers whose storey has a wind shear, of the lower-bound
/// slip load to the storey's design wind shear (`wind.storey_shears_kn`), with the
/// damper's floor (from 1); `None` without `wind` or without a storey under wind.
pub fn wind_margin(study: &Study, slip_loads_n: &[f64]) -> Option<(f64, usize)> {
    let w = study.config.wind.as_ref()?;
    let lo = study.checks.slip_load_range().0;
    study
        .space
        .dampers
        .iter()
        .zip(slip_loads_n)
        .filter_map(|(&floor, f)| {
            let v = *w.storey_shears_kn.get(floor)? * 1e3;
            (v > 0.0).then(|| (lo * f / v, floor + 1))
        })
        .fold(None, |m: Option<(f64, usize)>, x| match m {
            Some(m) if m.0 <= x.0 => Some(m),
            _ => Some(x),
        })
}

/// The largest ratio, over the dampers, of the brace's axial force at the upper-bound slip
/// load, λ_max F / (n cos θ), to its strength (`devices.brace_capacity_kn`), with the
/// damper's floor (from 1); `None` without brace strengths.
pub fn brace_ratio(study: &Study, slip_loads_n: &[f64]) -> Option<(f64, usize)> {
    let d = study.config.devices.as_ref()?;
    let (caps, angle) = (d.brace_capacity_kn.as_ref()?, d.brace_angle_deg?);
    let hi = study.checks.slip_load_range().1;
    let per = d.braces_per_damper.unwrap_or(1) as f64 * angle.to_radians().cos();
    study
        .space
        .dampers
        .iter()
        .zip(slip_loads_n)
        .zip(caps)
        .map(|((&floor, f), c)| (hi * f / per / (c * 1e3), floor + 1))
        .fold(None, |m: Option<(f64, usize)>, x| match m {
            Some(m) if m.0 >= x.0 => Some(m),
            _ => Some(x),
        })
}

/// The matrix of the design of slip loads `slip_loads_n` (N per damper) whose check is
/// `check` in `study`.
pub fn matrix(study: &Study, check: &DesignCheck, slip_loads_n: &[f64]) -> Vec<ComplianceRow> {
    let mut rows = Vec::new();
    for (i, suite) in study.suites.iter().enumerate() {
        // (a suite's name as Markdown text: the user's)
        let name = md_text(&suite.name);
        let code = study.config.suites.get(i).and_then(|s| match &s.scale {
            Some(ScaleConfig::CodeSpectrum(c)) => Some(c),
            _ => None,
        });
        match (&suite.code_scaling, code) {
            (Some(sc), Some(c)) => {
                let en = sc.rule == Some(ScalingRule::En1998);
                let (count, what, standard) = match (sc.pairs, en) {
                    (Some(p), false) => (p, "pairs", MIN_CODE_PAIRS),
                    (None, false) => (suite.range.len(), "records", MIN_CODE_RECORDS),
                    (Some(p), true) => (p, "pairs", MIN_EN1998_ACCELEROGRAMS),
                    (None, true) => (suite.range.len(), "records", MIN_EN1998_ACCELEROGRAMS),
                };
                let needed = c.min_records.unwrap_or(standard);
                rows.push(row(
                    if en {
                        "EN 1998-1 §3.2.3.1.2(4)a"
                    } else {
                        "§16.2.2"
                    },
                    format!("{name}: number of ground motions"),
                    format!("{count} {what}"),
                    format!(
                        "≥ {needed}{}",
                        if c.min_records.is_some() {
                            " (the study's rule)"
                        } else {
                            ""
                        }
                    ),
                    if count >= needed {
                        Status::Pass
                    } else {
                        Status::Fail
                    },
                ));
                let ratio = sc
                    .mean_sa_g
                    .iter()
                    .zip(&sc.target_sa_g)
                    .map(|(m, t)| m / t)
                    .fold(f64::INFINITY, f64::min);
                if let Some(z) = &sc.zero_period {
                    rows.push(row(
                        "EN 1998-1 §3.2.3.1.2(4)b",
                        format!("{name}: mean PGA of the scaled suite"),
                        format!("{:.4} g", z.mean_pga_g),
                        format!("≥ a_g·S = {:.4} g", z.ag_s_g),
                        if z.mean_pga_g >= z.ag_s_g * (1.0 - 1e-9) {
                            Status::Pass
                        } else {
                            Status::Fail
                        },
                    ));
                }
                rows.push(row(
                    if en {
                        "EN 1998-1 §3.2.3.1.2(4)c"
                    } else {
                        "§16.2.3"
                    },
                    format!(
                        "{name}: scaled mean spectrum over [{:.3}, {:.3}] s against the {} target",
                        sc.range_s[0],
                        sc.range_s[1],
                        sc.hazard.as_str()
                    ),
                    format!("{ratio:.3} of the target at its lowest"),
                    "≥ 0.90".into(),
                    if ratio >= 0.9 - 1e-9 {
                        Status::Pass
                    } else {
                        Status::Fail
                    },
                ));
            }
            _ => rows.push(row(
                "§16.2.2, §16.2.3",
                format!("{name}: ground motions selected and scaled to the target spectrum"),
                "scaled as the study says (not to a code spectrum)".into(),
                "—".into(),
                Status::NotChecked,
            )),
        }
        let lines: Vec<&CheckLine> = check
            .lines
            .iter()
            .filter(|l| l.suite == suite.name)
            .collect();
        if let Some(l) = worst(
            lines
                .iter()
                .copied()
                .filter(|l| l.source.ends_with("unacceptable")),
        ) {
            rows.push(row(
                "§16.4.1.1",
                format!(
                    "{name}: unacceptable responses (at the worst property case, {})",
                    l.case.as_str()
                ),
                format!("{:.0}", l.demand),
                match study.config.risk_category {
                    Some(rc) => format!("≤ {:.0} (Risk Category {})", l.limit, rc.as_str()),
                    None => format!("≤ {:.0}", l.limit),
                },
                if l.pass { Status::Pass } else { Status::Fail },
            ));
        }
        // each criterion at its worst case
        let mut sources: Vec<&str> = Vec::new();
        for l in lines.iter().filter(|l| l.source.contains(".criteria[")) {
            if !sources.contains(&l.source.as_str()) {
                sources.push(&l.source);
            }
        }
        for src in sources {
            let Some(l) = worst(lines.iter().copied().filter(|l| l.source == src)) else {
                continue;
            };
            let drift = l.criterion.ends_with(" peak_drift_ratio");
            rows.push(row(
                if drift {
                    "§16.4.1.2"
                } else {
                    "the study's criterion"
                },
                format!(
                    "{name}: {} (at the worst property case, {})",
                    l.criterion,
                    l.case.as_str()
                ),
                l.value_text(l.demand),
                format!("≤ {}", l.value_text(l.limit)),
                if l.pass { Status::Pass } else { Status::Fail },
            ));
        }
    }
    let cases = study.checks.cases();
    let (lo, hi) = study.checks.slip_load_range();
    let derived = !study.checks.derivations().is_empty();
    rows.push(row(
        "Ch. 18 (Eq. 17.2-1, 17.2-2)",
        "damper properties analysed at their upper and lower bounds".into(),
        if cases.len() > 1 {
            format!(
                "slip load × {lo} and × {hi}{}",
                if derived {
                    ", built from their parts"
                } else {
                    ", given as numbers"
                }
            )
        } else {
            "nominal only".into()
        },
        "λ_min, λ_max".into(),
        if cases.len() > 1 {
            Status::Stated
        } else {
            Status::NotChecked
        },
    ));
    let protocol: Option<TestProtocolConfig> =
        study.config.devices.as_ref().and_then(|d| d.test_protocol);
    rows.push(row(
        "§18.6.2",
        "prototype tests of each damper type at the maximum damper displacement".into(),
        match protocol {
            Some(p) => format!(
                "{} cycles, ±{} % band (device-table.md)",
                p.cycles, p.band_percent
            ),
            None => "no protocol (give devices.test_protocol)".into(),
        },
        "—".into(),
        if protocol.is_some() {
            Status::Stated
        } else {
            Status::NotChecked
        },
    ));
    let strength = FrameStrength::of(study);
    let requirement = format!(
        "the frame without dampers has at least {} % of the strength required without a damping system",
        strength.as_ref().map_or(75.0, |f| 100.0 * f.fraction)
    );
    rows.push(match strength.as_ref().map(|f| (f, f.least())) {
        Some((_, Some((ratio, storey)))) => row(
            "§18.2.1.1",
            requirement,
            format!("yield shear / required {ratio:.2} at storey {storey}, the least"),
            "≥ 1".into(),
            if ratio >= 1.0 {
                Status::Pass
            } else {
                Status::Fail
            },
        ),
        Some((_, None)) => row(
            "§18.2.1.1",
            requirement,
            "no storey has a yield shear (the model's frame is elastic)".into(),
            "—".into(),
            Status::NotChecked,
        ),
        None => row(
            "§18.2.1.1",
            requirement,
            "the study gives no `frame_strength`".into(),
            "—".into(),
            Status::NotChecked,
        ),
    });
    rows.push(match brace_ratio(study, slip_loads_n) {
        Some((ratio, floor)) => row(
            "Ch. 18 (force-controlled)",
            "braces carry the damper's force at the upper-bound slip load within their strength"
                .into(),
            format!("brace force / strength {ratio:.2} at floor {floor}, the largest"),
            "≤ 1".into(),
            if ratio <= 1.0 + 1e-9 {
                Status::Pass
            } else {
                Status::Fail
            },
        ),
        None => row(
            "Ch. 18 (force-controlled)",
            "braces carry the damper's force at the upper-bound slip load within their strength"
                .into(),
            "the study gives no brace strength (`devices.brace_capacity_kn`)".into(),
            "—".into(),
            Status::NotChecked,
        ),
    });
    let factor = study
        .config
        .wind
        .as_ref()
        .map_or(1.3, |w| w.factor.unwrap_or(1.3));
    let requirement = format!(
        "dampers do not slip in the design wind: lower-bound slip load at least {factor} × the storey's wind shear"
    );
    rows.push(match wind_margin(study, slip_loads_n) {
        Some((ratio, floor)) => row(
            "design practice",
            requirement,
            format!("slip load / wind shear {ratio:.2} at floor {floor}, the least"),
            format!("≥ {factor}"),
            if ratio >= factor * (1.0 - 1e-9) {
                Status::Pass
            } else {
                Status::Fail
            },
        ),
        None => row(
            "design practice",
            requirement,
            "the study gives no wind storey shears (`wind`)".into(),
            "—".into(),
            Status::NotChecked,
        ),
    });
    for (clause, requirement, why, status) in [
        (
            "§16.1.2",
            "drifts of deformation-sensitive nonstructural components (150 % flag)",
            "the study names no such components",
            Status::NotChecked,
        ),
        (
            "§12.3.2.1, §12.8.4.2",
            "torsional irregularity and accidental torsion",
            "a planar model has no plan",
            Status::NotCovered,
        ),
        (
            "§16.2.4",
            "both horizontal components applied together",
            "a planar model runs one component at a time",
            Status::NotCovered,
        ),
        (
            "§12.4.2.2",
            "vertical ground motion",
            "a planar model of horizontal motion",
            Status::NotCovered,
        ),
    ] {
        rows.push(row(
            clause,
            requirement.into(),
            why.into(),
            "—".into(),
            status,
        ));
    }
    rows
}

/// The matrix as a section of `code-check.md`.
pub fn to_markdown(rows: &[ComplianceRow]) -> String {
    let en = rows.iter().any(|r| r.clause.starts_with("EN 1998-1"));
    let mut s = format!(
        "## Compliance matrix\n\nASCE 7-16 clauses{} as this check reads them: `pass`/`FAIL` checked on the runs above, `stated` documented by the study's own numbers, `not checked` where the study gives no data for it, `not covered` where a planar model of one component cannot show it, `flagged` past a flag the study set (to be reviewed; the verdict does not read it).\n\n| clause | requirement | value | limit | status |\n|---|---|---|---|---|\n",
        if en {
            " (and EN 1998-1 where a row names it)"
        } else {
            ""
        }
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            r.clause,
            r.requirement,
            r.value,
            r.limit,
            r.status.as_str()
        );
    }
    s
}
