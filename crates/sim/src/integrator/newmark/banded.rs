//! The step of `newmark` in O(N) for banded frames: the same equations, the same friction
//! QP and the same answer as the dense step, without forming A⁻¹.
//!
//! The dense step precomputes A⁻¹K, A⁻¹C and the Delassus matrix W = γΔt BᵀG + diag(1/κ)
//! (all dense: O(N²) per step). When M, C and K are banded (a shear building with storey
//! stiffness and Rayleigh or storey damping: half-bandwidth 1; a building in plan with
//! Rayleigh damping, three DOFs a floor: 5; [`Plan::half_bandwidth`]) and every contact is
//! an elastic–perfectly plastic element (m′ = 0: a brace k′, c′ in series with a slider,
//! joining a floor to the floor below, or in plan a line's point on a floor to its point
//! on the floor below), the step stays in the original variables:
//!
//! - the right-hand side r = −K z_u − C z_v − (load) M r_g (− a second component's
//!   M r₂ a_g₂, + force, + HHT's friction memory α B F_n) is a banded product;
//! - a stick/slip pattern turns each stuck contact into a spring: the QP's variable of a
//!   contact is w = h₀ + γΔt bᵀa − F/κ (κ = k′βΔt/γ + c′, b = e(floor) − e(floor below)
//!   in a chain, top − bottom in plan: [`Ends`];
//!   h₀ its friction-free part at zero acceleration, as the dense step's
//!   `Link::free_slip_rate` forms it: from the slip of the step for an algebraic element,
//!   c′ = 0, from the end-of-step slip rate otherwise), so a stuck force is
//!   F = κ (h₀ + γΔt bᵀa) and the step's accelerations solve the banded system
//!   (A + (1+α)γΔt Σ_stuck κ b bᵀ) a = r − (1+α)[Σ_slipping b F± + Σ_stuck b κ h₀],
//!   one banded LDLᵀ factorisation (redone only when the stuck set changes) and one solve;
//! - the pattern is found by an active-set iteration started from the previous step's
//!   pattern (a primal–dual active-set pass flips every contact that breaks its condition:
//!   a stuck force outside its box slides at the bound it crossed, a sliding contact whose
//!   slip rate has the wrong sign sticks), and accepted only when it satisfies the KKT
//!   conditions of the box QP min ½FᵀWF − Fᵀw_free that the dense step solves, with the
//!   same round-off threshold as [`BoxQp`] (8 (m + 1) ε (‖W‖∞‖F‖∞ + ‖w_free‖∞) on the slip
//!   rates of sliding contacts). W is positive definite, so the KKT point is the unique
//!   minimiser: both steps give the same forces to round-off.
//! - A step whose iteration has not settled after [`MAX_PASSES`] passes is answered by
//!   [`BoxQp`] on the dense W (built once, O(N²) with banded solves) and w_free (one solve
//!   with A's own factor), as the dense step does: no regularisation, no penalty, the
//!   friction law exact at every step.
//!
//! Peaks and, when asked, energies are recorded as in the other loops; runs that ask for
//! histories take the general loop.

use super::band::{Band, Ldl, tri_rhs};
use super::link::{EppPred, Link};
use super::operators::StepConstants;
use super::outcome::{non_finite, outcome};
use super::spring::{ChainEnds, Ends, PlanEnds, Spring};
use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::integrator::state::{
    self, EnergyAccumulator, EppState, StepEnergyData, StepForms, epp_strain, initial_state,
    slip_rate,
};
use crate::plan::{ContactKind, Plan};
use crate::response::{Outcome, Peaks};

/// Largest half-bandwidth the banded step takes for a chain of floors (its factorisation
/// costs O(N p²)).
pub(super) const MAX_HALF_BANDWIDTH: usize = 3;

/// Largest half-bandwidth the banded step takes for a building in plan: three DOFs a
/// floor, storey elements between consecutive floors, give 5 ([`Plan::half_bandwidth`]).
pub(super) const MAX_PLAN_HALF_BANDWIDTH: usize = 5;

/// The largest half-bandwidth the banded step takes for `plan` (a chain's limit is the
/// one it always had, so a chain's choice of step is unchanged).
pub(super) fn max_half_bandwidth(plan: &Plan) -> usize {
    if plan.is_chain() {
        MAX_HALF_BANDWIDTH
    } else {
        MAX_PLAN_HALF_BANDWIDTH
    }
}

