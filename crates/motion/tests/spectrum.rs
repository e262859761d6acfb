//! Contract: the response spectrum integrates the SDOF oscillator exactly for the
//! piecewise-linear record. Checked against (1) an independent fourth-order Runge–Kutta
//! integration of the same oscillator with tiny steps, to 1e-6 relative, on a real record;
//! (2) closed forms: a step in ground acceleration (peak 2a/ω² for ζ = 0) and undamped
//! harmonic resonance (linearly growing amplitude).

use slipload_motion::{G, Record, Spectrum, read_record, sdof_displacement};
use std::f64::consts::PI;

fn el_centro_first_10_s() -> Record {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records/elCentro.AT2");
    let r = read_record(&path, None, None).expect("elCentro.AT2 reads");
    r.window(0.0, 10.0).expect("record is longer than 10 s")
}

/// RK4 on ü = −2ζωu̇ − ω²u − a_g(t), `fine` equal steps per record step, a_g linear within
/// the step (evaluated from the two samples directly, not through `Record::accel_at`).
/// Returns u after every fine step (and u(0)).
fn rk4(record: &Record, period: f64, zeta: f64, fine: usize) -> Vec<f64> {
    let w = 2.0 * PI / period;
    let h = record.dt() / fine as f64;
    let f = |u: f64, v: f64, ag: f64| (v, -2.0 * zeta * w * v - w * w * u - ag);
    let (mut u, mut v) = (0.0, 0.0);
    let mut out = vec![0.0];
    for s in record.samples().windows(2) {
        let ag = |j: f64| s[0] + (s[1] - s[0]) * j / fine as f64;
        for j in 0..fine {
            let j = j as f64;
            let (k1u, k1v) = f(u, v, ag(j));
            let (k2u, k2v) = f(u + 0.5 * h * k1u, v + 0.5 * h * k1v, ag(j + 0.5));
            let (k3u, k3v) = f(u + 0.5 * h * k2u, v + 0.5 * h * k2v, ag(j + 0.5));
            let (k4u, k4v) = f(u + h * k3u, v + h * k3v, ag(j + 1.0));
            u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            out.push(u);
        }
    }
    out
}

fn max_abs(x: impl Iterator<Item = f64>) -> f64 {
    x.fold(0.0, |m, y| m.max(y.abs()))
}

#[test]
fn matches_tiny_step_rk4_on_a_real_record() {
    let r = el_centro_first_10_s();
    for &period in &[0.05, 0.3, 1.0, 3.0] {
        for &zeta in &[0.0, 0.05, 0.2] {
            // the spectrum's own sub-step count (T < 10 dt), so RK4 visits the same points
            let sub = if period < 10.0 * r.dt() {
                (10.0 * r.dt() / period).ceil() as usize
            } else {
                1
            };
            let per_sub = 128;
            let fine = rk4(&r, period, zeta, sub * per_sub);
            let half = rk4(&r, period, zeta, sub * per_sub / 2);
            let scale = max_abs(fine.iter().copied());
            // the reference itself: RK4's global error is O(h⁴), so the fine run's error is
            // about (coarse − fine)/15; it must be at most a tenth of the 1e-6 being tested
            let self_check = max_abs(half.iter().zip(fine.iter().step_by(2)).map(|(a, b)| a - b));
            assert!(
                self_check / 15.0 <= 1e-7 * scale,
                "T={period} ζ={zeta}: RK4 not converged ({self_check:e})"
            );

            let u = sdof_displacement(&r, period, zeta).unwrap();
            let at_samples = fine.iter().step_by(sub * per_sub);
            let err = max_abs(u.iter().zip(at_samples).map(|(a, b)| a - b));
            // both integrate the same piecewise-linear input; 1e-6 relative is the contract
            assert!(
                err <= 1e-6 * scale,
                "T={period} ζ={zeta}: history error {err:e} vs {scale:e}"
            );

            let s = Spectrum::compute(&r, zeta, &[period]).unwrap();
            let sd_ref = max_abs(fine.iter().step_by(per_sub).copied());
            let rel = (s.sd_m[0] - sd_ref).abs() / sd_ref;
            assert!(
                rel <= 1e-6,
                "T={period} ζ={zeta}: Sd {} vs {sd_ref} ({rel:e})",
                s.sd_m[0]
            );
            let w = 2.0 * PI / period;
            assert_eq!(s.psa_m_s2[0], w * w * s.sd_m[0]);
            assert_eq!(s.psv_m_s[0], w * s.sd_m[0]);
        }
    }
}

