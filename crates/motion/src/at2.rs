//! The PEER NGA `.AT2` reader.
//!
//! Contract ([`parse_at2`]): the header is the first line that names NPTS and DT in one of
//! the two PEER layouts, matched case-insensitively:
//!
//! * `NPTS=  4000, DT= .01000 SEC` — comma after the NPTS value optional, `SEC` and a
//!   trailing comma optional, anything after (filter data) ignored;
//! * `2999    0.0100    NPTS, DT` (early NGA).
//!
//! The lines before it are free text (no fixed count). Exactly NPTS values are read from
//! the lines after it, any number per line; more values than NPTS is an error
//! ([`MotionError::NptsMismatch`]), text after the NPTS-th value is ignored. A value beyond
//! [`crate::MAX_ABS_ACCEL_G`] is an error ([`MotionError::Implausible`]). A header DT
//! that is not finite and positive, below [`crate::MIN_RECORD_DT_S`] or beyond
//! [`crate::MAX_RECORD_DT_S`] is refused, and so is an NPTS of zero or larger than the
//! text after the header can hold (two bytes a value) — before any value is read.
//! Values are in g and are converted with [`crate::G`]. Numbers may lack a leading zero
//! (`-.64E-02`) or use a `D` exponent. A line whose blank-separated tokens are not all
//! numbers is read as fixed-width columns (the width taken from the first data line,
//! e.g. 10 for `8F10.5`), and failing that by splitting touching numbers at their signs
//! (`-0.00123-0.00456`). CR, CRLF, a UTF-8 byte-order mark and a missing final newline
//! are all accepted.
//!
//! Units: a title line (before the header) may state the unit of the values, as PEER's
//! `ACCELERATION TIME SERIES IN UNITS OF G` does (the rule is that of
//! [`crate::unit_label`]). [`parse_at2`] reads the values in the unit the title states,
//! else in g, and refuses a unit slipload does not convert
//! ([`MotionError::UnknownHeaderUnits`]). [`parse_at2_in`] reads them in the unit it is
//! given; when the title states another one, the record carries a note that says so
//! ([`Record::notes`]).
//!
//! Malformed input gives a [`MotionError`]; the reader never panics.

use crate::error::snippet;
use crate::number::{parse_number, split_touching};
use crate::unit_label::{Stated, stated_in_at2_title};
use crate::{MotionError, Record, Units};

/// Reads a PEER `.AT2` record from its text, the values in the unit its title states
/// (PEER's files: g), else in g; `name` names it in errors and becomes the record's name.
pub fn parse_at2(text: &str, name: &str) -> Result<Record, MotionError> {
    read_at2(text, name, None)
}

/// Like [`parse_at2`], with the values read in `units` whatever the title says (for files
/// that use the AT2 layout with other units). When the title states another unit, the
/// record's [`Record::notes`] say that `units` overrode it.
pub fn parse_at2_in(text: &str, name: &str, units: Units) -> Result<Record, MotionError> {
    read_at2(text, name, Some(units))
}

/// The unit the title lines (`lines` before the header) state, with the 1-based line
/// and its text, if any.
fn title_units<'a>(lines: &[&'a str]) -> Option<(Stated, usize, &'a str)> {
    lines.iter().enumerate().find_map(|(i, l)| {
        let stated = stated_in_at2_title(l);
        (stated != Stated::Nothing).then(|| (stated, i + 1, l.trim()))
    })
}

