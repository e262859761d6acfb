//! Contract: `slipload_figures::study::write`, the one call every front makes after a
//! study, writes each figure present in the data as SVG + PNG + CSV into the folder and
//! returns their names; the same data gives the same bytes; a folder that cannot be one
//! is refused naming it, and a figure that cannot be drawn is refused naming the figure,
//! with no file written.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_figures::plot::meta::FigureMeta;
use slipload_figures::plot::{Figure, HeatMap, Panel};
use slipload_figures::{FigureError, check_fonts, study};
use slipload_opt::base::collapse::objective_text;
use slipload_opt::phases::figures::{
    Convergence, DriftLimit, DriftProfile, FigureData, ObjectiveMap, RecordScatter, SuiteFigures,
};
use std::path::{Path, PathBuf};

/// A fresh folder for one test (removed first if a previous run left it).
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-figures-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Every figure: a 3 × 2 map with one collapsed design, two refiners, two profiles over
/// three storeys, three records.
fn data() -> FigureData {
    FigureData {
        map: Some(ObjectiveMap {
            floors: [1, 3],
            loads_a_kn: vec![0.0, 500.0, 1000.0],
            loads_b_kn: vec![0.0, 400.0],
            objective: vec![1.0, 0.8, 0.7, f64::INFINITY, 0.75, 0.9],
            optimum_kn: [500.0, 400.0],
            label: "mean peak drift ratio".into(),
        }),
        convergence: vec![
            Convergence {
                refiner: "trust-region".into(),
                points: vec![(12, 0.8, 0.8), (15, 0.9, 0.8), (18, 0.7, 0.7)],
            },
            Convergence {
                refiner: "nelder-mead, 2".into(),
                points: vec![(12, 0.8, 0.8), (15, 0.75, 0.75)],
            },
        ],
        suites: vec![one_suite("", "")],
        fidelity: "newmark, dt 0.01 s".into(),
        spectra: vec![],
    }
}

