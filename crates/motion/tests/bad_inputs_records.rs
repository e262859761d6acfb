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

// ---- Paths that are not record files, files larger than any record, absurd headers ----
// A FIFO, a device or a folder is refused by kind without opening it (opening a FIFO for
// reading blocks until a writer comes; /dev/zero never ends); a file beyond
// slipload_motion::limits::MAX_RECORD_BYTES is refused by its size before it is read.

/// Runs `f` on a thread and fails the test if it has not returned within 20 s (a
/// regression that blocks on a FIFO fails instead of hanging the suite).
fn within_20s<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(std::time::Duration::from_secs(20))
        .expect("reading did not return within 20 s (blocked or unbounded)")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!(
        "slipload-bad-records-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn a_fifo_is_refused_by_kind_without_blocking() {
    let dir = scratch("fifo");
    let fifo = dir.join("rec.AT2");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let f = fifo.clone();
    let e = within_20s(move || slipload_motion::read_record(&f, None, None)).unwrap_err();
    assert!(matches!(e, MotionError::NotAFile { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("rec.AT2"), "{msg}");
    assert!(msg.contains("named pipe (FIFO)"), "{msg}");
    assert!(msg.contains("not a regular file"), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn dev_zero_is_refused_as_a_device_without_reading_it() {
    let e =
        within_20s(|| slipload_motion::read_record(std::path::Path::new("/dev/zero"), None, None))
            .unwrap_err();
    assert!(matches!(e, MotionError::NotAFile { .. }), "{e:?}");
    assert!(e.to_string().contains("character device"), "{e}");
}

#[test]
fn a_folder_given_as_a_record_says_it_is_a_folder() {
    let dir = scratch("folder");
    let e = slipload_motion::read_record(&dir, None, None).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("is a folder"), "{msg}");
    assert!(msg.contains(&dir.display().to_string()), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_beyond_the_size_limit_is_refused_before_it_is_read() {
    use slipload_motion::limits::MAX_RECORD_BYTES;
    let dir = scratch("huge");
    let path = dir.join("huge.AT2");
    // sparse: the size is set, no disk is written; reading it would allocate 1 GiB
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(16 * MAX_RECORD_BYTES).unwrap();
    drop(f);
    let p = path.clone();
    let e = within_20s(move || slipload_motion::read_record(&p, None, None)).unwrap_err();
    assert!(matches!(e, MotionError::FileTooLarge { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("huge.AT2"), "{msg}");
    assert!(msg.contains("1.0 GiB"), "{msg}");
    assert!(msg.contains("limit 64.0 MiB"), "{msg}");
    assert!(msg.contains("--allow-large"), "{msg}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_at2_dt_beyond_any_accelerograph_is_refused() {
    for dt in ["2.0", "1e300"] {
        let text = format!("TITLE\nNPTS= 2, DT= {dt} SEC\n0.1 0.2\n");
        let e = parse_at2(&text, "slow.AT2").unwrap_err();
        assert!(
            matches!(e, MotionError::ImplausibleLongTimeStep { .. }),
            "DT {dt}: {e:?}"
        );
        let msg = e.to_string();
        assert!(msg.contains("slow.AT2"), "{msg}");
        assert!(msg.contains("longer than any accelerograph"), "{msg}");
    }
    // one second itself is still a (coarse) record
    assert!(parse_at2("TITLE\nNPTS= 2, DT= 1.0 SEC\n0.1 0.2\n", "x").is_ok());
}

#[test]
fn an_at2_dt_that_is_zero_negative_or_not_finite_is_refused() {
    for dt in ["0", "-0.01", "NaN", "inf"] {
        let text = format!("TITLE\nNPTS= 2, DT= {dt} SEC\n0.1 0.2\n");
        match parse_at2(&text, "x.AT2") {
            Err(MotionError::BadTimeStep { .. } | MotionError::MalformedHeader { .. }) => {}
            other => panic!("DT {dt}: {other:?}"),
        }
    }
}

#[test]
fn an_npts_the_file_cannot_hold_is_refused_before_reading_values() {
    let text = "TITLE\nNPTS= 999999999999, DT= .0100 SEC\n0.1 0.2\n";
    let e = parse_at2(text, "n.AT2").unwrap_err();
    match &e {
        MotionError::NptsBeyondFile {
            line: 2,
            npts: 999_999_999_999,
            max_values,
            ..
        } => assert!(*max_values < 10, "{max_values}"),
        other => panic!("{other:?}"),
    }
    let msg = e.to_string();
    assert!(msg.contains("n.AT2:2"), "{msg}");
    assert!(msg.contains("can hold at most"), "{msg}");
    // an NPTS of zero is an empty record
    let e = parse_at2("TITLE\nNPTS= 0, DT= .0100 SEC\n", "z.AT2").unwrap_err();
    assert!(matches!(e, MotionError::Empty { .. }), "{e:?}");
}

#[test]
fn a_text_record_with_a_step_beyond_a_second_is_refused() {
    let e = parse_text("0,0.1\n5,0.2\n10,0.3\n", "slow.csv", Units::MPerS2, None).unwrap_err();
    assert!(
        matches!(e, MotionError::ImplausibleLongTimeStep { .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("slow.csv"), "{e}");
    let e = parse_text("0.1\n0.2\n", "one.csv", Units::MPerS2, Some(1e300)).unwrap_err();
    assert!(
        matches!(e, MotionError::ImplausibleLongTimeStep { .. }),
        "{e:?}"
    );
}

#[test]
fn a_synthetic_suite_beyond_the_count_limit_is_refused_before_generating() {
    use slipload_motion::limits::MAX_SUITE_RECORDS;
    use slipload_motion::{SuiteTarget, Synthetic, synthetic_suite};
    let e = within_20s(|| {
        synthetic_suite(
            &Synthetic::default(),
            1_000_000_000,
            1,
            SuiteTarget::Unscaled,
        )
    })
    .unwrap_err();
    assert!(matches!(e, MotionError::TooMany { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("1000000000 synthetic records"), "{msg}");
    assert!(msg.contains(&format!("limit {MAX_SUITE_RECORDS}")), "{msg}");
    assert!(msg.contains("--allow-large"), "{msg}");
    // within the count, the samples of the whole suite are bounded too
    let long = Synthetic {
        duration_s: 1e5,
        dt_s: 0.01,
        ..Synthetic::default()
    };
    let e = synthetic_suite(&long, 1000, 1, SuiteTarget::Unscaled).unwrap_err();
    assert!(
        e.to_string().contains("samples in 1000 synthetic records"),
        "{e}"
    );
}

#[test]
fn spectrum_settings_beyond_any_structure_are_refused_in_readable_numbers() {
    let r = Record::new("r", 0.01, vec![0.0, 1.0, -1.0, 0.5]).unwrap();
    let e = slipload_motion::Spectrum::compute(&r, 1e300, &[1.0]).unwrap_err();
    assert!(e.to_string().contains("damping ratio = 1e300"), "{e}");
    let e = slipload_motion::Spectrum::compute(&r, 0.05, &[1e300]).unwrap_err();
    assert!(e.to_string().contains("period (s) = 1e300"), "{e}");
    let e = slipload_motion::Spectrum::compute(&r, 0.05, &[1e-300]).unwrap_err();
    assert!(e.to_string().contains("period (s) = 1e-300"), "{e}");
    // the band's ends are still answers
    assert!(slipload_motion::Spectrum::compute(&r, 10.0, &[1e4]).is_ok());
}

/// Issue 40 §4: a synthetic record's step is held to the band the readers hold a file's
/// step to, so that `record synth` never writes a file `record info` refuses.
#[test]
fn a_synthetic_step_outside_the_readers_band_is_refused_as_the_readers_refuse_it() {
    use slipload_motion::{
        MAX_RECORD_DT_S, MIN_RECORD_DT_S, Synthetic, check_record_dt, format_csv,
    };
    for dt in [5.0, 2.0 * MAX_RECORD_DT_S, MIN_RECORD_DT_S / 2.0] {
        let p = Synthetic {
            dt_s: dt,
            duration_s: 20.0,
            ..Synthetic::default()
        };
        let e = p.validate().unwrap_err();
        assert_eq!(
            std::mem::discriminant(&e),
            std::mem::discriminant(&check_record_dt("synthetic record", dt).unwrap_err()),
            "{e}"
        );
        assert!(e.to_string().contains("accelerograph"), "{e}");
    }
    // at the band's ends a synthetic record is written and read back
    for dt in [MAX_RECORD_DT_S, 1e-3] {
        let p = Synthetic {
            dt_s: dt,
            duration_s: 20.0 * dt,
            ..Synthetic::default()
        };
        let r = p.generate(1, "s").unwrap();
        let back = parse_text(&format_csv(&r), "s.csv", None, None).unwrap();
        assert_eq!(back.len(), r.len());
    }
    assert!(check_record_dt("x", 0.0).is_err());
    assert!(check_record_dt("x", f64::NAN).is_err());
    assert!(check_record_dt("x", MIN_RECORD_DT_S).is_ok());
}
