//! The words the study summaries share: slip loads in kN, and the variables of a design
//! that sit on a bound of the study's space.

use slipload_opt::{OnBound, Study};

/// Slip loads (N) as kN with one decimal, `a / b / c`.
pub(crate) fn kn(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{:.1}", x / 1e3))
        .collect::<Vec<_>>()
        .join(" / ")
}

/// A design's slip loads for a summary line: every load (`kn`) up to 12 dampers; for a
/// taller frame a profile as its shape with its floor-1 and top loads, a free design as
/// its range, with where the per-floor loads are written — never a line of 60 numbers.
pub(crate) fn loads_text(study: &Study, loads: &[f64]) -> String {
    if loads.len() <= 12 {
        return format!("{} kN", kn(loads));
    }
    let floors = &study.space.dampers;
    let (first, last) = (loads[0] / 1e3, loads[loads.len() - 1] / 1e3);
    let (f0, fl) = (floors[0] + 1, floors[floors.len() - 1] + 1);
    match &study.space.shape {
        Some((shape, _)) => format!(
            "{} profile: {first:.1} kN at floor {f0} … {last:.1} kN at floor {fl} ({} dampers; per floor in optimum.json)",
            shape.as_str(),
            loads.len()
        ),
        None => {
            let lo = loads.iter().copied().fold(f64::INFINITY, f64::min) / 1e3;
            let hi = loads.iter().copied().fold(0.0, f64::max) / 1e3;
            format!(
                "{} dampers, {lo:.1} to {hi:.1} kN ({first:.1} kN at floor {f0} … {last:.1} kN at floor {fl}; per floor in optimum.json)",
                loads.len()
            )
        }
    }
}

/// The runs of each design, in words: `10 records`, or `11 records × 3 property cases
/// (nominal, lower, upper)` for a study with property bounds.
pub(crate) fn runs_text(m: &slipload_opt::phases::sweep::Manifest) -> String {
    let cases = m.checks.cases();
    let records = m.record_count();
    // how the pairs of a suite ran, where the study said: each way once, with its suites
    let mut ways: Vec<(&str, Vec<&str>)> = Vec::new();
    for s in &m.suites {
        if let Some(run) = s.pair_run.as_deref() {
            match ways.iter_mut().find(|(w, _)| *w == run) {
                Some((_, names)) => names.push(&s.name),
                None => ways.push((run, vec![&s.name])),
            }
        }
    }
    let pairs: String = ways
        .iter()
        .map(|(run, names)| format!(" (pairs of suite {}: {run})", names.join(", ")))
        .collect();
    if cases.len() == 1 {
        format!("{records} records{pairs}")
    } else {
        format!(
            "{records} records × {} property cases ({})",
            cases.len(),
            cases
                .iter()
                .map(|c| c.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ) + &pairs
    }
}

/// The design variables of the optimum that sit on a bound of the study's space, said
/// with the floors they set and their slip loads ("floor 1 at its upper bound, 2000.0 kN").
pub(crate) fn on_bound_text(study: &Study, loads: &[f64], on: &[OnBound]) -> String {
    let load_of = |floor: usize| {
        study
            .space
            .dampers
            .iter()
            .position(|&f| f + 1 == floor)
            .map_or(f64::NAN, |k| loads[k] / 1e3)
    };
    on.iter()
        .map(|b| {
            let floors: Vec<String> = b.floors.iter().map(usize::to_string).collect();
            if study.space.shape.is_some() {
                format!(
                    "the profile's {} (floors {}) at its {} bound, {} kN",
                    b.variable,
                    floors.join(", "),
                    b.bound.as_str(),
                    b.floors
                        .iter()
                        .map(|&f| format!("{:.1}", load_of(f)))
                        .collect::<Vec<_>>()
                        .join(" / ")
                )
            } else {
                format!(
                    "floor {} at its {} bound, {:.1} kN",
                    floors.join(", "),
                    b.bound.as_str(),
                    b.floors.first().map_or(f64::NAN, |&f| load_of(f))
                )
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}