/// Fewest DOFs for which `newmark` chooses the banded step by itself (below, the dense
/// fixed-size loops are as fast; results/performance/README.md, "banded frames").
pub(super) const MIN_DOFS: usize = 10;

/// Active-set passes of one step before the step is handed to [`BoxQp`].
pub(super) const MAX_PASSES: u32 = 8;

/// What the banded path did over a run (tests and the bench read it).
#[doc(hidden)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BandedStats {
    /// Steps whose pattern was answered by the dense [`BoxQp`] (the active-set iteration
    /// did not settle, or a pattern's factorisation failed).
    pub fallbacks: u64,
    /// Banded factorisations of a stuck set (the first one included).
    pub factorizations: u64,
    /// Active-set passes over the run (one banded solve each; 1 per step when the pattern
    /// is unchanged).
    pub passes: u64,
    /// The per-contact loops ran on aligned slices (one algebraic element per floor, in
    /// floor order, each against the floor below).
    pub aligned: bool,
}

/// The plan's half-bandwidth when the banded step can run it exactly: no histories, every
/// contact an elastic–perfectly plastic element with a finite box of positive width
/// (in a chain between a floor and the floor below, or the ground; in plan between two
/// points, b = top − bottom), and banded operators (half-bandwidth at most
/// [`max_half_bandwidth`]: [`MAX_HALF_BANDWIDTH`] for a chain, [`MAX_PLAN_HALF_BANDWIDTH`]
/// in plan). Dampers with mass (DOFs after the floors') and full damping (modal) are not.
pub(super) fn eligible(plan: &Plan) -> Option<usize> {
    if plan.outputs.histories || plan.outputs.sensitivities {
        return None;
    }
    let chain = plan.is_chain();
    let epp_only = plan.contacts.iter().all(|c| {
        c.kind == ContactKind::Epp
            && (!chain || c.below() == c.floor.checked_sub(1))
            && c.lower.is_finite()
            && c.upper.is_finite()
            && c.lower < c.upper
    });
    if !epp_only {
        return None;
    }
    let p = plan.half_bandwidth();
    (p <= max_half_bandwidth(plan)).then_some(p)
}

/// The half-bandwidth when `newmark` takes the banded step by itself: eligible plans of at
/// least [`MIN_DOFS`] DOFs whose bandwidth is small against their size, n ≥ k (p + 1) with
/// k = 4 for a chain and k = 2 in plan ([`SIZE_PER_BAND_IN_PLAN`]).
pub(super) fn chosen(plan: &Plan) -> Option<usize> {
    let n = plan.dofs();
    let k = if plan.is_chain() {
        4
    } else {
        SIZE_PER_BAND_IN_PLAN
    };
    eligible(plan).filter(|&p| n >= MIN_DOFS && k * (p + 1) <= n)
}

/// A building in plan takes the banded step by itself from n ≥ 2 (p + 1) DOFs: twelve, four
/// storeys (p = 5). Measured on plans of two and of four lines per direction with a
/// massless damper on every line and storey, both components at once: the banded step
/// is 1.2–1.5× faster at four storeys, 1.1–1.4× at three, and 0.9–1.2× at one or two
/// (results/performance/README.md, "Buildings in plan").
pub(super) const SIZE_PER_BAND_IN_PLAN: usize = 2;

/// What the banded step keeps of the dense operators, for the steps [`BoxQp`] answers.
struct Dense {
    /// Delassus matrix, column-major nc × nc.
    w: Vec<f64>,
    /// ‖W‖∞.
    w_norm: f64,
    /// Built on the first step that needs it.
    qp: Option<BoxQp>,
}

/// The per-contact predictors of a step, as the dense step's `Link::free_slip_rate` forms
/// them: an algebraic element's (c′ = 0) from the slip of the step (the return mapping),
/// a damped brace's from its end-of-step slip rate; writes the friction-free part h0 of
/// the QP's variable at zero acceleration, the element's predictors and κ h0.
fn general_predictors<E: Ends>(
    (epp, links, springs): (&[EppState], &[Link], &[Spring<E>]),
    (u, ut, vt): (&[f64], &[f64], &[f64]),
    (dt, c_u, c_v, bg): (f64, f64, f64, f64),
    (h0, pred, g0): (&mut [f64], &mut [EppPred], &mut [f64]),
) {
    for (c, s) in springs.iter().enumerate() {
        let e = epp[c];
        let (uj, vj) = (s.ends.bottom(ut), s.ends.bottom(vt));
        if links[c].algebraic {
            let base = e.u - s.ends.top_dof(u);
            h0[c] = (s.ends.top(ut) - uj + base) * s.k_over_kappa;
            pred[c] = EppPred {
                base,
                ..EppPred::default()
            };
        } else {
            let up = e.u + dt * e.v + c_u * e.a;
            let vp = e.v + c_v * e.a;
            let q = (up - uj) - bg * (vp - vj);
            h0[c] = s.diff(vt) + s.k_over_kappa * q;
            pred[c] = EppPred { up, vp, base: 0.0 };
        }
        g0[c] = s.kappa * h0[c];
    }
}

