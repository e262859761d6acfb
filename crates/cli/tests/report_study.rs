//! Contract: the report of an `optimize` folder prints numbers rounded as the Markdown
//! design tables round them (slip loads to 0.1 kN: never 1999.9999999999925; the full
//! value stays in the files and in the cell's tooltip), warns which floors sit on a bound
//! of the design space, and says what the optimum costs in base shear and floor
//! acceleration against the building file's slip loads and the bare frame (as the
//! summary `optimize` prints does); its wide
//! tables scroll sideways on screen and fit the page in print.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload};
use serde_json::Value;

/// The page's text between `<section id="ID">` and its end.
fn section<'a>(html: &'a str, id: &str) -> &'a str {
    let start = html
        .find(&format!("<section id=\"{id}\">"))
        .unwrap_or_else(|| panic!("no section {id}"));
    let end = start + html[start..].find("</section>").unwrap();
    &html[start..end]
}

#[test]
fn study_report_rounds_warns_on_bounds_and_states_the_costs() {
    let dir = root().join("results/benchmark-3story");
    let out_dir = scratch("report-study", "bench");
    let page = out_dir.join("page.html");
    let out = slipload(&[
        "report",
        dir.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).unwrap();

    // No number shown with every digit: the data hold the second floor's slip load a
    // hair below its 2000 kN bound, with every digit (1999.99999…).
    let optimum: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("optimum.json")).unwrap()).unwrap();
    let loads: Vec<f64> = optimum["slip_loads_kN"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let v = loads[1];
    assert!(
        v < 2000.0 && v > 1999.99 && v.to_string().len() > 12,
        "the data hold a many-digit value below the bound: {v}"
    );
    assert!(
        !html.contains(">1999.99"),
        "a shown slip load has every digit"
    );
    assert!(!html.contains(", 1999.99"), "a shown list has every digit");
    assert!(
        html.contains(&format!("title=\"{v}\">2000.0</td>")),
        "the CSV cell shows 2000.0, the full value in its tooltip"
    );

    let summary = section(&html, "summary");
    assert!(
        summary.contains("<p class=\"warn\"><strong>On a bound of the design space</strong>")
            && summary.contains("floor 2 at its upper bound (2000.0 kN)"),
        "{summary}"
    );
    let shown = loads
        .iter()
        .map(|x| format!("{x:.1}"))
        .collect::<Vec<_>>()
        .join(" / ");
    assert!(
        summary.contains(&format!("<td>{shown}</td>")),
        "{shown}: {summary}"
    );
    // What the optimum costs, from design-table.json, rounded as design-table.md rounds.
    let table: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("design-table.json")).unwrap())
            .unwrap();
    let row = |name: &str| {
        table["rows"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["design"] == name)
            .unwrap()
            .clone()
    };
    assert!(
        summary.contains("<h3>What the optimum costs</h3>"),
        "{summary}"
    );
    for (name, label) in [
        ("optimum", "optimum"),
        ("file", "building file&#39;s slip loads"),
        ("bare", "bare frame"),
    ] {
        let r = row(name);
        let shear = format!(
            "<td class=\"num\">{:.2}</td>",
            r["base_shear_mean"].as_f64().unwrap() / 1e6
        );
        let acc = format!(
            "<td class=\"num\">{:.2}</td>",
            r["peak_floor_acceleration_mean"].as_f64().unwrap()
        );
        let at = summary
            .find(&format!("<tr><td>{label}</td>"))
            .unwrap_or_else(|| panic!("no {label} row in\n{summary}"));
        let tr = &summary[at..at + summary[at..].find("</tr>").unwrap()];
        assert!(tr.contains(&shear) && tr.contains(&acc), "{tr}");
    }
    // the same numbers design-table.md gives: optimum 5.03 MN, 5.29 m/s²; bare 7.54, 8.99
    assert!(summary.contains("<td class=\"num\">5.03</td><td class=\"num\">5.29</td>"));
    assert!(summary.contains("<td class=\"num\">7.54</td><td class=\"num\">8.99</td>"));

    // On screen after `optimize` (its committed summary, which readme_numbers.rs holds to
    // what the command prints today): the same costs beside the building file's and the
    // bare frame's.
    let printed = std::fs::read_to_string(dir.join("summary.txt")).unwrap();
    let costs = printed
        .lines()
        .find(|l| l.starts_with("what the optimum costs"))
        .unwrap_or_else(|| panic!("no costs line in\n{printed}"));
    let (o, f, b) = (row("optimum"), row("file"), row("bare"));
    let mn = |r: &Value| format!("{:.2} MN", r["base_shear_mean"].as_f64().unwrap() / 1e6);
    let ms2 = |r: &Value| {
        format!(
            "{:.2} m/s²",
            r["peak_floor_acceleration_mean"].as_f64().unwrap()
        )
    };
    assert!(
        costs.contains(&format!(
            "base shear {} (building file's slip loads {}, bare frame {})",
            mn(&o),
            mn(&f),
            mn(&b)
        )) && costs.contains(&format!(
            "floor acceleration {} (building file's slip loads {}, bare frame {})",
            ms2(&o),
            ms2(&f),
            ms2(&b)
        )),
        "{costs}"
    );
    assert!(
        printed.contains("on a bound of the design space")
            && printed.contains("floor 2 at its upper bound, 2000.0 kN"),
        "{printed}"
    );

    // Wide tables: scroll on screen, fit the page in print.
    assert!(html.contains(".scroll{overflow-x:auto}"));
    let print = &html[html.find("@media print{").expect("print rules")..];
    assert!(print.contains("@page{size:A4 landscape"), "{print}");
    assert!(print.contains(".scroll{overflow:visible}"), "{print}");
    assert!(
        print.contains(".scroll>table{min-width:0;width:100%}"),
        "{print}"
    );
    // every Markdown and CSV table sits in a scroll box
    let tables = html.matches("<table>\n").count();
    assert!(
        tables >= 5,
        "design table (2), rank, family, CSVs: {tables}"
    );
    assert_eq!(
        html.matches("<div class=\"scroll\"><table>\n").count(),
        tables,
        "every Markdown and CSV table scrolls"
    );
    let _ = std::fs::remove_dir_all(&out_dir);
}

