//! Contract: the `simulate --plot DIR` folder keeps the scene it ran (`DIR/scene.json`:
//! the overrides applied, the building inline, the record's path relative to DIR, method, Δt and
//! duration as resolved), and running that file again gives the same responses from any
//! folder; `slipload report DIR` is titled by the scene, states building, record,
//! scaling, method and Δt, and shows the responses per storey in engineering units
//! (drift mm and %, acceleration m/s², slip mm, base shear kN, energies kJ) rounded for
//! people instead of a dump of `response.json`; a storey without a damper shows "—" for
//! its slip, on the page and in `simulate`'s table; a storey that never yielded shows a
//! plastic drift of 0, not round-off; `explain` counts in the right number.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload, slipload_in};
use serde_json::Value;

fn ok(o: &std::process::Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn f64s(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The `<section id="run">` of a report page.
fn run_section(html: &str) -> &str {
    let start = html.find("<section id=\"run\">").expect("a run section");
    let end = start + html[start..].find("</section>").unwrap();
    &html[start..end]
}

#[test]
fn plot_folder_keeps_the_scene_and_its_report_states_the_run_per_storey() {
    let dir = scratch("report-sim", "sylmar");
    let plot = dir.join("plot");
    let p = plot.to_str().unwrap();
    let printed = ok(&slipload(&[
        "simulate",
        "configs/paper-benchmark-sylmar.json",
        "--duration",
        "5",
        "--scale-pga-g",
        "0.3",
        "--plot",
        p,
        "--format",
        "json",
    ]));
    let first: Value = serde_json::from_str(&printed).unwrap();

    // The scene that ran, with its overrides, runnable from anywhere.
    let scene: Value =
        serde_json::from_str(&std::fs::read_to_string(plot.join("scene.json")).unwrap()).unwrap();
    assert_eq!(scene["name"], "paper-benchmark-sylmar");
    assert_eq!(scene["building"]["name"], "benchmark-3story", "inline");
    let record = scene["excitation"]["record"]["file"].as_str().unwrap();
    // relative to the folder, as a scene file's paths resolve: no machine's path in it,
    // and it names the repository's record
    assert!(!std::path::Path::new(record).is_absolute(), "{record}");
    assert_eq!(
        plot.join(record).canonicalize().unwrap(),
        root().join("records/SYL090.AT2").canonicalize().unwrap(),
        "{record}"
    );
    assert_eq!(scene["excitation"]["record"]["scale_pga_g"], 0.3);
    assert_eq!(scene["duration"], 5.0);
    assert_eq!(scene["method"]["name"], "newmark");
    assert_eq!(scene["method"]["dt"], first["dt"]);
    let elsewhere = scratch("report-sim", "elsewhere");
    // (with histories kept, as --plot keeps them: the same code path, the same bits)
    let again: Value = serde_json::from_str(&ok(&slipload_in(
        &elsewhere,
        &[
            "simulate",
            plot.join("scene.json").to_str().unwrap(),
            "--format",
            "json",
            "--history",
            "h.csv",
        ],
    )))
    .unwrap();
    for k in [
        "method",
        "dt",
        "steps",
        "peak_drift",
        "peak_abs_acceleration",
        "peak_slip",
        "peak_base_shear",
        "energy",
    ] {
        assert_eq!(again[k], first[k], "{k}: the kept scene runs the same");
    }

    // The report: titled by the scene, the run stated, the responses per storey.
    ok(&slipload(&["report", p]));
    let html = std::fs::read_to_string(plot.join("report.html")).unwrap();
    assert!(
        html.contains("<h1>paper-benchmark-sylmar</h1>"),
        "titled by the scene"
    );
    let run = run_section(&html);
    for want in [
        "<th>building</th><td>benchmark-3story: 3 storeys, dampers on floors 1, 2, 3</td>",
        "<th>ground motion</th><td>SYL090.AT2, window 10 s from 0 s</td>",
        "<th>scaling</th><td>scaled to a PGA of 0.3 g</td>",
        "<th>method</th><td>newmark</td>",
        "<th>time step Δt</th><td>0.0025 s, 2000 steps (5 s simulated)</td>",
        "<th class=\"num\">peak drift (mm)</th>",
        "<th class=\"num\">drift ratio (%)</th>",
        "<th class=\"num\">peak abs. acceleration (m/s²)</th>",
        "<th class=\"num\">damper slip (mm)</th>",
        "<th>peak base shear (kN)</th>",
        "<th>friction energy (kJ)</th>",
    ] {
        assert!(run.contains(want), "missing {want:?} in\n{run}");
    }
    // Each storey's row: its numbers in the table's units, rounded.
    let ratio = f64s(&first["peak_drift_ratio"]);
    let acc = f64s(&first["peak_abs_acceleration"]);
    for i in 0..3 {
        let row = format!("<tr><td>{}</td><td class=\"num\">", i + 1);
        let at = run
            .find(&row)
            .unwrap_or_else(|| panic!("storey {} row", i + 1));
        let tr = &run[at..at + run[at..].find("</tr>").unwrap()];
        assert!(
            tr.contains(&format!("<td class=\"num\">{:.3}</td>", 100.0 * ratio[i])),
            "drift ratio in %: {tr}"
        );
        assert!(
            tr.contains(&format!("<td class=\"num\">{:.2}</td>", acc[i])),
            "acceleration in m/s²: {tr}"
        );
    }
    let shear_kn = first["peak_base_shear"].as_f64().unwrap() / 1e3;
    assert!(
        run.contains(&format!("<td>{shear_kn:.0}</td>")),
        "base shear kN"
    );
    // energies in kJ, 4 significant digits (this run dissipates over 100 kJ by friction)
    let friction_kj = first["energy"]["friction"].as_f64().unwrap() / 1e3;
    assert!((100.0..1000.0).contains(&friction_kj), "{friction_kj}");
    let shown = format!("{friction_kj:.1}");
    let shown = shown.trim_end_matches('0').trim_end_matches('.');
    assert!(
        run.contains(&format!("<th>friction energy (kJ)</th><td>{shown}</td>")),
        "energy kJ {shown}"
    );
    // drifts in mm: 0.01 mm below 10 mm, 0.1 mm above
    let drift_mm = 1e3 * first["peak_drift"][0].as_f64().unwrap();
    let shown = if drift_mm < 10.0 {
        format!("{drift_mm:.2}")
    } else {
        format!("{drift_mm:.1}")
    };
    assert!(
        run.contains(&format!("<tr><td>1</td><td class=\"num\">{shown}</td>")),
        "storey 1 drift {shown} mm"
    );
    // No raw SI value with every digit (the JSON dump is gone from the page's tables).
    let raw = first["peak_drift"][0].to_string();
    assert!(raw.len() > 12, "{raw}");
    assert!(!run.contains(&raw), "raw {raw} in the run section");
    assert!(!html.contains("<h3>response.json</h3>"), "no JSON dump");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&elsewhere);
}

/// The benchmark building with a damper on floor 1 only, under the first synthetic record.
fn one_damper_scene(dir: &std::path::Path) -> std::path::PathBuf {
    let mut b: Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("configs/benchmark-3story.json")).unwrap(),
    )
    .unwrap();
    let first = b["dissipators"][0].clone();
    b["dissipators"] = Value::Array(vec![first]);
    let scene = serde_json::json!({
        "name": "one damper",
        "building": b,
        "excitation": { "synthetic": { "index": 0 } },
        "duration": 2.0
    });
    let path = dir.join("one-damper.json");
    std::fs::write(&path, serde_json::to_string_pretty(&scene).unwrap()).unwrap();
    path
}

