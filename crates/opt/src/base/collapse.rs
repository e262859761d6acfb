//! Collapse said in words. A design that collapses on a record of a study (the run passed
//! the building's drift limit and stopped) has the objective +∞ in memory
//! ([`crate::Objective::value`]), so it ranks after every design that stands; no table,
//! summary or JSON file shows that value as a number. Objectives are written
//! [`COLLAPSED`]; a reduction against the bare frame is [`COLLAPSED`] for a collapsed
//! design and [`BARE_COLLAPSED`] when only the reference collapsed (never "100 % lower");
//! the residual drift of a run that stopped is not reported.
//!
//! In memory a reduction carries the two cases as −∞ (the design collapsed) and +∞ (only
//! the bare frame did) ([`reduction`]); the serde helpers [`objective_serde`] and
//! [`reduction_serde`] write them as those words and read them back.

/// The word for a collapsed design's objective (and a statistic with no finished run).
pub const COLLAPSED: &str = "collapsed";
/// The word for a reduction whose reference, the bare frame, collapsed.
pub const BARE_COLLAPSED: &str = "bare frame collapsed";

/// 1 − f / f_bare, with collapses kept apart: −∞ when the design collapsed, +∞ when
/// only the bare frame did, 0 against a zero reference.
pub fn reduction(f: f64, f_bare: f64) -> f64 {
    if f == f64::INFINITY {
        f64::NEG_INFINITY
    } else if f_bare == f64::INFINITY {
        f64::INFINITY
    } else if f_bare != 0.0 {
        1.0 - f / f_bare
    } else {
        0.0
    }
}

/// An objective for a table: the value (`digits` decimals, or in full with `None`), or
/// [`COLLAPSED`].
pub fn objective_text(f: f64, digits: Option<usize>) -> String {
    if f.is_finite() {
        match digits {
            Some(d) => format!("{f:.d$}"),
            None => f.to_string(),
        }
    } else {
        COLLAPSED.to_string()
    }
}

/// A reduction for a table: as a percentage with `digits` decimals and " %"
/// (`percent`), or the plain fraction in full; or the words of a collapse.
pub fn reduction_text(r: f64, percent: Option<usize>) -> String {
    if r == f64::NEG_INFINITY {
        COLLAPSED.to_string()
    } else if r == f64::INFINITY {
        BARE_COLLAPSED.to_string()
    } else {
        match percent {
            Some(d) => format!("{:.d$} %", 100.0 * r),
            None => r.to_string(),
        }
    }
}

/// A value that is a number, or a word for a collapse.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(untagged)]
enum NumberOrWord {
    Number(f64),
    Word(String),
}

fn word_value<E: serde::de::Error>(w: &str, words: &[(&str, f64)]) -> Result<f64, E> {
    words
        .iter()
        .find(|(word, _)| *word == w)
        .map(|&(_, v)| v)
        .ok_or_else(|| {
            E::custom(format!(
                "expected a number or one of {:?}, got {w:?}",
                words.iter().map(|(w, _)| *w).collect::<Vec<_>>()
            ))
        })
}

/// Serde for an objective (or a mean over finished runs): a JSON number, or
/// `"collapsed"` for +∞.
pub mod objective_serde {
    use super::*;

    /// Writes the number, or `"collapsed"`.
    pub fn serialize<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        if v.is_finite() {
            NumberOrWord::Number(*v).serialize(s)
        } else {
            NumberOrWord::Word(COLLAPSED.into()).serialize(s)
        }
    }

    /// Reads a number, or `"collapsed"` as +∞.
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        use serde::Deserialize;
        match NumberOrWord::deserialize(d)? {
            NumberOrWord::Number(v) => Ok(v),
            NumberOrWord::Word(w) => word_value(&w, &[(COLLAPSED, f64::INFINITY)]),
        }
    }
}

/// Serde for a list of objectives ([`objective_serde`] for each).
pub mod objectives_serde {
    use super::*;

    /// Writes each number, or `"collapsed"`.
    pub fn serialize<S: serde::Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        v.iter()
            .map(|&x| {
                if x.is_finite() {
                    NumberOrWord::Number(x)
                } else {
                    NumberOrWord::Word(COLLAPSED.into())
                }
            })
            .collect::<Vec<_>>()
            .serialize(s)
    }

    /// Reads numbers, `"collapsed"` as +∞.
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        use serde::Deserialize;
        Vec::<NumberOrWord>::deserialize(d)?
            .into_iter()
            .map(|x| match x {
                NumberOrWord::Number(v) => Ok(v),
                NumberOrWord::Word(w) => word_value(&w, &[(COLLAPSED, f64::INFINITY)]),
            })
            .collect()
    }
}

/// Serde for a reduction ([`reduction`]): a JSON number, `"collapsed"` (−∞) or
/// `"bare frame collapsed"` (+∞).
pub mod reduction_serde {
    use super::*;

    /// Writes the number or the words.
    pub fn serialize<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        if v.is_finite() {
            NumberOrWord::Number(*v).serialize(s)
        } else {
            NumberOrWord::Word(reduction_text(*v, None)).serialize(s)
        }
    }

    /// Reads a number or the words.
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        use serde::Deserialize;
        match NumberOrWord::deserialize(d)? {
            NumberOrWord::Number(v) => Ok(v),
            NumberOrWord::Word(w) => word_value(
                &w,
                &[
                    (COLLAPSED, f64::NEG_INFINITY),
                    (BARE_COLLAPSED, f64::INFINITY),
                ],
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collapses_are_words_never_numbers() {
        assert_eq!(
            reduction_text(reduction(f64::INFINITY, 1.0), Some(1)),
            "collapsed"
        );
        assert_eq!(
            reduction_text(reduction(0.5, f64::INFINITY), Some(1)),
            "bare frame collapsed"
        );
        assert_eq!(
            reduction_text(reduction(f64::INFINITY, f64::INFINITY), Some(1)),
            "collapsed"
        );
        assert_eq!(reduction_text(reduction(0.5, 1.0), Some(1)), "50.0 %");
        assert_eq!(objective_text(f64::INFINITY, Some(5)), "collapsed");
        assert_eq!(objective_text(0.25, Some(2)), "0.25");
    }
}
