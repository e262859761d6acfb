//! What the plan reductions save: the same scene compiled reduced and as the full 2N
//! model, peaks only (energies off), on the first record of the embedded synthetic suite.
//! Run: `cargo bench -p slipload-sim --bench plan_reductions`.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use slipload_sim::{Plan, Scene, SceneOverrides, run_plan};
use std::hint::black_box;
use std::path::Path;

fn scene(building_file: &str, edit: impl Fn(String) -> String, reduce: bool) -> Scene {
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    let building =
        edit(std::fs::read_to_string(configs.join(building_file)).expect("shipped config"));
    let json = format!(
        r#"{{ "building": {building}, "excitation": {{ "synthetic": {{ "index": 0 }} }},
             "outputs": {{ "energies": false }}, "reduce": {reduce} }}"#
    );
    Scene::from_json(
        &json,
        &configs.join("bench.json"),
        &SceneOverrides::default(),
    )
    .expect("bench scene")
}

/// (group name, building file, edit of the building JSON)
type Case = (&'static str, &'static str, fn(String) -> String);

fn bench(c: &mut Criterion) {
    let cases: [Case; 2] = [
        (
            "ten-story m'=0 (EPP elements vs zero-mass DOFs)",
            "ten-story.json",
            |s| s,
        ),
        (
            "benchmark m'=0, dampers on floor 1 only (mu N = 0 above)",
            "benchmark-3story.json",
            |s| {
                s.replace("\"350.11 kg\"", "0")
                    .replace("\"740.831 kN\"", "0")
                    .replace("\"437.510 kN\"", "0")
            },
        ),
    ];
    for (name, file, edit) in cases {
        let mut g = c.benchmark_group(name);
        g.sample_size(20);
        for reduce in [true, false] {
            let plan = Plan::compile(&scene(file, edit, reduce)).expect("compiles");
            let label = if reduce {
                format!("reduced ({} DOFs)", plan.dofs())
            } else {
                format!("full ({} DOFs)", plan.dofs())
            };
            g.bench_function(label, |b| {
                b.iter(|| run_plan(black_box(&plan)).expect("runs"))
            });
        }
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