/// [`general_predictors`] for an aligned frame (contact c on floor c against the floor
/// below, every element algebraic): the same arithmetic, on slices of one length, with no
/// gathers.
#[allow(clippy::needless_range_loop)] // the indices are the formula's
fn aligned_predictors<E: Ends>(
    epp: &[EppState],
    u: &[f64],
    ut: &[f64],
    springs: &[Spring<E>],
    (h0, pred, g0): (&mut [f64], &mut [EppPred], &mut [f64]),
) {
    let n = springs.len();
    let (epp, u, below, floor) = (&epp[..n], &u[..n], &ut[..n], &ut[1..=n]);
    let (h0, pred, g0) = (&mut h0[..n], &mut pred[..n], &mut g0[..n]);
    for c in 0..n {
        let s = &springs[c];
        let base = epp[c].u - u[c];
        h0[c] = (floor[c] - below[c] + base) * s.k_over_kappa;
        pred[c] = EppPred {
            base,
            ..EppPred::default()
        };
        g0[c] = s.kappa * h0[c];
    }
}

/// What the KKT check reads of a candidate pattern's forces and slip rates.
struct Candidate {
    /// ‖F‖∞.
    f_norm: f64,
    /// Every free force inside its box.
    inside: bool,
    /// The largest slip rate of a held force against its bound's sign (NaN-safe: a NaN
    /// fails both this and `inside`).
    wrong_max: f64,
    /// The sum of the slip rates (finite when they all are).
    finite: f64,
}

/// A step's stick/slip pattern as the candidate loop reads it (per contact): free or held,
/// the held force, the sign its slip rate must not have, and the friction-free parts κ h0
/// and h0.
struct PatternView<'a> {
    free: &'a [bool],
    held: &'a [f64],
    sign: &'a [f64],
    g0: &'a [f64],
    h0: &'a [f64],
}

/// The forces and slip rates of the candidate whose accelerations are `x` (ground
/// first), written to `f` and `w`; `aligned` as in [`aligned_predictors`] (the same
/// arithmetic without gathers).
fn candidate<E: Ends>(
    aligned: bool,
    (springs, x, gdt): (&[Spring<E>], &[f64], f64),
    pattern: PatternView,
    out: (&mut [f64], &mut [f64]),
) -> Candidate {
    let nc = springs.len();
    if aligned {
        let (below, floor) = (&x[..nc], &x[1..=nc]);
        candidate_with(springs, gdt, pattern, out, |c, _| floor[c] - below[c])
    } else {
        candidate_with(springs, gdt, pattern, out, |_, s| s.diff(x))
    }
}

/// [`candidate`] with bᵀx of contact c given by `diff(c, spring)`.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the indices are the formula's
fn candidate_with<E: Ends>(
    springs: &[Spring<E>],
    gdt: f64,
    pattern: PatternView,
    (f, w): (&mut [f64], &mut [f64]),
    diff: impl Fn(usize, &Spring<E>) -> f64,
) -> Candidate {
    let nc = springs.len();
    let PatternView {
        free: fr,
        held: fb,
        sign: sg,
        g0,
        h0,
    } = pattern;
    let (fr, fb, sg, g0, h0) = (&fr[..nc], &fb[..nc], &sg[..nc], &g0[..nc], &h0[..nc]);
    let (f, w) = (&mut f[..nc], &mut w[..nc]);
    let mut out = Candidate {
        f_norm: 0.0,
        inside: true,
        wrong_max: 0.0,
        finite: 0.0,
    };
    for c in 0..nc {
        let s = &springs[c];
        let da = gdt * diff(c, s);
        let fc = if fr[c] { g0[c] + s.kappa * da } else { fb[c] };
        let wc = (h0[c] + da) - fc * s.inv_kappa;
        f[c] = fc;
        w[c] = wc;
        // the larger of the two by one comparison (a single max instruction): a NaN never
        // replaces the maximum, as with `f64::max`, whose NaN handling costs a longer chain
        let (fa, wr) = (fc.abs(), sg[c] * wc);
        out.f_norm = if fa > out.f_norm { fa } else { out.f_norm };
        out.inside &= !fr[c] || (fc >= s.lo && fc <= s.hi);
        out.wrong_max = if wr > out.wrong_max {
            wr
        } else {
            out.wrong_max
        };
        out.finite += wc;
    }
    out
}

