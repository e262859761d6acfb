//! A validated building ([`Building`]) and its validated parts ([`Dissipator`],
//! [`StoreyYield`]), SI units, with what they answer by themselves.

use crate::modes::Modes;
use nalgebra::DMatrix;

/// A validated yielding storey, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StoreyYield {
    /// Initial stiffness k of the storey spring, N/m.
    pub stiffness: f64,
    /// Yield shear Fy, N.
    pub yield_shear: f64,
    /// Post-yield stiffness ratio α in [0, 1).
    pub post_yield_ratio: f64,
}

impl StoreyYield {
    /// Yield drift Fy/k, m.
    pub fn yield_drift(&self) -> f64 {
        self.yield_shear / self.stiffness
    }
}

/// A validated dissipator, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dissipator {
    /// Brace stiffness k′, N/m.
    pub brace_stiffness: f64,
    /// Dissipator mass m′, kg.
    pub mass: f64,
    /// Brace damping c′, N·s/m.
    pub brace_damping: f64,
    /// Lower friction bound F⁻ ≤ 0, N (−∞ when locked).
    pub lower: f64,
    /// Upper friction bound F⁺ ≥ 0, N (+∞ when locked).
    pub upper: f64,
}

impl Dissipator {
    /// True when the contact can never slip.
    pub fn is_locked(&self) -> bool {
        self.upper == f64::INFINITY && self.lower == f64::NEG_INFINITY
    }
    /// True when the contact transmits no force.
    pub fn is_free(&self) -> bool {
        self.upper == 0.0 && self.lower == 0.0
    }
}

/// The periods a code-scaled suite's range is built from: the first period of the frame
/// with its dampers slipping (the bare frame: a slipping damper adds a force, no
/// stiffness) and with them stuck (every brace acting as a storey spring), and the modes
/// that make up 90 % of the mass in each state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScalingPeriods {
    /// First period of the bare frame (dampers slipping), s.
    pub bare_t1_s: f64,
    /// First period with every damper stuck (braced), s.
    pub stuck_t1_s: f64,
    /// How many modes of the bare frame make up 90 % of its mass.
    pub bare_modes_90: usize,
    /// How many modes of the braced frame make up 90 % of its mass.
    pub stuck_modes_90: usize,
    /// The shorter of the two frames' periods of the last of those modes, s.
    pub mass_90_period_s: f64,
}

/// The modes (in ascending frequency) whose effective masses first add up to 90 % of the
/// total, for ground motion along `r`.
struct MassParticipation {
    modes: usize,
    period_s: f64,
}

impl MassParticipation {
    fn of(m: &DMatrix<f64>, modes: &Modes, r: &nalgebra::DVector<f64>) -> MassParticipation {
        // mass-normalised shapes: effective mass of mode k = (φₖᵀ M r)²; their sum over all
        // modes is rᵀ M r
        let mr = m * r;
        let total = r.dot(&mr);
        let mut sum = 0.0;
        let n = modes.omega.len();
        for k in 0..n {
            let gamma = modes.shapes.column(k).dot(&mr);
            sum += gamma * gamma;
            if sum >= 0.9 * total || k + 1 == n {
                return MassParticipation {
                    modes: k + 1,
                    period_s: 2.0 * std::f64::consts::PI / modes.omega[k],
                };
            }
        }
        MassParticipation {
            modes: n,
            period_s: 2.0 * std::f64::consts::PI / modes.omega[n - 1],
        }
    }
}

/// A validated building, SI units, floors numbered 0..n from the bottom.
#[derive(Debug, Clone)]
pub struct Building {
    /// Name.
    pub name: String,
    /// Frame mass matrix Mˢˢ (kg).
    pub mass: DMatrix<f64>,
    /// Frame stiffness matrix Kˢˢ (N/m).
    pub stiffness: DMatrix<f64>,
    /// Frame damping matrix Cˢˢ (N·s/m).
    pub damping: DMatrix<f64>,
    /// Storey heights (m), when given.
    pub storey_heights: Option<Vec<f64>>,
    /// Dissipator of each floor, if any.
    pub dissipators: Vec<Option<Dissipator>>,
    /// Yield law of each storey, if it yields (`None`: elastic).
    pub storey_yield: Vec<Option<StoreyYield>>,
    /// P-Δ gravity load Pᵢ of each storey (N), when P-Δ is on.
    pub gravity_loads: Option<Vec<f64>>,
    /// Drift of each storey (m) past which a run stops with a collapse, when set.
    pub collapse_drift: Option<Vec<f64>>,
    /// Modes of the bare frame.
    pub modes: Modes,
}

impl Building {
    /// Whether any storey yields or P-Δ acts (effects beyond the linear frame).
    pub fn is_nonlinear_frame(&self) -> bool {
        self.storey_yield.iter().any(Option::is_some) || self.gravity_loads.is_some()
    }

    /// Number of floors.
    pub fn floors(&self) -> usize {
        self.mass.nrows()
    }

    /// Fundamental period of the bare frame, s.
    pub fn t1(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.modes.omega[0]
    }

    /// The first periods the range of a code-scaled suite is built from
    /// ([`ScalingPeriods`]); `None` when the braced frame has no modes (an unstable or
    /// massless frame, which validation refuses before).
    pub fn scaling_periods(&self) -> Option<ScalingPeriods> {
        let n = self.floors();
        let ones = nalgebra::DVector::from_element(n, 1.0);
        let bare = MassParticipation::of(&self.mass, &self.modes, &ones);
        // every dissipator stuck: its brace k′ is a storey spring between floors i−1 and i,
        // its mass m′ moves with floor i (docs/MODEL.md § The model, μN → ∞)
        let mut m = self.mass.clone();
        let mut k = self.stiffness.clone();
        for (i, d) in self.dissipators.iter().enumerate() {
            let Some(d) = d else { continue };
            m[(i, i)] += d.mass;
            k[(i, i)] += d.brace_stiffness;
            if i > 0 {
                k[(i - 1, i - 1)] += d.brace_stiffness;
                k[(i - 1, i)] -= d.brace_stiffness;
                k[(i, i - 1)] -= d.brace_stiffness;
            }
        }
        let stuck_modes = Modes::compute(&m, &k)?;
        let stuck = MassParticipation::of(&m, &stuck_modes, &ones);
        Some(ScalingPeriods {
            bare_t1_s: self.t1(),
            stuck_t1_s: 2.0 * std::f64::consts::PI / stuck_modes.omega[0],
            bare_modes_90: bare.modes,
            stuck_modes_90: stuck.modes,
            mass_90_period_s: bare.period_s.min(stuck.period_s),
        })
    }

    /// Replaces the slip load of every dissipator by `slip_loads[i]` (N; `None` keeps the
    /// floor as it is). Used by sweeps.
    pub fn with_slip_loads(&self, slip_loads: &[Option<f64>]) -> Building {
        let mut b = self.clone();
        for (d, s) in b.dissipators.iter_mut().zip(slip_loads) {
            if let (Some(d), Some(s)) = (d.as_mut(), s) {
                d.lower = -s;
                d.upper = *s;
            }
        }
        b
    }
}
