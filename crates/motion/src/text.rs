//! The text/CSV record reader, and the CSV writer it round-trips with.
//!
//! Contract ([`parse_text`]): one record per file, one sample per line, either two
//! columns (time s, acceleration) or one column (acceleration, with the time step given).
//! A UTF-8 byte-order mark before the first line is not part of it. Columns are separated
//! by commas, semicolons or blanks. Blank lines and lines starting with `#` are skipped;
//! the first remaining line may be a column header (any line that does not parse as
//! numbers there is taken as one). The header's last field labels the acceleration
//! column; when it states a unit (`accel_g`, `acc (cm/s2)`, `a_m_s2`, … — the rule and
//! the spellings are those of [`crate::unit_label`]) the values are read in it, and
//! `units` given by the caller must agree with it ([`MotionError::UnitsContradictHeader`];
//! a unit slipload does not convert is [`MotionError::UnknownHeaderUnits`]). Without
//! either the values are in m/s². With a time column, the step is
//! (t_last − t_first)/(n − 1) and every step must be positive and within 0.1 % of it
//! (printed time columns carry rounding; a larger deviation means a non-uniform grid,
//! which a [`Record`] cannot represent). The record starts at its first sample: a time
//! column that starts at t₀ ≠ 0 is shifted to 0 (noted in the provenance). Values are
//! converted from `units` to m/s²; a value beyond [`crate::MAX_ABS_ACCEL_G`] is an error,
//! and so is a step outside [`crate::MIN_RECORD_DT_S`] … [`crate::MAX_RECORD_DT_S`].
//! Malformed input gives a [`MotionError`]; the reader
//! never panics. [`format_csv`] writes `time_s,accel_m_s2` that reads back bit for bit.

use crate::error::snippet;
use crate::number::{parse_number, within};
use crate::unit_label::{Stated, stated_in_label};
use crate::{MotionError, Record, Units};

/// Relative tolerance on each step of a time column (see the module docs).
const TIME_STEP_TOLERANCE: f64 = 1e-3;

/// Reads a text/CSV record. `units` are those of the acceleration column when given
/// (`Units::G` or `Some(Units::G)`: a header that states another unit is then refused);
/// `None` takes the unit the column header states, else m/s². `dt_s` (s) is required for
/// one column and, with a time column, must agree with it (to 0.1 %) and is then used as
/// the step. `name` names the record and appears in errors.
pub fn parse_text(
    text: &str,
    name: &str,
    units: impl Into<Option<Units>>,
    dt_s: Option<f64>,
) -> Result<Record, MotionError> {
    let given = units.into();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let file = || name.to_string();
    // the header (which comes before any value) may set the unit
    let mut units = given.unwrap_or(Units::MPerS2);
    let mut from_header = false;
    let mut factor = units.to_m_s2();
    let mut columns: Option<usize> = None;
    let mut column_header: Option<&str> = None;
    let mut times: Vec<(usize, f64)> = Vec::new();
    let mut accel: Vec<f64> = Vec::new();
    for (index, raw) in text.split('\n').enumerate() {
        let line_no = index + 1;
        let line = raw.trim_end_matches('\r').trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields = split_fields(line);
        let parsed: Vec<Option<f64>> = fields.iter().map(|f| parse_number(f)).collect();
        if columns.is_none() && column_header.is_none() && parsed.iter().any(Option::is_none) {
            column_header = Some(line);
            let label = fields.last().copied().unwrap_or(line);
            match stated_in_label(label) {
                Stated::Nothing => {}
                Stated::Known(stated) => {
                    if let Some(given) = given.filter(|g| *g != stated) {
                        return Err(MotionError::UnitsContradictHeader {
                            file: file(),
                            line: line_no,
                            header: snippet(line),
                            stated,
                            given,
                        });
                    }
                    units = stated;
                    from_header = true;
                    factor = units.to_m_s2();
                }
                Stated::Unknown(unit) => {
                    return Err(MotionError::UnknownHeaderUnits {
                        file: file(),
                        line: line_no,
                        header: snippet(line),
                        unit: snippet(&unit),
                    });
                }
            }
            continue;
        }
        let expected = *columns.get_or_insert(fields.len());
        if !(1..=2).contains(&expected) || fields.len() != expected {
            return Err(MotionError::ColumnCount {
                file: file(),
                line: line_no,
                expected: expected.clamp(1, 2),
                found: fields.len(),
            });
        }
        let mut values = Vec::with_capacity(2);
        for (field, value) in fields.iter().zip(&parsed) {
            let Some(v) = *value else {
                return Err(MotionError::NotANumber {
                    file: file(),
                    line: line_no,
                    token: snippet(field),
                    expected: if expected == 2 {
                        "time (s) and acceleration"
                    } else {
                        "an acceleration value"
                    },
                });
            };
            if !v.is_finite() {
                return Err(MotionError::NonFinite {
                    file: file(),
                    line: line_no,
                    token: snippet(field),
                });
            }
            values.push(v);
        }
        let a = values[values.len() - 1] * factor;
        if !a.is_finite() {
            return Err(MotionError::NonFinite {
                file: file(),
                line: line_no,
                token: snippet(fields[fields.len() - 1]),
            });
        }
        if a.abs() > crate::max_abs_accel_m_s2() {
            return Err(MotionError::Implausible {
                file: file(),
                line: line_no,
                token: snippet(fields[fields.len() - 1]),
                accel_g: a / crate::G,
                limit_g: crate::MAX_ABS_ACCEL_G,
                units: units.to_string(),
            });
        }
        if expected == 2 {
            times.push((line_no, values[0]));
        }
        accel.push(a);
    }
    if accel.is_empty() {
        return Err(MotionError::Empty { file: file() });
    }
    let mut notes = vec![format!("text record {name}")];
    if let Some(h) = column_header {
        notes.push(format!("columns `{}`", snippet(h)));
    }
    let dt = if times.is_empty() {
        let dt = dt_s.ok_or_else(|| MotionError::MissingDt { file: file() })?;
        notes.push(format!("one column, dt = {dt} s given"));
        dt
    } else {
        let step = time_column_step(&times, name)?;
        let dt = match (step, dt_s) {
            (None, None) => return Err(MotionError::MissingDt { file: file() }),
            (None, Some(given)) => given,
            (Some(found), None) => found,
            (Some(found), Some(given)) => {
                if !within(given, found, TIME_STEP_TOLERANCE) {
                    return Err(MotionError::DtMismatch {
                        file: file(),
                        given_s: given,
                        found_s: found,
                    });
                }
                given
            }
        };
        let t0 = times[0].1;
        if t0 != 0.0 {
            notes.push(format!("time column starts at {t0} s, shifted to 0"));
        }
        notes.push(format!("two columns, dt = {dt} s"));
        dt
    };
    crate::record::check_record_dt(&file(), dt)?;
    if from_header {
        notes.push(format!(
            "values in {units} (as the header says) converted to m/s2"
        ));
    } else {
        notes.push(format!("values in {units} converted to m/s2"));
    }
    Ok(Record::new(name, dt, accel)?.with_provenance(notes.join("; ")))
}

