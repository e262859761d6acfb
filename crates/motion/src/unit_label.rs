//! The acceleration unit a file states in words: a CSV column header or an AT2 title.
//!
//! Contract ([`stated_in_label`], [`stated_in_at2_title`]): a unit is *stated* when one of
//! the spellings below stands as a word of the label, matched case-insensitively:
//!
//! | unit | spellings |
//! |---|---|
//! | g | `g` |
//! | m/s² | `m/s2`, `m/s^2`, `m/s²`, `m/s/s`, `m/sec2`, `m/sec^2`, `m/sec/sec`, `mps2` |
//! | cm/s² | `cm/s2`, `cm/s^2`, `cm/s²`, `cm/s/s`, `cm/sec2`, `cm/sec^2`, `cm/sec/sec`, `cmps2`, `gal` |
//!
//! In a column header (the label of the acceleration column: the header's last field) the
//! unit is looked for, in this order, inside each pair of brackets (`accel (g)`,
//! `acc [cm/s2]`, `a (in g)`), then in the label without its brackets: its last word, or
//! its last two or three words read as one unit with `/` between them (words are
//! separated by `_`, blanks, `:` and `=`: `accel_g`, `a_g`, `acc_m_s2` = m/s²,
//! `accel_cm_s_s` = cm/s², `accel gal`). In an AT2 title the unit is the word after
//! `UNITS` (skipping `OF`, `ARE`, `:` or `=`, brackets and a final `.`/`,`/`;` around it),
//! as PEER writes it: `ACCELERATION TIME SERIES IN UNITS OF G`, `The units are (g)`.
//!
//! A word that reads as an acceleration unit slipload does not convert (it holds a `/`
//! and ends in `s2`, `s^2`, `s²`, `/s/s`, `sec2`, `sec^2` or `/sec/sec`: `ft/s2`,
//! `in/sec/sec`, `accel_ft_s2`) is reported as [`Stated::Unknown`], so that the caller
//! refuses it instead of reading the values in another unit. Anything else states no unit.

use crate::{MotionError, Units};

/// What a label says about the unit of its values.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Stated {
    /// No unit is named.
    Nothing,
    /// A unit slipload reads.
    Known(Units),
    /// A word that names an acceleration unit slipload does not convert (as written,
    /// lower-cased).
    Unknown(String),
}

/// The unit one of the spellings of the module table names, if any (`word` lower-cased).
fn known(word: &str) -> Option<Units> {
    match word {
        "g" => Some(Units::G),
        "m/s2" | "m/s^2" | "m/s²" | "m/s/s" | "m/sec2" | "m/sec^2" | "m/sec/sec" | "mps2" => {
            Some(Units::MPerS2)
        }
        "cm/s2" | "cm/s^2" | "cm/s²" | "cm/s/s" | "cm/sec2" | "cm/sec^2" | "cm/sec/sec"
        | "cmps2" | "gal" => Some(Units::CmPerS2),
        _ => None,
    }
}

/// `true` for a word that reads as an acceleration unit (see the module docs).
fn looks_like_acceleration(word: &str) -> bool {
    word.contains('/')
        && ["s2", "s^2", "s²", "/s/s", "sec2", "sec^2", "/sec/sec"]
            .iter()
            .any(|end| word.ends_with(end))
}

/// The unit stated by `words` (a label split into words): the last word, or the last two
/// or three joined by `/`.
fn stated_by_words(words: &[&str]) -> Stated {
    let tail = |k: usize| (k <= words.len()).then(|| words[words.len() - k..].join("/"));
    for k in 1..=3 {
        if let Some(u) = tail(k).as_deref().and_then(known) {
            return Stated::Known(u);
        }
    }
    for k in 1..=2 {
        if let Some(w) = tail(k).filter(|w| looks_like_acceleration(w)) {
            return Stated::Unknown(w);
        }
    }
    Stated::Nothing
}

fn split_words(text: &str) -> Vec<&str> {
    text.split(|c: char| c == '_' || c == ':' || c == '=' || c.is_whitespace())
        .filter(|w| !w.is_empty())
        .collect()
}

/// The unit a column label states (see the module docs).
pub(crate) fn stated_in_label(label: &str) -> Stated {
    let lower = label.trim().to_lowercase();
    let mut outside = String::new();
    let mut unknown: Option<String> = None;
    let mut rest = lower.as_str();
    while let Some(open) = rest.find(['(', '[']) {
        outside.push_str(&rest[..open]);
        outside.push(' ');
        let close_char = if rest[open..].starts_with('(') {
            ')'
        } else {
            ']'
        };
        let inner_start = open + 1;
        let inner_end = rest[inner_start..]
            .find(close_char)
            .map_or(rest.len(), |e| inner_start + e);
        match stated_by_words(&split_words(&rest[inner_start..inner_end])) {
            Stated::Known(u) => return Stated::Known(u),
            Stated::Unknown(w) => {
                unknown.get_or_insert(w);
            }
            Stated::Nothing => {}
        }
        rest = rest.get(inner_end + 1..).unwrap_or("");
    }
    outside.push_str(rest);
    match stated_by_words(&split_words(&outside)) {
        Stated::Nothing => unknown.map_or(Stated::Nothing, Stated::Unknown),
        found => found,
    }
}