fn read_at2(text: &str, name: &str, given: Option<Units>) -> Result<Record, MotionError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines: Vec<&str> = text.split('\n').map(|l| l.trim_end_matches('\r')).collect();
    let header = find_header(&lines, name)?;
    let stated = title_units(&lines[..header.line_index]);
    let mut override_note = None;
    let units = match (&stated, given) {
        (None | Some((Stated::Nothing, ..)), given) => given.unwrap_or(Units::G),
        (Some((Stated::Known(u), ..)), None) => *u,
        (Some((Stated::Unknown(unit), line, text)), None) => {
            return Err(MotionError::UnknownHeaderUnits {
                file: name.to_string(),
                line: *line,
                header: snippet(text),
                unit: snippet(unit),
            });
        }
        (Some((Stated::Known(u), ..)), Some(g)) if *u == g => g,
        (Some((said, line, text)), Some(g)) => {
            let said = match said {
                Stated::Known(u) => u.to_string(),
                Stated::Unknown(w) => w.clone(),
                Stated::Nothing => String::new(),
            };
            override_note = Some(format!(
                "{name}: values read in {g} as given, not in {said} as its header says (line {line}: `{}`)",
                snippet(text)
            ));
            g
        }
    };
    crate::record::check_record_dt(name, header.dt_s)?;
    if header.npts == 0 {
        return Err(MotionError::Empty {
            file: name.to_string(),
        });
    }
    // a value takes at least two bytes (a digit and a separator; the last one may lack
    // its separator): a header that announces more cannot describe this file
    let max_values = text.len().saturating_sub(
        lines[..=header.line_index]
            .iter()
            .map(|l| l.len() + 1)
            .sum::<usize>(),
    ) / 2
        + 1;
    if header.npts > max_values {
        return Err(MotionError::NptsBeyondFile {
            file: name.to_string(),
            line: header.line_index + 1,
            npts: header.npts,
            file_bytes: text.len(),
            max_values,
        });
    }
    let factor = units.to_m_s2();
    // Never trust NPTS for an allocation: a value takes at least two bytes.
    let mut values = Vec::with_capacity(header.npts);
    let mut width: Option<usize> = None;
    let limit = crate::max_abs_accel_m_s2();
    // values beyond NPTS: counted (a header that disagrees with its data is an error)
    let mut extra = 0usize;
    for (index, line) in lines.iter().enumerate().skip(header.line_index + 1) {
        let line_no = index + 1;
        let tokens = match split_line(line, width) {
            Ok(t) => t,
            // text after the NPTS-th value (an end marker, a note) is not data
            Err(_) if values.len() == header.npts => break,
            Err(token) => {
                return Err(MotionError::NotANumber {
                    file: name.to_string(),
                    line: line_no,
                    token: snippet(token),
                    expected: "an acceleration value in g",
                });
            }
        };
        if width.is_none() && !tokens.is_empty() {
            width = column_width(line, tokens.len());
        }
        for (token, value) in tokens {
            if values.len() == header.npts {
                extra += 1;
                continue;
            }
            let a = value * factor;
            if !a.is_finite() {
                return Err(MotionError::NonFinite {
                    file: name.to_string(),
                    line: line_no,
                    token: snippet(token),
                });
            }
            if a.abs() > limit {
                return Err(MotionError::Implausible {
                    file: name.to_string(),
                    line: line_no,
                    token: snippet(token),
                    accel_g: a / crate::G,
                    limit_g: crate::MAX_ABS_ACCEL_G,
                    units: units.to_string(),
                });
            }
            values.push(a);
        }
    }
    if extra > 0 {
        return Err(MotionError::NptsMismatch {
            file: name.to_string(),
            npts: header.npts,
            found: header.npts + extra,
        });
    }
    if values.len() < header.npts {
        return Err(MotionError::Truncated {
            file: name.to_string(),
            expected: header.npts,
            found: values.len(),
        });
    }
    let title: Vec<&str> = lines[..header.line_index]
        .iter()
        .map(|l| l.trim())
        .filter(|l| !l.is_empty())
        .collect();
    let provenance = format!(
        "PEER AT2 {name}: {}; header line {}: NPTS = {}, DT = {} s; values in {units} converted to m/s2",
        title.join(" | "),
        header.line_index + 1,
        header.npts,
        header.dt_s,
    );
    let record = Record::new(name, header.dt_s, values)?.with_provenance(provenance);
    Ok(match override_note {
        Some(note) => record.with_note(note),
        None => record,
    })
}

/// NPTS and DT and where they were found.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Header {
    line_index: usize,
    npts: usize,
    dt_s: f64,
}

/// The first line that parses as a header. If lines mention NPTS but none parses, the
/// first of them is reported as malformed.
fn find_header(lines: &[&str], name: &str) -> Result<Header, MotionError> {
    let mut first_candidate: Option<usize> = None;
    for (index, line) in lines.iter().enumerate() {
        let upper = line.to_ascii_uppercase();
        if !upper.contains("NPTS") {
            continue;
        }
        if let Some((npts, dt_s)) = header_equals_form(&upper).or_else(|| header_nga1_form(&upper))
        {
            return Ok(Header {
                line_index: index,
                npts,
                dt_s,
            });
        }
        first_candidate.get_or_insert(index);
    }
    match first_candidate {
        Some(index) => Err(MotionError::MalformedHeader {
            file: name.to_string(),
            line: index + 1,
            text: snippet(lines[index].trim()),
            expected: "`NPTS= n, DT= dt` or `n dt NPTS, DT` with n a whole number",
        }),
        None => Err(MotionError::MissingHeader {
            file: name.to_string(),
        }),
    }
}

