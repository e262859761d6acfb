//! docs/REFERENCE.md documents every key the config parsers accept, and nothing else.
//!
//! The keys are not listed here: they are read from the parsers themselves, by the tracer
//! of `config_schema` (its own checks are in `config_tracer.rs`).
//!
//! The reference is then held to that trace: each object has a section whose heading
//! names its path in backticks (`scene.excitation.record`), with one table row per key
//! (`| key | type | unit | default | allowed | meaning |`). Every accepted key has its row,
//! every row is an accepted key; the type column says `quantity` exactly where unit strings
//! are accepted, `list` for lists, `object`/`number`/`integer`/`bool`/`string` for the
//! value; the allowed column names every value of an enum; the default column says
//! `required` exactly for the keys that may not be left out; and every unit a quantity
//! accepts is listed under "Quantities".
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
mod config_schema;

use common::root;
use config_schema::{Kind, Schema};
use serde::de::DeserializeOwned;
use std::collections::{BTreeMap, BTreeSet};

// ---------------------------------------------------------------------------------------
// The reference
// ---------------------------------------------------------------------------------------

#[derive(Debug, Clone)]
struct Row {
    key: String,
    cells: Vec<String>,
    line: usize,
}

/// The sections of the reference: heading's first backticked span → its table rows.
fn sections(doc: &str) -> BTreeMap<String, Vec<Row>> {
    let mut out: BTreeMap<String, Vec<Row>> = BTreeMap::new();
    let mut current: Option<String> = None;
    for (i, line) in doc.lines().enumerate() {
        if line.starts_with('#') {
            current = line.split('`').nth(1).map(String::from);
            if let Some(c) = &current {
                out.entry(c.clone()).or_default();
            }
            continue;
        }
        let Some(section) = &current else { continue };
        if !line.starts_with('|') {
            continue;
        }
        let cells: Vec<String> = line
            .trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect();
        let first = &cells[0];
        if !(first.starts_with('`') && first.ends_with('`') && first.len() > 2) {
            continue; // header or separator
        }
        out.get_mut(section).unwrap().push(Row {
            key: first.trim_matches('`').to_string(),
            cells,
            line: i + 1,
        });
    }
    out
}

/// The sections that document their object by another's: a section headed `P` whose text
/// says "Same keys as `Q`" takes Q's rows for P, and Q.x's for P.x, all the way down (a
/// study in plan's `property_bounds` are a chain study's). P → Q.
fn aliases(doc: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut current: Option<String> = None;
    for line in doc.lines() {
        if line.starts_with('#') {
            current = line.split('`').nth(1).map(String::from);
            continue;
        }
        if let (Some(c), Some(rest)) = (&current, line.strip_prefix("Same keys as `"))
            && let Some(target) = rest.split('`').next()
        {
            out.insert(c.clone(), target.to_string());
        }
    }
    out
}

/// The rows documenting `path`: its own section's, or through an alias of it or of an
/// object above it ([`aliases`]).
fn rows_of<'a>(
    path: &str,
    secs: &'a BTreeMap<String, Vec<Row>>,
    aliases: &BTreeMap<String, String>,
) -> Option<&'a Vec<Row>> {
    if let Some(rows) = secs.get(path).filter(|r| !r.is_empty()) {
        return Some(rows);
    }
    aliases.iter().find_map(|(from, to)| {
        let rest = path.strip_prefix(from.as_str())?;
        (rest.is_empty() || rest.starts_with('.'))
            .then(|| secs.get(&format!("{to}{rest}")))
            .flatten()
    })
}

const COLUMNS: usize = 6; // key | type | unit | default | allowed | meaning
const TYPE: usize = 1;
const DEFAULT: usize = 3;
const ALLOWED: usize = 4;

/// Where `doc` and the parsers disagree: each object (and each enum written as an object)
/// at path P needs a section headed `P` with a row per key and no other rows; every row
/// is checked by [`check_row`]; every unit a quantity accepts is listed under Quantities;
/// and no object ignores unknown keys (the reference says they are refused).
fn problems(doc: &str, schema: &Schema) -> Vec<String> {
    let secs = sections(doc);
    let aliases = aliases(doc);
    let mut out: Vec<String> = schema
        .open
        .iter()
        .map(|p| {
            format!(
                "`{p}` ignores keys it does not know; the reference says every object refuses them"
            )
        })
        .collect();
    for (path, node) in &schema.nodes {
        let keys: Vec<&str> = match &node.kind {
            Kind::Struct(fields) => fields.clone(),
            Kind::Enum(variants) if !schema.unit_enum(path, variants) => variants.clone(),
            _ => continue,
        };
        let Some(rows) = rows_of(path, &secs, &aliases) else {
            out.push(format!(
                "no section for `{path}` (a heading naming `{path}` with a row per key: {keys:?})"
            ));
            continue;
        };
        for key in &keys {
            if !rows.iter().any(|r| r.key == *key) {
                out.push(format!("`{path}`: key `{key}` is accepted but has no row"));
            }
        }
        for row in rows {
            if !keys.contains(&row.key.as_str()) {
                out.push(format!(
                    "line {}: `{path}` has a row `{}` the parser does not accept (it accepts {keys:?})",
                    row.line, row.key
                ));
                continue;
            }
            check_row(
                path,
                row,
                schema,
                matches!(node.kind, Kind::Struct(_)),
                &mut out,
            );
        }
    }
    for (path, rows) in &secs {
        if !rows.is_empty() && !schema.nodes.contains_key(path) {
            out.push(format!(
                "section `{path}` documents an object the parsers do not have"
            ));
        }
    }
    let units: BTreeSet<&String> = schema.quantities.values().flatten().collect();
    let quantities_section = doc
        .split("\n## ")
        .find(|s| s.starts_with("Quantities"))
        .unwrap_or("");
    for unit in units {
        if !quantities_section.contains(&format!("`{unit}`")) {
            out.push(format!(
                "unit `{unit}` is accepted in quantities but not listed under \"## Quantities\""
            ));
        }
    }
    out
}

