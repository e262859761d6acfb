//! Contract: every recorded accelerogram in `records/` (and `records/pairs/`) reads, and its NPTS, DT and
//! PGA agree with `records/index.csv` (read here, not hard-coded). The index prints
//! PGA in g to 4 significant figures, so the measured PGA must lie within half a unit of
//! that last figure; NPTS is exact and DT is a short decimal, compared to 1e-12 relative
//! (one decimal-to-binary rounding).

use slipload_motion::{G, Record, read_record};
use std::path::PathBuf;

fn records_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../records")
}

struct IndexRow {
    file: String,
    npts: usize,
    dt_s: f64,
    pga_g: f64,
}

fn index() -> Vec<IndexRow> {
    let path = records_dir().join("index.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(
        lines.next().map(str::trim),
        Some("file,npts,dt_s,pga_g"),
        "index.csv columns changed"
    );
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').map(str::trim).collect();
            assert_eq!(f.len(), 4, "index row {l:?}");
            IndexRow {
                file: f[0].to_string(),
                npts: f[1].parse().expect("index npts is an integer"),
                dt_s: f[2].parse().expect("index dt_s is a number"),
                pga_g: f[3].parse().expect("index pga_g is a number"),
            }
        })
        .collect()
}

fn read(file: &str) -> Record {
    let path = records_dir().join(file);
    read_record(&path, None, None).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_record_matches_the_index() {
    let rows = index();
    assert!(rows.len() >= 25, "index lists {} records", rows.len());
    for row in &rows {
        let r = read(&row.file);
        assert_eq!(r.len(), row.npts, "{}: NPTS", row.file);
        assert!(
            (r.dt() - row.dt_s).abs() <= 1e-12 * row.dt_s,
            "{}: DT {} vs {}",
            row.file,
            r.dt(),
            row.dt_s
        );
        let pga_g = r.pga() / G;
        // half a unit in the 4th significant figure of the printed index value
        let half_ulp = 0.5 * 10f64.powf(row.pga_g.log10().floor() - 3.0);
        assert!(
            (pga_g - row.pga_g).abs() <= half_ulp * (1.0 + 1e-9),
            "{}: PGA {pga_g} g vs index {} g",
            row.file,
            row.pga_g
        );
        assert!(r.samples().iter().all(|a| a.is_finite()));
    }
}

#[test]
fn every_file_in_the_folder_is_indexed() {
    let rows = index();
    // records/ and records/pairs/ (the second components of pairs, kept out of the
    // `RSN*.AT2` patterns of the shipped studies), indexed as `pairs/FILE`
    let mut on_disk: Vec<String> = Vec::new();
    for (dir, prefix) in [(records_dir(), ""), (records_dir().join("pairs"), "pairs/")] {
        on_disk.extend(
            std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| n.to_ascii_lowercase().ends_with(".at2"))
                .map(|n| format!("{prefix}{n}")),
        );
    }
    on_disk.sort();
    let mut indexed: Vec<String> = rows.into_iter().map(|r| r.file).collect();
    indexed.sort();
    assert_eq!(on_disk, indexed);
}

#[test]
fn first_values_are_read_exactly_in_every_layout() {
    // layout A (old PEER, no leading zero), B (NGA-West1 header), C' (CRLF, no comma), D (8F10.5)
    let cases = [
        ("I-ELC180.AT2", None),
        ("WON185.AT2", Some(0.125534E-04)),
        ("RSN900_LANDERS_YER270.AT2", Some(-0.1485837E-02)),
        ("elCentro.AT2", Some(0.00630)),
    ];
    for (file, first_g) in cases {
        let r = read(file);
        if let Some(a) = first_g {
            assert_eq!(r.samples()[0], a * G, "{file}");
        }
        assert!(
            r.provenance().contains("PEER AT2"),
            "{file}: {}",
            r.provenance()
        );
    }
    // the last value of the file without a final newline is read
    let r = read("elCentro.AT2");
    assert_eq!(r.samples()[r.len() - 1], 0.0);
    assert_eq!(r.samples()[r.len() - 2], -0.00006 * G);
}