#[test]
fn a_study_in_plan_gets_its_page_summary_check_devices_and_plan_figures() {
    let dir = root().join("results/plan-ten-story");
    let out_dir = scratch("report-study", "plan");
    let page = out_dir.join("page.html");
    let out = slipload(&[
        "report",
        dir.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("report of the study in plan"), "{err}");
    let html = std::fs::read_to_string(&page).unwrap();
    // titled by the study, its summary first, as plan-summary.txt says it
    assert!(html.contains("<title>plan-ten-story"), "title");
    let summary = section(&html, "summary");
    assert!(
        summary.contains("placement of the optimum&#39;s slip load")
            || summary.contains("placement of the optimum's slip load"),
        "{summary}"
    );
    // the check page before the device table before the damper table
    let tables = section(&html, "tables");
    let at = |name: &str| {
        tables
            .find(&format!("<p class=\"src\">{name}</p>"))
            .unwrap_or_else(|| panic!("no {name}"))
    };
    assert!(at("plan-check.md") < at("plan-devices.md"));
    assert!(at("plan-devices.md") < at("plan-dampers.md"));
    // the plan's figures inlined with their data
    let figures = section(&html, "figures");
    for stem in ["plan-view", "line-drift-profiles"] {
        assert!(
            figures.contains(&format!("<figure id=\"fig-{stem}\">")),
            "{stem}"
        );
    }
    // the optimum's file is what the summary and tables show: not repeated as raw JSON
    assert!(
        !html.contains("<summary>plan-optimum.json"),
        "raw optimum repeated"
    );
}
