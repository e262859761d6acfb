//! The banded step of `newmark` (O(N) per step on shear buildings with Rayleigh or storey
//! damping and massless dissipators) solves the same equations and the same friction QP
//! as the dense step, so their answers may differ only by round-off: peaks and energies
//! agree on random banded scenes (1 to 60 storeys, stiff and light braces, tiny, moderate
//! and huge slip loads, dampers on some floors only, Rayleigh and storey damping, HHT-α,
//! yielding storeys), the energy balance holds, the bits do not depend on the threads
//! running other simulations, and the automatic choice leaves every committed scene
//! (full frame matrices, modal damping, dissipators with mass) on the dense step.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::integrator::newmark::{BandedStats, StepPath, run_on_path};
use slipload_sim::{Outcome, Plan, SceneOverrides};

/// A small deterministic generator (xorshift64*), so every scene is reproducible.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// How a random scene is damped.
#[derive(Debug, Clone, Copy)]
enum Damping {
    Rayleigh,
    Storey,
}

/// Slip loads of a random scene, against the weight above each floor.
#[derive(Debug, Clone, Copy)]
enum Slip {
    /// 1e-4 of the weight above: slides at almost any motion.
    Tiny,
    /// 1–10 %: the design range, sticks and slides.
    Moderate,
    /// 1000 × the weight above: never slides (braced frame).
    Huge,
    /// A mix of the three, floor by floor.
    Mixed,
}

/// One random scene's choices, as [`scene_json`] reads them.
#[derive(Debug, Clone, Copy)]
struct Case {
    seed: u64,
    n: usize,
    damping: Damping,
    brace: f64,
    slip: Slip,
    some: bool,
    alpha: f64,
    yields: bool,
    duration: f64,
    /// The share of dampers given a brace dashpot c′ > 0 (the others have c′ = 0).
    dashpots: f64,
}

