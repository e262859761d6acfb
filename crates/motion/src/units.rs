//! Acceleration units of input files.
//!
//! Contract: [`Units::to_m_s2`] is the factor from the unit to m/s²; g is standard gravity
//! [`crate::G`] = 9.80665 m/s² (the value PEER uses), 1 gal = 1 cm/s² = 0.01 m/s².

/// Standard gravity, m/s² per g (the value used by PEER and by ASCE 7).
pub const G: f64 = 9.80665;

/// The unit of acceleration values in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Units {
    /// Standard gravity, g = 9.80665 m/s² (PEER AT2 files).
    G,
    /// m/s² (the default for text/CSV records).
    MPerS2,
    /// cm/s² (gal).
    CmPerS2,
}

impl Units {
    /// Multiply a value in this unit by this factor to get m/s².
    pub fn to_m_s2(self) -> f64 {
        match self {
            Units::G => G,
            Units::MPerS2 => 1.0,
            Units::CmPerS2 => 0.01,
        }
    }
}

impl std::fmt::Display for Units {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Units::G => "g",
            Units::MPerS2 => "m/s2",
            Units::CmPerS2 => "cm/s2",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MotionError;

    #[test]
    fn parses_every_spelling() {
        for (s, u) in [
            ("g", Units::G),
            (" G ", Units::G),
            ("m/s2", Units::MPerS2),
            ("m/s^2", Units::MPerS2),
            ("cm/s2", Units::CmPerS2),
            ("gal", Units::CmPerS2),
            ("GAL", Units::CmPerS2),
        ] {
            assert_eq!(s.parse::<Units>().unwrap(), u, "{s}");
            assert_eq!(u.to_string().parse::<Units>().unwrap(), u);
        }
        assert!(matches!(
            "ft/s2".parse::<Units>(),
            Err(MotionError::UnknownUnits { .. })
        ));
    }
}
