//! The step loops: one peaks-only run of the benchmark three-storey and the ten-storey
//! buildings under a 15 s synthetic record (seed 2007, dt 0.01 s) at the default time step
//! (`newmark`), and the benchmark with `exact`, each also with the per-damper demands
//! asked; the `box_qp` bench times the friction QP
//! alone. Run: `cargo bench -p slipload-sim --bench step_loop`. `slipload bench` prints
//! the same figures beside their targets.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use slipload_sim::{MethodName, Plan, Scene, SceneOverrides, run_plan};
use std::hint::black_box;
use std::path::Path;

fn plan(building_file: &str, method: MethodName, dampers: bool) -> Plan {
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    let building = std::fs::read_to_string(configs.join(building_file)).expect("shipped config");
    let json = format!(
        r#"{{ "building": {building},
             "excitation": {{ "synthetic": {{ "seed": 2007, "duration": 15, "dt": 0.01 }} }},
             "outputs": {{ "energies": false, "dampers": {dampers} }} }}"#
    );
    let over = SceneOverrides {
        method: Some(method),
        ..Default::default()
    };
    let scene = Scene::from_json(&json, &configs.join("bench.json"), &over).expect("bench scene");
    Plan::compile(&scene).expect("compiles")
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("step loop, 15 s synthetic, peaks only");
    for (label, file, method, samples, dampers) in [
        (
            "benchmark-3story newmark",
            "benchmark-3story.json",
            MethodName::Newmark,
            50,
            false,
        ),
        (
            "ten-story newmark",
            "ten-story.json",
            MethodName::Newmark,
            20,
            false,
        ),
        (
            "benchmark-3story exact",
            "benchmark-3story.json",
            MethodName::Exact,
            10,
            false,
        ),
        // the same runs with the per-damper demands asked (`outputs.dampers`)
        (
            "benchmark-3story newmark, dampers",
            "benchmark-3story.json",
            MethodName::Newmark,
            50,
            true,
        ),
        (
            "ten-story newmark, dampers",
            "ten-story.json",
            MethodName::Newmark,
            20,
            true,
        ),
        (
            "benchmark-3story exact, dampers",
            "benchmark-3story.json",
            MethodName::Exact,
            10,
            true,
        ),
    ] {
        let p = plan(file, method, dampers);
        g.throughput(Throughput::Elements(p.steps as u64));
        g.sample_size(samples);
        g.bench_function(label, |b| b.iter(|| run_plan(black_box(&p)).expect("runs")));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
