//! `exact` — the event-driven reference integrator (docs/MODEL.md § Integrators).
//!
//! Between stick↔slip events the plan is linear and time-invariant, driven by a ground
//! acceleration that is linear between record samples, a harmonic force and constant slip
//! forces. The state is augmented with the generators of those inputs,
//! y = (u, v, x′ of the elastic–perfectly plastic contacts, a_g, ȧ_g, sin, cos, 1), so that
//! each mode set (which contacts stick, which slide and which way) is one autonomous linear
//! system ẏ = A y, and y(t + τ) = exp(Aτ) y(t) exactly (Van Loan 1978). The exponential is
//! applied as its Taylor series p_k = Aᵏy/k!, truncated at [`TAYLOR_TERMS`] terms on
//! substeps with ρτ ≤ [`SUBSTEP_PHASE`], where ρ bounds the spectral radius of the current
//! mode set's A (|λ| ≤ ν_max + ω_max for the quadratic eigenproblem, ν and ω² the extreme
//! Rayleigh quotients of C and K over M on the subspace the stuck dissipators leave free,
//! plus k′/c′ of sliding damped massless dissipators and the harmonic ω): the remainder is
//! below (ρτ)²²/22! ≈ 2e-28 of the state, i.e. the series is exact to round-off. The bound
//! is per mode set because a stuck dissipator with mass moves with its floor: the
//! dissipator's own fast mode (k′/m′ on a stiff brace, hundreds of rad/s) rings only while
//! it slides, and the substeps of the stuck phases follow the frame's modes. The same
//! polynomial gives every quantity inside the substep as a scalar polynomial in τ, which is
//! where events and peaks are located. A thread keeps the mode sets it forms (those of
//! the last two buildings it ran, keyed by the bits of everything they are formed from)
//! within a byte budget ([`MemoryBudget`], least recently used out first), so the records
//! of a suite on one design form each mode set's operators and propagators once while the
//! budget holds them; when a run steps with a mode set's propagators is decided by that
//! run's own use count of it (at most [`MODE_CACHE`] counts, restarted when full), so its
//! bits depend neither on what ran before it on the thread nor on what the budget evicted
//! (a mode set met again is formed again, the same bits). A scene whose run cannot hold
//! two mode sets and the scratch of forming one within the budget is refused before its
//! first step ([`SimError::ExactMemory`](crate::error::SimError::ExactMemory)).
//!
//! Map of the module, by concept, each file importing only those listed before it:
//! - `params`: the method's constants; `gauss`: the quadrature rule of the energies;
//!   `kernels`: the step loop's small products; `search`: event and extremum search inside
//!   a substep (scan, Illinois);
//! - `model`: contacts and mode sets — the augmented state's layout, the run-wide model
//!   (spectral bound ρ), and the data fixed for one mode set and its propagators;
//! - `modes`: each mode set's operators (mode matrix, force and slip-rate rows, event
//!   functions, the substep grid);
//! - `energy`: the powers as quadratic forms, their quadrature, the stored energies;
//! - `propagate`: the truncated series per substep and the cached grid propagators;
//! - `memory`: a mode set's bytes, their bounds for a plan, a run's working set and the
//!   budget ([`MemoryBudget`]);
//! - `cache`: the mode sets of a run over those the thread keeps, within the budget;
//!   `decide`: the box QP that decides contacts at an event;
//! - `run`: the run itself (inputs per record piece, substeps, events, peaks, outputs).
//!
//! Frames: the run advances frame by frame, a frame being one output step, or, when the run
//! asks for peaks only (no histories, no energies) on a record whose sample interval is q
//! output steps, that record interval (q output steps). Whole frames run on the mode set's
//! grid: m = q⌈Δt ρ/[`SUBSTEP_PHASE`]⌉ substeps where an output step is longer than the
//! longest substep, else q/s substeps of s output steps (s the largest divisor of q with
//! sΔt ρ ≤ [`SUBSTEP_PHASE`]); output steps are grid points either way. The output steps
//! inside a frame are observed from the substep that reaches them, and only where a
//! sampled peak can change there: every observed quantity (drifts, displacements,
//! absolute accelerations, base shear, slips) is a row r on y, and where
//! |r y| + Σ_j |y_j| Σ_{k≥1} |r Aᵏ/k!|_j hᵏ stays within its peak on a grid substep
//! (a stuck contact's slip does not change), none of the output steps inside it can
//! raise a peak or pass the collapse limit; elsewhere their states come from exp(AΔt)
//! (one product each) or the substep's Taylor coefficients. The test is made where it
//! costs less than the output steps it can spare. So a fine output step (T₁/400 of a
//! stiff one-storey frame is 15 to the record's step) costs no substeps of its own: the
//! substeps follow the dynamics (ρ) and the record.
//!
//! Once a mode set has lasted as many grid substeps as forming them costs, it caches the
//! same truncated series as a matrix, exp(A h) (and, when energies are asked for, the work
//! over h as quadratic forms of the starting state, below), and each scanned function's
//! Taylor rows r Aᵏ/k!; a grid
//! substep is then one matrix–vector product, and a scan starts from the bound
//! |g(τ) − g(0)| ≤ Σ_j |y_j| Σ_{k≥1} |r Aᵏ/k!|_j hᵏ, which rules out most of them; failing
//! that, from the same bound on the terms past the first [`LEAD_TERMS`] coefficients,
//! which are formed exactly (their negative parts at their largest). That second test
//! rules out functions that are near zero but moving away from it, which the first
//! cannot (on the benchmark it saves about 7 % of the run time). Substeps
//! off the grid (after an event, or where record samples cut a frame) sum the
//! series for their own length; when no longer than the grid interval they are ruled out
//! by the same bounds (every term grows with τ). A drift that fails them but whose rate
//! keeps one sign on the substep (its leading quadratic against a bound on the rest) has
//! its peak at the substep's end, taken without a scan. Where the mode set has no
//! propagators yet, an event function is ruled out from its first [`LEAD_TERMS`]
//! coefficients and Σ_j |r_j| Σ_{k≥L} |p_k,j| τᵏ before the rest are formed. A is applied
//! by its nonzeros: only its n acceleration rows are full.
//!
//! Contacts:
//! - a dissipator with mass that sticks is the constraint w = 0, imposed by a Lagrange
//!   multiplier λ = W_S⁻¹B_SᵀM⁻¹f (W_S = B_SᵀM⁻¹B_S): the dissipator moves with its floor and
//!   its brace acts between floors i−1 and i; the multiplier is the stuck friction force;
//! - a sliding contact applies its constant bound F⁺ or F⁻;
//! - a massless dissipator (plan `ContactKind::Epp`) carries its position x′ as a state:
//!   stuck, ẋ′ = ẋᵢ and its force is k′(x′ − xᵢ₋₁) + c′(ẋᵢ − ẋᵢ₋₁) (an elastic brace between
//!   the floors); sliding, its force is the bound and the brace follows
//!   k′(x′ − xᵢ₋₁) + c′(ẋ′ − ẋᵢ₋₁) = F±, i.e. ẋ′ = ẋᵢ₋₁ for c′ = 0 and the first-order law
//!   ẋ′ = ẋᵢ₋₁ + (F± − k′(x′ − xᵢ₋₁))/c′ for c′ > 0 (a Maxwell element, exact as well; its
//!   rate k′/c′ enters ρ, so a tiny c′ costs substeps).
//! - a dissipator with zero mass that keeps a DOF (unreduced plan) is rejected: compile
//!   with `reduce` on, which turns it into the equivalent elastic–perfectly plastic element;
//! - a yielding storey's plastic element (plan `ContactRole::Storey`) is an
//!   elastic–perfectly plastic contact like a massless dissipator, between the storey's
//!   floors; its work is the plastic energy, kept apart from friction, and its changes are
//!   no dissipator's transitions.
//!
//! Events: a stuck contact's force reaching a bound, a sliding contact's slip rate reaching
//! zero. Each event function g (positive while the mode is consistent) is scanned at
//! [`SCAN_POINTS`] points per substep together with ġ; a sign change, or a local minimum
//! (ġ from − to +) below −ε, brackets the first crossing, which the Illinois method locates
//! to about 1e-14 s. ε is the grazing threshold: [`GRAZE_REL`] times the force bound (force
//! functions) or the largest floor velocity so far (slip-rate functions). A function that
//! touches zero without going below −ε is a grazing contact and no event. At an event:
//! - a stuck contact whose force reached a bound slides toward it (forces are continuous
//!   there, so no other contact changes);
//! - a massless dissipator whose slip rate reached zero sticks;
//! - a dissipator with mass whose slip rate reached zero, together with every stuck one,
//!   is decided at once by the box QP at the acceleration level (Delassus B_UᵀM⁻¹B_U, as
//!   `newmark`'s initial state): Free = stick, a bound = slide that way (reversal). The
//!   velocities are then projected M-orthogonally onto B_Sᵀv = 0 (the residual of the
//!   located root, ~1e-11 m/s; its kinetic energy goes to friction). The same projection
//!   is repeated at the end of every frame, so round-off drift of the stuck constraints
//!   cannot accumulate over many substeps (it matters on very stiff braces, k′ ~ 1e12 N/m);
//! - a contact with F⁻ = F⁺ (μN = 0 in an unreduced plan) applies that force and has no
//!   events.
//!
//! Chattering rule: a run whose substep estimate duration·ρ/[`SUBSTEP_PHASE`] exceeds
//! [`MAX_SUBSTEPS`], or whose events exceed [`MAX_EVENTS`], stops with
//! [`SimError::ExactBudget`](crate::error::SimError::ExactBudget) (light, stiff dissipators ring too fast for an event-driven
//! reference: use `newmark`, or the massless limit). More than 4·contacts + 16 events at one
//! instant (less than 1e-14 s apart) is Zeno behaviour: [`SimError::ExactZeno`](crate::error::SimError::ExactZeno).
//!
//! Peaks: drift peaks are those of the continuous solution (each storey's drift extremum
//! located inside its substep by the same root finding on the drift rate); the peaks at
//! the output steps are reported beside them (`Diagnostics::sampled_peak_drift`). Other
//! peaks (displacement, acceleration, base shear, slip) are taken at the output steps,
//! where a drift past the plan's collapse limit also stops the run (`Response::collapse`).
//! Energies: input, viscous, friction and (yielding storeys) plastic powers integrated by 6-point Gauss–Legendre on
//! every substep (exact to degree 11; with phase 2ρτ ≤ 1 the rule's error term is below
//! 2e-16 of the powers' scale: Davis & Rabinowitz 1984, §2.7).
//! Each power is a quadratic form p(y) = yᵀ Q_p y of the augmented state, so on the grid
//! substeps of a lasting mode set the rule is summed once, W_p = h Σ_g w_g Φ_gᵀ Q_p Φ_g
//! (Φ_g = exp(A x_g h)), and a substep's work is yᵀ W_p y: the same quadrature, three
//! matrix–vector products instead of six states and their powers.

mod cache;
mod decide;
mod energy;
mod gauss;
mod kernels;
mod memory;
mod model;
mod modes;
mod params;
mod propagate;
mod run;
mod search;

pub use cache::release_thread_cache;
pub use memory::{MemoryBudget, working_set_bytes};
pub use params::{
    GRAZE_REL, LEAD_TERMS, MAX_EVENTS, MAX_SUBSTEPS, MEMORY_CAP, MEMORY_FLOOR, MODE_CACHE,
    MODE_SETS_KEPT, SCAN_POINTS, SUBSTEP_PHASE, TAYLOR_TERMS,
};
pub use run::Exact;
pub(crate) use run::check;