/// A random shear building of `n` storeys with m′ = 0 dampers (on every floor, or on a
/// random half of them when `some`), braces `brace` times the storey stiffness (times a
/// random factor in [0.5, 2]), the given damping and slip loads, HHT `alpha`, under a
/// synthetic record of `duration` s at Δt = 2.5 ms; yielding storeys on a random third of
/// the storeys when `yields`.
fn scene_json(case: Case) -> String {
    let Case {
        seed,
        n,
        damping,
        brace,
        slip,
        some,
        alpha,
        yields,
        duration,
        dashpots,
    } = case;
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let m: Vec<f64> = (0..n).map(|_| r.range(3e5, 7e5)).collect();
    // storey stiffness for T1 ≈ 0.1 n s on a uniform building, varied ±30 %
    let t1 = 0.1 * n as f64;
    let w1 = 2.0 * std::f64::consts::PI / t1;
    let s = (std::f64::consts::PI / (2.0 * (2 * n + 1) as f64)).sin();
    let k0 = 5e5 * (w1 / (2.0 * s)).powi(2);
    let k: Vec<f64> = (0..n).map(|_| k0 * r.range(0.7, 1.3)).collect();
    let damping = match damping {
        // 2 % at ω1, and about 2 % at 3ω1
        Damping::Rayleigh => format!(
            r#"{{ "rayleigh": {{ "alpha": {}, "beta": {} }} }}"#,
            0.02 * 1.5 * w1,
            0.02 / (2.0 * w1)
        ),
        Damping::Storey => {
            let cs: Vec<String> = k
                .iter()
                .map(|ki| format!("{}", r.range(0.005, 0.05) * 2.0 * (ki * 5e5).sqrt()))
                .collect();
            format!(r#"{{ "storey": [{}] }}"#, cs.join(", "))
        }
    };
    let mut ds = Vec::new();
    for i in 0..n {
        if some && r.next() < 0.5 {
            continue;
        }
        let above: f64 = m[i..].iter().sum::<f64>() * 9.81;
        let kind = match slip {
            Slip::Mixed => [Slip::Tiny, Slip::Moderate, Slip::Huge][(r.next() * 3.0) as usize],
            s => s,
        };
        let load = match kind {
            Slip::Tiny => 1e-4 * above,
            Slip::Moderate => r.range(0.01, 0.1) * above,
            _ => 1e3 * above,
        };
        let c_brace = if r.next() < dashpots {
            r.range(0.0, 0.02) * 2.0 * (brace * k[i] * m[i]).sqrt()
        } else {
            0.0
        };
        ds.push(format!(
            r#"{{ "floor": {}, "brace_stiffness": "{} N/m", "mass": 0, "brace_damping": {c_brace}, "slip_load": "{load} N" }}"#,
            i + 1,
            brace * k[i] * r.range(0.5, 2.0),
        ));
    }
    let mut yl = Vec::new();
    if yields {
        for i in 0..n {
            if r.next() < 1.0 / 3.0 {
                yl.push(format!(
                    r#"{{ "storey": {}, "yield_drift": "{} m", "post_yield_ratio": {} }}"#,
                    i + 1,
                    r.range(0.005, 0.02),
                    r.range(0.05, 0.3)
                ));
            }
        }
    }
    let list = |v: &[f64], unit: &str| {
        v.iter()
            .map(|x| format!("\"{x} {unit}\""))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let method = if alpha == 0.0 {
        r#"{ "name": "newmark", "dt": 0.0025 }"#.to_string()
    } else {
        format!(r#"{{ "name": "hht", "alpha": {alpha}, "dt": 0.0025 }}"#)
    };
    format!(
        r#"{{ "name": "banded-{seed}",
             "building": {{ "name": "shear-{n}", "floor_masses": [{}], "storey_stiffness": [{}],
                           "damping": {damping}, "dissipators": [{}], "storey_yield": [{}] }},
             "excitation": {{ "synthetic": {{ "seed": {seed}, "duration": {duration}, "dt": 0.01 }} }},
             "method": {method},
             "outputs": {{ "energies": true, "histories": false }} }}"#,
        list(&m, "kg"),
        list(&k, "N/m"),
        ds.join(", "),
        yl.join(", "),
    )
}

fn plan_of(json: &str) -> Plan {
    Plan::compile(&scene_json_checked(json)).unwrap()
}

fn scene_json_checked(text: &str) -> slipload_sim::Scene {
    common::scene_json(text, &SceneOverrides::default())
}

/// Runs `plan` on the banded and on the dense step.
fn both(plan: &Plan) -> (Outcome, BandedStats, Outcome) {
    let (b, stats) = run_on_path(plan, StepPath::Banded).unwrap();
    let (d, none) = run_on_path(plan, StepPath::Dense).unwrap();
    assert!(
        none.is_none(),
        "the dense path reports no banded statistics"
    );
    (b, stats.unwrap(), d)
}

/// Largest relative difference of two peak arrays, to the arrays' largest value or
/// `floor`, whichever is larger.
fn rel_diff(a: &[f64], b: &[f64], floor: f64) -> f64 {
    let scale = a
        .iter()
        .chain(b)
        .fold(floor, |m, v| m.max(v.abs()))
        .max(1e-300);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

/// Peaks to `PEAK_REL` of each array's largest value (lengths: or of the largest peak
/// displacement, so that the slip of a contact that never slides, round-off both ways,
/// is compared with the motion) and the energies to `ENERGY_REL` of
/// the input energy: the two steps solve the same linear systems (one by a dense Cholesky
/// factor of A and explicit products with A⁻¹K, A⁻¹C, the other by banded LDLᵀ of A plus
/// the stuck braces) and the same strictly convex QP, whose minimiser is unique, so each
/// step differs by the round-off of those solves, ~κ(A)·ε with κ(A) ≤ 1e2 here (A is M
/// plus Δt² K: well conditioned at Δt = T₁/400); the dissipative map does not amplify it
/// over the run, and a grazing contact decided at the round-off threshold moves a force by
/// at most that threshold. The measured differences are at most 1.5e-12 (peak
/// accelerations with stiff braces, k′ = 20k, which jump at slip→stick) and ~1e-13 for
/// the displacements; 1e-10 leaves room for other records and machines, while a wrong
/// force in a single step (a wrong stick/slip decision, a missed HHT term) moves peaks by
/// 1e-4 or more.
const PEAK_REL: f64 = 1e-10;
const ENERGY_REL: f64 = 1e-10;

fn assert_agree(name: &str, b: &Outcome, d: &Outcome) {
    let (rb, rd) = (&b.response, &d.response);
    assert_eq!(rb.steps, rd.steps, "{name}: steps");
    let motion = rd.peak_displacement.iter().fold(0.0f64, |m, v| m.max(*v));
    for (what, x, y) in [
        ("peak_drift", &rb.peak_drift, &rd.peak_drift),
        (
            "peak_displacement",
            &rb.peak_displacement,
            &rd.peak_displacement,
        ),
        (
            "peak_abs_acceleration",
            &rb.peak_abs_acceleration,
            &rd.peak_abs_acceleration,
        ),
        ("peak_slip", &rb.peak_slip, &rd.peak_slip),
        ("residual_drift", &rb.residual_drift, &rd.residual_drift),
    ] {
        let floor = if what == "peak_abs_acceleration" {
            0.0
        } else {
            motion
        };
        let e = rel_diff(x, y, floor);
        assert!(
            e <= PEAK_REL,
            "{name}: {what} differs by {e:e}: {x:?} vs {y:?}"
        );
    }
    let e = rel_diff(&[rb.peak_base_shear], &[rd.peak_base_shear], 0.0);
    assert!(e <= PEAK_REL, "{name}: base shear differs by {e:e}");
    // stick↔slip counts: a grazing contact may stick for one step on one path only
    for (i, (p, q)) in rb.transitions.iter().zip(&rd.transitions).enumerate() {
        assert!(
            p.abs_diff(*q) <= 2u64.max(q / 100),
            "{name}: transitions[{i}] {p} vs {q}"
        );
    }
    let (eb, ed) = (rb.energy.as_ref().unwrap(), rd.energy.as_ref().unwrap());
    let scale = ed.input.abs().max(1e-300);
    for (what, x, y) in [
        ("input", eb.input, ed.input),
        ("kinetic", eb.kinetic, ed.kinetic),
        ("strain", eb.strain, ed.strain),
        ("viscous", eb.viscous, ed.viscous),
        ("friction", eb.friction, ed.friction),
        (
            "plastic",
            eb.plastic.unwrap_or(0.0),
            ed.plastic.unwrap_or(0.0),
        ),
    ] {
        assert!(
            (x - y).abs() <= ENERGY_REL * scale,
            "{name}: energy {what} {x} vs {y} (input {scale})"
        );
    }
}

/// Random banded scenes of 1 to 60 storeys: every peak and energy of the banded step is
/// the dense step's, and at α = 0 the banded step's energies balance to round-off.
#[test]
fn banded_step_is_the_dense_step_on_random_scenes() {
    let cases: &[(usize, Damping, f64, Slip, bool, f64, bool)] = &[
        (1, Damping::Storey, 2.0, Slip::Moderate, false, 0.0, false),
        (2, Damping::Rayleigh, 20.0, Slip::Tiny, false, 0.0, false),
        (5, Damping::Storey, 0.05, Slip::Moderate, true, -0.1, false),
        (
            10,
            Damping::Rayleigh,
            2.0,
            Slip::Moderate,
            false,
            0.0,
            false,
        ),
        (13, Damping::Rayleigh, 20.0, Slip::Mixed, true, 0.0, false),
        (17, Damping::Storey, 0.2, Slip::Tiny, false, -0.3, false),
        (24, Damping::Rayleigh, 5.0, Slip::Huge, false, 0.0, false),
        (31, Damping::Storey, 2.0, Slip::Mixed, false, -0.05, true),
        (40, Damping::Rayleigh, 0.5, Slip::Moderate, true, 0.0, false),
        (
            50,
            Damping::Rayleigh,
            2.0,
            Slip::Moderate,
            false,
            0.0,
            false,
        ),
        (
            60,
            Damping::Storey,
            10.0,
            Slip::Moderate,
            false,
            -1.0 / 3.0,
            false,
        ),
    ];
    for (seed, &(n, damping, brace, slip, some, alpha, yields)) in cases.iter().enumerate() {
        let json = scene_json(Case {
            seed: seed as u64 + 1,
            n,
            damping,
            brace,
            slip,
            some,
            alpha,
            yields,
            duration: 4.0,
            dashpots: 0.3,
        });
        let plan = plan_of(&json);
        assert!(
            plan.half_bandwidth() <= 1,
            "shear buildings are tridiagonal"
        );
        let (b, stats, d) = both(&plan);
        let name = format!("{n} storeys, {damping:?}, k'/k {brace}, {slip:?}, alpha {alpha}");
        assert_agree(&name, &b, &d);
        let e = b.response.energy.as_ref().unwrap();
        if alpha == 0.0 {
            // Δt·v̄ᵀ(the equation averaged over the step) is an identity of the method
            assert!(
                b.diagnostics.balance_error_max_relative <= 1e-9,
                "{name}: balance error {:e}",
                b.diagnostics.balance_error_max_relative
            );
        }
        assert!(
            e.input.is_finite() && e.input != 0.0,
            "{name}: input energy"
        );
        assert_eq!(stats.fallbacks, 0, "{name}: {stats:?}");
    }
}

/// A massless damper without a brace dashpot on every floor, contact c joining floor c to
/// the floor below: the frames whose per-contact loops the banded step runs on aligned
/// slices. They agree with the dense step (to `PEAK_REL`, as every banded scene) on random
/// scenes of 2 to 50 storeys (one storey has no band below the diagonal and takes the
/// general loops), every slip level and HHT-α; a frame that is not aligned (a brace
/// dashpot on some dampers, dampers on some floors only, yielding storeys with a second
/// element on their floors) takes the general loops.
#[test]
fn aligned_frames_agree_with_the_dense_step() {
    let aligned: &[(usize, Damping, f64, Slip, f64)] = &[
        (3, Damping::Storey, 2.0, Slip::Moderate, 0.0),
        (2, Damping::Rayleigh, 20.0, Slip::Tiny, 0.0),
        (10, Damping::Rayleigh, 2.0, Slip::Mixed, 0.0),
        (17, Damping::Storey, 0.2, Slip::Huge, -0.1),
        (50, Damping::Rayleigh, 2.0, Slip::Moderate, 0.0),
        (50, Damping::Storey, 5.0, Slip::Mixed, -1.0 / 3.0),
    ];
    for (i, &(n, damping, brace, slip, alpha)) in aligned.iter().enumerate() {
        let plan = plan_of(&scene_json(Case {
            seed: 200 + i as u64,
            n,
            damping,
            brace,
            slip,
            some: false,
            alpha,
            yields: false,
            duration: 3.0,
            dashpots: 0.0,
        }));
        let (b, stats, d) = both(&plan);
        let name = format!("aligned, {n} storeys, {damping:?}, {slip:?}, alpha {alpha}");
        assert!(stats.aligned, "{name}: the aligned loops did not run");
        assert_agree(&name, &b, &d);
    }
    for (i, (dashpots, some, yields)) in
        [(0.3, false, false), (0.0, true, false), (0.0, false, true)]
            .into_iter()
            .enumerate()
    {
        let plan = plan_of(&scene_json(Case {
            seed: 300 + i as u64,
            n: 20,
            damping: Damping::Rayleigh,
            brace: 2.0,
            slip: Slip::Moderate,
            some,
            alpha: 0.0,
            yields,
            duration: 2.0,
            dashpots,
        }));
        let (b, stats, d) = both(&plan);
        let name = format!("not aligned: dashpots {dashpots}, some {some}, yields {yields}");
        assert!(!stats.aligned, "{name}: took the aligned loops");
        assert_agree(&name, &b, &d);
    }
}

/// Every slipping and sticking regime at once on a 30-storey building, across slip-load
/// levels from tiny to huge: the banded step agrees with the dense one, and slides
/// (friction energy) where the dense step slides.
#[test]
fn slip_load_levels_from_tiny_to_huge() {
    for (i, slip) in [Slip::Tiny, Slip::Moderate, Slip::Huge]
        .into_iter()
        .enumerate()
    {
        let json = scene_json(Case {
            seed: 100 + i as u64,
            n: 30,
            damping: Damping::Storey,
            brace: 3.0,
            slip,
            some: false,
            alpha: 0.0,
            yields: false,
            duration: 3.0,
            dashpots: 0.3,
        });
        let plan = plan_of(&json);
        let (b, _, d) = both(&plan);
        assert_agree(&format!("{slip:?}"), &b, &d);
        let e = b.response.energy.as_ref().unwrap();
        let friction = e.friction;
        match slip {
            // F·w with w at round-off (F ~ 1e3 × the weight above)
            Slip::Huge => assert!(
                friction.abs() <= 1e-9 * e.input,
                "huge slip loads never slide: {friction} J of {} J",
                e.input
            ),
            _ => assert!(friction > 0.0, "{slip:?} slip loads slide"),
        }
    }
}

/// One simulation gives the same bits whichever threads run others beside it.
#[test]
fn same_bits_across_threads() {
    let plan = plan_of(&scene_json(Case {
        seed: 7,
        n: 20,
        damping: Damping::Rayleigh,
        brace: 2.0,
        slip: Slip::Mixed,
        some: false,
        alpha: -0.1,
        yields: false,
        duration: 3.0,
        dashpots: 0.3,
    }));
    let (serial, _) = run_on_path(&plan, StepPath::Banded).unwrap();
    let bits = |o: &Outcome| {
        let r = &o.response;
        let e = r.energy.as_ref().unwrap();
        r.peak_drift
            .iter()
            .chain(&r.peak_abs_acceleration)
            .chain(&r.peak_slip)
            .chain([&e.input, &e.friction, &e.balance_error])
            .map(|v| v.to_bits())
            .collect::<Vec<u64>>()
    };
    let reference = bits(&serial);
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|_| s.spawn(|| bits(&run_on_path(&plan, StepPath::Banded).unwrap().0)))
            .collect();
        for h in handles {
            assert_eq!(h.join().unwrap(), reference);
        }
    });
}

