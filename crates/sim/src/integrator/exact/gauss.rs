//! The 6-point Gauss–Legendre rule on [0, 1] that integrates the powers over a substep
//! (the energies' quadrature, [`GAUSS`]).

/// 6-point Gauss–Legendre nodes on [0, 1] and weights (sum 1). Exact to degree 11; on a
/// power p(t) = y(t)ᵀQy(t) over a substep of length τ its error is
/// τ¹³(6!)⁴/(13·(12!)³)·p⁽¹²⁾(ξ) (Davis & Rabinowitz, *Methods of Numerical Integration*,
/// 2nd ed., 1984, §2.7). With the state's derivatives bounded by ρᵏ‖y‖ (ρ the substep's
/// spectral bound, as the Taylor truncation takes it), |p⁽ᵏ⁾| ≤ (2ρ)ᵏ‖Q‖‖y‖², and with
/// 2ρτ ≤ 2·[`SUBSTEP_PHASE`](super::params::SUBSTEP_PHASE) = 1 the error is at most 1.9e-16·τ·‖Q‖·max‖y‖²: round-off.
pub(super) const GAUSS: [(f64, f64); 6] = {
    const X: [f64; 3] = [
        0.238_619_186_083_196_9,
        0.661_209_386_466_264_5,
        0.932_469_514_203_152,
    ];
    const W: [f64; 3] = [
        0.467_913_934_572_691,
        0.360_761_573_048_138_6,
        0.171_324_492_379_170_3,
    ];
    [
        (0.5 - 0.5 * X[2], 0.5 * W[2]),
        (0.5 - 0.5 * X[1], 0.5 * W[1]),
        (0.5 - 0.5 * X[0], 0.5 * W[0]),
        (0.5 + 0.5 * X[0], 0.5 * W[0]),
        (0.5 + 0.5 * X[1], 0.5 * W[1]),
        (0.5 + 0.5 * X[2], 0.5 * W[2]),
    ]
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    pub(super) fn gauss_rule_is_exact_to_degree_11_and_not_beyond() {
        // ∫₀¹ xᵏ dx = 1/(k+1) for every k ≤ 2·6 − 1, to round-off of the nodes' digits.
        for k in 0..=11 {
            let s: f64 = GAUSS.iter().map(|(x, w)| w * x.powi(k)).sum();
            assert!((s - 1.0 / (k + 1) as f64).abs() < 1e-15, "degree {k}: {s}");
        }
        // Degree 12 carries the rule's error term: (6!)⁴·12!/(13·(12!)³) ≈ 8.9e-8.
        let s: f64 = GAUSS.iter().map(|(x, w)| w * x.powi(12)).sum();
        let e = 720f64.powi(4) / (13.0 * 479_001_600f64.powi(2));
        assert!(
            ((1.0 / 13.0 - s) - e).abs() < 1e-3 * e,
            "{}",
            1.0 / 13.0 - s
        );
    }
}
