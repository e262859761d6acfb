//! The periods a code-scaled suite of a study in plan is built on
//! ([`FloorPlan::scaling_periods`]): the first-mode period of each principal horizontal
//! direction, with the dampers slipping (the bare frame) and stuck (every brace a spring
//! along its line), and the modes that make up 90 % of the mass along each direction;
//! and the secant periods a device test is run at ([`FloorPlan::secant_periods`]).

use super::build::{line_ends, line_point};
use super::model::FloorPlan;
use crate::building::{MassParticipation, ScalingPeriods};
use crate::kinematics::{Kin, add_between};
use crate::modes::Modes;
use nalgebra::{DMatrix, DVector};

/// A plan's modes read along x and y.
struct Directions {
    /// The first-mode period of each direction (the mode with the largest effective mass
    /// along it), s.
    first: [f64; 2],
    /// The modes that make up 90 % of the mass along each direction.
    ninety: [MassParticipation; 2],
}

fn directions(mass: &DMatrix<f64>, modes: &Modes) -> Directions {
    let n = mass.nrows() / 3;
    let along = |d: usize| {
        let mut r = DVector::zeros(3 * n);
        for f in 0..n {
            r[3 * f + d] = 1.0;
        }
        r
    };
    let first = |r: &DVector<f64>| {
        let mr = mass * r;
        let mut best = (0.0, 0);
        for k in 0..modes.omega.len() {
            let gamma = modes.shapes.column(k).dot(&mr);
            if gamma * gamma > best.0 {
                best = (gamma * gamma, k);
            }
        }
        2.0 * std::f64::consts::PI / modes.omega[best.1]
    };
    let (rx, ry) = (along(0), along(1));
    Directions {
        first: [first(&rx), first(&ry)],
        ninety: [
            MassParticipation::of(mass, modes, &rx),
            MassParticipation::of(mass, modes, &ry),
        ],
    }
}

impl FloorPlan {
    /// The periods a code-scaled suite's range is built from (ASCE 7-16 §16.2.3.1 reads
    /// them in the principal horizontal directions): `bare_t1_s` the larger first-mode
    /// period of x and y with the dampers slipping (the bare frame; a direction's first
    /// mode is the one with the largest effective mass along it, so a first mode that is
    /// mostly twist does not set it), `stuck_t1_s` the smaller with every damper stuck
    /// (its brace a spring along its line, its mass on the line's point), the modes
    /// making up 90 % of the mass along each direction (the larger count of the two) and
    /// the shortest period of the last of them over both directions and both frames.
    /// `None` when the braced plan has no modes.
    pub fn scaling_periods(&self) -> Option<ScalingPeriods> {
        let (mut k, mut m) = (self.stiffness.clone(), self.mass.clone());
        for line in &self.lines {
            for (f, d) in line.dissipators.iter().enumerate() {
                let Some(d) = d else { continue };
                let (top, bottom) = line_ends(line, f);
                add_between(&mut k, &top, &bottom, d.brace_stiffness);
                add_between(&mut m, &line_point(line, f), &Kin::GROUND, d.mass);
            }
        }
        let stuck_modes = Modes::compute(&m, &k)?;
        let bare = directions(&self.mass, &self.modes);
        let stuck = directions(&m, &stuck_modes);
        let shortest = [&bare, &stuck]
            .iter()
            .flat_map(|d| d.ninety.iter().map(|p| p.period_s))
            .fold(f64::INFINITY, f64::min);
        let count = |d: &Directions| d.ninety[0].modes.max(d.ninety[1].modes);
        Some(ScalingPeriods {
            bare_t1_s: bare.first[0].max(bare.first[1]),
            stuck_t1_s: stuck.first[0].min(stuck.first[1]),
            bare_modes_90: count(&bare),
            stuck_modes_90: count(&stuck),
            mass_90_period_s: shortest,
        })
    }
}

impl FloorPlan {
    /// The first-mode periods along x and along y (s) of the plan with every line's storey
    /// at its secant stiffness at the drift `drift[line][storey]` (m, along the line;
    /// `None` or 0: its initial stiffness): a yielding storey at its bilinear secant, a
    /// damper with slip load `force[line][storey]` (N) as F/δ in series with nothing once
    /// its brace would carry more than F (it slips), else its brace k′ — the frame whose
    /// period ASCE 7-16 §18.6.2 runs the prototype test at (T_1M at the maximum
    /// displacement). Damper masses are left out (they set no frame period). `None` when
    /// the secant plan has no positive mode.
    pub fn secant_periods(
        &self,
        drift: &[Vec<Option<f64>>],
        force: &[Vec<f64>],
    ) -> Option<[f64; 2]> {
        let mut k = self.stiffness.clone();
        for (l, line) in self.lines.iter().enumerate() {
            for f in 0..self.storeys() {
                let Some(d) = drift
                    .get(l)
                    .and_then(|v| v.get(f))
                    .copied()
                    .flatten()
                    .map(f64::abs)
                    .filter(|d| *d > 0.0)
                else {
                    continue;
                };
                let mut add = 0.0;
                if let Some(y) = line.storey_yield[f]
                    && d > y.yield_drift()
                {
                    let secant = (y.yield_shear
                        + y.post_yield_ratio * y.stiffness * (d - y.yield_drift()))
                        / d;
                    add -= y.stiffness - secant;
                }
                if let Some(b) = line.dissipators[f] {
                    let fs = force.get(l).and_then(|v| v.get(f)).copied().unwrap_or(0.0);
                    add += if d * b.brace_stiffness > fs {
                        fs / d
                    } else {
                        b.brace_stiffness
                    };
                }
                if add != 0.0 {
                    let (top, bottom) = line_ends(line, f);
                    add_between(&mut k, &top, &bottom, add);
                }
            }
        }
        let modes = Modes::compute(&self.mass, &k)?;
        if !modes.omega.iter().all(|w| *w > 0.0 && w.is_finite()) {
            return None;
        }
        Some(directions(&self.mass, &modes).first)
    }
}