/// The unit an AT2 title line states after the word `UNITS` (see the module docs).
pub(crate) fn stated_in_at2_title(line: &str) -> Stated {
    let lower = line.to_lowercase();
    let Some(at) = lower.find("units") else {
        return Stated::Nothing;
    };
    let mut words = lower[at + "units".len()..]
        .split(|c: char| c.is_whitespace() || c == ':' || c == '=')
        .filter(|w| !w.is_empty())
        .skip_while(|w| matches!(*w, "of" | "are" | "in"));
    let Some(word) = words.next() else {
        return Stated::Nothing;
    };
    let word = word
        .trim_end_matches(['.', ',', ';'])
        .trim_start_matches(['(', '['])
        .trim_end_matches([')', ']'])
        .trim_end_matches(['.', ',', ';']);
    match known(word) {
        Some(u) => Stated::Known(u),
        None if looks_like_acceleration(word) => Stated::Unknown(word.to_string()),
        None => Stated::Nothing,
    }
}

impl std::str::FromStr for Units {
    type Err = MotionError;

    /// Accepts (case-insensitive, surrounding blanks ignored) `g`, `m/s2`, `m/s^2`,
    /// `m/s²`, `cm/s2`, `cm/s^2`, `cm/s²`, `gal`.
    fn from_str(s: &str) -> Result<Units, MotionError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "g" => Ok(Units::G),
            "m/s2" | "m/s^2" | "m/s²" => Ok(Units::MPerS2),
            "cm/s2" | "cm/s^2" | "cm/s²" | "gal" => Ok(Units::CmPerS2),
            _ => Err(MotionError::UnknownUnits {
                given: crate::error::snippet(s),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_labels() {
        let k = |s: &str| stated_in_label(s);
        for (label, u) in [
            ("accel_g", Units::G),
            ("a_g", Units::G),
            ("ACC_G", Units::G),
            ("accel (g)", Units::G),
            ("accel(g)", Units::G),
            ("a (in g)", Units::G),
            ("acc_m_s2", Units::MPerS2),
            ("accel_m_s2", Units::MPerS2),
            ("accel [m/s^2]", Units::MPerS2),
            ("accel m/s²", Units::MPerS2),
            ("a_mps2", Units::MPerS2),
            ("accel_cm_s2", Units::CmPerS2),
            ("cm/s2", Units::CmPerS2),
            ("Acc [cm/s/s]", Units::CmPerS2),
            ("accel_gal", Units::CmPerS2),
            ("gal", Units::CmPerS2),
            ("accel_cm_s_s", Units::CmPerS2),
            ("acc (NS) [g]", Units::G),
        ] {
            assert_eq!(k(label), Stated::Known(u), "{label}");
        }
        for label in [
            "accel", "a", "t", "time_s", "x", "acc_ns", "signal", "s2", "gs", "(none)",
        ] {
            assert_eq!(k(label), Stated::Nothing, "{label}");
        }
        assert_eq!(k("accel_ft_s2"), Stated::Unknown("ft/s2".into()));
        assert_eq!(k("a (in/sec/sec)"), Stated::Unknown("in/sec/sec".into()));
        assert_eq!(k("a [mm/s^2"), Stated::Unknown("mm/s^2".into()));
    }

    #[test]
    fn at2_titles() {
        let t = |s: &str| stated_in_at2_title(s);
        assert_eq!(
            t("ACCELERATION TIME SERIES IN UNITS OF G"),
            Stated::Known(Units::G)
        );
        assert_eq!(
            t("ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 Hz LP=23.0 Hz"),
            Stated::Known(Units::G)
        );
        assert_eq!(t("The units are (g)"), Stated::Known(Units::G));
        assert_eq!(
            t("ACCELERATION IN UNITS OF CM/SEC/SEC"),
            Stated::Known(Units::CmPerS2)
        );
        assert_eq!(t("UNITS: GAL"), Stated::Known(Units::CmPerS2));
        assert_eq!(
            t("UNITS OF FT/SEC/SEC"),
            Stated::Unknown("ft/sec/sec".into())
        );
        assert_eq!(t("PEER STRONG MOTION DATABASE RECORD"), Stated::Nothing);
        assert_eq!(t("UNITS OF MEASURE VARY"), Stated::Nothing);
        assert_eq!(t("UNITS"), Stated::Nothing);
    }
}