/// Runs `plan` (half-bandwidth `p`, [`eligible`]) with the banded step, a step's
/// active-set iteration handed to [`BoxQp`] after `max_passes` passes ([`MAX_PASSES`]
/// unless a test asks for fewer): a chain's contacts read as two floors, a building in
/// plan's as two points.
pub(super) fn run(
    plan: &Plan,
    p: usize,
    max_passes: u32,
) -> Result<(Outcome, BandedStats), SimError> {
    if plan.is_chain() {
        run_with::<ChainEnds>(plan, p, max_passes)
    } else {
        run_with::<PlanEnds>(plan, p, max_passes)
    }
}

/// [`run`] with the contacts' ends read by `E`.
fn run_with<E: Ends>(
    plan: &Plan,
    p: usize,
    max_passes: u32,
) -> Result<(Outcome, BandedStats), SimError> {
    let n = plan.dofs();
    let nc = plan.contacts.len();
    let dt = plan.method.dt;
    let alpha = plan.method.alpha;
    let gamma = 0.5 - alpha;
    let beta = (1.0 - alpha) * (1.0 - alpha) / 4.0;
    let k = StepConstants::new(dt, beta, gamma);
    let (c_u, c_v, gdt, bdt2, bg) = (k.c_u, k.c_v, k.gdt, k.bdt2, k.bg);
    let (mass, damping, stiffness) = (&plan.mass, &plan.damping, &plan.stiffness);
    let a_dense = mass + (damping * (gamma * dt) + stiffness * (beta * dt * dt)) * (1.0 + alpha);
    let a_base = Band::of(&a_dense, p);
    let (mb, cb, kb) = (
        Band::of(mass, p),
        Band::of(damping, p),
        Band::of(stiffness, p),
    );
    let mut base = Ldl::new(n, p);
    if !base.factor(&a_base) {
        return Err(SimError::NotPositiveDefinite {
            what: "Newmark iteration matrix M + γΔtC + βΔt²K".into(),
            hint: " (a mass, damping or stiffness matrix is invalid)".into(),
        });
    }
    let mut stats = BandedStats {
        factorizations: 1,
        ..Default::default()
    };
    let springs: Vec<Spring<E>> = plan
        .contacts
        .iter()
        .map(|ct| Spring::of(ct, (beta, gamma, dt)))
        .collect();
    let links: Vec<Link> = plan
        .contacts
        .iter()
        .zip(&springs)
        .map(|(ct, s)| Link {
            top: ct.top,
            other: ct.bottom,
            epp: true,
            algebraic: ct.is_algebraic(),
            k_over_kappa: s.k_over_kappa,
            slot: ct.slot,
        })
        .collect();
    // The Delassus matrix W = (1+α)γΔt BᵀA⁻¹B + diag(1/κ), one banded solve per column.
    let mut dense = {
        let mut w = vec![0.0; nc * nc];
        let mut x = vec![0.0; n + 1];
        for (c, s) in springs.iter().enumerate() {
            x.fill(0.0);
            s.sub(&mut x, -1.0);
            x[0] = 0.0;
            base.solve(&mut x[1..]);
            for (r, t) in springs.iter().enumerate() {
                w[r + c * nc] = t.diff(&x) * (1.0 + alpha) * (gamma * dt);
            }
            w[c + c * nc] += s.inv_kappa;
        }
        for c in 0..nc {
            for r in 0..c {
                let mean = 0.5 * (w[r + c * nc] + w[c + r * nc]);
                w[r + c * nc] = mean;
                w[c + r * nc] = mean;
            }
        }
        let w_norm = (0..nc)
            .map(|r| (0..nc).map(|c| w[r + c * nc].abs()).sum::<f64>())
            .fold(0.0, f64::max);
        Dense {
            w,
            w_norm,
            qp: None,
        }
    };
    let tol_factor = 8.0 * (nc as f64 + 1.0) * f64::EPSILON;
    let tol_w = tol_factor * dense.w_norm;

    // M r and rᵀM r: a chain's r is 1 on every floor (its band product, as it always
    // was); a plan's as the dense step forms them.
    let (mr, msum) = if plan.is_chain() {
        let ones = vec![1.0; n];
        let mut mr = vec![0.0; n];
        mb.mul_sub(&ones, &mut mr);
        for x in &mut mr {
            *x = -*x;
        }
        let msum: f64 = mr.iter().sum();
        (mr, msum)
    } else {
        (
            plan.mass_influence().as_slice().to_vec(),
            plan.influence_mass(),
        )
    };
    // A second ground component (a plan under both of a pair): M r₂, and r₁ᵀM r₂ for the
    // base shear along the first component's direction.
    let mr2: Option<Vec<f64>> = plan.mass_influence2().map(|m| m.as_slice().to_vec());
    let cross = plan.cross_mass();
    let base_shear = |a: &[f64], ag: f64, p: f64, ag2: f64| {
        if mr2.is_some() {
            // signed along the first component, then its size (as the dense step)
            (state::signed_base_shear(&mr, msum, a, ag, p) + cross * ag2).abs()
        } else {
            state::base_shear(&mr, msum, a, ag, p)
        }
    };

    let start = initial_state(plan)?;
    let (mut u, mut v, mut a) = (start.u.clone(), start.v.clone(), start.a.clone());
    let mut f_old = start.f.clone();
    let mut f_new = vec![0.0; nc];
    let mut epp = start.epp.clone();
    let mut stuck = start.stuck.clone();
    // The pattern: stuck contacts free, sliding ones at the bound their force sits on.
    let mut status: Vec<Bound> = (0..nc)
        .map(|c| {
            if stuck[c] {
                Bound::Free
            } else if f_old[c] >= springs[c].hi {
                Bound::Upper
            } else {
                Bound::Lower
            }
        })
        .collect();
    // The pattern as the candidate loop reads it, without branches: free or held, the
    // force a held contact carries, and the sign its slip rate must not have (+1 at the
    // lower bound, −1 at the upper, 0 free).
    let mut fr = vec![false; nc];
    let mut fb = vec![0.0; nc];
    let mut sg = vec![0.0; nc];
    for c in 0..nc {
        (fr[c], fb[c], sg[c]) = coded(status[c], &springs[c]);
    }
    // The friction forces gathered for the right-hand side ([`Ends::gather`]): a chain's
    // per padded floor, on the contacts of that floor (the floor below takes their
    // opposite, B F = φ(i) − φ(i+1)); a plan's B F itself.
    let mut phi = vec![0.0; n + 2];
    // `pattern` holds the factorisation of the stuck set of `status` in its rows before
    // `dirty` (n: all of them).
    let mut dirty = 0usize;
    let mut pattern = Ldl::new(n, p);
    let mut a_pattern = a_base.clone();

    let energies = plan.outputs.energies;
    let mut acc = EnergyAccumulator::start(plan, &start.u, &start.v, &epp);
    let mut w_old: Vec<f64> = (0..nc).map(|c| slip_rate(plan, c, &v, &epp)).collect();
    let mut w_new = vec![0.0; nc];
    let mut v_old = vec![0.0; n];
    let mut vm = vec![0.0; n];

    let mut peaks = Peaks::for_plan(plan);
    let mut ag0 = plan.ground_accel(0.0);
    let mut ground = plan.ground_steps();
    let mut ag2_0 = plan.ground2_accel(0.0);
    let mut ground2 = plan.ground2_steps();
    let mut p0 = plan.force(0.0);
    let force_floor = plan.harmonic.map(|h| h.floor);
    peaks.observe_floors2(&u, &a, ag0, ag2_0);
    peaks.observe_base_shear(base_shear(&a, ag0, p0, ag2_0));
    for (c, l) in links.iter().enumerate() {
        l.observe_start(&u, epp[c].u, &mut peaks);
    }
    state::observe_dampers(plan, &mut peaks, 0.0, &u, &f_old, &w_old, &epp);

    // Floor vectors ground first (index 0).
    let mut ut = vec![0.0; n + 1];
    let mut vt = vec![0.0; n + 1];
    let mut r0 = vec![0.0; n + 1];
    let mut x = vec![0.0; n + 1];
    let mut y = vec![0.0; n + 1];
    let mut zu = vec![0.0; n];
    let mut zv = vec![0.0; n];
    // Per contact and step: the elements' predictors, the friction-free part h0 of the
    // QP's variable at zero acceleration (the dense step's `Link::free_slip_rate` without
    // its γΔt bᵀa term), and the force a stuck contact would carry at zero acceleration,
    // κ h0.
    let mut h0 = vec![0.0; nc];
    let mut pred = vec![EppPred::default(); nc];
    let mut g0 = vec![0.0; nc];
    let mut wfree = vec![0.0; nc];
    let lo: Vec<f64> = springs.iter().map(|s| s.lo).collect();
    let hi: Vec<f64> = springs.iter().map(|s| s.hi).collect();
    let mut qp_total: u64 = 0;
    let mut qp_max: u32 = 0;
    let hhht = alpha != 0.0 && nc > 0;
    // One algebraic element per floor, floor c's joining it to the floor below, in floor
    // order (a shear building with a massless damper on every floor): the per-contact
    // loops run on slices of one length, without gathers.
    let aligned = p == 1
        && nc == n
        && springs
            .iter()
            .enumerate()
            .all(|(c, s)| s.ends.chain() == Some((c + 1, c)))
        && links.iter().all(|l| l.algebraic);
    stats.aligned = aligned;
    let op = 1.0 + alpha;

    for step in 0..plan.steps {
        let t1 = (step + 1) as f64 * dt;
        let ag1 = ground.next_accel();
        let ag2_1 = ground2.next_accel();
        let p1 = if force_floor.is_some() {
            plan.force(t1)
        } else {
            0.0
        };
        for i in 0..n {
            ut[i + 1] = u[i] + dt * v[i] + c_u * a[i];
            vt[i + 1] = v[i] + c_v * a[i];
        }
        let (zu, zv): (&[f64], &[f64]) = if alpha == 0.0 {
            (&ut[1..], &vt[1..])
        } else {
            for i in 0..n {
                zu[i] = op * ut[i + 1] - alpha * u[i];
                zv[i] = op * vt[i + 1] - alpha * v[i];
            }
            (&zu, &zv)
        };
        // r0 = load·M r − K z_u − C z_v (+ force, + α B F_n).
        let load = -(op * ag1 - alpha * ag0);
        {
            let r = &mut r0[1..];
            if p == 1 {
                tri_rhs(load, &mr, &kb, zu, &cb, zv, r);
            } else {
                for i in 0..n {
                    r[i] = load * mr[i];
                }
                kb.mul_sub(zu, r);
                cb.mul_sub(zv, r);
            }
            if let Some(mr2) = &mr2 {
                let load2 = -(op * ag2_1 - alpha * ag2_0);
                for i in 0..n {
                    r[i] += load2 * mr2[i];
                }
            }
            if let Some(fl) = force_floor {
                r[fl] += op * p1 - alpha * p0;
            }
        }
        if hhht {
            for (s, &fo) in springs.iter().zip(&f_old) {
                s.sub(&mut r0, -alpha * fo);
            }
        }
        // The predictors of each element (its condensed massless DOF).
        if aligned {
            aligned_predictors(&epp, &u, &ut, &springs, (&mut h0, &mut pred, &mut g0));
        } else {
            general_predictors(
                (&epp, &links, &springs),
                (&u, &ut, &vt),
                (dt, c_u, c_v, bg),
                (&mut h0, &mut pred, &mut g0),
            );
        }

        // The active-set iteration on the stick/slip pattern.
        let mut passes = 0u32;
        let mut wfree_norm: Option<f64> = None;
        let settled = loop {
            if passes == max_passes {
                break false;
            }
            passes += 1;
            if dirty < n {
                a_pattern.a.copy_from_slice(&a_base.a);
                let w = p + 1;
                for (s, b) in springs.iter().zip(&status) {
                    if *b == Bound::Free {
                        s.ends.stamp(&mut a_pattern.a, w, op * gdt * s.kappa);
                    }
                }
                stats.factorizations += 1;
                if !pattern.factor_from(&a_pattern, dirty) {
                    dirty = 0;
                    break false;
                }
                dirty = n;
            }
            if aligned {
                // one contact per floor, in floor order: each floor's entry is its own
                // contact's (0.0 + keeps the sign of a zero as the sum below does)
                let phi = &mut phi[1..=n];
                let (fr, g0, fb) = (&fr[..n], &g0[..n], &fb[..n]);
                for c in 0..n {
                    let g = if fr[c] { g0[c] } else { fb[c] };
                    phi[c] = 0.0 + op * g;
                }
            } else {
                phi.fill(0.0);
                for (c, s) in springs.iter().enumerate() {
                    let g = if fr[c] { g0[c] } else { fb[c] };
                    s.ends.gather(&mut phi, op * g);
                }
            }
            x[0] = 0.0;
            pattern.solve_with(&mut x[1..], |_, i| E::rhs(&r0, &phi, i));
            // Forces and slip rates of the candidate.
            let Candidate {
                f_norm,
                inside,
                wrong_max,
                finite,
            } = candidate(
                aligned,
                (&springs, &x, gdt),
                PatternView {
                    free: &fr,
                    held: &fb,
                    sign: &sg,
                    g0: &g0,
                    h0: &h0,
                },
                (&mut f_new, &mut w_new),
            );
            if inside && wrong_max <= tol_w * f_norm && finite.is_finite() {
                // the usual step: the pattern holds (the forces are finite: a free one
                // inside its box, a held one at its bound)
                break true;
            }
            // KKT, as BoxQp: free forces inside the box, held ones' slip rates of the sign
            // their bound allows beyond 8 (m + 1) ε (‖W‖∞‖F‖∞ + ‖w_free‖∞). The threshold
            // without ‖w_free‖∞ decides most rates; w_free is computed when one falls
            // between it and the full threshold.
            let tol_lo = tol_w * f_norm;
            let mut changed = false;
            let mut bad = !f_norm.is_finite();
            for c in 0..nc {
                let s = &springs[c];
                let next = match status[c] {
                    Bound::Free => {
                        let fc = f_new[c];
                        if fc < s.lo {
                            Bound::Lower
                        } else if fc > s.hi {
                            Bound::Upper
                        } else {
                            bad |= fc.is_nan();
                            continue;
                        }
                    }
                    held => {
                        let wrong = if held == Bound::Lower {
                            w_new[c]
                        } else {
                            -w_new[c]
                        };
                        if wrong.is_nan() {
                            bad = true;
                            continue;
                        }
                        if wrong <= tol_lo {
                            continue;
                        }
                        let b_norm = *wfree_norm.get_or_insert_with(|| {
                            free_slip_rates(&base, &springs, &r0, &h0, gdt, &mut y, &mut wfree)
                        });
                        if wrong <= tol_lo + tol_factor * b_norm {
                            continue;
                        }
                        Bound::Free
                    }
                };
                status[c] = next;
                (fr[c], fb[c], sg[c]) = coded(next, s);
                changed = true;
                // the first row of A its stuck spring enters (its lower floor's)
                dirty = dirty.min(s.ends.first_row());
            }
            if bad {
                break false;
            }
            if !changed {
                break true;
            }
        };
        stats.passes += u64::from(passes);
        let iterations = if settled {
            passes
        } else {
            // The dense box QP, as the dense step solves it.
            stats.fallbacks += 1;
            free_slip_rates(&base, &springs, &r0, &h0, gdt, &mut y, &mut wfree);
            let qp = match &mut dense.qp {
                Some(qp) => qp,
                slot @ None => slot.insert(
                    BoxQp::new(&dense.w, nc)
                        .map_err(|source| SimError::Friction { t: t1, source })?,
                ),
            };
            let st = qp
                .solve(&wfree, &lo, &hi, &mut f_new)
                .map_err(|source| SimError::Friction { t: t1, source })?;
            x.copy_from_slice(&r0);
            for (c, s) in springs.iter().enumerate() {
                s.sub(&mut x, op * f_new[c]);
                status[c] = qp.status(c);
                (fr[c], fb[c], sg[c]) = coded(status[c], s);
            }
            x[0] = 0.0;
            base.solve(&mut x[1..]);
            for (c, s) in springs.iter().enumerate() {
                w_new[c] = (h0[c] + gdt * s.diff(&x)) - f_new[c] * s.inv_kappa;
            }
            dirty = 0;
            passes + st.iterations
        };
        qp_total += u64::from(iterations);
        qp_max = qp_max.max(iterations);

        if energies {
            v_old.copy_from_slice(&v);
        }
        let mut finite = 0.0;
        for i in 0..n {
            let ai = x[i + 1];
            a[i] = ai;
            u[i] = ut[i + 1] + bdt2 * ai;
            v[i] = vt[i + 1] + gdt * ai;
            finite += u[i];
        }
        if !finite.is_finite() {
            return Err(non_finite(step + 1, dt));
        }
        if aligned {
            // `Link::finish_step` of an algebraic element on floor c, on aligned slices
            let (u, v) = (&u[..nc], &v[..nc]);
            let (epp, stuck, status) = (&mut epp[..nc], &mut stuck[..nc], &status[..nc]);
            let (pred, w_new) = (&pred[..nc], &mut w_new[..nc]);
            for (c, l) in links.iter().enumerate() {
                let rate;
                (epp[c], rate) = l.algebraic_update(&k, (pred[c].base, w_new[c]), u[c], v[c]);
                w_new[c] = rate;
                let now_stuck = status[c] == Bound::Free;
                l.observe_end(now_stuck, &mut stuck[c], u[c] - epp[c].u, &mut peaks);
            }
        } else {
            for (c, l) in links.iter().enumerate() {
                w_new[c] = l.finish_step(
                    &k,
                    (pred[c], w_new[c]),
                    (&u, &v),
                    status[c] == Bound::Free,
                    &mut epp[c],
                    &mut stuck[c],
                    &mut peaks,
                );
            }
        }
        state::observe_dampers(plan, &mut peaks, t1, &u, &f_new, &w_new, &epp);
        peaks.observe_floors2(&u, &a, ag1, ag2_1);
        peaks.observe_base_shear(base_shear(&a, ag1, p1, ag2_1));
        if energies {
            let data = StepEnergyData {
                second: mr2.as_deref().map(|m2| (m2, (ag2_0, ag2_1))),
                dt,
                mr: &mr,
                ag: (ag0, ag1),
                p: (p0, p1),
                force_floor,
                v: (&v_old, &v),
                f: (&f_old, &f_new),
                w: (&w_old, &w_new),
                epp_mean_rate: true,
            };
            for i in 0..n {
                vm[i] = 0.5 * (v_old[i] + v[i]);
            }
            let forms = StepForms {
                cvv: cb.quad(&vm),
                kinetic: 0.5 * mb.quad(&v),
                strain: 0.5 * kb.quad(&u) + epp_strain(plan, &u, &epp),
            };
            acc.step(plan, &data, forms, &epp);
            std::mem::swap(&mut w_old, &mut w_new);
        }
        std::mem::swap(&mut f_old, &mut f_new);
        ag0 = ag1;
        ag2_0 = ag2_1;
        p0 = p1;
        if peaks.collapsed(t1) {
            break;
        }
    }
    let energy = energies.then(|| acc.finish(plan, &u, &v, &epp));
    let mut out = outcome(plan, peaks, &acc, energy, (qp_total, qp_max), None);
    out.diagnostics.work = work_per_step(n, p, nc) * out.response.steps as u64;
    Ok((out, stats))
}

