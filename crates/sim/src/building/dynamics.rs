//! A building's dynamics as an engineer states them: the bare frame's modes with the
//! damping ratio each has, and the periods with the dampers stuck (every brace a storey
//! spring) and slipping (a slipping damper adds no stiffness: the bare frame's).

use super::check::lock_brace;
use super::validated::Building;
use crate::modes::Modes;
use std::fmt::Write as _;

/// Off-diagonal terms of ΦᵀCΦ below this fraction of the geometric mean of their
/// diagonal terms leave the modes uncoupled: the damping is classical (Rayleigh, modal
/// and stiffness-proportional storey dashpots are, up to round-off ~1e-15).
const CLASSICAL_COUPLING: f64 = 1e-9;

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
        let (mut k, mut m) = (self.stiffness.clone(), self.mass.clone());
        let mut any = false;
        for (floor, d) in self.dissipators.iter().enumerate() {
            if let Some(d) = d.filter(|d| !d.is_free()) {
                lock_brace(&mut k, &mut m, floor, &d);
                any = true;
            }
        }
        Dynamics {
            damping_ratios,
            classical,
            stuck: if any { Modes::compute(&m, &k) } else { None },
        }
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
