//! A building's dynamics as an engineer states them: the bare frame's modes with the
//! damping ratio each has, the periods with the dampers stuck (every brace a storey
//! spring) and slipping (a slipping damper adds no stiffness: the bare frame's), and the
//! periods a code-scaled suite's range is built from ([`ScalingPeriods`]).

use super::check::lock_brace;
use super::validated::Building;
use crate::modes::Modes;
use nalgebra::DMatrix;
use std::fmt::Write as _;

/// Off-diagonal terms of ΦᵀCΦ below this fraction of the geometric mean of their
/// diagonal terms leave the modes uncoupled: the damping is classical (Rayleigh, modal
/// and stiffness-proportional storey dashpots are, up to round-off ~1e-15).
const CLASSICAL_COUPLING: f64 = 1e-9;

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
pub(crate) struct MassParticipation {
    pub(crate) modes: usize,
    pub(crate) period_s: f64,
}

impl MassParticipation {
    pub(crate) fn of(
        m: &DMatrix<f64>,
        modes: &Modes,
        r: &nalgebra::DVector<f64>,
    ) -> MassParticipation {
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

/// The modal facts of a building ([`Building::dynamics`]).
#[derive(Debug, Clone)]
pub struct Dynamics {
    /// Damping ratio of each bare-frame mode (first mode first): (φₙᵀCφₙ)/(2ωₙ) with
    /// mass-normalised shapes, exact for classical damping.
    pub damping_ratios: Vec<f64>,
    /// Whether the frame damping is classical (ΦᵀCΦ diagonal): otherwise the ratios are
    /// the diagonal's and the modes couple through damping.
    pub classical: bool,
    /// Modes with every damper that can stick stuck (braces as storey springs, the
    /// dissipators' masses on their floors); `None` without such a damper, or when that
    /// frame has no modes (refused elsewhere).
    pub stuck: Option<Modes>,
}

impl Building {
    /// The damping ratio of each bare-frame mode and the modes with the dampers stuck.
    pub fn dynamics(&self) -> Dynamics {
        let phi = &self.modes.shapes;
        let c = phi.transpose() * &self.damping * phi;
        let n = c.nrows();
        let damping_ratios = (0..n)
            .map(|i| c[(i, i)] / (2.0 * self.modes.omega[i]))
            .collect();
        let classical = (0..n).all(|i| {
            (0..n).all(|j| {
                i == j
                    || c[(i, j)].abs()
                        <= CLASSICAL_COUPLING * (c[(i, i)].abs() * c[(j, j)].abs()).sqrt()
            })
        });
        let any = self.dissipators.iter().flatten().any(|d| !d.is_free());
        Dynamics {
            damping_ratios,
            classical,
            stuck: if any { self.stuck(false).1 } else { None },
        }
    }

    /// The frame with its dampers stuck (each brace a storey spring between floors i − 1
    /// and i, its m′ moving with floor i: docs/MODEL.md § The model, μN → ∞) — every
    /// damper (`all`: the slip loads a design may give them), or those whose contact can
    /// stick as the building stands (not free) — as its mass matrix and its modes
    /// (`None`: none).
    fn stuck(&self, all: bool) -> (DMatrix<f64>, Option<Modes>) {
        let (mut k, mut m) = (self.stiffness.clone(), self.mass.clone());
        for (floor, d) in self.dissipators.iter().enumerate() {
            if let Some(d) = d.filter(|d| all || !d.is_free()) {
                lock_brace(&mut k, &mut m, floor, &d);
            }
        }
        let modes = Modes::compute(&m, &k);
        (m, modes)
    }

    /// The first periods the range of a code-scaled suite is built from
    /// ([`ScalingPeriods`]); `None` when the braced frame has no modes (an unstable or
    /// massless frame, which validation refuses before).
    pub fn scaling_periods(&self) -> Option<ScalingPeriods> {
        let n = self.floors();
        let ones = nalgebra::DVector::from_element(n, 1.0);
        let bare = MassParticipation::of(&self.mass, &self.modes, &ones);
        // every damper stuck, whatever the file's slip load: a design gives it one
        let (m, stuck_modes) = self.stuck(true);
        let stuck_modes = stuck_modes?;
        let stuck = MassParticipation::of(&m, &stuck_modes, &ones);
        Some(ScalingPeriods {
            bare_t1_s: self.t1(),
            stuck_t1_s: 2.0 * std::f64::consts::PI / stuck_modes.omega[0],
            bare_modes_90: bare.modes,
            stuck_modes_90: stuck.modes,
            mass_90_period_s: bare.period_s.min(stuck.period_s),
        })
    }

    /// The bare frame's periods, mode shapes (each scaled to a largest entry of 1, floors
    /// bottom to top) and damping ratios, and the periods with the dampers stuck and
    /// slipping: what `slipload explain` prints first.
    pub fn describe_modes(&self) -> String {
        let dy = self.dynamics();
        let list = |ts: &[f64]| {
            ts.iter()
                .map(|t| format!("{t:.4}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut s = String::new();
        let periods = self.modes.periods();
        let _ = writeln!(
            s,
            "bare frame of {}: {} floors, periods (s) [{}]",
            self.name,
            self.floors(),
            list(&periods)
        );
        for (k, t) in periods.iter().enumerate() {
            let col = self.modes.shapes.column(k);
            let peak = col
                .iter()
                .fold(0.0f64, |m, v| if v.abs() > m.abs() { *v } else { m });
            let shape: Vec<String> = col
                .iter()
                .map(|v| format!("{:.4}", if peak != 0.0 { v / peak } else { *v }))
                .collect();
            let _ = writeln!(
                s,
                "  mode {}: T = {t:.4} s, shape [{}], damping {:.2} %",
                k + 1,
                shape.join(", "),
                100.0 * dy.damping_ratios[k]
            );
        }
        if !dy.classical {
            let _ = writeln!(
                s,
                "  (the frame damping is not classical: the modes couple through it; each ratio is the diagonal term of its mode)"
            );
        }
        match &dy.stuck {
            Some(stuck) => {
                let _ = writeln!(
                    s,
                    "dampers stuck (braces as storey springs, dissipator masses on their floors): periods (s) [{}]",
                    list(&stuck.periods())
                );
                let _ = writeln!(
                    s,
                    "dampers slipping: the bare frame's periods (a slipping damper adds no stiffness to its storey{})",
                    if self.dissipators.iter().flatten().any(|d| d.mass > 0.0) {
                        "; a dissipator's mass rides on its brace"
                    } else {
                        ""
                    }
                );
            }
            None => {
                let _ = writeln!(s, "no damper that can stick: the bare frame's periods hold");
            }
        }
        s
    }
}