/// `newmark` takes the banded step by itself on banded plans of ten DOFs or more, and
/// the dense step on every shipped building (condensed frame matrices, modal damping,
/// dissipators with mass) and on small frames, whose committed results it keeps to the bit.
#[test]
fn automatic_choice_keeps_committed_scenes_dense() {
    for file in [
        "benchmark-3story.json",
        "benchmark-3story-massless.json",
        "ten-story.json",
        "ten-story-yielding.json",
        "paper-1story.json",
    ] {
        let building = std::fs::read_to_string(configs().join(file)).unwrap();
        let json = format!(
            r#"{{ "building": {building}, "excitation": {{ "synthetic": {{ "seed": 1, "duration": 1, "dt": 0.01 }} }} }}"#
        );
        let plan = plan_of(&json);
        let (_, stats) = run_on_path(&plan, StepPath::Auto).unwrap();
        assert!(stats.is_none(), "{file}: takes the dense step");
    }
    let nine = Case {
        seed: 3,
        n: 9,
        damping: Damping::Rayleigh,
        brace: 2.0,
        slip: Slip::Moderate,
        some: false,
        alpha: 0.0,
        yields: false,
        duration: 1.0,
        dashpots: 0.3,
    };
    let small = plan_of(&scene_json(nine));
    assert!(
        run_on_path(&small, StepPath::Auto).unwrap().1.is_none(),
        "9 storeys: dense"
    );
    let large = plan_of(&scene_json(Case { n: 10, ..nine }));
    assert!(
        run_on_path(&large, StepPath::Auto).unwrap().1.is_some(),
        "10 storeys: banded"
    );
}

