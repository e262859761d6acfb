//! Contract: malformed input never panics; each kind of defect gives its own
//! [`MotionError`] variant, with the line it was found on; and (property tests) any string
//! or byte sequence fed to the parsers either fails with an error or gives a record whose
//! samples are finite and whose dt is positive.

use proptest::prelude::*;
use slipload_motion::{MotionError, Units, parse_at2, parse_text, read_record};

const HEADER: &str =
    "PEER NGA STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES IN UNITS OF G\n";

fn at2(values: &str, npts: usize) -> String {
    format!("{HEADER}NPTS= {npts}, DT= .0100 SEC\n{values}")
}

#[test]
fn truncated_at2_reports_counts() {
    let e = parse_at2(&at2(".1 .2 .3\n.4 .5 .6 .7\n", 10), "t.AT2").unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::Truncated {
                expected: 10,
                found: 7,
                ..
            }
        ),
        "{e:?}"
    );
    // a real record cut in half
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records/elCentro.AT2");
    let text = std::fs::read_to_string(path).unwrap();
    let cut = &text[..text.len() / 2];
    let cut = &cut[..cut.rfind('\n').unwrap()];
    assert!(matches!(
        parse_at2(cut, "half"),
        Err(MotionError::Truncated { expected: 1559, .. })
    ));
}

#[test]
fn extra_values_after_npts_are_refused_trailing_text_is_ignored() {
    // issue 16: more values than NPTS was read silently as the first NPTS
    let e = parse_at2(&at2(".1 .2 .3\n.4 .0\ngarbage here", 4), "x").unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::NptsMismatch {
                npts: 4,
                found: 5,
                ..
            }
        ),
        "{e:?}"
    );
    let r = parse_at2(&at2(".1 .2 .3\n.4\ngarbage here", 4), "x").unwrap();
    assert_eq!(r.len(), 4);
}

#[test]
fn non_finite_values_name_their_line() {
    for bad in ["NaN", "inf", "-infinity", "1e400"] {
        let e = parse_at2(&at2(&format!(".1 .2\n.3 {bad}\n"), 4), "x").unwrap_err();
        assert!(
            matches!(e, MotionError::NonFinite { line: 6, .. }),
            "{bad}: {e:?}"
        );
        let e = parse_text(&format!("0,1\n0.01,{bad}\n"), "x", Units::MPerS2, None).unwrap_err();
        assert!(
            matches!(e, MotionError::NonFinite { line: 2, .. }),
            "{bad}: {e:?}"
        );
    }
    // finite in g, overflows in m/s²
    let e = parse_at2(&at2("1e308\n", 1), "x").unwrap_err();
    assert!(matches!(e, MotionError::NonFinite { line: 5, .. }), "{e:?}");
}

#[test]
fn text_in_numbers_names_line_and_token() {
    let e = parse_at2(&at2(".1 .2\n.3 abc\n", 4), "x").unwrap_err();
    match e {
        MotionError::NotANumber { line, token, .. } => {
            assert_eq!((line, token.as_str()), (6, "abc"))
        }
        other => panic!("{other:?}"),
    }
    let e = parse_text("t,a\n0,1\n0.01,x2\n", "x", Units::G, None).unwrap_err();
    assert!(
        matches!(e, MotionError::NotANumber { line: 3, .. }),
        "{e:?}"
    );
    let e = parse_text("1\n2\nthree\n", "x", Units::G, Some(0.01)).unwrap_err();
    assert!(
        matches!(e, MotionError::NotANumber { line: 3, .. }),
        "{e:?}"
    );
}

#[test]
fn empty_inputs() {
    assert!(matches!(
        parse_at2("", "x"),
        Err(MotionError::MissingHeader { .. })
    ));
    assert!(matches!(
        parse_at2(&at2("", 0), "x"),
        Err(MotionError::Empty { .. })
    ));
    assert!(matches!(
        parse_text("", "x", Units::G, Some(0.01)),
        Err(MotionError::Empty { .. })
    ));
    assert!(matches!(
        parse_text(
            "# only a comment\n\n time,accel \n",
            "x",
            Units::G,
            Some(0.01)
        ),
        Err(MotionError::Empty { .. })
    ));
}

#[test]
fn wrong_or_missing_header() {
    let e = parse_at2(&format!("{HEADER}NPTS= abc, DT= .01 SEC\n.1\n"), "x").unwrap_err();
    assert!(
        matches!(e, MotionError::MalformedHeader { line: 4, .. }),
        "{e:?}"
    );
    let e = parse_at2(&format!("{HEADER}NPTS= 3\n.1 .2 .3\n"), "x").unwrap_err();
    assert!(
        matches!(e, MotionError::MalformedHeader { line: 4, .. }),
        "{e:?}"
    );
    let e = parse_at2(&format!("{HEADER}.1 .2 .3\n"), "x").unwrap_err();
    assert!(matches!(e, MotionError::MissingHeader { .. }), "{e:?}");
    // NPTS too large for usize is malformed, not a panic
    let e = parse_at2(
        &at2(".1", 0).replace("NPTS= 0", "NPTS= 99999999999999999999999"),
        "x",
    )
    .unwrap_err();
    assert!(matches!(e, MotionError::MalformedHeader { .. }), "{e:?}");
}

