//! Issue 40 §2, never read a record wrongly: a CSV with a UTF-8 byte-order mark keeps its
//! first sample; a column header that states its unit is read in that unit, and units
//! given that contradict it are refused naming the file and the line; units that override
//! an AT2 title's unit leave a note on the record; every file that read before reads the
//! same numbers; a record says by what factor it was scaled.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{
    G, MotionError, Record, Units, default_suite, parse_at2, parse_at2_in, parse_text, read_record,
};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "slipload-issue40-motion-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn records() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records")
}

#[test]
fn a_byte_order_mark_is_not_a_header() {
    let dir = scratch("bom");
    // one column, no header: the mark sat in front of the first value, which was then
    // taken for a header and lost
    let p = write(&dir, "one.csv", "\u{feff}0.1\n0.2\n0.3\n".as_bytes());
    let r = read_record(&p, None, Some(0.01)).unwrap();
    assert_eq!(r.samples(), &[0.1, 0.2, 0.3]);
    // two columns, no header: the first row also gives the time column's origin
    let p = write(
        &dir,
        "two.csv",
        "\u{feff}0,0.1\r\n0.01,0.2\r\n0.02,0.3\r\n".as_bytes(),
    );
    let r = read_record(&p, None, None).unwrap();
    assert_eq!(r.samples(), &[0.1, 0.2, 0.3]);
    assert_eq!(r.dt(), 0.01);
    // with a header, the mark does not hide the header's unit
    let p = write(
        &dir,
        "g.csv",
        "\u{feff}time_s,accel_g\n0,0.1\n0.01,0.2\n".as_bytes(),
    );
    let r = read_record(&p, None, None).unwrap();
    assert_eq!(r.samples(), &[0.1 * G, 0.2 * G]);
    // the text reader called directly, and an AT2 file with a mark
    let r = parse_text("\u{feff}1\n2\n", "x", Units::MPerS2, Some(0.01)).unwrap();
    assert_eq!(r.samples(), &[1.0, 2.0]);
    let r = parse_at2("\u{feff}TITLE\nNPTS= 2, DT= .0100 SEC\n.1 .2\n", "m.AT2").unwrap();
    assert_eq!(r.samples(), &[0.1 * G, 0.2 * G]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every documented way of writing a unit in a column header, with the unit it states.
const LABELS: &[(&str, Units)] = &[
    ("accel_g", Units::G),
    ("a_g", Units::G),
    ("Accel (g)", Units::G),
    ("acc [g]", Units::G),
    ("acc_m_s2", Units::MPerS2),
    ("accel (m/s^2)", Units::MPerS2),
    ("accel m/s2", Units::MPerS2),
    ("acc_cm_s2", Units::CmPerS2),
    ("accel (cm/s2)", Units::CmPerS2),
    ("cm/s2", Units::CmPerS2),
    ("accel_gal", Units::CmPerS2),
    ("gal", Units::CmPerS2),
];

#[test]
fn a_header_that_states_its_unit_is_read_in_it() {
    let dir = scratch("header-units");
    for (k, (label, units)) in LABELS.iter().enumerate() {
        let body = "0,0.25\n0.01,-0.5\n0.02,1\n";
        let p = write(
            &dir,
            &format!("h{k}.csv"),
            format!("time_s,{label}\n{body}").as_bytes(),
        );
        let r = read_record(&p, None, None).unwrap_or_else(|e| panic!("{label}: {e}"));
        // the same values with no header, read in the unit given: bit for bit
        let plain = parse_text(body, "plain", *units, None).unwrap();
        assert_eq!(r.samples(), plain.samples(), "{label}");
        // the unit given agrees with the header: read alike
        let agreed = read_record(&p, Some(*units), None).unwrap();
        assert_eq!(agreed.samples(), plain.samples(), "{label}");
        // one column with a header, blank-separated
        let p = write(
            &dir,
            &format!("c{k}.txt"),
            format!("{label}\n0.25\n-0.5\n1\n").as_bytes(),
        );
        let r = read_record(&p, None, Some(0.01)).unwrap_or_else(|e| panic!("{label}: {e}"));
        assert_eq!(r.samples(), plain.samples(), "{label} (one column)");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn units_that_contradict_the_header_are_refused_naming_the_file_and_line() {
    let dir = scratch("contradiction");
    let p = write(
        &dir,
        "kobe.csv",
        b"# Kobe, from a spreadsheet\ntime_s,accel_g\n0,0.1\n0.01,0.2\n",
    );
    let e = read_record(&p, Some(Units::MPerS2), None).unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::UnitsContradictHeader {
                line: 2,
                stated: Units::G,
                given: Units::MPerS2,
                ..
            }
        ),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(msg.contains(&format!("{}:2", p.display())), "{msg}");
    assert!(msg.contains("accel_g") && msg.contains("m/s2"), "{msg}");
    // the direct reader refuses alike when given a unit
    let e = parse_text("t,a (cm/s2)\n0,1\n0.01,2\n", "x.csv", Units::G, None).unwrap_err();
    assert!(
        matches!(e, MotionError::UnitsContradictHeader { line: 1, .. }),
        "{e:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_unit_slipload_does_not_convert_is_refused() {
    for (header, unit) in [
        ("time_s,accel_ft_s2", "ft/s2"),
        ("t, a (in/sec/sec)", "in/sec/sec"),
    ] {
        for given in [None, Some(Units::MPerS2)] {
            let e =
                parse_text(&format!("{header}\n0,1\n0.01,2\n"), "f.csv", given, None).unwrap_err();
            assert!(
                matches!(&e, MotionError::UnknownHeaderUnits { line: 1, unit: u, .. } if u == unit),
                "{header}: {e:?}"
            );
            assert!(e.to_string().starts_with("f.csv:1: "), "{e}");
        }
    }
    let e = parse_at2(
        "TITLE\nACCELERATION IN UNITS OF FT/SEC/SEC\nNPTS= 2, DT= .0100 SEC\n.1 .2\n",
        "ft.AT2",
    )
    .unwrap_err();
    assert!(
        matches!(e, MotionError::UnknownHeaderUnits { line: 2, .. }),
        "{e:?}"
    );
}

#[test]
fn files_that_read_before_read_the_same_numbers() {
    // headers that state no unit, or the default one: m/s² as before
    for header in [
        "time_s,accel_m_s2",
        "t,a",
        "time,accel",
        "time acceleration",
    ] {
        let text = format!("{header}\n0,0.25\n0.01,-0.5\n");
        let text = if header.contains(',') {
            text
        } else {
            text.replace(',', " ")
        };
        let r = parse_text(&text, "x", None, None).unwrap();
        assert_eq!(r.samples(), &[0.25, -0.5], "{header}");
        let explicit = parse_text(&text, "x", Units::MPerS2, None).unwrap();
        assert_eq!(explicit.samples(), r.samples(), "{header}");
    }
    // the CSV slipload writes reads back bit for bit, with or without units given
    let r = Record::new("r", 0.01, vec![0.1, -1.0 / 3.0, 2.5e-7]).unwrap();
    let text = slipload_motion::format_csv(&r);
    assert_eq!(
        parse_text(&text, "r", None, None).unwrap().samples(),
        r.samples()
    );
    // every AT2 file of the repository states g: read alike with and without units
    let mut n = 0;
    for e in std::fs::read_dir(records()).unwrap() {
        let p = e.unwrap().path();
        if !p.extension().is_some_and(|x| x.eq_ignore_ascii_case("at2")) {
            continue;
        }
        let by_title = read_record(&p, None, None).unwrap();
        let in_g = read_record(&p, Some(Units::G), None).unwrap();
        assert_eq!(by_title.samples(), in_g.samples(), "{}", p.display());
        assert!(by_title.notes().is_empty() && in_g.notes().is_empty());
        n += 1;
    }
    assert!(n >= 20, "the repository's AT2 files were found ({n})");
}

#[test]
fn units_that_override_an_at2_title_say_so() {
    let text = "PEER NGA STRONG MOTION DATABASE RECORD\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= .0100 SEC\n.5 1 -1.5\n";
    let in_cm = [0.5 * 0.01, 1.0 * 0.01, -1.5 * 0.01];
    let r = parse_at2_in(text, "cm.AT2", Units::CmPerS2).unwrap();
    assert_eq!(r.samples(), &in_cm);
    assert_eq!(r.notes().len(), 1, "{:?}", r.notes());
    let note = &r.notes()[0];
    assert!(
        note.contains("cm.AT2")
            && note.contains("cm/s2")
            && note.contains("line 2")
            && note.contains("UNITS OF G"),
        "{note}"
    );
    // the note stays with the record through a window and a scaling
    let w = r.window(0.0, 0.01).unwrap().scaled_to_pga(0.02).unwrap();
    assert_eq!(w.notes(), r.notes());
    // no note when the units given are the title's, or none are given
    assert!(
        parse_at2_in(text, "g.AT2", Units::G)
            .unwrap()
            .notes()
            .is_empty()
    );
    assert!(parse_at2(text, "g.AT2").unwrap().notes().is_empty());
    // a title that states another unit is read in it when none is given
    let cm = text.replace("UNITS OF G", "UNITS OF CM/SEC/SEC");
    let r = parse_at2(&cm, "cm.AT2").unwrap();
    assert_eq!(r.samples(), &in_cm);
    // read_record passes the units through to the AT2 reader
    let dir = scratch("at2-override");
    let p = write(&dir, "cm.AT2", text.as_bytes());
    let r = read_record(&p, Some(Units::CmPerS2), None).unwrap();
    assert_eq!(r.notes().len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_record_says_by_what_factor_it_was_scaled() {
    let r = Record::new("r", 0.01, vec![0.0, 2.0, -4.0, 1.0]).unwrap();
    assert_eq!(r.scale_factor(), 1.0);
    let s = r.scaled_to_pga(0.5 * G).unwrap();
    assert_eq!(s.scale_factor(), 0.5 * G / 4.0);
    let t = s.try_scaled(2.0).unwrap();
    assert_eq!(t.scale_factor(), 2.0 * (0.5 * G / 4.0));
    assert_eq!(
        t.window(0.01, 0.01).unwrap().scale_factor(),
        t.scale_factor()
    );
    // the PGA before scaling, recovered from the factor
    assert!((t.pga() / t.scale_factor() - r.pga()).abs() < 1e-12);
    // the embedded suite is generated at its PGA: not a scaling of a read record
    assert!(default_suite().iter().all(|r| r.scale_factor() == 1.0));
}
