//! Contract: synthetic motions are reproducible bit for bit from their seed, suites are
//! scaled exactly to their target, and the mean spectrum has the Clough–Penzien shape
//! (amplified near the soil period 2π/ω_g, much weaker at long periods).

use slipload_motion::{
    DEFAULT_SUITE_PGA_G, DEFAULT_SUITE_SIZE, G, Spectrum, SuiteTarget, Synthetic, default_suite,
    derive_seed, spectral_acceleration, synthetic_suite,
};
use std::f64::consts::PI;

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

/// FNV-1a over the samples' bit patterns.
fn fingerprint(x: &[f64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for v in x {
        for b in v.to_bits().to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

#[test]
fn same_seed_same_bits() {
    let p = Synthetic::default();
    let a = p.generate(42, "a").unwrap();
    let b = p.generate(42, "b").unwrap();
    assert_eq!(bits(a.samples()), bits(b.samples()));
    let c = p.generate(43, "c").unwrap();
    assert_ne!(bits(a.samples()), bits(c.samples()));
    let s1 = default_suite();
    let s2 = default_suite();
    assert_eq!(s1.len(), DEFAULT_SUITE_SIZE);
    for (x, y) in s1.iter().zip(&s2) {
        assert_eq!(bits(x.samples()), bits(y.samples()));
    }
}

#[test]
fn default_suite_bits_are_pinned() {
    // Recorded from this implementation (integer PRNG + libm + IEEE arithmetic only, so the
    // same on every platform). A change here means the generator changed: the default suite,
    // and every result computed with it, would change too. Update only on purpose.
    let suite = default_suite();
    let prints: Vec<u64> = suite.iter().map(|r| fingerprint(r.samples())).collect();
    let pinned: [u64; 10] = [
        0xaa69_fb5a_7a69_85ad,
        0x1fad_8f8f_0a2d_212d,
        0xd7ec_9378_032a_2867,
        0x2a55_ce0a_4d10_5d5d,
        0x217b_df6f_a319_f377,
        0xd67d_4701_146e_9b43,
        0x245f_76a4_31da_58ca,
        0xb616_e767_270b_3a2c,
        0xb7d4_c54c_de05_81ce,
        0x7802_81dc_b928_3991,
    ];
    assert_eq!(prints, pinned, "{prints:#x?}");
}

#[test]
fn derived_seeds_are_distinct() {
    let mut seeds: Vec<u64> = (0..1000).map(|i| derive_seed(7, i)).collect();
    seeds.extend((0..1000).map(|i| derive_seed(8, i)));
    seeds.sort_unstable();
    seeds.dedup();
    assert_eq!(seeds.len(), 2000);
}

#[test]
fn pga_scaling_is_exact() {
    for r in default_suite() {
        assert_eq!(r.pga(), DEFAULT_SUITE_PGA_G * G, "{}", r.name());
        assert_eq!(r.len(), 2001);
        assert_eq!(r.dt(), 0.01);
    }
    let p = Synthetic {
        duration_s: 5.0,
        ..Synthetic::default()
    };
    for target in [0.1, 0.35 * G, 1.0 / 3.0, 7.77] {
        for r in synthetic_suite(&p, 3, 11, SuiteTarget::Pga { pga_m_s2: target }).unwrap() {
            assert_eq!(r.pga(), target);
        }
    }
}

#[test]
fn spectral_acceleration_target_is_met() {
    let p = Synthetic {
        duration_s: 10.0,
        ..Synthetic::default()
    };
    let target = SuiteTarget::SpectralAcceleration {
        period_s: 1.0,
        damping: 0.05,
        sa_m_s2: 3.0,
    };
    for r in synthetic_suite(&p, 4, 5, target).unwrap() {
        let sa = spectral_acceleration(&r, 1.0, 0.05).unwrap();
        // linear scaling: one rounding of the factor and of each sample, ~1e-16 each
        assert!((sa - 3.0).abs() <= 1e-12 * 3.0, "{sa}");
    }
}

/// Clough–Penzien power spectral density (up to S₀) at ω, rad/s.
fn clough_penzien(p: &Synthetic, w: f64) -> f64 {
    let (wg, zg, wf, zf) = (
        p.ground_freq_rad_s,
        p.ground_damping,
        p.highpass_freq_rad_s,
        p.highpass_damping,
    );
    let kt = (wg.powi(4) + 4.0 * zg * zg * wg * wg * w * w)
        / ((wg * wg - w * w).powi(2) + 4.0 * zg * zg * wg * wg * w * w);
    let hp = w.powi(4) / ((wf * wf - w * w).powi(2) + 4.0 * zf * zf * wf * wf * w * w);
    kt * hp
}

#[test]
fn mean_spectrum_is_amplified_near_the_soil_period() {
    let p = Synthetic::default();
    let suite = default_suite();
    let t_soil = 2.0 * PI / p.ground_freq_rad_s; // 0.4 s
    let t_long = 3.0;
    let mean = |t: f64| {
        suite
            .iter()
            .map(|r| Spectrum::compute(r, 0.05, &[t]).unwrap().psa_m_s2[0])
            .sum::<f64>()
            / suite.len() as f64
    };
    let ratio = mean(t_soil) / mean(t_long);
    // Random vibration: a lightly damped oscillator under broadband stationary input has
    // σ_u² = πS(ω)/(2ζω³), so PSA = ω²·(peak factor)·σ_u ∝ √(S(ω)·ω). That predicts
    // the ratio below; the 3 s oscillator also never reaches stationarity in a ~10 s strong
    // phase, which only raises the ratio. The margin 1.5 covers the scatter of a 10-record
    // mean (record-to-record COV of PSA ≈ 0.25 → ≈ 0.08 per mean, 0.11 on the ratio: 4σ).
    let w1 = 2.0 * PI / t_soil;
    let w2 = 2.0 * PI / t_long;
    let theory = ((clough_penzien(&p, w1) * w1) / (clough_penzien(&p, w2) * w2)).sqrt();
    assert!(
        ratio >= theory / 1.5,
        "mean PSA(0.4 s)/PSA(3 s) = {ratio}, theory {theory}"
    );
}
