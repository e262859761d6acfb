//! A resolved scene ([`Scene`]): the validated building, the ground motion, the harmonic
//! force and initial state in SI units, the method's settings and what to compute — what
//! a plan is compiled from.

use super::config::OutputsConfig;
use super::method::MethodSettings;
use crate::building::Building;
use slipload_motion::Record;
use std::sync::Arc;

/// A harmonic floor force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Floor index from 0.
    pub floor: usize,
    /// Amplitude, N.
    pub amplitude: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// Phase, rad.
    pub phase: f64,
}

impl Harmonic {
    /// P(t), N.
    #[inline]
    pub fn force(&self, t: f64) -> f64 {
        self.amplitude * (self.omega * t + self.phase).sin()
    }
}

/// Initial state, SI, one entry per floor.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialState {
    /// Floor displacements, m.
    pub floor_displacement: Vec<f64>,
    /// Floor velocities, m/s.
    pub floor_velocity: Vec<f64>,
    /// Dissipator displacements, m.
    pub dissipator_displacement: Vec<f64>,
    /// Dissipator velocities, m/s.
    pub dissipator_velocity: Vec<f64>,
}

impl InitialState {
    /// At rest.
    pub fn rest(n: usize) -> Self {
        InitialState {
            floor_displacement: vec![0.0; n],
            floor_velocity: vec![0.0; n],
            dissipator_displacement: vec![0.0; n],
            dissipator_velocity: vec![0.0; n],
        }
    }
    /// True when everything is zero.
    pub fn is_rest(&self) -> bool {
        [
            &self.floor_displacement,
            &self.floor_velocity,
            &self.dissipator_displacement,
            &self.dissipator_velocity,
        ]
        .iter()
        .all(|v| v.iter().all(|x| *x == 0.0))
    }
}

/// A resolved scene, ready to compile into a plan.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Name.
    pub name: String,
    /// The building.
    pub building: Building,
    /// Ground acceleration record, m/s².
    pub record: Option<Arc<Record>>,
    /// Harmonic floor force.
    pub harmonic: Option<Harmonic>,
    /// Initial state.
    pub initial: InitialState,
    /// Simulated time, s.
    pub duration: f64,
    /// Method.
    pub method: MethodSettings,
    /// What to compute.
    pub outputs: OutputsConfig,
    /// Compile into a reduced plan.
    pub reduce: bool,
    /// What the scene decided that the user should hear about (a window or duration
    /// past the record's end, a nominal duration for `explain`), one sentence each.
    pub notes: Vec<String>,
}

impl Scene {
    /// Ground acceleration at `t`, m/s² (zero without a record and after its end).
    #[inline]
    pub fn ground_accel(&self, t: f64) -> f64 {
        self.record.as_ref().map_or(0.0, |r| r.accel_at(t))
    }

    /// Number of steps: enough to reach the duration (the last step ends at or just after
    /// it; a relative slack of 1e-9 absorbs the round-off of duration/dt), at least one.
    pub fn steps(&self) -> usize {
        ((self.duration / self.method.dt * (1.0 - 1e-9)).ceil() as usize).max(1)
    }
}
