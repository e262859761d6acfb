//! Sweep throughput: (design, record) tasks per second on the benchmark study (3 storeys,
//! dissipators with mass, 5 s synthetic records), run through the same parallel path as
//! `slipload sweep`. Throughput = 16 tasks / measured time.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use slipload_opt::Study;
use slipload_opt::eval::evaluate::{Task, run_tasks};
use slipload_opt::model::fidelity::Fidelity;
use std::hint::black_box;
use std::path::Path;

fn study() -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let text = std::fs::read_to_string(&path).expect("the benchmark study is in configs/");
    let mut v: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    v["suites"][0]["synthetic"]["count"] = 4.into();
    v["suites"][0]["synthetic"]["duration_s"] = 5.0.into();
    Study::from_json(&v.to_string(), &path).expect("a valid study")
}

fn tasks_per_second(c: &mut Criterion) {
    let st = study();
    let tasks: Vec<Task> = (0..4)
        .flat_map(|d| {
            (0..4).map(move |r| Task {
                label: format!("#{d}"),
                slip_loads: vec![500e3 * (d + 1) as f64; 3],
                friction: None,
                record: r,
            })
        })
        .collect();
    let fid = Fidelity::sweep(&st);
    let mut g = c.benchmark_group("sweep");
    g.throughput(Throughput::Elements(tasks.len() as u64));
    g.sample_size(10);
    g.bench_function("benchmark-3story, 16 tasks of 5 s", |b| {
        b.iter(|| run_tasks(black_box(&st), &tasks, &fid, &|_, _| Ok(())).expect("tasks run"))
    });
    g.finish();
}

criterion_group!(benches, tasks_per_second);
criterion_main!(benches);