/// The record as CSV text: a `time_s,accel_m_s2` header, then one line per sample with
/// t = k·dt (s) and the acceleration (m/s²), both in Rust's shortest round-trip form, so
/// [`parse_text`] reads the samples back bit for bit.
pub fn format_csv(record: &Record) -> String {
    let mut out = String::with_capacity(24 * record.len() + 20);
    out.push_str("time_s,accel_m_s2\n");
    for (k, a) in record.samples().iter().enumerate() {
        let t = k as f64 * record.dt();
        out.push_str(&format!("{t},{a}\n"));
    }
    out
}

/// Fields of a data line: comma-, semicolon- or blank-separated; one trailing empty field
/// (`1.0,2.0,`) is dropped.
fn split_fields(line: &str) -> Vec<&str> {
    let mut fields: Vec<&str> = if line.contains(',') {
        line.split(',').map(str::trim).collect()
    } else if line.contains(';') {
        line.split(';').map(str::trim).collect()
    } else {
        line.split_whitespace().collect()
    };
    if fields.len() > 1 && fields.last().is_some_and(|f| f.is_empty()) {
        fields.pop();
    }
    fields
}

/// The uniform step of a time column (None for a single row); errors for decreasing,
/// repeated or non-uniform times.
fn time_column_step(times: &[(usize, f64)], name: &str) -> Result<Option<f64>, MotionError> {
    let (Some(&(_, first)), Some(&(_, last))) = (times.first(), times.last()) else {
        return Ok(None);
    };
    if times.len() < 2 {
        return Ok(None);
    }
    for pair in times.windows(2) {
        let ((_, previous_s), (line, time_s)) = (pair[0], pair[1]);
        if time_s <= previous_s {
            return Err(MotionError::TimeNotIncreasing {
                file: name.to_string(),
                line,
                time_s,
                previous_s,
            });
        }
    }
    let dt = (last - first) / (times.len() - 1) as f64;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(MotionError::BadTimeStep {
            file: name.to_string(),
            dt_s: dt,
        });
    }
    for pair in times.windows(2) {
        let ((_, t0), (line, t1)) = (pair[0], pair[1]);
        let step = t1 - t0;
        if !within(step, dt, TIME_STEP_TOLERANCE) {
            return Err(MotionError::NonUniformTime {
                file: name.to_string(),
                line,
                expected_s: dt,
                found_s: step,
            });
        }
    }
    Ok(Some(dt))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_columns_with_header_and_crlf() {
        let r = parse_text(
            "time_s,accel_m_s2\r\n0,0.1\r\n0.01,0.2\r\n0.02,-0.3",
            "x",
            Units::MPerS2,
            None,
        )
        .unwrap();
        assert_eq!(r.samples(), &[0.1, 0.2, -0.3]);
        assert_eq!(r.dt(), 0.01);
    }

    #[test]
    fn csv_round_trip_is_bit_exact() {
        let r = Record::new("r", 0.01, vec![0.1, -1.0 / 3.0, 2.5e-7, 0.0]).unwrap();
        let back = parse_text(&format_csv(&r), "r", Units::MPerS2, None).unwrap();
        assert_eq!(back.samples(), r.samples());
        assert!((back.dt() - 0.01).abs() < 1e-15);
    }

    #[test]
    fn one_column_needs_dt() {
        let t = "# comment\n1\n2\n\n3\n";
        assert!(matches!(
            parse_text(t, "x", Units::G, None),
            Err(MotionError::MissingDt { .. })
        ));
        let r = parse_text(t, "x", Units::CmPerS2, Some(0.02)).unwrap();
        assert_eq!(r.samples(), &[0.01, 0.02, 0.03]);
    }

    #[test]
    fn blank_separated_and_semicolons() {
        let r = parse_text("0 1\n0.5 2\n1.0 3", "x", Units::MPerS2, None).unwrap();
        assert_eq!(r.dt(), 0.5);
        let r = parse_text("0;1\n0.5;2\n", "x", Units::MPerS2, Some(0.5)).unwrap();
        assert_eq!(r.len(), 2);
        assert!(matches!(
            parse_text("0;1\n0.5;2\n", "x", Units::MPerS2, Some(0.4)),
            Err(MotionError::DtMismatch { .. })
        ));
    }
}
