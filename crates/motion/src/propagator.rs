//! The exact one-step propagator of a linear system under piecewise-linear input.
//!
//! Contract: for ẋ = A x + b p(t) with p linear over a step of length h, from p₀ to p₁,
//! [`Propagator::step`] returns x(h) = Φ x(0) + Γ₀ p₀ + Γ₁ p₁ with Φ = e^{Ah} and Γ₀, Γ₁
//! the exact input integrals. This is the Nigam–Jennings (1969) recurrence, written for any
//! small linear system: the coefficients come from the exponential of the augmented matrix
//! [[A, b, 0], [0, 0, 1], [0, 0, 0]]·h (state x, input p, input slope), computed by scaling
//! and squaring a truncated Taylor series. That uses only + and ×, so it is bit-reproducible
//! on every IEEE-754 platform, needs no special case for ζ = 0 or ζ ≥ 1, and does not suffer
//! the cancellation of the closed-form coefficients at small ωh.

/// Exact propagator of an `N`-state linear system over one step.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Propagator<const N: usize> {
    phi: [[f64; N]; N],
    gamma0: [f64; N],
    gamma1: [f64; N],
}

impl<const N: usize> Propagator<N> {
    /// The propagator of ẋ = A x + b p over a step `h` (in the time unit of A); h > 0.
    pub(crate) fn new(a: [[f64; N]; N], b: [f64; N], h: f64) -> Propagator<N> {
        let d = N + 2;
        let mut m = vec![0.0; d * d];
        for i in 0..N {
            for j in 0..N {
                m[i * d + j] = a[i][j] * h;
            }
            m[i * d + N] = b[i] * h;
        }
        m[N * d + N + 1] = h;
        let e = expm(&m, d);
        let mut phi = [[0.0; N]; N];
        let mut gamma0 = [0.0; N];
        let mut gamma1 = [0.0; N];
        for i in 0..N {
            for j in 0..N {
                phi[i][j] = e[i * d + j];
            }
            // x(h) = Φx + E[i][N]·p₀ + E[i][N+1]·(p₁ − p₀)/h
            let slope = e[i * d + N + 1] / h;
            gamma0[i] = e[i * d + N] - slope;
            gamma1[i] = slope;
        }
        Propagator {
            phi,
            gamma0,
            gamma1,
        }
    }

    /// State after one step from `x` with input p₀ at the start and p₁ at the end.
    #[inline]
    pub(crate) fn step(&self, x: &[f64; N], p0: f64, p1: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = self.gamma0[i] * p0 + self.gamma1[i] * p1;
            for (j, xj) in x.iter().enumerate() {
                s += self.phi[i][j] * xj;
            }
            *o = s;
        }
        out
    }
}

/// e^M for a dense row-major d×d matrix: scale by 2⁻ˢ so that ‖M‖₁ ≤ ½, sum the Taylor
/// series to 20 terms (truncation ≤ ½²¹/21! ≈ 1e-26 relative), square s times.
fn expm(m: &[f64], d: usize) -> Vec<f64> {
    let norm = (0..d)
        .map(|j| (0..d).map(|i| m[i * d + j].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut s = 0u32;
    let mut scale = 1.0;
    while norm * scale > 0.5 && s < 1000 {
        s += 1;
        scale *= 0.5;
    }
    let x: Vec<f64> = m.iter().map(|v| v * scale).collect();
    let identity = |k: usize| if k.is_multiple_of(d + 1) { 1.0 } else { 0.0 };
    // Horner: I + X/1 (I + X/2 (I + … (I + X/20)))
    let mut e: Vec<f64> = (0..d * d).map(identity).collect();
    for k in (1..=20).rev() {
        let xe = matmul(&x, &e, d);
        e = (0..d * d).map(|i| identity(i) + xe[i] / k as f64).collect();
    }
    for _ in 0..s {
        e = matmul(&e, &e, d);
    }
    e
}

fn matmul(a: &[f64], b: &[f64], d: usize) -> Vec<f64> {
    let mut c = vec![0.0; d * d];
    for i in 0..d {
        for k in 0..d {
            let aik = a[i * d + k];
            for j in 0..d {
                c[i * d + j] += aik * b[k * d + j];
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chopra, Dynamics of Structures, Table 5.2.1 (piecewise-exact coefficients for
    /// ü + 2ζωu̇ + ω²u = p/m, m = 1), evaluated where they do not cancel badly (ωh = 0.5).
    #[test]
    fn matches_closed_form_nigam_jennings_coefficients() {
        let (omega, zeta, h) = (5.0_f64, 0.05_f64, 0.1_f64);
        let p = Propagator::new(
            [[0.0, 1.0], [-omega * omega, -2.0 * zeta * omega]],
            [0.0, 1.0],
            h,
        );
        let k = omega * omega;
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let r = zeta / (1.0 - zeta * zeta).sqrt();
        let (e, s, c) = ((-zeta * omega * h).exp(), (wd * h).sin(), (wd * h).cos());
        let a = e * (r * s + c);
        let b = e * s / wd;
        let cc = (2.0 * zeta / (omega * h)
            + e * (((1.0 - 2.0 * zeta * zeta) / (wd * h) - r) * s
                - (1.0 + 2.0 * zeta / (omega * h)) * c))
            / k;
        let dd = (1.0 - 2.0 * zeta / (omega * h)
            + e * ((2.0 * zeta * zeta - 1.0) / (wd * h) * s + 2.0 * zeta / (omega * h) * c))
            / k;
        let a2 = -e * omega / (1.0 - zeta * zeta).sqrt() * s;
        let b2 = e * (c - r * s);
        let c2 = (-1.0 / h
            + e * ((omega / (1.0 - zeta * zeta).sqrt() + zeta / (h * (1.0 - zeta * zeta).sqrt()))
                * s
                + c / h))
            / k;
        let d2 = (1.0 - e * (r * s + c)) / (k * h);
        let expect = [[a, b, cc, dd], [a2, b2, c2, d2]];
        let got = [
            [p.phi[0][0], p.phi[0][1], p.gamma0[0], p.gamma1[0]],
            [p.phi[1][0], p.phi[1][1], p.gamma0[1], p.gamma1[1]],
        ];
        for i in 0..2 {
            for j in 0..4 {
                let scale = expect[i][j].abs().max(1e-3);
                // both are exact formulas; the difference is round-off (~1e-15 × a few terms)
                assert!(
                    (got[i][j] - expect[i][j]).abs() < 1e-12 * scale,
                    "{i},{j}: {} vs {}",
                    got[i][j],
                    expect[i][j]
                );
            }
        }
    }

    #[test]
    fn integrates_a_ramp_exactly() {
        // ẋ = p, p from 1 to 3 over h = 2: x(2) = x0 + 4
        let p = Propagator::new([[0.0]], [1.0], 2.0);
        assert!((p.step(&[1.0], 1.0, 3.0)[0] - 5.0).abs() < 1e-14);
    }
}
