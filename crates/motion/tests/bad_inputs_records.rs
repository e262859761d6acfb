//! Issue 16, the record readers: accelerations beyond any physical record, an AT2 whose
//! NPTS disagrees with its data, and scalings to an impossible PGA are typed errors that
//! say what is wrong (never a record whose responses overflow).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{G, MAX_ABS_ACCEL_G, MotionError, Record, Units, parse_at2, parse_text};

fn at2(values: &str, npts: usize) -> String {
    format!("TITLE\nNPTS= {npts}, DT= .0100 SEC\n{values}")
}

#[test]
fn at2_sample_of_1e300_is_refused_naming_the_line_and_the_physics() {
    let e = parse_at2(&at2(".1 .2\n.3 1e300\n", 4), "big.AT2").unwrap_err();
    assert!(
        matches!(e, MotionError::Implausible { line: 4, .. }),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(msg.contains("big.AT2:4"), "{msg}");
    assert!(msg.contains("beyond any physical record"), "{msg}");
    assert!(msg.contains("4-5 g"), "{msg}");
}

#[test]
fn at2_just_within_the_bound_is_read() {
    let v = format!(".1 {}\n", MAX_ABS_ACCEL_G * 0.999);
    let r = parse_at2(&at2(&v, 2), "x").unwrap();
    assert!(r.pga() <= MAX_ABS_ACCEL_G * G);
}

#[test]
fn text_record_beyond_the_bound_is_refused() {
    // 30 g in m/s² (wrong units is the usual cause)
    let e = parse_text("0,1\n0.01,294.2\n", "t.csv", Units::MPerS2, None).unwrap_err();
    assert!(
        matches!(e, MotionError::Implausible { line: 2, .. }),
        "{e:?}"
    );
    // the same number read in cm/s² is 0.3 g: fine
    assert!(parse_text("0,1\n0.01,294.2\n", "t.csv", Units::CmPerS2, None).is_ok());
}

#[test]
fn npts_smaller_than_the_data_is_refused_naming_both_counts() {
    let e = parse_at2(&at2(".1 .2 .3\n.4 .5 .6\n", 4), "n.AT2").unwrap_err();
    assert!(
        matches!(
            e,
            MotionError::NptsMismatch {
                npts: 4,
                found: 6,
                ..
            }
        ),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(msg.contains("NPTS = 4") && msg.contains("holds 6"), "{msg}");
}

#[test]
fn scaling_beyond_the_bound_is_refused() {
    let r = Record::new("r", 0.01, vec![0.0, 1.0, -2.0]).unwrap();
    assert!(matches!(
        r.scaled_to_pga(25.0 * G),
        Err(MotionError::ImplausibleScale { .. })
    ));
    assert!(matches!(
        r.try_scaled(1e3),
        Err(MotionError::ImplausibleScale { .. })
    ));
    assert!(r.scaled_to_pga(2.0 * G).is_ok());
}

#[test]
fn a_sample_interval_below_a_microsecond_is_refused() {
    let e = parse_at2("TITLE\nNPTS= 2, DT= 1e-12 SEC\n0.1 0.2\n", "f.AT2").unwrap_err();
    assert!(
        matches!(e, MotionError::ImplausibleTimeStep { .. }),
        "{e:?}"
    );
    let e = parse_text("0.1\n0.2\n", "f.csv", Units::G, Some(1e-9)).unwrap_err();
    assert!(
        matches!(e, MotionError::ImplausibleTimeStep { .. }),
        "{e:?}"
    );
}
