//! The certificate of a box-QP answer: its KKT residual relative to the problem's size,
//! computed from the problem alone (any solver's answer can be checked against it).

/// KKT violation of `f` for min ½FᵀWF − Fᵀb over lo ≤ F ≤ hi, relative to the problem's size.
///
/// With `w = b − WF` and `L = ‖W‖∞`, each variable contributes the natural (projected-gradient)
/// residual `L·|F_i − clamp(F_i + w_i/L, lo_i, hi_i)|`, which is `|w_i|` for an interior
/// variable, the wrong-sign part of `w_i` at a bound, and covers infeasibility too; the
/// maximum is divided by `L‖F‖∞ + ‖b‖∞` (if that is 0, it is returned unscaled). 0 exactly at
/// the minimiser; round-off gives a few `m·ε`. Returns `+∞` if any input is non-finite or a
/// bound pair is invalid. `w` is column-major m×m.
///
/// For positive definite `W` with smallest eigenvalue `μ`, the distance to the minimiser is at
/// most `2 ‖r‖₂ / μ`, where `r` is the vector of unscaled per-variable residuals.
///
/// # Panics
/// If a slice length does not match `m`.
pub fn kkt_residual(w: &[f64], m: usize, b: &[f64], lo: &[f64], hi: &[f64], f: &[f64]) -> f64 {
    assert_eq!(w.len(), m * m, "W must be m×m");
    for s in [b, lo, hi, f] {
        assert_eq!(s.len(), m, "vectors must have length m");
    }
    if w.iter().chain(b).chain(f).any(|v| !v.is_finite())
        || lo
            .iter()
            .zip(hi)
            .any(|(l, h)| l.is_nan() || h.is_nan() || l > h)
    {
        return f64::INFINITY;
    }
    let w_norm = (0..m)
        .map(|i| (0..m).map(|j| w[i + j * m].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let step = if w_norm > 0.0 { w_norm } else { 1.0 };
    let mut worst = 0.0f64;
    for i in 0..m {
        let wi = b[i] - (0..m).map(|j| w[i + j * m] * f[j]).sum::<f64>();
        let projected = (f[i] + wi / step).min(hi[i]).max(lo[i]);
        worst = worst.max(step * (f[i] - projected).abs());
    }
    let f_norm = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let b_norm = b.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let scale = w_norm * f_norm + b_norm;
    if scale > 0.0 { worst / scale } else { worst }
}