#[test]
fn step_acceleration_peaks_at_twice_the_static_displacement() {
    // a_g = a0 from t = 0, ζ = 0: u = −(a0/ω²)(1 − cos ωt), peak 2a0/ω² at t = T/2, 3T/2, …
    // (T = 1 s, dt = 0.01 s: the half-periods fall on samples). Exact method, so only
    // round-off remains: ~300 steps × 1e-16.
    let a0 = 0.3 * G;
    let period = 1.0;
    let r = Record::new("step", 0.01, vec![a0; 301]).unwrap();
    let w = 2.0 * PI / period;
    let s = Spectrum::compute(&r, 0.0, &[period]).unwrap();
    let expect = 2.0 * a0 / (w * w);
    assert!(
        (s.sd_m[0] - expect).abs() <= 1e-12 * expect,
        "{} vs {expect}",
        s.sd_m[0]
    );
    let u = sdof_displacement(&r, period, 0.0).unwrap();
    for (k, uk) in u.iter().enumerate() {
        let t = k as f64 * r.dt();
        let exact = -(a0 / (w * w)) * (1.0 - (w * t).cos());
        assert!(
            (uk - exact).abs() <= 1e-12 * expect,
            "t={t}: {uk} vs {exact}"
        );
    }
}

#[test]
fn undamped_resonance_grows_linearly() {
    // a_g = A sin ωt at the oscillator's own frequency, ζ = 0:
    // u = −(A/2ω²)(sin ωt − ωt cos ωt). The record is the linear interpolant of the sine,
    // whose component at ω has amplitude A·sinc²(ω dt/2) (the triangle kernel); the other
    // components sit at ω(1 ± kN), N = T/dt = 200, are ~1/(kN)² smaller and not resonant,
    // so they add < 1e-9 of the grown amplitude. Hence the exact scaled closed form to 1e-8.
    let (amp, period, n) = (2.0, 0.5, 200usize);
    let dt = period / n as f64;
    let w = 2.0 * PI / period;
    let cycles = 10;
    let a: Vec<f64> = (0..=cycles * n)
        .map(|k| amp * (w * k as f64 * dt).sin())
        .collect();
    let r = Record::new("sine", dt, a).unwrap();
    let x = w * dt / 2.0;
    let sinc2 = (x.sin() / x).powi(2);
    let u = sdof_displacement(&r, period, 0.0).unwrap();
    let exact = |t: f64| -(amp * sinc2 / (2.0 * w * w)) * ((w * t).sin() - w * t * (w * t).cos());
    let peak = amp / (2.0 * w * w) * w * r.duration();
    for (k, uk) in u.iter().enumerate() {
        let t = k as f64 * dt;
        assert!(
            (uk - exact(t)).abs() <= 1e-8 * peak,
            "t={t}: {uk} vs {}",
            exact(t)
        );
    }
}

#[test]
fn spectrum_is_linear_in_the_record() {
    let r = el_centro_first_10_s();
    let periods = [0.1, 0.5, 2.0];
    let s1 = Spectrum::compute(&r, 0.05, &periods).unwrap();
    let s2 = Spectrum::compute(&r.scaled(2.0), 0.05, &periods).unwrap();
    for k in 0..periods.len() {
        // scaling by 2 is exact in binary floating point
        assert_eq!(s2.psa_m_s2[k], 2.0 * s1.psa_m_s2[k]);
    }
}