/// A contact's pattern as the candidate loop reads it: free, the held force, the sign.
fn coded<E>(b: Bound, s: &Spring<E>) -> (bool, f64, f64) {
    match b {
        Bound::Free => (true, 0.0, 0.0),
        Bound::Lower => (false, s.lo, 1.0),
        Bound::Upper => (false, s.hi, -1.0),
    }
}

/// The slip rates w_free of the step without friction forces (one solve with A's own
/// factor, in the scratch `y`, ground first), written to `wfree`; returns ‖w_free‖∞.
fn free_slip_rates<E: Ends>(
    base: &Ldl,
    springs: &[Spring<E>],
    r0: &[f64],
    h0: &[f64],
    gdt: f64,
    y: &mut [f64],
    wfree: &mut [f64],
) -> f64 {
    y.copy_from_slice(r0);
    y[0] = 0.0;
    base.solve(&mut y[1..]);
    let mut norm = 0.0f64;
    for (c, s) in springs.iter().enumerate() {
        wfree[c] = h0[c] + gdt * s.diff(y);
        norm = norm.max(wfree[c].abs());
    }
    norm
}

/// Multiply-adds of one banded step: the two band products of the right-hand side, one
/// banded solve, the contacts' predictors and slip rates, and the predictor and corrector
/// updates.
fn work_per_step(n: usize, p: usize, nc: usize) -> u64 {
    let (n, p, nc) = (n as u64, p as u64, nc as u64);
    2 * n * (2 * p + 1) + 2 * n * (p + 1) + 12 * nc + 12 * n
}
