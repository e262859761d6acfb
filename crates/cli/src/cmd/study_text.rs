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

/// The runs of each design, in words: `10 records`, or `11 records × 3 property cases
/// (nominal, lower, upper)` for a study with property bounds.
pub(crate) fn runs_text(m: &slipload_opt::phases::sweep::Manifest) -> String {
    let cases = m.checks.cases();
    let records = m.record_count();
    if cases.len() == 1 {
        format!("{records} records")
    } else {
        format!(
            "{records} records × {} property cases ({})",
            cases.len(),
            cases
                .iter()
                .map(|c| c.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )
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
