//! Cost of one friction-force solve ([`BoxQp::solve`]) for m = 3, 10, 50 dampers.
//!
//! W is the Delassus matrix of a shear building (one damper per storey) under Newmark
//! average acceleration: W = γΔt Bᵀ A⁻¹ B, A = M + γΔt C + βΔt² K, B the storey-drift
//! operator. The right-hand sides b = W F_u(θ) make the unconstrained forces
//! F_u(θ) = 1.5 · slip · (cos θ u + sin θ v) rotate slowly (0.01 rad per step), so dampers
//! pass between stick and slip as in a time history. `warm` keeps the solver's state from
//! step to step (the production use); `cold` resets it before every solve.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use slipload_sim::friction::BoxQp;
use std::hint::black_box;

struct Scene {
    m: usize,
    w: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    bs: Vec<Vec<f64>>,
}

fn scene(m: usize) -> Scene {
    let (dt, gamma, beta) = (0.005, 0.5, 0.25);
    // Storey masses 2e5 kg, stiffness tapering from 4e8 to 2e8 N/m, 2 % stiffness damping.
    let k: Vec<f64> = (0..m)
        .map(|i| 4e8 - 2e8 * i as f64 / m.max(2) as f64)
        .collect();
    let mut kk = DMatrix::<f64>::zeros(m, m);
    for i in 0..m {
        kk[(i, i)] += k[i];
        if i + 1 < m {
            kk[(i, i)] += k[i + 1];
            kk[(i, i + 1)] -= k[i + 1];
            kk[(i + 1, i)] -= k[i + 1];
        }
    }
    let mm = DMatrix::<f64>::identity(m, m) * 2e5;
    let cc = &kk * 0.002;
    let a = &mm + &cc * (gamma * dt) + &kk * (beta * dt * dt);
    let mut bmat = DMatrix::<f64>::zeros(m, m);
    for i in 0..m {
        bmat[(i, i)] = 1.0;
        if i > 0 {
            bmat[(i - 1, i)] = -1.0;
        }
    }
    let a_inv_b = a.cholesky().expect("A is SPD").solve(&bmat);
    let w = (bmat.transpose() * a_inv_b) * (gamma * dt);
    let w = (&w + w.transpose()) * 0.5;
    // Slip loads 5 % of the storey's weight share above it.
    let slip: Vec<f64> = (0..m).map(|i| 0.05 * 9.81 * 2e5 * (m - i) as f64).collect();
    let u: Vec<f64> = (0..m).map(|i| (1.3 * i as f64 + 0.5).sin()).collect();
    let v: Vec<f64> = (0..m).map(|i| (0.7 * i as f64 + 0.2).cos()).collect();
    let bs = (0..629)
        .map(|s| {
            let th = 0.01 * s as f64;
            let fu = DVector::from_iterator(
                m,
                (0..m).map(|i| 1.5 * slip[i] * (th.cos() * u[i] + th.sin() * v[i])),
            );
            (&w * fu).as_slice().to_vec()
        })
        .collect();
    Scene {
        m,
        w: w.as_slice().to_vec(),
        lo: slip.iter().map(|s| -s).collect(),
        hi: slip,
        bs,
    }
}

fn box_qp_bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("box_qp");
    for m in [3, 10, 50] {
        let sc = scene(m);
        // One pass over the sequence to report the work per solve next to the timings.
        let mut qp = BoxQp::new(&sc.w, sc.m).expect("Delassus matrix is SPD");
        let mut f = vec![0.0; sc.m];
        let (mut iters, mut facts, mut held) = (0u32, 0u32, 0usize);
        for b in &sc.bs {
            let st = qp.solve(b, &sc.lo, &sc.hi, &mut f).expect("valid scene");
            iters += st.iterations;
            facts += st.factorizations;
            held += (0..sc.m)
                .filter(|&i| qp.status(i) != slipload_sim::friction::box_qp::Bound::Free)
                .count();
        }
        let n = sc.bs.len() as f64;
        eprintln!(
            "m = {m}: warm {:.2} iterations, {:.2} factor updates per solve; {:.0} % of dampers slip",
            iters as f64 / n,
            facts as f64 / n,
            100.0 * held as f64 / (n * m as f64)
        );

        let mut step = 0usize;
        g.bench_function(format!("warm m={m}"), |bch| {
            bch.iter(|| {
                step = (step + 1) % sc.bs.len();
                qp.solve(black_box(&sc.bs[step]), &sc.lo, &sc.hi, &mut f)
                    .expect("valid scene")
            })
        });
        let mut cold = BoxQp::new(&sc.w, sc.m).expect("Delassus matrix is SPD");
        let mut step = 0usize;
        g.bench_function(format!("cold m={m}"), |bch| {
            bch.iter(|| {
                step = (step + 1) % sc.bs.len();
                cold.reset();
                f.fill(0.0);
                cold.solve(black_box(&sc.bs[step]), &sc.lo, &sc.hi, &mut f)
                    .expect("valid scene")
            })
        });
    }
    g.finish();
}

criterion_group!(benches, box_qp_bench);
criterion_main!(benches);
