//! One elastic–perfectly plastic contact as the banded step reads it ([`Spring`]): its
//! constants and its two ends, read through [`Ends`]. A chain's contact joins a floor to
//! the floor below ([`ChainEnds`]: two indices, b = e(floor) − e(floor below)); a building
//! in plan's joins two points, each a weighted sum of at most three DOFs of its floor
//! ([`PlanEnds`]: b = top − bottom, at most six entries). The step is generic over the
//! ends, chosen once per run, so the chain's loops are the arithmetic they were.
//!
//! Vectors of DOF quantities are stored with the ground first (index 0, always 0; a sink
//! for the ground's share of a force), so a contact reads and writes both its ends without
//! a branch.

use crate::kinematics::Kin;
use crate::plan::Contact;

/// How a contact reads and loads the DOFs: its vector b and what the banded step needs of
/// it. "Ground first": index 0 is the ground, DOF i at i + 1.
pub(super) trait Ends: Copy {
    /// The ends of `ct` (an elastic–perfectly plastic contact the banded step runs).
    fn of(ct: &Contact) -> Self;

    /// bᵀx, `x` ground first.
    fn diff(&self, x: &[f64]) -> f64;

    /// x −= s·b, `x` ground first (its ground entry may then hold garbage).
    fn sub(&self, x: &mut [f64], s: f64);

    /// The top point of `x`, ground first.
    fn top(&self, x: &[f64]) -> f64;

    /// The bottom point of `x`, ground first.
    fn bottom(&self, x: &[f64]) -> f64;

    /// The top point of `x` indexed by DOF (not ground first).
    fn top_dof(&self, x: &[f64]) -> f64;

    /// Adds `coef`·b bᵀ to the band `a` (row i holds A(i, i − d) at `a[i·w + d]`).
    fn stamp(&self, a: &mut [f64], w: usize, coef: f64);

    /// The first row of A the contact's spring b bᵀ enters.
    fn first_row(&self) -> usize;

    /// Adds the force `g` of the contact to `phi`, which [`Ends::rhs`] reads.
    fn gather(&self, phi: &mut [f64], g: f64);

    /// Row `i` (by DOF) of r − B F, from r (`r0`, ground first) and the gathered forces.
    fn rhs(r0: &[f64], phi: &[f64], i: usize) -> f64;

    /// (1 + floor, 1 + floor below) of a chain's contact; `None` in plan.
    fn chain(&self) -> Option<(usize, usize)>;
}

/// A chain's contact: floor `f1 − 1` against the floor below (`j1 − 1`; 0 the ground).
/// The banded step runs chains whose contacts join consecutive floors, j1 = f1 − 1.
#[derive(Debug, Clone, Copy)]
pub(super) struct ChainEnds {
    /// 1 + its floor.
    f1: usize,
    /// 1 + the floor below, 0 for the ground.
    j1: usize,
}

impl Ends for ChainEnds {
    fn of(ct: &Contact) -> Self {
        ChainEnds {
            f1: ct.floor + 1,
            j1: ct.below().map_or(0, |j| j + 1),
        }
    }

    /// x(floor) − x(floor below).
    #[inline(always)]
    fn diff(&self, x: &[f64]) -> f64 {
        x[self.f1] - x[self.j1]
    }

    #[inline(always)]
    fn sub(&self, x: &mut [f64], s: f64) {
        x[self.f1] -= s;
        x[self.j1] += s;
    }

    #[inline(always)]
    fn top(&self, x: &[f64]) -> f64 {
        x[self.f1]
    }

    #[inline(always)]
    fn bottom(&self, x: &[f64]) -> f64 {
        x[self.j1]
    }

    #[inline(always)]
    fn top_dof(&self, x: &[f64]) -> f64 {
        x[self.f1 - 1]
    }

    #[inline(always)]
    fn stamp(&self, a: &mut [f64], w: usize, coef: f64) {
        let f = self.f1 - 1;
        a[f * w] += coef;
        if self.j1 > 0 {
            let j = self.j1 - 1;
            a[j * w] += coef;
            a[f * w + (f - j)] -= coef;
        }
    }

    #[inline(always)]
    fn first_row(&self) -> usize {
        if self.j1 > 0 {
            self.j1 - 1
        } else {
            self.f1 - 1
        }
    }

