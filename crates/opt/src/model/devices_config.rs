//! The study key `devices` ([`DevicesConfig`]): what the device table needs beyond the
//! building — the braces' geometry, the devices' stroke capacity and the test protocol.

use crate::base::error::OptError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Most braces one damper's force is shared by (`devices.braces_per_damper`).
pub const MAX_BRACES_PER_DAMPER: usize = 8;

/// The study key `devices`: the geometry the device specification needs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DevicesConfig {
    /// The brace's angle to the horizontal, degrees (0 ≤ θ < 90): the device table then
    /// gives the brace's axial force F/cos θ and axial stiffness k′/cos²θ, where F and k′
    /// are the storey-level (horizontal) force and stiffness the building gives.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brace_angle_deg: Option<f64>,
    /// Braces that carry one damper's force, each at the brace angle (1: a single
    /// diagonal, the default; 2: a chevron or inverted V): the device table then gives
    /// each brace's axial force F/(n cos θ) and stiffness k′/(n cos²θ).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub braces_per_damper: Option<usize>,
    /// The devices' stroke capacity each way from their neutral position, mm: in every
    /// suite with limits a run in which any damper's peak |slip| exceeds it responds
    /// unacceptably (it is counted with the collapses), and the device table states each
    /// damper's stroke against it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke_capacity_mm: Option<f64>,
    /// Each damper's brace's axial design strength, kN, one per damper bottom to top
    /// (needs `brace_angle_deg`): the brace is a force-controlled element, and the force
    /// the damper can put into it is its slip load at the upper property bound, so every
    /// design of the space must keep λ_max F / (n cos θ) within it (a space that does not
    /// is refused naming the bound), and the check states each brace's demand.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brace_capacity_kn: Option<Vec<f64>>,
    /// The prototype and production test protocol the device table writes
    /// ([`TestProtocolConfig`]); none: no protocol.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub test_protocol: Option<TestProtocolConfig>,
    /// How many devices make up each storey's damper, and the redundancy rule that
    /// raises their design values when they are few ([`RedundancyConfig`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub redundancy: Option<RedundancyConfig>,
}

/// The study key `devices.redundancy`: the devices each storey's damper stands for, and
/// the rule that raises the design values of few devices (docs/MODEL.md § Redundancy).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RedundancyConfig {
    /// Devices per storey in the direction analysed (the model's damper is their sum).
    pub devices_per_storey: u32,
    /// Devices on each side of the storey's centre of rigidity (the fewer side), when
    /// the study states it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub devices_per_side: Option<u32>,
    /// Fewer devices per storey than this raise the design values; default 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_per_storey: Option<u32>,
    /// Fewer devices on a side than this raise them; default 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_per_side: Option<u32>,
    /// The factor on the design displacement and velocity; default 1.3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factor: Option<f64>,
}

impl RedundancyConfig {
    /// Fewer devices per storey than this raise the design values (default 4).
    pub const MIN_PER_STOREY: u32 = 4;
    /// Fewer devices on a side than this raise them (default 2).
    pub const MIN_PER_SIDE: u32 = 2;
    /// The factor on the design values (default 1.3).
    pub const FACTOR: f64 = 1.3;

    /// Whether the rule raises the design values, and why (in words).
    pub fn applies(&self) -> (bool, String) {
        let min_storey = self.min_per_storey.unwrap_or(Self::MIN_PER_STOREY);
        let min_side = self.min_per_side.unwrap_or(Self::MIN_PER_SIDE);
        let mut why = Vec::new();
        if self.devices_per_storey < min_storey {
            why.push(format!(
                "{} devices per storey, fewer than {min_storey}",
                self.devices_per_storey
            ));
        }
        if let Some(side) = self.devices_per_side
            && side < min_side
        {
            why.push(format!(
                "{side} on a side of the centre of rigidity, fewer than {min_side}"
            ));
        }
        if why.is_empty() {
            (
                false,
                format!(
                    "{} devices per storey{}: at least {min_storey} per storey{}",
                    self.devices_per_storey,
                    self.devices_per_side
                        .map_or(String::new(), |s| format!(", {s} on each side")),
                    if self.devices_per_side.is_some() {
                        format!(" and {min_side} per side")
                    } else {
                        String::new()
                    }
                ),
            )
        } else {
            (true, why.join("; "))
        }
    }

    fn validate(&self, path: &Path) -> Result<(), OptError> {
        let bad = |field: &str, why: String| {
            Err(OptError::invalid(
                path,
                format!("devices.redundancy.{field}"),
                why,
            ))
        };
        if self.devices_per_storey == 0 {
            return bad(
                "devices_per_storey",
                "at least 1: the devices each storey's damper stands for".into(),
            );
        }
        if let Some(s) = self.devices_per_side
            && (s == 0 || 2 * s > self.devices_per_storey)
        {
            return bad(
                "devices_per_side",
                format!(
                    "{s}: the devices on the fewer side, at least 1 and at most half of devices_per_storey ({})",
                    self.devices_per_storey
                ),
            );
        }
        if let Some(f) = self.factor
            && !(f.is_finite() && (1.0..=3.0).contains(&f))
        {
            return bad("factor", format!("{f}: a factor from 1 to 3 (default 1.3)"));
        }
        Ok(())
    }
}

