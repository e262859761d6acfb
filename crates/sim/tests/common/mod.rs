//! Helpers shared by the integration tests: paths, scenes from JSON, and the exact
//! solution of linear structures (matrix exponential of the augmented state-space system).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset of these helpers

use nalgebra::{DMatrix, DVector};
use slipload_motion::Record;
use slipload_sim::{Response, Scene, SceneOverrides};
use std::path::{Path, PathBuf};

/// The repository's configs folder.
pub fn configs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs")
}

/// The repository's earthquake records folder (`records/`).
pub fn records() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records")
}

/// A scene from JSON text (relative paths resolve against `configs/`).
pub fn scene_json(text: &str, over: &SceneOverrides) -> Scene {
    Scene::from_json(text, &configs().join("inline-test.json"), over).expect("test scene is valid")
}

/// Loads a shipped config as a scene.
pub fn scene_file(name: &str, over: &SceneOverrides) -> Scene {
    Scene::load(&configs().join(name), over).expect("shipped config loads")
}

/// Linear loads with exact solutions.
pub enum Load<'a> {
    /// Ground acceleration, linear between samples.
    Ground(&'a Record),
    /// amplitude · sin(ω t) on floor `floor` (from 0).
    Harmonic {
        floor: usize,
        amplitude: f64,
        omega: f64,
    },
}

/// Exact displacements of M ü + C u̇ + K u = load at t = k·h, k = 0..=steps, from rest.
///
/// The state is augmented with the load's generator (ground: value and slope, constant
/// within a sample interval; harmonic: sin and cos) so one matrix exponential per step
/// length propagates it exactly (Van Loan 1978); h must divide the record's dt.
pub fn exact_linear(
    m: &DMatrix<f64>,
    c: &DMatrix<f64>,
    k: &DMatrix<f64>,
    load: Load,
    h: f64,
    steps: usize,
) -> Vec<DVector<f64>> {
    let n = m.nrows();
    let minv = m.clone().try_inverse().expect("M invertible");
    let mut a = DMatrix::zeros(2 * n + 2, 2 * n + 2);
    a.view_mut((0, n), (n, n)).fill_with_identity();
    a.view_mut((n, 0), (n, n)).copy_from(&(-&minv * k));
    a.view_mut((n, n), (n, n)).copy_from(&(-&minv * c));
    let mut y = DVector::zeros(2 * n + 2);
    match load {
        Load::Ground(rec) => {
            let r = DVector::from_element(n, 1.0);
            a.view_mut((n, 2 * n), (n, 1))
                .copy_from(&(-&minv * &m.clone() * &r));
            a[(2 * n, 2 * n + 1)] = 1.0;
            let e = (a * h).exp();
            let per = (rec.dt() / h).round() as usize;
            assert!(
                (per as f64 * h - rec.dt()).abs() < 1e-12 * rec.dt(),
                "h must divide the record dt"
            );
            let mut out = vec![y.rows(0, n).into_owned()];
            for s in 0..steps {
                let t0 = s as f64 * h;
                if s % per == 0 {
                    let i = (t0 / rec.dt()).round() as usize;
                    let a0 = rec.samples().get(i).copied().unwrap_or(0.0);
                    let a1 = rec.samples().get(i + 1).copied().unwrap_or(0.0);
                    y[2 * n] = rec.accel_at(t0);
                    y[2 * n + 1] = (a1 - a0) / rec.dt();
                    if i + 1 >= rec.len() {
                        y[2 * n] = 0.0;
                        y[2 * n + 1] = 0.0;
                    }
                }
                y = &e * &y;
                out.push(y.rows(0, n).into_owned());
            }
            out
        }
        Load::Harmonic {
            floor,
            amplitude,
            omega,
        } => {
            let mut f = DVector::zeros(n);
            f[floor] = amplitude;
            a.view_mut((n, 2 * n), (n, 1)).copy_from(&(&minv * f));
            a[(2 * n, 2 * n + 1)] = omega;
            a[(2 * n + 1, 2 * n)] = -omega;
            y[2 * n + 1] = 1.0; // sin(0) = 0, cos(0) = 1
            let e = (a * h).exp();
            let mut out = vec![y.rows(0, n).into_owned()];
            for _ in 0..steps {
                y = &e * &y;
                out.push(y.rows(0, n).into_owned());
            }
            out
        }
    }
}