/// Checks one row: type, default and allowed values against the parser.
fn check_row(parent: &str, row: &Row, schema: &Schema, is_field: bool, out: &mut Vec<String>) {
    let at = format!("line {}: `{parent}` `{}`", row.line, row.key);
    if row.cells.len() != COLUMNS {
        out.push(format!(
            "{at}: {} cells, expected {COLUMNS} (key | type | unit | default | allowed | meaning)",
            row.cells.len()
        ));
        return;
    }
    let path = format!("{parent}.{}", row.key);
    let ty = row.cells[TYPE].as_str();
    // The value's chain: lists down to what they hold.
    let mut p = path.clone();
    let mut listed = false;
    let leaf = loop {
        match schema.kind(&p) {
            Some(Kind::Seq) => {
                listed = true;
                p.push_str("[]");
            }
            Some(Kind::Tuple(n)) => {
                listed = true;
                if !ty.contains(&format!("list of {n}")) {
                    out.push(format!(
                        "{at}: the value is a list of exactly {n}; the type column says {ty:?}"
                    ));
                }
                p.push_str("[]");
            }
            other => break other.cloned(),
        }
    };
    if listed && !ty.contains("list") {
        out.push(format!(
            "{at}: the value is a list; the type column says {ty:?}"
        ));
    }
    let quantity = schema.quantities.keys().any(|q| *q == p);
    if quantity != ty.contains("quantity") {
        out.push(format!(
            "{at}: {} unit strings; the type column ({ty:?}) must {}say `quantity`",
            if quantity {
                "accepts"
            } else {
                "does not accept"
            },
            if quantity { "" } else { "not " },
        ));
    }
    let word = match &leaf {
        Some(Kind::Struct(_)) => Some("object"),
        Some(Kind::Enum(v)) if schema.unit_enum(&p, v) => {
            for variant in v {
                if !row.cells[ALLOWED].contains(&format!("`{variant}`")) {
                    out.push(format!(
                        "{at}: value `{variant}` is accepted but not in the allowed column"
                    ));
                }
            }
            Some("string")
        }
        Some(Kind::Enum(_)) => Some("object"),
        Some(Kind::Float) => Some("number"),
        Some(Kind::Int) => Some("integer"),
        Some(Kind::Bool) => Some("bool"),
        Some(Kind::Str) => Some("string"),
        _ => None,
    };
    if let Some(word) = word
        && !ty.contains(word)
    {
        out.push(format!(
            "{at}: the value is {word}; the type column says {ty:?}"
        ));
    }
    if is_field {
        let required = schema.required.contains(&path);
        let default = row.cells[DEFAULT].as_str();
        if required != (default == "required") {
            out.push(format!(
                "{at}: the key {}; the default column says {default:?}",
                if required {
                    "is required: say `required`"
                } else {
                    "may be left out: give its default"
                }
            ));
        }
    }
}

fn reference() -> String {
    std::fs::read_to_string(root().join("docs/REFERENCE.md")).unwrap()
}

// ---------------------------------------------------------------------------------------
// The tests
// ---------------------------------------------------------------------------------------

