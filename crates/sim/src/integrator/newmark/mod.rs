//! `newmark` — Newmark/HHT-α with the friction forces of each step solved exactly and
//! implicitly (docs/MODEL.md § Integrators).
//!
//! With A = M + (1+α)(γΔt C + βΔt² K) factorised once, the step's accelerations are
//! a = a_free − G F with G = (1+α)A⁻¹B, and the slip rates at the end of the step are
//! w = w_free − W F with the Delassus matrix W = γΔt BᵀG (+ 1/κ on the diagonal of
//! elastic–perfectly plastic contacts, κ = k′βΔt/γ + c′, which is the exact condensation
//! of a massless dissipator DOF). The friction law is then the box QP
//! F = argmin_{F⁻≤F≤F⁺} ½FᵀWF − Fᵀw_free, solved exactly by [`BoxQp`](crate::friction::BoxQp).
//!
//! The linear part of a step is one precomputed n×2n operator [−A⁻¹K, −A⁻¹C] applied to the
//! (HHT-weighted) Newmark predictors of u and v.
//! Nothing is allocated inside the step loop unless histories are asked for; the ground
//! acceleration of each step is interpolated incrementally ([`Plan::ground_steps`](crate::plan::Plan::ground_steps)).
//! Runs without histories, of the sizes `fixed_dispatch!` lists, step in the fixed-size
//! loop of `newmark/fixed.rs` (DOF and contact counts compile-time constants, the friction
//! QP answered from its stick/slip pattern, energies when asked); runs that ask for
//! histories, and other sizes, step in the general loop of `newmark/dense.rs`, compiled
//! once per small DOF count (1–8, 10, 12, 20) with the count a constant and once for any
//! other count.
//! Banded frames of at least ten DOFs whose contacts are all elastic–perfectly plastic
//! (m′ = 0 shear buildings with Rayleigh or storey damping; buildings in plan with
//! Rayleigh damping, from twelve DOFs) step in O(N) in `newmark/banded.rs`: the same QP,
//! solved in the original banded variables.
//!
//! HHT-α (Hilber, Hughes & Taylor 1977): γ = ½ − α, β = (1 − α)²/4, α ∈ [−⅓, 0]; the
//! equation of motion is weighted (1+α) at t_{n+1} and −α at t_n, friction forces included.
//! α = 0 is Newmark's average acceleration, for which the energies below balance to
//! round-off (Δt·v̄ᵀ(equation averaged over the step) is an exact identity of the method).
//!
//! Files, each importing only those listed before it: `operators` (the run's fixed
//! operators and step constants), `link` (one contact as the loops read it), `outcome`
//! (how a loop ends), `fixed` (the fixed-size loop), `tangent` (the step's derivatives
//! with respect to the slip loads), `dense` (the dense run and the general loop), `band` (band matrices and their LDLᵀ factorisation),
//! `spring` (a contact's ends as the banded step reads them, a chain's or a plan's),
//! `banded` (the banded step), `run` (the integrator and the choice of step).

mod band;
mod banded;
mod dense;
mod fixed;
mod link;
mod operators;
mod outcome;
mod run;
mod spring;
mod tangent;

pub use banded::BandedStats;
pub use run::{Newmark, StepPath, run_on_path};