#[test]
fn storeys_without_a_damper_show_a_dash_and_counts_agree_in_number() {
    let dir = scratch("report-sim", "one-damper");
    let scene = one_damper_scene(&dir);
    let s = scene.to_str().unwrap();
    // simulate's table: storeys 2 and 3 have no slip to report
    let table = ok(&slipload(&["simulate", s]));
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| {
            l.split_whitespace()
                .next()
                .is_some_and(|c| ["1", "2", "3"].contains(&c))
        })
        .collect();
    assert_eq!(rows.len(), 3, "{table}");
    let last_two = |l: &str| -> Vec<String> {
        l.split_whitespace()
            .rev()
            .take(2)
            .map(str::to_string)
            .collect()
    };
    assert_ne!(
        last_two(rows[0]),
        vec!["—", "—"],
        "floor 1 has a damper: {table}"
    );
    for r in &rows[1..] {
        assert_eq!(last_two(r), vec!["—", "—"], "{r}");
    }
    assert!(!table.contains("0.0000e0"), "{table}");
    // the report says the same
    let plot = dir.join("plot");
    ok(&slipload(&[
        "simulate",
        s,
        "--plot",
        plot.to_str().unwrap(),
    ]));
    ok(&slipload(&["report", plot.to_str().unwrap()]));
    let html = std::fs::read_to_string(plot.join("report.html")).unwrap();
    let run = run_section(&html);
    assert!(run.contains("3 storeys, a damper on floor 1</td>"), "{run}");
    for storey in ["2", "3"] {
        let at = run
            .find(&format!("<tr><td>{storey}</td>"))
            .unwrap_or_else(|| panic!("storey {storey}"));
        let tr = &run[at..at + run[at..].find("</tr>").unwrap()];
        assert!(
            tr.ends_with("<td class=\"num\">—</td><td class=\"num\">—</td>"),
            "slip and transitions of storey {storey}: {tr}"
        );
    }
    // explain: one friction contact, one dissipator (not "1 friction contacts")
    let plan = ok(&slipload(&["explain", s]));
    assert!(
        plan.contains("(3 floors + 1 dissipator), 1 friction contact ("),
        "{plan}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_storey_that_never_yielded_has_no_plastic_drift() {
    let dir = scratch("report-sim", "yield");
    let scene = dir.join("two.json");
    // storey 1 yields at 100 kN; storey 2 would need 100 MN, far beyond what it carries
    std::fs::write(
        &scene,
        r#"{ "name": "two storeys, one yields", "building": { "floor_masses": [1.0e5, 1.0e5],
              "storey_stiffness": [4.0e7, 4.0e7], "storey_heights": [3.0, 3.0],
              "storey_yield": [ { "storey": 1, "yield_shear": "100 kN" },
                                { "storey": 2, "yield_shear": "100 MN" } ] },
             "excitation": { "initial": { "floor_velocity": [0.5, 0.5] } },
             "duration": 3.0, "method": { "name": "exact", "dt": 0.001 } }"#,
    )
    .unwrap();
    let out = ok(&slipload(&["simulate", scene.to_str().unwrap()]));
    let v: Value = serde_json::from_str(&ok(&slipload(&[
        "simulate",
        scene.to_str().unwrap(),
        "--format",
        "json",
    ])))
    .unwrap();
    let plastic = f64s(&v["peak_plastic_drift"]);
    assert!(plastic[0] > 1e-4, "storey 1 yields: {plastic:?}");
    assert!(v["peak_ductility"][1].as_f64().unwrap() < 1.0);
    let head = out.find("plastic drift (m)").unwrap();
    let rows: Vec<Vec<&str>> = out[head..]
        .lines()
        .skip(1)
        .take(2)
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows[0][0], "1");
    assert_eq!(rows[0][2], format!("{:.4e}", plastic[0]), "{out}");
    assert_eq!(rows[1][0], "2");
    assert_eq!(rows[1][2], "0", "storey 2 never yielded: {out}");
    let _ = std::fs::remove_dir_all(&dir);
}