#[test]
fn the_reference_documents_every_key_the_parsers_accept_and_no_other() {
    let problems = problems(&reference(), &Schema::read());
    assert!(
        problems.is_empty(),
        "docs/REFERENCE.md and the parsers disagree ({} problems):\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn a_missing_row_an_unknown_row_or_a_wrong_column_is_found() {
    let schema = Schema::read();
    let doc = reference();
    let lines: Vec<&str> = doc.lines().collect();
    let row_of = |key: &str| {
        lines
            .iter()
            .position(|l| l.starts_with(&format!("| `{key}` |")))
            .unwrap_or_else(|| panic!("no row `{key}`"))
    };
    let with_line = |i: usize, new: Option<String>| -> String {
        let mut v: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        match new {
            Some(l) => v[i] = l,
            None => {
                v.remove(i);
            }
        }
        v.join("\n")
    };
    // An alias whose words are gone: its object and every one below it lose their rows.
    let i = lines
        .iter()
        .position(|l| l.starts_with("Same keys as `study.property_bounds`"))
        .unwrap();
    let p = problems(&with_line(i, Some(String::new())), &schema);
    for path in [
        "plan_study.property_bounds",
        "plan_study.property_bounds.slip_load.derivation",
    ] {
        assert!(
            p.iter()
                .any(|m| m.contains(&format!("no section for `{path}`"))),
            "{p:?}"
        );
    }
    // A key without its row.
    let i = row_of("scale_pga_g");
    let p = problems(&with_line(i, None), &schema);
    assert!(
        p.iter()
            .any(|m| m.contains("`scene.excitation.record`: key `scale_pga_g`")),
        "{p:?}"
    );
    // A row for a key the parser refuses.
    let extra = lines[i].replacen("`scale_pga_g`", "`scale_pgv`", 1);
    let p = problems(&with_line(i, Some(extra)), &schema);
    assert!(p.iter().any(|m| m.contains("row `scale_pgv`")), "{p:?}");
    // A quantity not said to be one.
    let i = row_of("brace_stiffness");
    let q = lines[i].replacen("quantity", "number", 1);
    let p = problems(&with_line(i, Some(q)), &schema);
    assert!(
        p.iter()
            .any(|m| m.contains("`brace_stiffness`") && m.contains("accepts unit strings")),
        "{p:?}"
    );
    // A required key given a default.
    let r = lines[i].replacen("| required |", "| 0 |", 1);
    let p = problems(&with_line(i, Some(r)), &schema);
    assert!(
        p.iter()
            .any(|m| m.contains("`brace_stiffness`") && m.contains("is required")),
        "{p:?}"
    );
    // An enum value left out of the allowed column.
    let i = row_of("sampler");
    let s = lines[i].replacen("`halton`", "halton", 1);
    let p = problems(&with_line(i, Some(s)), &schema);
    assert!(p.iter().any(|m| m.contains("value `halton`")), "{p:?}");
}

#[test]
fn the_record_units_listed_are_the_ones_the_readers_accept() {
    let secs = sections(&reference());
    for (section, key) in [
        ("scene.excitation.record", "units"),
        ("study.suites[]", "units"),
    ] {
        let row = secs[section].iter().find(|r| r.key == key).unwrap();
        let spellings: Vec<&str> = row.cells[ALLOWED].split('`').skip(1).step_by(2).collect();
        assert!(spellings.len() >= 3, "{section}.{key}: {spellings:?}");
        for s in spellings {
            assert!(
                s.parse::<slipload_motion::Units>().is_ok(),
                "{section}.{key}: `{s}` is not accepted by the record readers"
            );
        }
    }
}

/// The defaults serde itself fills in (objects that parse from `{}`), against the default
/// column: the cell's value before any remark in parentheses or after a semicolon.
#[test]
fn the_defaults_listed_are_the_ones_the_parsers_fill_in() {
    fn defaults<T: DeserializeOwned + serde::Serialize>() -> serde_json::Value {
        serde_json::to_value(serde_json::from_str::<T>("{}").unwrap()).unwrap()
    }
    let secs = sections(&reference());
    let mut checked = 0;
    for (section, value) in [
        (
            "scene.outputs",
            defaults::<slipload_sim::scene::OutputsConfig>(),
        ),
        (
            "study.suites[].synthetic",
            defaults::<slipload_opt::model::config::SyntheticSuiteConfig>(),
        ),
        (
            "study.fidelity",
            defaults::<slipload_opt::model::config::FidelityConfig>(),
        ),
        (
            "study.sweep",
            defaults::<slipload_opt::model::config::SweepConfig>(),
        ),
        (
            "study.refine",
            defaults::<slipload_opt::model::config::RefineConfig>(),
        ),
    ] {
        for (key, v) in value.as_object().unwrap() {
            if v.is_null() {
                continue; // resolved later, not by the parser: said in words
            }
            let row = secs[section]
                .iter()
                .find(|r| r.key == *key)
                .unwrap_or_else(|| panic!("`{section}` has no row `{key}`"));
            let cell = row.cells[DEFAULT]
                .split([';', '('])
                .next()
                .unwrap()
                .trim()
                .trim_matches('`');
            let same = match v {
                serde_json::Value::Number(n) => cell.parse::<f64>().ok() == n.as_f64(),
                serde_json::Value::String(s) => cell == s,
                serde_json::Value::Bool(b) => cell == if *b { "true" } else { "false" },
                other => panic!("`{section}` `{key}`: a default of another kind: {other}"),
            };
            assert!(
                same,
                "line {}: `{section}` `{key}` defaults to {v}; the reference says {:?}",
                row.line, row.cells[DEFAULT]
            );
            checked += 1;
        }
    }
    assert!(checked >= 18, "{checked} defaults checked");
}