/// Two profiles over three storeys and three records, of the suite `suite` whose
/// figures' names add `suffix`.
fn one_suite(suite: &str, suffix: &str) -> SuiteFigures {
    SuiteFigures {
        suite: suite.into(),
        suffix: suffix.into(),
        profiles: vec![
            DriftProfile {
                design: "best".into(),
                mean: vec![0.004, 0.005, 0.003],
                p84: vec![0.006, 0.007, 0.004],
            },
            DriftProfile {
                design: "bare".into(),
                mean: vec![0.010, 0.012, 0.008],
                p84: vec![0.014, 0.016, 0.011],
            },
        ],
        scatter: Some(RecordScatter {
            design: "best".into(),
            records: vec!["a".into(), "b".into(), "c".into()],
            suites: vec![suite.into(); 3],
            bare: vec![0.010, 0.020, 0.015],
            design_values: vec![0.004, 0.008, 0.006],
        }),
        limits: vec![],
    }
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn every_figure_is_written_with_its_data_and_named() {
    check_fonts().unwrap();
    let dir = scratch("all");
    let names = study::write(&data(), &dir).unwrap();
    assert_eq!(
        names,
        [
            "objective-map",
            "convergence",
            "drift-profiles",
            "records-scatter"
        ]
    );
    let mut expected: Vec<String> = names
        .iter()
        .flat_map(|n| ["csv", "png", "svg"].map(|e| format!("{n}.{e}")))
        .collect();
    expected.sort();
    assert_eq!(
        files(&dir),
        expected,
        "three files per figure, nothing else"
    );

    let svg = String::from_utf8(read(&dir.join("objective-map.svg"))).unwrap();
    let m = FigureMeta::from_svg(&svg).unwrap();
    let h = m.panels[0].heatmap.as_ref().unwrap();
    assert_eq!(
        (h.nx, h.ny, h.missing),
        (3, 2, 1),
        "the collapsed design is a grey cell"
    );
    assert_eq!(h.z, [Some(0.7), Some(1.0)]);
    let png = read(&dir.join("objective-map.png"));
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");

    let map = String::from_utf8(read(&dir.join("objective-map.csv"))).unwrap();
    assert_eq!(
        map.lines().next(),
        Some("slip_load_kN_1,slip_load_kN_3,objective")
    );
    assert_eq!(map.lines().count(), 1 + 6);
    // objective[i * 2 + j] at (a[i], b[j]): the infinite one is a[1] = 500, b[1] = 400
    assert!(
        map.contains(&format!(
            "500,400,{}\n",
            objective_text(f64::INFINITY, None)
        )),
        "{map}"
    );
    let conv = String::from_utf8(read(&dir.join("convergence.csv"))).unwrap();
    assert!(conv.contains("\"nelder-mead, 2\",15,0.75,0.75\n"), "{conv}");
    let prof = String::from_utf8(read(&dir.join("drift-profiles.csv"))).unwrap();
    assert!(prof.contains("bare,2,0.012,0.016\n"), "{prof}");
    let sc = String::from_utf8(read(&dir.join("records-scatter.csv"))).unwrap();
    assert_eq!(
        sc.lines().next(),
        Some("record,bare_peak_drift_ratio,best_peak_drift_ratio,suite")
    );

    let svg = String::from_utf8(read(&dir.join("drift-profiles.svg"))).unwrap();
    let p = &FigureMeta::from_svg(&svg).unwrap().panels[0];
    assert_eq!((p.y.min, p.y.max), (0.5, 3.5), "one row per storey");
    assert_eq!(p.series.len(), 4, "mean and p84 per design");
    assert_eq!(p.series[2].x, [Some(0.8), Some(1.2)], "percent");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_same_data_writes_the_same_bytes() {
    let (a, b) = (scratch("same-a"), scratch("same-b"));
    let names = study::write(&data(), &a).unwrap();
    assert_eq!(study::write(&data(), &b).unwrap(), names);
    assert_eq!(files(&a), files(&b));
    for f in files(&a) {
        assert!(read(&a.join(&f)) == read(&b.join(&f)), "{f} differs");
    }
    std::fs::remove_dir_all(&a).unwrap();
    std::fs::remove_dir_all(&b).unwrap();
}

#[test]
fn no_figure_data_writes_nothing() {
    let dir = scratch("none");
    let empty = FigureData {
        map: None,
        convergence: vec![],
        suites: vec![],
        fidelity: String::new(),
        spectra: vec![],
    };
    assert!(study::write(&empty, &dir).unwrap().is_empty());
    assert!(!dir.exists() || files(&dir).is_empty());
}

#[test]
fn a_file_where_the_folder_goes_is_refused_naming_it() {
    let dir = scratch("file");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("out");
    std::fs::write(&file, "a file").unwrap();
    let e = study::write(&data(), &file).unwrap_err();
    assert!(matches!(e, FigureError::Write(_)), "{e:?}");
    assert!(e.to_string().contains(file.to_str().unwrap()), "{e}");
    assert_eq!(files(&dir), ["out"], "nothing written");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_figure_that_cannot_be_drawn_is_refused_naming_it_and_writes_nothing() {
    let dir = scratch("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let fig = Figure::new("bad map").panel(Panel::new("a (kN)", "b (kN)").heatmap(HeatMap {
        x: vec![0.0, 1.0, 2.0],
        y: vec![0.0, 1.0],
        z: vec![vec![1.0, 2.0, 3.0]],
        label: "objective (-)".into(),
        z_range: None,
    }));
    let stem = dir.join("map");
    let e = fig.save(&stem).unwrap_err();
    assert!(
        e.to_string()
            .contains(&format!("drawing figure {}", stem.display())),
        "{e}"
    );
    let cause = std::error::Error::source(&e).unwrap().to_string();
    assert_eq!(cause, "heat map \"objective (-)\" needs 2 rows of 3 values");
    assert!(files(&dir).is_empty(), "no partial file");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_svg_without_figure_metadata_is_refused() {
    let e = FigureMeta::from_svg("<svg></svg>").unwrap_err();
    assert_eq!(
        e.to_string(),
        "no <metadata id=\"slipload-figure\"> in the SVG"
    );
    let e = FigureMeta::from_svg("<svg><metadata id=\"slipload-figure\">{").unwrap_err();
    assert_eq!(e.to_string(), "unterminated figure metadata");
    let e = FigureMeta::from_svg("<svg><metadata id=\"slipload-figure\">{}</metadata></svg>")
        .unwrap_err();
    assert!(matches!(e, FigureError::MetadataJson(_)), "{e:?}");
}

#[test]
fn a_code_scaled_suite_draws_its_mean_against_the_target() {
    use slipload_opt::model::config::Hazard;
    use slipload_opt::model::study::CodeScaling;
    let dir = scratch("spectra");
    let c = CodeScaling {
        hazard: Hazard::MceR,
        sds_g: Some(0.5),
        sd1_g: Some(0.3),
        tl_s: Some(8.0),
        table: None,
        en1998: None,
        rule: None,
        zero_period: None,
        period_s: 1.2,
        range_s: [0.24, 2.4],
        stuck_period_s: None,
        mass_90_period_s: None,
        pairs: None,
        factor: 1.04,
        controlling_period_s: 0.675,
        periods_s: vec![0.24, 0.675, 2.4],
        mean_sa_g: vec![1.1, 0.81, 0.3],
        target_sa_g: vec![1.2, 0.9, 0.19],
        record_factors: vec![],
    };
    let data = FigureData {
        map: None,
        convergence: vec![],
        suites: vec![],
        fidelity: String::new(),
        spectra: vec![("mce".into(), c)],
    };
    assert_eq!(
        study::write(&data, &dir).unwrap(),
        vec!["code-spectra".to_string()]
    );
    let csv = String::from_utf8(read(&dir.join("code-spectra.csv"))).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "suite,hazard,factor,period_s,mean_sa_g,target_sa_g"
    );
    assert_eq!(lines[2], "mce,mce_r,1.04,0.675,0.81,0.9");
    assert_eq!(lines.len(), 4);
    // the 90 % line the panel title names as dotted is drawn and in the legend
    let svg = String::from_utf8(read(&dir.join("code-spectra.svg"))).unwrap();
    let p = &FigureMeta::from_svg(&svg).unwrap().panels[0];
    assert!(p.title.contains("dotted: 90 % of it"), "{}", p.title);
    // the clause of the rule the suite was scaled by
    assert!(p.title.ends_with("(ASCE 7-16 §16.2.3)"), "{}", p.title);
    let ninety = p
        .series
        .iter()
        .find(|s| s.name == "mce 90 % of target")
        .unwrap_or_else(|| panic!("no 90 % series in {:?}", p.series));
    assert_eq!(ninety.drawn, 3);
    let [lo, hi] = ninety.y.map(Option::unwrap);
    assert!((lo - 0.9 * 0.19).abs() < 1e-12 && (hi - 0.9 * 1.2).abs() < 1e-12);
    assert!(
        svg.contains(">\nmce 90 % of target\n</text>"),
        "named in the legend"
    );
    std::fs::remove_dir_all(&dir).unwrap();

    // a suite scaled by the EN 1998-1 rule cites its clause, not ASCE 7's; a study with
    // suites of both rules cites both
    use slipload_opt::model::code_spectrum::ScalingRule;
    let en = CodeScaling {
        rule: Some(ScalingRule::En1998),
        ..data.spectra[0].1.clone()
    };
    let title = |spectra: Vec<(String, CodeScaling)>| {
        let dir = scratch("spectra-rule");
        let data = FigureData {
            spectra,
            ..data.clone()
        };
        study::write(&data, &dir).unwrap();
        let svg = String::from_utf8(read(&dir.join("code-spectra.svg"))).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        FigureMeta::from_svg(&svg).unwrap().panels[0].title.clone()
    };
    let t = title(vec![("en".into(), en.clone())]);
    assert!(
        t.ends_with("(EN 1998-1 §3.2.3.1.2)") && !t.contains("ASCE"),
        "{t}"
    );
    let t = title(vec![
        ("asce".into(), data.spectra[0].1.clone()),
        ("en".into(), en),
    ]);
    assert!(
        t.ends_with("(ASCE 7-16 §16.2.3; EN 1998-1 §3.2.3.1.2)"),
        "{t}"
    );
}

/// The pixel of the data point (`x`, `y`) in a panel whose axes are linear.
fn pixel(p: &slipload_figures::plot::meta::PanelMeta, x: f64, y: f64) -> (f64, f64) {
    let [l, t, r, b] = p.plot_area.unwrap().map(f64::from);
    (
        l + (x - p.x.min) / (p.x.max - p.x.min) * (r - l),
        b - (y - p.y.min) / (p.y.max - p.y.min) * (b - t),
    )
}

#[test]
fn the_objective_maps_legend_never_covers_the_optimum_marker() {
    // the optimum in each corner of the grid and inside it: a legend inside the axes
    // covers the marker in one corner or another
    let radius = f64::from(slipload_figures::plot::style::MARKER_RADIUS);
    // an 11 × 11 grid (optimize's default): its corner cells are smaller than a legend
    let grid = |top: f64| {
        (0..11)
            .map(|i| top * f64::from(i) / 10.0)
            .collect::<Vec<_>>()
    };
    for (k, optimum) in [
        [1000.0, 400.0],
        [0.0, 400.0],
        [0.0, 0.0],
        [1000.0, 0.0],
        [500.0, 200.0],
    ]
    .into_iter()
    .enumerate()
    {
        let mut d = data();
        d.convergence.clear();
        d.suites.clear();
        if let Some(m) = d.map.as_mut() {
            m.loads_a_kn = grid(1000.0);
            m.loads_b_kn = grid(400.0);
            m.objective = (0..121).map(|i| 1.0 + f64::from(i % 7) / 10.0).collect();
            m.optimum_kn = optimum;
        }
        let dir = scratch(&format!("map-legend-{k}"));
        study::write(&d, &dir).unwrap();
        let svg = String::from_utf8(read(&dir.join("objective-map.svg"))).unwrap();
        let p = &FigureMeta::from_svg(&svg).unwrap().panels[0];
        let [l, t, r, b] = p.legend.expect("the map has a legend").map(f64::from);
        let (x, y) = pixel(p, optimum[0], optimum[1]);
        let apart = x + radius < l || x - radius > r || y + radius < t || y - radius > b;
        assert!(
            apart,
            "optimum {optimum:?} at ({x:.1}, {y:.1}) px, legend {:?}",
            [l, t, r, b]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn each_design_keeps_its_colour_whatever_its_rank() {
    let ranked = ["optimum", "storey-shear", "uniform", "file", "bare"];
    let colours = study::design_colors(&ranked);
    for (i, c) in colours.iter().enumerate() {
        assert!(!colours[..i].contains(c), "{} shares a colour", ranked[i]);
    }
    // every other order of the same designs gives each the same colour
    for shift in 1..ranked.len() {
        let mut order = ranked;
        order.rotate_left(shift);
        let again = study::design_colors(&order);
        for (n, c) in order.iter().zip(&again) {
            let k = ranked.iter().position(|r| r == n).unwrap();
            assert_eq!(*c, colours[k], "{n} in {order:?}");
        }
    }
    // a sweep's designs (sample labels) are as stable, and distinct from the named ones
    let sweep = ["s0012", "file", "s0003", "bare", "s0040"];
    let a = study::design_colors(&sweep);
    let b = study::design_colors(&["bare", "s0040", "s0003", "file", "s0012"]);
    let of = |names: &[&str], c: &[plotters::style::RGBColor], n: &str| {
        c[names.iter().position(|x| *x == n).unwrap()]
    };
    for n in sweep {
        assert_eq!(
            of(&sweep, &a, n),
            of(&["bare", "s0040", "s0003", "file", "s0012"], &b, n),
            "{n}"
        );
        let same = sweep
            .iter()
            .filter(|m| of(&sweep, &a, m) == of(&sweep, &a, n));
        assert_eq!(same.count(), 1, "{n} shares a colour");
    }

    // the figure draws them so: the bare frame is black wherever it ranks
    let profiles = || one_suite("", "").profiles;
    for profiles in [profiles(), profiles().into_iter().rev().collect()] {
        let mut d = data();
        d.map = None;
        d.suites[0].profiles = profiles
            .into_iter()
            .map(|mut p| {
                if p.design == "best" {
                    p.design = "optimum".into();
                }
                p
            })
            .collect();
        let dir = scratch("profile-colours");
        study::write(&d, &dir).unwrap();
        let svg = String::from_utf8(read(&dir.join("drift-profiles.svg"))).unwrap();
        assert!(
            svg.contains("stroke=\"#000000\""),
            "the bare frame is black"
        );
        assert!(svg.contains("stroke=\"#0072B2\""), "the optimum is blue");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn several_suites_draw_their_figures_apart_with_their_limits() {
    check_fonts().unwrap();
    let dir = scratch("suites");
    let mut design = one_suite("design", "-design");
    design.limits = vec![DriftLimit {
        applies_to: "mean".into(),
        ratio: 0.02,
    }];
    let mut mce = one_suite("mce_r", "-mce_r");
    mce.limits = vec![
        DriftLimit {
            applies_to: "mean".into(),
            ratio: 0.04,
        },
        DriftLimit {
            applies_to: "per record".into(),
            ratio: 0.06,
        },
    ];
    let d = FigureData {
        map: None,
        convergence: vec![],
        suites: vec![design, mce],
        fidelity: "newmark, dt 0.01 s".into(),
        spectra: vec![],
    };
    assert_eq!(
        d.suite_stems(),
        [
            "drift-profiles-design",
            "records-scatter-design",
            "drift-profiles-mce_r",
            "records-scatter-mce_r"
        ]
    );
    let names = study::write(&d, &dir).unwrap();
    assert_eq!(names, d.suite_stems(), "no figure over both suites");
    // each limit is a vertical line at its value in percent, named in the legend
    for (stem, limits) in [
        ("drift-profiles-design", vec![("limit, mean: 2 %", 2.0)]),
        (
            "drift-profiles-mce_r",
            vec![("limit, mean: 4 %", 4.0), ("limit, per record: 6 %", 6.0)],
        ),
    ] {
        let svg = String::from_utf8(read(&dir.join(format!("{stem}.svg")))).unwrap();
        let m = FigureMeta::from_svg(&svg).unwrap();
        let suite = stem.trim_start_matches("drift-profiles-");
        assert!(m.title.ends_with(&format!("suite {suite}")), "{}", m.title);
        let p = &m.panels[0];
        assert!(p.title.contains("dotted: limit"), "{}", p.title);
        for (name, x) in limits {
            let s = p
                .series
                .iter()
                .find(|s| s.name == name)
                .unwrap_or_else(|| panic!("{stem}: no series {name:?} in {:?}", p.series));
            assert_eq!(s.x, [Some(x), Some(x)], "{stem}: {name}");
            assert_eq!(s.y, [Some(0.5), Some(3.5)], "{stem}: the whole height");
            assert!(p.x.max >= x, "{stem}: the axis shows the limit");
            assert!(
                svg.contains(&format!(">\n{name}\n</text>")),
                "{stem}: {name} in the legend"
            );
        }
    }
    // each scatter's rows name their suite
    for suite in ["design", "mce_r"] {
        let csv =
            String::from_utf8(read(&dir.join(format!("records-scatter-{suite}.csv")))).unwrap();
        let mut lines = csv.lines();
        assert_eq!(
            lines.next(),
            Some("record,bare_peak_drift_ratio,best_peak_drift_ratio,suite")
        );
        let rows: Vec<&str> = lines.collect();
        assert_eq!(rows.len(), 3);
        assert!(
            rows.iter().all(|r| r.ends_with(&format!(",{suite}"))),
            "{csv}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn one_suite_without_limits_draws_no_limit_line() {
    check_fonts().unwrap();
    let dir = scratch("one-suite");
    study::write(&data(), &dir).unwrap();
    let svg = String::from_utf8(read(&dir.join("drift-profiles.svg"))).unwrap();
    let p = &FigureMeta::from_svg(&svg).unwrap().panels[0];
    assert_eq!(
        p.title,
        "solid: mean, dashed: 84th percentile; newmark, dt 0.01 s"
    );
    assert!(!p.series.iter().any(|s| s.name.starts_with("limit")));
    std::fs::remove_dir_all(&dir).unwrap();
}
