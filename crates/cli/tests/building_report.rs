//! Contract (issue 48 §3): `slipload optimize` keeps the building it ran in its folder
//! (`building.json`, `building.md`, the library's page of the study's building), lists
//! them among the files it wrote (so `--fresh` removes them) while a user's own file
//! under those names is refused, never overwritten — in an older slipload's folder
//! without a list too —, and `slipload report` puts the building's inputs first on the
//! page.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{scratch, slipload_in, stderr, tiny_study, utf8};
use slipload_opt::Study;
use slipload_opt::phases::building::BuildingPage;

#[test]
fn optimize_keeps_the_building_and_the_report_shows_it_first() {
    let dir = scratch("building", "report");
    let study = tiny_study(&dir);
    let out = slipload_in(&dir, &["optimize", utf8(&study), "--out", "res", "--quiet"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("/{building.json,building.md,"), "{text}");
    let res = dir.join("res");
    // the library's page of the study's building, byte for byte
    let page = BuildingPage::of(&Study::load(&study).unwrap()).unwrap();
    assert_eq!(
        std::fs::read_to_string(res.join("building.json")).unwrap(),
        page.json
    );
    let md = std::fs::read_to_string(res.join("building.md")).unwrap();
    assert_eq!(md, page.markdown);
    // slipload's own files: in the folder's list
    let list = std::fs::read_to_string(res.join(".slipload.lock")).unwrap();
    for f in ["building.json", "building.md"] {
        assert!(list.lines().any(|l| l == f), "{f} in\n{list}");
    }

    let out = slipload_in(&dir, &["report", "res"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let html = std::fs::read_to_string(res.join("report.html")).unwrap();
    let first = html.find("<section id=\"").unwrap();
    assert!(
        html[first..].starts_with("<section id=\"building\">"),
        "the building's inputs come first"
    );
    let end = first + html[first..].find("</section>").unwrap();
    let section = &html[first..end];
    // its tables: the frame per storey and the dampers, with their units
    for needle in [
        "<th class=\"num\">floor mass (t)</th>",
        "<th class=\"num\">brace stiffness k′ (kN/m, horizontal)</th>",
        "<td class=\"num\">834.1</td>",
        "Inherent damping:",
    ] {
        assert!(section.contains(needle), "{needle:?} in\n{section}");
    }
    assert!(
        html.find("<section id=\"summary\">").unwrap() > end,
        "the summary after the building"
    );
    // shown once, and building.json among the inputs
    assert_eq!(html.matches(">building.md</p>").count(), 1);
    assert!(html.contains("<summary>building.json (input)</summary>"));

    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_users_building_file_in_the_folder_is_never_overwritten() {
    let dir = scratch("building", "users");
    let study = tiny_study(&dir);
    let mine = "{ \"my\": \"building\" }\n";
    // a folder of the user's own, and an older slipload's folder (a manifest, no list)
    for (name, older) in [("mine", false), ("older", true)] {
        let out_dir = dir.join(name);
        std::fs::create_dir_all(&out_dir).unwrap();
        std::fs::write(out_dir.join("building.json"), mine).unwrap();
        if older {
            std::fs::write(out_dir.join("manifest.json"), "{}\n").unwrap();
        }
        let out = slipload_in(&dir, &["optimize", utf8(&study), "--out", name, "--quiet"]);
        assert!(!out.status.success(), "{name}: the run went ahead");
        assert!(stderr(&out).contains("building.json"), "{}", stderr(&out));
        assert_eq!(
            std::fs::read_to_string(out_dir.join("building.json")).unwrap(),
            mine
        );
        // --fresh keeps it too: it is not slipload's
        let out = slipload_in(
            &dir,
            &[
                "optimize",
                utf8(&study),
                "--out",
                name,
                "--quiet",
                "--fresh",
            ],
        );
        assert!(!out.status.success(), "{name}: --fresh went ahead");
        assert_eq!(
            std::fs::read_to_string(out_dir.join("building.json")).unwrap(),
            mine
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