/// Forcing the banded step on a plan it cannot run exactly is refused with what it needs.
#[test]
fn banded_step_refuses_dense_plans() {
    let building = std::fs::read_to_string(configs().join("ten-story.json")).unwrap();
    let json = format!(
        r#"{{ "building": {building}, "excitation": {{ "synthetic": {{ "seed": 1, "duration": 1, "dt": 0.01 }} }} }}"#
    );
    let err = run_on_path(&plan_of(&json), StepPath::Banded)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("half-bandwidth of at most 3 (this plan's is 9)"),
        "{err}"
    );
}

/// A harmonic floor force (the force term of the right-hand side) instead of a ground
/// record, with HHT-α: the banded step is the dense step.
#[test]
fn harmonic_floor_force_with_hht() {
    let json = scene_json(Case {
        seed: 11,
        n: 14,
        damping: Damping::Storey,
        brace: 2.0,
        slip: Slip::Moderate,
        some: false,
        alpha: -0.1,
        yields: false,
        duration: 3.0,
        dashpots: 0.3,
    });
    let synthetic = r#""excitation": { "synthetic": { "seed": 11, "duration": 3, "dt": 0.01 } }"#;
    assert!(json.contains(synthetic), "{json}");
    let json = json.replace(
        synthetic,
        r#""excitation": { "harmonic": { "floor": 7, "amplitude": "2 MN", "omega": 4.5 } }, "duration": 3"#,
    );
    let plan = plan_of(&json);
    assert!(plan.harmonic.is_some() && plan.record.is_none());
    let (b, stats, d) = both(&plan);
    assert_agree("harmonic, 14 storeys", &b, &d);
    assert!(
        b.response.transitions.iter().sum::<u64>() > 0,
        "the dampers slide"
    );
    assert_eq!(stats.fallbacks, 0, "{stats:?}");
}
