//! Samples of the design space in scaled variables z ∈ [0, 1]^d: full grids, Latin
//! hypercubes and shifted Halton sequences. Seeded and deterministic; points that break
//! the linear constraints are dropped (grid) or replaced by further draws (lhs, halton).
//! A point becomes a [`Design`] of the sweep: labelled, with its slip loads.

use crate::model::config::{SamplerKind, SweepConfig};
use crate::model::space::DesignSpace;
use serde::{Deserialize, Serialize};

/// One design of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Design {
    /// `bare`, `file`, or `s0001`… for sample points.
    pub label: String,
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// Scaled variables (sample points only).
    pub z: Option<Vec<f64>>,
    /// The friction law per dissipator, as the building file writes it, where it is not
    /// a symmetric slip load (a `locked` contact, asymmetric bounds): then it, not
    /// `slip_loads_n`, is what runs. Absent for every other design.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_n: Option<Vec<FrictionLaw>>,
}

/// The friction law of one dissipator where a symmetric slip load cannot say it: the
/// building file's `locked` contact or its asymmetric `bounds` (docs/MODEL.md, friction
/// law: F ∈ [F⁻, F⁺]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FrictionLaw {
    /// Bounds [F⁻, F⁺] with F⁻ ≤ 0 ≤ F⁺ (N, or kN where the field says so).
    Bounds([f64; 2]),
    /// Never slips (μN → ∞): the dissipator moves with its floor.
    Locked,
}

impl FrictionLaw {
    /// The law with its forces times `k` (a locked contact stays locked).
    pub fn scaled(self, k: f64) -> FrictionLaw {
        match self {
            FrictionLaw::Bounds([lo, hi]) => FrictionLaw::Bounds([lo * k, hi * k]),
            FrictionLaw::Locked => FrictionLaw::Locked,
        }
    }

    /// (F⁻, F⁺), N (±∞ when locked).
    pub fn bounds(self) -> (f64, f64) {
        match self {
            FrictionLaw::Bounds([lo, hi]) => (lo, hi),
            FrictionLaw::Locked => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// For tables: `locked`, or `F⁻..F⁺` in the unit of the law divided by `unit`.
    pub fn text(self, unit: f64) -> String {
        match self {
            FrictionLaw::Bounds([lo, hi]) => format!("{}..{}", lo / unit, hi / unit),
            FrictionLaw::Locked => "locked".into(),
        }
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a small, well-mixed, seedable generator.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SplitMix(u64);

impl SplitMix {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix(seed)
    }
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform integer in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f64) as usize).min(n.saturating_sub(1))
    }
}

const PRIMES: [u64; 20] = [
    2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71,
];

fn radical_inverse(mut i: u64, base: u64) -> f64 {
    let mut f = 1.0;
    let mut r = 0.0;
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

/// Full factorial grid, `levels` per variable, first variable varying slowest.
pub fn grid(d: usize, levels: usize) -> Vec<Vec<f64>> {
    let total = levels.pow(d as u32);
    (0..total)
        .map(|mut k| {
            let mut z = vec![0.0; d];
            for j in (0..d).rev() {
                z[j] = (k % levels) as f64 / (levels - 1) as f64;
                k /= levels;
            }
            z
        })
        .collect()
}

/// Latin hypercube of `n` points: one point in each of n strata per variable, randomly
/// placed within the stratum, strata permuted independently per variable.
pub fn lhs(d: usize, n: usize, rng: &mut SplitMix) -> Vec<Vec<f64>> {
    let mut pts = vec![vec![0.0; d]; n];
    for j in 0..d {
        let mut perm: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            perm.swap(i, rng.below(i + 1));
        }
        for (i, p) in pts.iter_mut().enumerate() {
            p[j] = (perm[i] as f64 + rng.uniform()) / n as f64;
        }
    }
    pts
}

/// Points `start..start+n` of the Halton sequence in `d` ≤ 20 dimensions, shifted
/// modulo 1 by `shift` (a Cranley–Patterson rotation).
pub fn halton(d: usize, start: u64, n: usize, shift: &[f64]) -> Vec<Vec<f64>> {
    (0..n as u64)
        .map(|k| {
            (0..d)
                .map(|j| {
                    (radical_inverse(start + k + 1, PRIMES[j % PRIMES.len()]) + shift[j]).fract()
                })
                .collect()
        })
        .collect()
}

/// The sweep's feasible sample.
pub fn sample(space: &DesignSpace, cfg: &SweepConfig) -> Vec<Vec<f64>> {
    let d = space.dim();
    let mut rng = SplitMix::new(cfg.seed);
    match cfg.sampler {
        SamplerKind::Grid => grid(d, cfg.levels)
            .into_iter()
            .filter(|z| space.is_feasible(z))
            .collect(),
        SamplerKind::Lhs | SamplerKind::Halton => {
            let shift: Vec<f64> = (0..d).map(|_| rng.uniform()).collect();
            let mut out = Vec::with_capacity(cfg.points);
            let mut drawn = 0u64;
            // at most 100 batches: a feasible region below 1 % of the box leaves the sample short
            for _ in 0..100 {
                let batch = match cfg.sampler {
                    SamplerKind::Lhs => lhs(d, cfg.points, &mut rng),
                    _ => halton(d, drawn, cfg.points, &shift),
                };
                drawn += cfg.points as u64;
                for z in batch {
                    if out.len() < cfg.points && space.is_feasible(&z) {
                        out.push(z);
                    }
                }
                if out.len() == cfg.points {
                    break;
                }
            }
            out
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lhs_has_one_point_per_stratum() {
        let mut rng = SplitMix::new(7);
        let pts = lhs(3, 10, &mut rng);
        for j in 0..3 {
            let mut strata: Vec<usize> = pts.iter().map(|p| (p[j] * 10.0) as usize).collect();
            strata.sort();
            assert_eq!(strata, (0..10).collect::<Vec<_>>());
        }
    }

    #[test]
    fn grid_and_halton_cover_the_box() {
        let g = grid(2, 3);
        assert_eq!(g.len(), 9);
        assert_eq!(g[0], vec![0.0, 0.0]);
        assert_eq!(g[8], vec![1.0, 1.0]);
        let h = halton(2, 0, 4, &[0.0, 0.0]);
        assert_eq!(h[0], vec![0.5, 1.0 / 3.0]);
        assert_eq!(h[1], vec![0.25, 2.0 / 3.0]);
    }
}