/// `NPTS\s*=\s*(\d+)` followed somewhere by `DT\s*=\s*([-+0-9.ED]+)`, on an upper-cased line.
fn header_equals_form(upper: &str) -> Option<(usize, f64)> {
    let after_npts = &upper[upper.find("NPTS")? + 4..];
    let rest = after_npts.trim_start().strip_prefix('=')?.trim_start();
    let digits_end = rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len());
    let npts: usize = rest[..digits_end].parse().ok()?;
    let mut search = &rest[digits_end..];
    while let Some(pos) = search.find("DT") {
        let after = &search[pos + 2..];
        if let Some(value) = after.trim_start().strip_prefix('=') {
            let value = value.trim_start();
            let end = value
                .find(|c: char| !(c.is_ascii_digit() || matches!(c, '-' | '+' | '.' | 'E' | 'D')))
                .unwrap_or(value.len());
            return Some((npts, parse_number(&value[..end])?));
        }
        search = after;
    }
    None
}

/// `^\s*(\d+)\s+(\S+)\s+NPTS\s*,\s*DT`, on an upper-cased line.
fn header_nga1_form(upper: &str) -> Option<(usize, f64)> {
    let mut tokens = upper.split_whitespace();
    let npts: usize = tokens.next()?.parse().ok()?;
    let dt_s = parse_number(tokens.next()?)?;
    let rest: String = tokens.collect::<Vec<_>>().concat();
    rest.starts_with("NPTS,DT").then_some((npts, dt_s))
}

/// The numbers on one data line with their source text, trying blank-separated tokens,
/// then fixed-width columns of `width`, then touching numbers split at their signs.
/// Returns the first token that fails every reading.
fn split_line(line: &str, width: Option<usize>) -> Result<Vec<(&str, f64)>, &str> {
    let by_blanks: Vec<&str> = line.split_whitespace().collect();
    if let Some(v) = parse_all(&by_blanks) {
        return Ok(v);
    }
    if let Some(w) = width.filter(|_| line.is_ascii()) {
        let fields: Vec<&str> = (0..line.len())
            .step_by(w)
            .map(|start| line[start..(start + w).min(line.len())].trim())
            .filter(|f| !f.is_empty())
            .collect();
        if let Some(v) = parse_all(&fields) {
            return Ok(v);
        }
    }
    let pieces: Vec<&str> = by_blanks.iter().flat_map(|t| split_touching(t)).collect();
    if let Some(v) = parse_all(&pieces) {
        return Ok(v);
    }
    let bad = by_blanks
        .iter()
        .find(|t| parse_number(t).is_none())
        .copied()
        .unwrap_or(line);
    Err(bad)
}

fn parse_all<'a>(tokens: &[&'a str]) -> Option<Vec<(&'a str, f64)>> {
    tokens
        .iter()
        .map(|t| Some((*t, parse_number(t)?)))
        .collect()
}

/// The field width of a fixed-column line holding `count` values, when its length (trailing
/// blanks removed) is a whole multiple of `count`.
fn column_width(line: &str, count: usize) -> Option<usize> {
    let len = line.trim_end().len();
    (line.is_ascii() && len > 0 && len.is_multiple_of(count)).then_some(len / count)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_forms() {
        let h = |s: &str| header_equals_form(&s.to_ascii_uppercase());
        assert_eq!(h("NPTS=  4000, DT= .01000 SEC"), Some((4000, 0.01)));
        assert_eq!(h("NPTS=   7500  DT=   .0200 SEC,"), Some((7500, 0.02)));
        assert_eq!(
            h("NPTS=   1991, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 POLE @      .05000"),
            Some((1991, 0.01))
        );
        assert_eq!(h("NPTS=   1451, dt=  .02000"), Some((1451, 0.02)));
        assert_eq!(h("NPTS= x, DT= 0.01"), None);
        assert_eq!(h("NPTS= 10"), None);
        assert_eq!(
            header_nga1_form("2999    0.0100    NPTS, DT"),
            Some((2999, 0.01))
        );
        assert_eq!(header_nga1_form("2999 0.0100 NPTS DT"), None);
    }

    #[test]
    fn fixed_width_lines() {
        assert_eq!(column_width("   0.00630   0.00364", 2), Some(10));
        let v = split_line("  -0.00123-100.00456   0.00100", Some(10)).unwrap();
        let values: Vec<f64> = v.iter().map(|p| p.1).collect();
        assert_eq!(values, vec![-0.00123, -100.00456, 0.001]);
        let v = split_line("-0.00123-0.00456", None).unwrap();
        assert_eq!(v.len(), 2);
        assert_eq!(split_line("0.1 abc 0.3", Some(4)).unwrap_err(), "abc");
    }
}
