//! Studies in plan (docs/MODEL.md § Studies in plan): the slip loads of a building in
//! plan's dampers chosen over suites of two-component ground motions, each pair run at
//! orientations to the plan's axes, for the drift at the plan's edges (or the torsion,
//! the floors' rotation, the least slip load that passes), accidental torsion as
//! property cases.
//!
//! Files: `config` (the study file as written), `study` (validated and loaded: the cases,
//! the pairs, the design space over the dampers by line), `evaluate` (designs run in
//! parallel, reduced to the objective and the limits' ratios), `report` (the final
//! table's text, CSV, Markdown and figure data), `protocol` (the optimum's device tests). The run itself, with its journal, folder
//! and figures, is [`crate::pipeline::optimize_in_plan`].

pub mod config;
pub mod evaluate;
pub mod protocol;
pub mod report;
pub mod study;

pub use config::{Placement, PlanMetric, PlanStatistic, PlanStudyConfig};
pub use evaluate::{DesignEval, Devices, Peaks, Step, evaluate_loads};
pub use report::{PlanFigureData, PlanReport, PlanRow};
pub use study::PlanStudy;

/// Whether the JSON file at `path` is a study in plan: an object with `suites` whose
/// `building` is a building in plan (inline, with `floors` and `lines`, or a file that
/// is one). A file that cannot be read or parsed is not (the chain study's reader then
/// says what is wrong with it).
pub fn is_plan_study(path: &std::path::Path) -> bool {
    let read = |p: &std::path::Path| -> Option<serde_json::Value> {
        let text = slipload_motion::limits::read_input_text(
            p,
            "study",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )
        .ok()?;
        serde_json::from_str(&text).ok()
    };
    let is_plan = |v: &serde_json::Value| {
        v.as_object()
            .is_some_and(|o| o.contains_key("lines") && o.contains_key("floors"))
    };
    let Some(v) = read(path) else { return false };
    let Some(o) = v.as_object() else { return false };
    if !o.contains_key("suites") {
        return false;
    }
    match o.get("building") {
        Some(serde_json::Value::String(p)) => {
            let base = path.parent().unwrap_or(std::path::Path::new("."));
            read(&base.join(p)).is_some_and(|b| is_plan(&b))
        }
        Some(b) => is_plan(b),
        None => false,
    }
}