#[test]
fn bad_time_steps() {
    for dt in ["0.0", "-.01", "NaN"] {
        let text = format!("{HEADER}NPTS= 2, DT= {dt} SEC\n.1 .2\n");
        let e = parse_at2(&text, "x").unwrap_err();
        assert!(
            matches!(
                e,
                MotionError::BadTimeStep { .. } | MotionError::MalformedHeader { .. }
            ),
            "{dt}: {e:?}"
        );
    }
    let e = parse_at2(&format!("{HEADER}NPTS= 2, DT= 0.0 SEC\n.1 .2\n"), "x").unwrap_err();
    assert!(matches!(e, MotionError::BadTimeStep { .. }), "{e:?}");
    let e = parse_text("1\n2\n", "x", Units::G, Some(0.0)).unwrap_err();
    assert!(matches!(e, MotionError::BadTimeStep { .. }), "{e:?}");
    let e = parse_text("1\n2\n", "x", Units::G, None).unwrap_err();
    assert!(matches!(e, MotionError::MissingDt { .. }), "{e:?}");
}

#[test]
fn bad_time_columns() {
    let e = parse_text("0,1\n0.01,2\n0.01,3\n", "x", Units::G, None).unwrap_err();
    assert!(
        matches!(e, MotionError::TimeNotIncreasing { line: 3, .. }),
        "{e:?}"
    );
    let e = parse_text("0,1\n0.02,2\n0.01,3\n", "x", Units::G, None).unwrap_err();
    assert!(
        matches!(e, MotionError::TimeNotIncreasing { line: 3, .. }),
        "{e:?}"
    );
    let e = parse_text("0,1\n0.01,2\n0.03,3\n0.04,4\n", "x", Units::G, None).unwrap_err();
    assert!(matches!(e, MotionError::NonUniformTime { .. }), "{e:?}");
    let e = parse_text("0,1,2\n", "x", Units::G, None).unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::ColumnCount {
                line: 1,
                expected: 2,
                found: 3,
                ..
            }
        ),
        "{e:?}"
    );
    let e = parse_text("0,1\n0.01\n", "x", Units::G, None).unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::ColumnCount {
                line: 2,
                expected: 2,
                found: 1,
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn missing_file_is_an_io_error() {
    let e = read_record(std::path::Path::new("/nonexistent/x.AT2"), None, None).unwrap_err();
    assert!(matches!(e, MotionError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("/nonexistent/x.AT2"));
}

#[test]
fn line_endings_and_layouts() {
    // CR CR LF, no final newline, touching fixed-width values, lower-case dt without SEC
    let text = "title\r\r\nNPTS=   4, dt=  .02000\r\r\n  -0.00123-0.00456\r\r\n .1D-01  2.0";
    let r = parse_at2(text, "x").unwrap();
    assert_eq!(r.len(), 4);
    assert_eq!(r.dt(), 0.02);
    assert_eq!(r.samples()[1], -0.00456 * slipload_motion::G);
    assert_eq!(r.samples()[2], 0.01 * slipload_motion::G);
    // NGA-West1 header
    let r = parse_at2(
        "a\nb\nc\n3    0.0050    NPTS, DT\n0.1E-01 -0.2E-01 0.3\n",
        "x",
    )
    .unwrap();
    assert_eq!((r.len(), r.dt()), (3, 0.005));
}

fn assert_valid(result: Result<slipload_motion::Record, MotionError>) -> Result<(), TestCaseError> {
    if let Ok(r) = result {
        prop_assert!(r.dt() > 0.0 && r.dt().is_finite());
        prop_assert!(!r.is_empty());
        prop_assert!(r.samples().iter().all(|a| a.is_finite()));
    }
    Ok(())
}

/// Text that looks like a record: a header variant, then tokens drawn from numbers,
/// Fortran forms, junk and separators.
fn record_like() -> impl Strategy<Value = String> {
    let header = prop_oneof![
        (0usize..40, "[-.0-9]{0,6}").prop_map(|(n, dt)| format!("NPTS= {n}, DT= {dt} SEC")),
        (0usize..40, "[-.0-9]{0,6}").prop_map(|(n, dt)| format!("{n} {dt} NPTS, DT")),
        "[ -~]{0,30}",
    ];
    let token = prop_oneof![
        any::<f64>().prop_map(|v| format!("{v:e}")),
        (-1.0e3..1.0e3f64).prop_map(|v| format!("{v}")),
        "-?\\.[0-9]{1,7}E[-+][0-9]{2}",
        "[-+.0-9eEdD]{1,12}",
        Just("NaN".to_string()),
        "[ ,;\t]{1,3}",
        Just("\r\n".to_string()),
        Just("\n".to_string()),
    ];
    (header, prop::collection::vec(token, 0..60))
        .prop_map(|(h, toks)| format!("t1\nt2\n{h}\n{}", toks.join(" ")))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn parsers_never_panic_on_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400), dt in prop::option::of(-1.0..1.0f64)) {
        let text = String::from_utf8_lossy(&bytes);
        assert_valid(parse_at2(&text, "fuzz"))?;
        assert_valid(parse_text(&text, "fuzz", Units::G, dt))?;
    }

    #[test]
    fn parsers_never_panic_on_arbitrary_strings(text in "\\PC{0,300}", dt in prop::option::of(any::<f64>())) {
        assert_valid(parse_at2(&text, "fuzz"))?;
        assert_valid(parse_text(&text, "fuzz", Units::MPerS2, dt))?;
    }

    #[test]
    fn parsers_never_panic_on_record_like_text(text in record_like(), dt in prop::option::of(any::<f64>())) {
        assert_valid(parse_at2(&text, "fuzz"))?;
        assert_valid(parse_text(&text, "fuzz", Units::CmPerS2, dt))?;
    }
}
