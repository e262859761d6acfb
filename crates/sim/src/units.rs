//! Physical quantities in configs: a bare number is SI; a string carries a unit, as an
//! engineer writes it (`"448.12 MN/m"`, `"834.095 kN"`, `"350.11 kg"`, `"3.96 m"`).
//!
//! Each quantity type accepts only units of its own dimension, so `"834 kN"` where a
//! stiffness is expected is an error that names what was expected.

use serde::de::{self, Deserializer, Visitor};
use std::fmt;

/// A physical dimension with its accepted units and their factors to SI.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// Mass, kg.
    Mass,
    /// Force, N.
    Force,
    /// Stiffness, N/m.
    Stiffness,
    /// Viscous damping coefficient, N·s/m.
    Damping,
    /// Length, m.
    Length,
    /// Time, s.
    Time,
    /// Velocity, m/s.
    Velocity,
    /// Circular frequency, rad/s.
    AngularFrequency,
    /// Angle, rad.
    Angle,
}

impl Dimension {
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Dimension::Mass => &[("kg", 1.0), ("t", 1e3), ("g", 1e-3)],
            Dimension::Force => &[("N", 1.0), ("kN", 1e3), ("MN", 1e6)],
            Dimension::Stiffness => &[
                ("N/m", 1.0),
                ("kN/m", 1e3),
                ("MN/m", 1e6),
                ("GN/m", 1e9),
                ("N/mm", 1e3),
                ("kN/mm", 1e6),
            ],
            Dimension::Damping => &[
                ("N·s/m", 1.0),
                ("N*s/m", 1.0),
                ("Ns/m", 1.0),
                ("N s/m", 1.0),
                ("kN·s/m", 1e3),
                ("kN*s/m", 1e3),
                ("kNs/m", 1e3),
                ("kN s/m", 1e3),
                ("MN·s/m", 1e6),
                ("MN*s/m", 1e6),
            ],
            Dimension::Length => &[("m", 1.0), ("cm", 1e-2), ("mm", 1e-3)],
            Dimension::Time => &[("s", 1.0), ("ms", 1e-3)],
            Dimension::Velocity => &[("m/s", 1.0), ("cm/s", 1e-2), ("mm/s", 1e-3)],
            Dimension::AngularFrequency => &[("rad/s", 1.0), ("Hz", std::f64::consts::TAU)],
            Dimension::Angle => &[("rad", 1.0), ("deg", std::f64::consts::PI / 180.0)],
        }
    }

    /// SI unit name and an example, for error messages.
    fn expected(self) -> &'static str {
        match self {
            Dimension::Mass => "a mass in kg, or a string like \"350.11 kg\" or \"478 t\"",
            Dimension::Force => "a force in N, or a string like \"834.095 kN\"",
            Dimension::Stiffness => "a stiffness in N/m, or a string like \"448.12 MN/m\"",
            Dimension::Damping => {
                "a damping coefficient in N·s/m, or a string like \"13.12 kN·s/m\""
            }
            Dimension::Length => "a length in m, or a string like \"3.96 m\"",
            Dimension::Time => "a time in s, or a string like \"10 s\"",
            Dimension::Velocity => "a velocity in m/s, or a string like \"50 cm/s\"",
            Dimension::AngularFrequency => {
                "a circular frequency in rad/s, or a string like \"15.98 rad/s\" or \"2.5 Hz\""
            }
            Dimension::Angle => "an angle in rad, or a string like \"0.5 rad\" or \"90 deg\"",
        }
    }
}

/// Parses `"value unit"` (or a bare number) as a quantity of dimension `dim`, in SI.
pub fn parse_quantity(text: &str, dim: Dimension) -> Result<f64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .unwrap_or(t.len());
    // A unit may start with 'e'? None of ours does, but "1e5" must stay a number.
    let (num, unit) = t.split_at(split);
    let value: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("expected {}, got {text:?}", dim.expected()))?;
    let unit = unit.trim();
    let factor = if unit.is_empty() {
        1.0
    } else {
        dim.units()
            .iter()
            .find(|(u, _)| *u == unit)
            .map(|(_, f)| *f)
            .ok_or_else(|| {
                let names: Vec<&str> = dim.units().iter().map(|(u, _)| *u).collect();
                format!(
                    "unknown unit {unit:?} in {text:?}: expected {} (units: {})",
                    dim.expected(),
                    names.join(", ")
                )
            })?
    };
    let v = value * factor;
    if !v.is_finite() {
        return Err(format!("{text:?} is not a finite number"));
    }
    Ok(v)
}

struct QuantityVisitor(Dimension);

