//! Contract: the Markdown design table lists every storey of every design, those without
//! a damper too (slip load "no damper", its ratios and stroke "—", its drifts as
//! computed), rounded as the table's units say; the CSV keeps every digit.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::phases::table::{DesignTable, TableRow};

/// Three storeys, dampers on floors 1 and 3.
fn table() -> DesignTable {
    let row = |name: &str, loads: [f64; 2]| TableRow {
        design: name.into(),
        slip_load_kn: loads.to_vec(),
        friction_kn: None,
        ratio_to_floor_weight: vec![0.41567, 0.2],
        ratio_to_weight_above: vec![0.135, 0.2],
        drift_ratio_mean: vec![0.004961, 0.005452, 0.004321],
        drift_ratio_p84: vec![0.005931, 0.006641, 0.006001],
        drift_ratio_max: vec![0.006481, 0.008261, 0.006911],
        objective: 0.005476257,
        objective_reduction: 0.694,
        peak_drift_ratio_mean: 0.00548,
        peak_drift_reduction: 0.694,
        residual_drift_ratio_mean: 0.000419,
        peak_floor_acceleration_mean: 5.2954,
        base_shear_mean: 5.038e6,
        // a storey without a damper has no stroke: 0 in the data
        stroke_max: vec![0.0213, 0.0, 0.0241],
        energy_ratio_mean: 0.92,
        rpi_mean: 0.226,
        objective_at_75pct: 0.00595,
        objective_at_125pct: 0.00534,
        by_suite: None,
    };
    DesignTable {
        study: "gap".into(),
        objective: "mean peak_drift_ratio".into(),
        fidelity: "exact at 1 x the sweep time step".into(),
        damper_floors: vec![1, 3],
        records: 10,
        rows: vec![
            row("optimum", [1950.4456797051607, 1999.9999999999925]),
            row("bare", [0.0, 0.0]),
        ],
    }
}

#[test]
fn every_storey_is_listed_and_one_without_a_damper_says_so() {
    let md = table().to_markdown();
    let lines: Vec<&str> = md.lines().filter(|l| l.starts_with("| ")).collect();
    // header + 2 designs × 3 storeys, then the responses table (header + 2)
    assert_eq!(
        lines[1..7]
            .iter()
            .map(|l| l.split('|').nth(2).unwrap().trim())
            .collect::<Vec<_>>(),
        ["1", "2", "3", "1", "2", "3"],
        "{md}"
    );
    assert_eq!(
        lines[1],
        "| optimum | 1 | 1950.4 | 0.416 | 0.135 | 0.496 | 0.593 | 0.648 | 21.3 |"
    );
    assert_eq!(
        lines[2], "|  | 2 | no damper | — | — | 0.545 | 0.664 | 0.826 | — |",
        "the storey between the dampers"
    );
    assert_eq!(
        lines[3], "|  | 3 | 2000.0 | 0.200 | 0.200 | 0.432 | 0.600 | 0.691 | 24.1 |",
        "rounded as the table says (never 1999.9999999999925)"
    );
    assert!(!md.contains("1999.99"), "{md}");
    // the bare frame's storey 2 also has no damper; its storeys 1 and 3 carry 0 kN
    assert_eq!(
        lines[4],
        "| bare | 1 | 0.0 | 0.416 | 0.135 | 0.496 | 0.593 | 0.648 | 21.3 |"
    );
    assert!(
        lines[5].starts_with("|  | 2 | no damper | — | — |"),
        "{}",
        lines[5]
    );
    // the CSV keeps every digit of the data
    let csv = table().to_csv();
    assert!(csv.contains(",1999.9999999999925,"), "{csv}");
}