/// Max over the trajectory of |x_num − x_exact| for floor `floor`, with the numerical
/// history sampled every `stride` rows onto the exact grid.
pub fn max_error(hist: &[f64], exact: &[DVector<f64>], floor: usize, stride: usize) -> f64 {
    exact
        .iter()
        .enumerate()
        .map(|(k, x)| (hist[k * stride] - x[floor]).abs())
        .fold(0.0, f64::max)
}

/// Every peak array and the peak base shear of `a` and `b` to `rel` of the array's (or the
/// shear's) largest value; `what` names the comparison in a failure.
pub fn assert_peaks_close(what: &str, a: &Response, b: &Response, rel: f64) {
    let pairs = [
        ("peak_drift", &a.peak_drift, &b.peak_drift),
        (
            "peak_displacement",
            &a.peak_displacement,
            &b.peak_displacement,
        ),
        (
            "peak_abs_acceleration",
            &a.peak_abs_acceleration,
            &b.peak_abs_acceleration,
        ),
        ("peak_slip", &a.peak_slip, &b.peak_slip),
        ("residual_drift", &a.residual_drift, &b.residual_drift),
    ];
    for (name, x, y) in pairs {
        assert_eq!(x.len(), y.len(), "{what}: {name} lengths");
        let scale = x
            .iter()
            .chain(y.iter())
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(1e-30);
        for (i, (p, q)) in x.iter().zip(y.iter()).enumerate() {
            assert!(
                (p - q).abs() <= rel * scale,
                "{what}: {name}[{i}]: {p} vs {q}"
            );
        }
    }
    assert!(
        (a.peak_base_shear - b.peak_base_shear).abs()
            <= rel * a.peak_base_shear.abs().max(b.peak_base_shear.abs()),
        "{what}: peak base shear {} vs {}",
        a.peak_base_shear,
        b.peak_base_shear
    );
}

/// A short, broadband ground motion (m/s², dt 0.01 s, 4 s): a few decaying sines scaled
/// to `pga`, enough to slip dampers and yield a weak line; `phase` shifts its content so
/// two components differ (0: the plan tests' first component).
pub fn decaying_sines(pga: f64, phase: f64) -> std::sync::Arc<Record> {
    let dt = 0.01;
    let a: Vec<f64> = (0..400)
        .map(|i| {
            let t = i as f64 * dt;
            let env = (t / 0.5).min(1.0) * (-(t - 0.5).max(0.0) / 1.5).exp();
            env * ((7.3 * t + phase).sin()
                + 0.6 * (17.1 * t + 0.4).sin()
                + 0.35 * (3.1 * t - phase).sin())
        })
        .collect();
    let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    std::sync::Arc::new(
        Record::new(
            "decaying sines",
            dt,
            a.iter().map(|x| x * pga / peak).collect(),
        )
        .unwrap(),
    )
}

/// A building in plan from its JSON text (named `inline-plan.json` in errors).
pub fn floor_plan(json: &str) -> slipload_sim::floorplan::FloorPlan {
    let cfg: slipload_sim::floorplan::FloorPlanConfig = serde_json::from_str(json).unwrap();
    slipload_sim::floorplan::FloorPlan::from_config(&cfg, Path::new("inline-plan.json")).unwrap()
}

/// |a − b| over the larger magnitude.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE)
}

/// The chain `building` from rest under `record` for its whole duration, with the method
/// settings `method` (its step included) and `outputs`: the response a plan's run is
/// compared with.
pub fn chain_response(
    building: &slipload_sim::Building,
    record: &std::sync::Arc<Record>,
    method: slipload_sim::scene::MethodSettings,
    outputs: slipload_sim::scene::OutputsConfig,
) -> Response {
    let scene = Scene {
        name: "chain".into(),
        building: building.clone(),
        record: Some(record.clone()),
        harmonic: None,
        initial: slipload_sim::scene::InitialState::rest(building.floors()),
        duration: record.duration(),
        method,
        outputs,
        reduce: true,
        notes: Vec::new(),
    };
    slipload_sim::simulate(&scene).unwrap().response
}
