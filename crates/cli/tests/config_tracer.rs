//! The tracer of `config_schema` reaches every level of the config files (through lists,
//! options and enum variants), finds the required keys and the quantities, and tells an
//! object that refuses unknown keys from one that ignores them; so the checks of
//! docs/REFERENCE.md against it (`docs_reference.rs`) cannot pass by seeing too little.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod config_schema;

use config_schema::{Kind, Schema, Trace, Walk, walk};
use std::cell::RefCell;

#[test]
fn the_trace_reaches_every_level_of_the_configs() {
    let s = Schema::read();
    // A few levels of each file, reached only by descending into lists, options and
    // enum variants: a tracer that stops early fails here rather than passing vacuously.
    for path in [
        "building.dissipators[]",
        "building.storey_yield[]",
        "building.damping.rayleigh",
        "scene.excitation.record",
        "scene.method",
        "study.suites[].synthetic",
        "study.space.profile",
        "study.objective.terms[]",
        "designs[]",
    ] {
        assert!(
            matches!(s.kind(path), Some(Kind::Struct(_))),
            "{path}: {:?}",
            s.kind(path)
        );
    }
    assert!(s.required.contains("building.dissipators[].floor"));
    assert!(!s.required.contains("building.dissipators[].mass"));
    assert!(
        s.quantities
            .contains_key("building.dissipators[].brace_stiffness")
    );
    assert!(
        s.quantities
            .contains_key("building.dissipators[].slip_load")
    );
    assert!(
        !s.quantities.contains_key("scene.building"),
        "a path, not a quantity"
    );
    // The extra-key walk tells an object that refuses unknown keys from one that ignores them.
    #[derive(serde::Deserialize)]
    #[allow(dead_code)]
    struct Lenient {
        a: f64,
    }
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Strict {
        a: f64,
    }
    let extra = Walk {
        unknown_key: Some("x".into()),
        ..Walk::default()
    };
    let t = RefCell::new(Trace::default());
    assert_eq!(walk::<Lenient>("x", &extra, &t), Ok(()));
    let e = walk::<Strict>("x", &extra, &t).unwrap_err();
    assert!(e.starts_with("unknown field `zz_unknown`"), "{e}");
    assert!(s.open.is_empty(), "{:?}", s.open);
    let structs = s
        .nodes
        .values()
        .filter(|n| matches!(n.kind, Kind::Struct(_)))
        .count();
    assert!(structs >= 20, "{structs} objects traced");
}