/// The study key `devices.test_protocol`: the numbers of the device tests the study
/// follows (ASCE 7-16 §18.6.2 asks for a prototype test at the maximum damper
/// displacement at the frequency 1/T_1M, a wind-cycle test unless exempt, acceptance
/// bands on each cycle, and production tests; the study states the counts and bands its
/// specification uses, and the device table computes the amplitudes, frequencies and
/// velocities from the response history).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TestProtocolConfig {
    /// Fully reversed sinusoidal cycles of the prototype test at the maximum damper
    /// displacement.
    pub cycles: u32,
    /// Acceptance band, percent: each cycle's largest and smallest force and its loop
    /// energy within ± this of the test's average.
    pub band_percent: f64,
    /// Cycles of the wind test at the frame's first frequency (none: the study claims the
    /// exemption, which the protocol states with its condition).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind_cycles: Option<u32>,
    /// Factor on the test amplitude (EN 15129's amplification of the design displacement
    /// where the study follows it); default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement_factor: Option<f64>,
    /// Cycles of each unit's production test at the test amplitude (none: no production
    /// test sheet).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub production_cycles: Option<u32>,
}

/// Most cycles a test of `devices.test_protocol` may ask for.
pub const MAX_TEST_CYCLES: u32 = 100_000;

impl DevicesConfig {
    /// Every key in range; errors name the field (`devices.…`) of the study at `path`.
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        if let Some(t) = self.brace_angle_deg
            && !(t.is_finite() && (0.0..90.0).contains(&t))
        {
            return Err(OptError::invalid(
                path,
                "devices.brace_angle_deg",
                format!("must be in [0, 90) degrees from the horizontal, got {t}"),
            ));
        }
        if let Some(n) = self.braces_per_damper {
            if !(1..=MAX_BRACES_PER_DAMPER).contains(&n) {
                return Err(OptError::invalid(
                    path,
                    "devices.braces_per_damper",
                    format!(
                        "must be 1 (a single diagonal) to {MAX_BRACES_PER_DAMPER} (2: a chevron), got {n}"
                    ),
                ));
            }
            if self.brace_angle_deg.is_none() {
                return Err(OptError::invalid(
                    path,
                    "devices.braces_per_damper",
                    "the braces' forces and stiffnesses need their angle: give devices.brace_angle_deg",
                ));
            }
        }
        if let Some(r) = &self.redundancy {
            r.validate(path)?;
        }
        if let Some(c) = self.stroke_capacity_mm
            && !(c.is_finite() && c > 0.0)
        {
            return Err(OptError::invalid(
                path,
                "devices.stroke_capacity_mm",
                format!("must be a finite stroke > 0 mm (each way), got {c}"),
            ));
        }
        if let Some(caps) = &self.brace_capacity_kn {
            if self.brace_angle_deg.is_none() {
                return Err(OptError::invalid(
                    path,
                    "devices.brace_capacity_kn",
                    "a brace's axial force needs its angle: give devices.brace_angle_deg",
                ));
            }
            if let Some((i, c)) = caps
                .iter()
                .enumerate()
                .find(|(_, c)| !(c.is_finite() && **c > 0.0))
            {
                return Err(OptError::invalid(
                    path,
                    format!("devices.brace_capacity_kn[{i}]"),
                    format!("must be an axial strength > 0 kN, got {c}"),
                ));
            }
        }
        if let Some(t) = self.test_protocol {
            t.validate(path)?;
        }
        Ok(())
    }
}

impl TestProtocolConfig {
    /// Counts and band in range; errors name `devices.test_protocol.…` of the study at
    /// `path` (a chain study's or a study in plan's: the key is the same).
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        let t = self;
        let field = |f: &str| format!("devices.test_protocol.{f}");
        for (name, n) in [
            ("cycles", Some(t.cycles)),
            ("wind_cycles", t.wind_cycles),
            ("production_cycles", t.production_cycles),
        ] {
            if let Some(n) = n
                && !(1..=MAX_TEST_CYCLES).contains(&n)
            {
                return Err(OptError::invalid(
                    path,
                    field(name),
                    format!("must be a count of cycles from 1 to {MAX_TEST_CYCLES}, got {n}"),
                ));
            }
        }
        if !(t.band_percent.is_finite() && t.band_percent > 0.0 && t.band_percent < 100.0) {
            return Err(OptError::invalid(
                path,
                field("band_percent"),
                format!(
                    "must be a band in (0, 100) percent of the test's average, got {}",
                    t.band_percent
                ),
            ));
        }
        if let Some(f) = t.displacement_factor
            && !(f.is_finite() && (1.0..=10.0).contains(&f))
        {
            return Err(OptError::invalid(
                path,
                field("displacement_factor"),
                format!(
                    "must be a factor from 1 to 10 on the maximum damper displacement, got {f}"
                ),
            ));
        }
        Ok(())
    }
}