impl Visitor<'_> for QuantityVisitor {
    type Value = f64;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0.expected())
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        Ok(v)
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<f64, E> {
        parse_quantity(v, self.0).map_err(E::custom)
    }
}

macro_rules! quantity {
    ($(#[$doc:meta])* $name:ident, $dim:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
        #[serde(transparent)]
        pub struct $name(pub f64);
        impl<'de> serde::Deserialize<'de> for $name {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                d.deserialize_any(QuantityVisitor($dim)).map($name)
            }
        }
        impl From<$name> for f64 {
            fn from(q: $name) -> f64 {
                q.0
            }
        }
    };
}

quantity!(
    /// A mass in kg (config value).
    Mass,
    Dimension::Mass
);
quantity!(
    /// A force in N (config value).
    Force,
    Dimension::Force
);
quantity!(
    /// A stiffness in N/m (config value).
    Stiffness,
    Dimension::Stiffness
);
quantity!(
    /// A viscous damping coefficient in N·s/m (config value).
    Damping,
    Dimension::Damping
);
quantity!(
    /// A length in m (config value).
    Length,
    Dimension::Length
);
quantity!(
    /// A time in s (config value).
    Time,
    Dimension::Time
);
quantity!(
    /// A velocity in m/s (config value).
    Velocity,
    Dimension::Velocity
);
quantity!(
    /// A circular frequency in rad/s (config value; `"2.5 Hz"` is 2π·2.5 rad/s).
    AngularFrequency,
    Dimension::AngularFrequency
);
quantity!(
    /// An angle in rad (config value).
    Angle,
    Dimension::Angle
);

/// A number for people: six significant digits, trailing zeros dropped (0.002, not
/// 0.0020000000000006963); exponent form for very large or small ones.
pub fn short_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor();
    if !(-4.0..9.0).contains(&magnitude) {
        return format!("{x:.5e}");
    }
    let decimals = (5.0 - magnitude).max(0.0) as usize;
    let text = format!("{x:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// True for a finite x > 0 (false for NaN and ±∞).
#[inline]
pub fn is_positive(x: f64) -> bool {
    x > 0.0 && x.is_finite()
}

/// True for a finite x ≥ 0 (false for NaN and ±∞).
#[inline]
pub fn is_non_negative(x: f64) -> bool {
    x >= 0.0 && x.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_engineering_units() {
        assert_eq!(
            parse_quantity("448.12 MN/m", Dimension::Stiffness).unwrap(),
            448.12e6
        );
        assert_eq!(
            parse_quantity("834.095 kN", Dimension::Force).unwrap(),
            834_095.0
        );
        assert_eq!(
            parse_quantity("350.11 kg", Dimension::Mass).unwrap(),
            350.11
        );
        assert_eq!(
            parse_quantity("4.78e5 kg", Dimension::Mass).unwrap(),
            4.78e5
        );
        assert_eq!(parse_quantity("3.96", Dimension::Length).unwrap(), 3.96);
        assert_eq!(
            parse_quantity("13.12177 kN·s/m", Dimension::Damping).unwrap(),
            13121.77
        );
    }

    #[test]
    fn parses_times_velocities_frequencies_and_angles() {
        assert_eq!(parse_quantity("2s", Dimension::Time).unwrap(), 2.0);
        assert_eq!(parse_quantity("5 ms", Dimension::Time).unwrap(), 5e-3);
        assert_eq!(parse_quantity("50 cm/s", Dimension::Velocity).unwrap(), 0.5);
        assert_eq!(
            parse_quantity("2 Hz", Dimension::AngularFrequency).unwrap(),
            4.0 * std::f64::consts::PI
        );
        assert_eq!(
            parse_quantity("180 deg", Dimension::Angle).unwrap(),
            std::f64::consts::PI
        );
        let e = parse_quantity("2 m", Dimension::Time).unwrap_err();
        assert!(e.contains("a time in s"), "{e}");
    }

    #[test]
    fn rejects_wrong_dimension_and_garbage() {
        let e = parse_quantity("834 kN", Dimension::Stiffness).unwrap_err();
        assert!(e.contains("stiffness") && e.contains("kN"), "{e}");
        assert!(parse_quantity("abc", Dimension::Force).is_err());
        assert!(parse_quantity("1e999 N", Dimension::Force).is_err());
    }

    #[test]
    fn deserializes_numbers_and_strings() {
        let v: Vec<Force> = serde_json::from_str(r#"[1000, "2 kN", 3.5]"#).unwrap();
        assert_eq!(v, vec![Force(1000.0), Force(2000.0), Force(3.5)]);
        let e = serde_json::from_str::<Force>(r#""2 kg""#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("force"), "{e}");
    }
}