    /// Per padded floor: the forces of the contacts on that floor (the floor below takes
    /// their opposite, B F = φ(i) − φ(i+1)).
    #[inline(always)]
    fn gather(&self, phi: &mut [f64], g: f64) {
        phi[self.f1] += g;
    }

    #[inline(always)]
    fn rhs(r0: &[f64], phi: &[f64], i: usize) -> f64 {
        (r0[i + 1] - phi[i + 1]) + phi[i + 2]
    }

    #[inline(always)]
    fn chain(&self) -> Option<(usize, usize)> {
        Some((self.f1, self.j1))
    }
}

/// A building in plan's contact: b = top − bottom, each point a weighted sum of at most
/// three DOFs (the ground none).
#[derive(Debug, Clone, Copy)]
pub(super) struct PlanEnds {
    top: Kin,
    bottom: Kin,
}

impl PlanEnds {
    /// The (DOF, weight) entries of b (a DOF read by both points appears twice).
    fn entries(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.top
            .entries()
            .chain(self.bottom.entries().map(|(i, w)| (i, -w)))
    }
}

impl Ends for PlanEnds {
    fn of(ct: &Contact) -> Self {
        PlanEnds {
            top: ct.top,
            bottom: ct.bottom,
        }
    }

    #[inline(always)]
    fn diff(&self, x: &[f64]) -> f64 {
        self.top.at_offset(x, 1) - self.bottom.at_offset(x, 1)
    }

    #[inline(always)]
    fn sub(&self, x: &mut [f64], s: f64) {
        self.top.add_offset(x, 1, -s);
        self.bottom.add_offset(x, 1, s);
    }

    #[inline(always)]
    fn top(&self, x: &[f64]) -> f64 {
        self.top.at_offset(x, 1)
    }

    #[inline(always)]
    fn bottom(&self, x: &[f64]) -> f64 {
        self.bottom.at_offset(x, 1)
    }

    #[inline(always)]
    fn top_dof(&self, x: &[f64]) -> f64 {
        self.top.at(x)
    }

    /// Every ordered pair of entries (i, wᵢ), (j, wⱼ) adds coef·wᵢwⱼ to A(i, j); the band
    /// keeps the lower triangle, i ≥ j (a repeated DOF's pairs all land on its diagonal).
    fn stamp(&self, a: &mut [f64], w: usize, coef: f64) {
        for (i, wi) in self.entries() {
            for (j, wj) in self.entries() {
                if i >= j {
                    a[i * w + (i - j)] += coef * wi * wj;
                }
            }
        }
    }

    fn first_row(&self) -> usize {
        self.entries().map(|(i, _)| i).min().unwrap_or(0)
    }

    /// φ = Σ b g over the contacts, ground first.
    #[inline(always)]
    fn gather(&self, phi: &mut [f64], g: f64) {
        self.sub(phi, -g);
    }

    #[inline(always)]
    fn rhs(r0: &[f64], phi: &[f64], i: usize) -> f64 {
        r0[i + 1] - phi[i + 1]
    }

    #[inline(always)]
    fn chain(&self) -> Option<(usize, usize)> {
        None
    }
}

/// One contact as the banded step reads it: its ends and its constants.
#[derive(Debug, Clone, Copy)]
pub(super) struct Spring<E> {
    pub(super) ends: E,
    pub(super) kappa: f64,
    pub(super) inv_kappa: f64,
    /// k′/κ.
    pub(super) k_over_kappa: f64,
    pub(super) lo: f64,
    pub(super) hi: f64,
}

impl<E: Ends> Spring<E> {
    /// The contact `ct` with κ = k′βΔt/γ + c′.
    pub(super) fn of(ct: &Contact, (beta, gamma, dt): (f64, f64, f64)) -> Self {
        let kappa = ct.brace_stiffness * beta * dt / gamma + ct.brace_damping;
        Spring {
            ends: E::of(ct),
            kappa,
            inv_kappa: 1.0 / kappa,
            k_over_kappa: ct.brace_stiffness / kappa,
            lo: ct.lower,
            hi: ct.upper,
        }
    }

    /// bᵀx, `x` ground first.
    #[inline(always)]
    pub(super) fn diff(&self, x: &[f64]) -> f64 {
        self.ends.diff(x)
    }

    /// x −= s·b, `x` ground first.
    #[inline(always)]
    pub(super) fn sub(&self, x: &mut [f64], s: f64) {
        self.ends.sub(x, s);
    }
}
