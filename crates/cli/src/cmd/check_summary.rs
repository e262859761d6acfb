//! The code check on screen: one line per property case with its governing criterion,
//! then the verdict; and the outcome a script can tell from a crash (exit code 3: the
//! study ran and wrote its files, but no evaluated design meets its limits).

use slipload_opt::model::check::{CheckLine, governing};
use slipload_opt::phases::check::CodeCheck;
use slipload_opt::phases::devices::DeviceTable;

/// The exit code of a study that ran to its end but found no design meeting its limits.
pub const NO_ACCEPTABLE_DESIGN: u8 = 3;

/// The study ran and wrote its files, but no evaluated design meets every limit: the
/// process exits with [`NO_ACCEPTABLE_DESIGN`].
#[derive(Debug)]
pub struct NoAcceptableDesign(pub String);

impl std::fmt::Display for NoAcceptableDesign {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for NoAcceptableDesign {}

/// A criterion's line: its demand against its limit (a drift in percent of the storey
/// height), the ratio and the study key.
fn line_text(l: &CheckLine) -> String {
    format!(
        "{} of {}: {} against {} (ratio {:.3}, {})",
        l.criterion,
        l.suite,
        l.value_text(l.demand),
        l.value_text(l.limit),
        l.ratio,
        l.source
    )
}

/// The check's lines for the summary: per property case, how many criteria pass and the
/// governing one.
pub fn lines(c: &CodeCheck) -> Vec<String> {
    let mut out = vec![format!(
        "code check of the recommended design ({}; {}):",
        c.chosen_as, c.fidelity
    )];
    for case in &c.cases {
        let lines: Vec<&CheckLine> = c.case_lines(case.name).collect();
        let pass = lines.iter().filter(|l| l.pass).count();
        let gov = governing(lines.iter().copied());
        out.push(format!(
            "  {} properties (slip loads × {}, braces × {}): {pass} of {} criteria pass{}",
            case.name.as_str(),
            case.slip_load,
            case.brace_stiffness,
            lines.len(),
            gov.map_or(String::new(), |g| format!("; governing {}", line_text(g)))
        ));
    }
    out
}

/// The verdict line (the summary's last).
pub fn verdict(c: &CodeCheck) -> String {
    format!("verdict: {}", c.verdict)
}

/// `Err` with [`NoAcceptableDesign`] when the check fails: names the governing limit, the
/// closest design and its margin.
pub fn outcome(c: Option<&CodeCheck>) -> anyhow::Result<()> {
    match c {
        Some(c) if !c.passes => {
            let gov = c.check.governing().map_or(String::new(), |g| {
                format!("; governing limit {}", line_text(g))
            });
            Err(NoAcceptableDesign(format!(
                "no evaluated design meets the study's limits: the closest, slip loads {} kN, misses by {:.1} %{gov} (files written; exit code {NO_ACCEPTABLE_DESIGN})",
                c.slip_loads_kn
                    .iter()
                    .map(|v| format!("{v:.1}"))
                    .collect::<Vec<_>>()
                    .join(" / "),
                -100.0 * c.margin
            ))
            .into())
        }
        _ => Ok(()),
    }
}

/// The device table for the summary: one line per damper up to 12 (force, stroke each
/// way, velocity, cycles, energy), else where the table is; and every damper that never
/// slipped, flagged.
pub fn device_lines(d: &DeviceTable) -> Vec<String> {
    let mut out = vec![format!(
        "devices to specify (largest over {} runs; device-table.md has travel, per-suite strokes{}):",
        d.runs,
        if d.brace_angle_deg.is_some() {
            " and the braces' axial force and stiffness"
        } else {
            ""
        }
    )];
    if d.dampers.len() <= 12 {
        for r in &d.dampers {
            out.push(format!(
                "  floor {}: slip load {:.1} kN ({:.1} to {:.1}), force {:.1} kN, stroke +{:.1} / -{:.1} mm, velocity {:.0} mm/s, {} cycles, {:.1} kJ",
                r.floor,
                r.slip_load_kn,
                r.slip_load_range_kn[0],
                r.slip_load_range_kn[1],
                r.peak_force_kn,
                r.stroke_mm[0],
                r.stroke_mm[1],
                r.peak_velocity_mm_s,
                r.cycles,
                r.energy_kj
            ));
        }
    } else {
        out.push(format!(
            "  {} dampers: see device-table.md",
            d.dampers.len()
        ));
    }
    let rigid = d.rigid_floors();
    if !rigid.is_empty() {
        out.push(format!(
            "  never slips on any record: the damper of floor {} (acts as a rigid brace at this slip load)",
            rigid
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    out
}
