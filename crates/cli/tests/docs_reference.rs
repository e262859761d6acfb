//! docs/REFERENCE.md documents every key the config parsers accept, and nothing else.
//!
//! The keys are not listed here: they are read from the parsers themselves. A tracing
//! [`Deserializer`] walks each file type (building, scene, study, candidate designs) as
//! its serde derive asks to be walked: `deserialize_struct` hands over the struct's field
//! names (every struct of the configs denies unknown fields — checked too: each is walked
//! once with an extra key — so these are exactly the keys accepted), `deserialize_enum` its variant names, and each field's value is walked in
//! turn, so nested objects, lists and enum variants (one pass per variant index) are all
//! reached. Two more questions go to the parser field by field: whether a key may be left
//! out (its struct is walked once without it: serde's "missing field" means required), and
//! whether a value accepts a string with a unit (the value is given as `"1 zz"`: a
//! quantity answers "unknown unit", and lists the units it knows).
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

use common::root;
use serde::de::{
    self, DeserializeOwned, DeserializeSeed, Deserializer, EnumAccess, IntoDeserializer, MapAccess,
    SeqAccess, VariantAccess, Visitor,
};
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

// ---------------------------------------------------------------------------------------
// The tracer
// ---------------------------------------------------------------------------------------

/// What the parser asked for at one path.
#[derive(Debug, Clone, PartialEq)]
enum Kind {
    /// An object with these keys.
    Struct(Vec<&'static str>),
    /// One of these variant names (externally tagged: a string, or `{"variant": value}`).
    Enum(Vec<&'static str>),
    /// A list (`[]` appended to the path for its elements).
    Seq,
    /// A fixed-length list.
    Tuple(usize),
    Float,
    Int,
    Bool,
    Str,
    /// A value of the parser's own choosing (`deserialize_any`): quantities, untagged enums.
    Any,
    /// A unit variant of an enum.
    Unit,
}

#[derive(Debug, Clone)]
struct Node {
    kind: Kind,
    /// The first pass that reached this path (the variant choices that lead to it).
    pass: usize,
}

/// How one walk goes.
#[derive(Debug, Clone, Default)]
struct Walk {
    /// Every enum takes its variant number `pass % variants`.
    pass: usize,
    /// Leave this key (a full path) out of its object.
    omit: Option<String>,
    /// Give `"1 zz"` (a number with an unknown unit) at this path's `deserialize_any`.
    unit_probe: Option<String>,
    /// Add the key `zz_unknown` to the object at this path.
    unknown_key: Option<String>,
}

#[derive(Debug, Default)]
struct Trace {
    nodes: BTreeMap<String, Node>,
}

impl Trace {
    fn record(&mut self, path: &str, kind: Kind, pass: usize) {
        self.nodes
            .entry(path.to_string())
            .or_insert(Node { kind, pass });
    }
}

#[derive(Debug)]
struct TraceError(String);

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for TraceError {}

impl de::Error for TraceError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        TraceError(msg.to_string())
    }
}

#[derive(Clone, Copy)]
struct Tracer<'a> {
    path: &'a str,
    walk: &'a Walk,
    trace: &'a RefCell<Trace>,
}

impl<'a> Tracer<'a> {
    fn record(&self, kind: Kind) {
        self.trace
            .borrow_mut()
            .record(self.path, kind, self.walk.pass);
    }
}

macro_rules! scalar {
    ($($method:ident => $kind:expr, $visit:ident($value:expr);)*) => {
        $(fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
            self.record($kind);
            visitor.$visit($value)
        })*
    };
}

impl<'de> Deserializer<'de> for Tracer<'_> {
    type Error = TraceError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
        self.record(Kind::Any);
        if self.walk.unit_probe.as_deref() == Some(self.path) {
            visitor.visit_str("1 zz")
        } else {
            visitor.visit_str("1")
        }
    }

    scalar! {
        deserialize_bool => Kind::Bool, visit_bool(true);
        deserialize_i8 => Kind::Int, visit_i64(1);
        deserialize_i16 => Kind::Int, visit_i64(1);
        deserialize_i32 => Kind::Int, visit_i64(1);
        deserialize_i64 => Kind::Int, visit_i64(1);
        deserialize_u8 => Kind::Int, visit_u64(1);
        deserialize_u16 => Kind::Int, visit_u64(1);
        deserialize_u32 => Kind::Int, visit_u64(1);
        deserialize_u64 => Kind::Int, visit_u64(1);
        deserialize_f32 => Kind::Float, visit_f64(1.0);
        deserialize_f64 => Kind::Float, visit_f64(1.0);
        deserialize_char => Kind::Str, visit_char('1');
        deserialize_str => Kind::Str, visit_str("1");
        deserialize_string => Kind::Str, visit_str("1");
        deserialize_identifier => Kind::Str, visit_str("1");
        deserialize_bytes => Kind::Str, visit_bytes(b"1");
        deserialize_byte_buf => Kind::Str, visit_bytes(b"1");
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
        visitor.visit_some(self)
    }

    fn deserialize_unit<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
        self.record(Kind::Unit);
        visitor.visit_unit()
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        self.deserialize_unit(visitor)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
        self.record(Kind::Seq);
        let path = format!("{}[]", self.path);
        visitor.visit_seq(Elements {
            tracer: Tracer {
                path: &path,
                ..self
            },
            left: 1,
        })
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        self.record(Kind::Tuple(len));
        let path = format!("{}[]", self.path);
        visitor.visit_seq(Elements {
            tracer: Tracer {
                path: &path,
                ..self
            },
            left: len,
        })
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        self.deserialize_tuple(len, visitor)
    }

    fn deserialize_map<V: Visitor<'de>>(self, _visitor: V) -> Result<V::Value, TraceError> {
        Err(TraceError(format!(
            "{}: a map with free keys; the reference cannot list its keys",
            self.path
        )))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        self.record(Kind::Struct(fields.to_vec()));
        visitor.visit_map(Fields {
            tracer: self,
            fields,
            next: 0,
            unknown_given: false,
            value_path: String::new(),
        })
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        self.record(Kind::Enum(variants.to_vec()));
        let variant = variants[self.walk.pass % variants.len()];
        visitor.visit_enum(Variant {
            tracer: self,
            variant,
        })
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TraceError> {
        visitor.visit_unit()
    }
}

/// The elements of a list: one (a `Vec`), or as many as a fixed-length list has.
struct Elements<'a> {
    tracer: Tracer<'a>,
    left: usize,
}

impl<'de> SeqAccess<'de> for Elements<'_> {
    type Error = TraceError;
    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, TraceError> {
        if self.left == 0 {
            return Ok(None);
        }
        self.left -= 1;
        seed.deserialize(self.tracer).map(Some)
    }
}

/// The keys of an object, each with a traced value.
struct Fields<'a> {
    tracer: Tracer<'a>,
    fields: &'static [&'static str],
    next: usize,
    unknown_given: bool,
    value_path: String,
}

impl<'de> MapAccess<'de> for Fields<'_> {
    type Error = TraceError;
    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, TraceError> {
        while let Some(&field) = self.fields.get(self.next) {
            self.next += 1;
            self.value_path = format!("{}.{field}", self.tracer.path);
            if self.tracer.walk.omit.as_deref() == Some(self.value_path.as_str()) {
                continue;
            }
            let key: de::value::StrDeserializer<'_, TraceError> = field.into_deserializer();
            return seed.deserialize(key).map(Some);
        }
        if !self.unknown_given && self.tracer.walk.unknown_key.as_deref() == Some(self.tracer.path)
        {
            self.unknown_given = true;
            self.value_path = format!("{}.zz_unknown", self.tracer.path);
            let key: de::value::StrDeserializer<'_, TraceError> = "zz_unknown".into_deserializer();
            return seed.deserialize(key).map(Some);
        }
        Ok(None)
    }

    fn next_value_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<T::Value, TraceError> {
        let path = self.value_path.clone();
        seed.deserialize(Tracer {
            path: &path,
            ..self.tracer
        })
    }
}

/// The variant this pass takes.
struct Variant<'a> {
    tracer: Tracer<'a>,
    variant: &'static str,
}

impl<'de> EnumAccess<'de> for Variant<'_> {
    type Error = TraceError;
    type Variant = Self;
    fn variant_seed<T: DeserializeSeed<'de>>(
        self,
        seed: T,
    ) -> Result<(T::Value, Self), TraceError> {
        let name: de::value::StrDeserializer<'_, TraceError> = self.variant.into_deserializer();
        Ok((seed.deserialize(name)?, self))
    }
}

impl<'de> VariantAccess<'de> for Variant<'_> {
    type Error = TraceError;

    fn unit_variant(self) -> Result<(), TraceError> {
        let path = format!("{}.{}", self.tracer.path, self.variant);
        Tracer {
            path: &path,
            ..self.tracer
        }
        .record(Kind::Unit);
        Ok(())
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(
        self,
        seed: T,
    ) -> Result<T::Value, TraceError> {
        let path = format!("{}.{}", self.tracer.path, self.variant);
        seed.deserialize(Tracer {
            path: &path,
            ..self.tracer
        })
    }

    fn tuple_variant<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        let path = format!("{}.{}", self.tracer.path, self.variant);
        Tracer {
            path: &path,
            ..self.tracer
        }
        .deserialize_tuple(len, visitor)
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, TraceError> {
        let path = format!("{}.{}", self.tracer.path, self.variant);
        Tracer {
            path: &path,
            ..self.tracer
        }
        .deserialize_struct("", fields, visitor)
    }
}

/// Walks `T` once from `root`.
fn walk<T: DeserializeOwned>(
    root: &str,
    walk: &Walk,
    trace: &RefCell<Trace>,
) -> Result<(), String> {
    T::deserialize(Tracer {
        path: root,
        walk,
        trace,
    })
    .map(drop)
    .map_err(|e| e.0)
}

/// The file types, by the root of their paths.
type WalkFn = fn(&Walk, &RefCell<Trace>) -> Result<(), String>;

fn walk_building(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_sim::building::BuildingConfig>("building", w, t)
}

fn walk_scene(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_sim::scene::SceneConfig>("scene", w, t)
}

fn walk_study(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_opt::model::config::StudyConfig>("study", w, t)
}

fn walk_designs(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<Vec<slipload_opt::phases::rank::NamedDesign>>("designs", w, t)
}

fn roots() -> [(&'static str, WalkFn); 4] {
    [
        ("building", walk_building as WalkFn),
        ("scene", walk_scene),
        ("study", walk_study),
        ("designs", walk_designs),
    ]
}

fn root_of(path: &str) -> WalkFn {
    let name = path.split(['.', '[']).next().unwrap_or_default();
    roots()
        .into_iter()
        .find(|(r, _)| *r == name)
        .map(|(_, f)| f)
        .unwrap_or_else(|| panic!("no root for {path}"))
}

/// What the parsers accept, read from the parsers.
#[derive(Debug)]
struct Schema {
    nodes: BTreeMap<String, Node>,
    /// Keys (full paths) that may not be left out.
    required: BTreeSet<String>,
    /// Paths whose `deserialize_any` accepts a unit string, with the units it lists.
    quantities: BTreeMap<String, Vec<String>>,
    /// Objects that accept (and ignore) keys they do not know.
    open: Vec<String>,
}

impl Schema {
    fn read() -> Schema {
        let trace = RefCell::new(Trace::default());
        // One pass per variant index: pass k takes variant k of every enum (k mod its count).
        let mut pass = 0;
        loop {
            for (root, f) in roots() {
                let w = Walk {
                    pass,
                    ..Walk::default()
                };
                f(&w, &trace).unwrap_or_else(|e| panic!("walking {root} (pass {pass}): {e}"));
            }
            let most = trace
                .borrow()
                .nodes
                .values()
                .filter_map(|n| match &n.kind {
                    Kind::Enum(v) => Some(v.len()),
                    _ => None,
                })
                .max()
                .unwrap_or(1);
            pass += 1;
            if pass >= most {
                break;
            }
        }
        let nodes = trace.into_inner().nodes;
        let mut required = BTreeSet::new();
        let mut quantities = BTreeMap::new();
        let mut open = Vec::new();
        for (path, node) in &nodes {
            match &node.kind {
                Kind::Struct(fields) => {
                    let w = Walk {
                        pass: node.pass,
                        unknown_key: Some(path.clone()),
                        ..Walk::default()
                    };
                    match root_of(path)(&w, &RefCell::new(Trace::default())) {
                        Ok(()) => open.push(path.clone()),
                        Err(e) if e.starts_with("unknown field `zz_unknown`") => {}
                        Err(e) => panic!("walking {path} with an unknown key: {e}"),
                    }
                    for field in fields {
                        let key = format!("{path}.{field}");
                        let w = Walk {
                            pass: node.pass,
                            omit: Some(key.clone()),
                            ..Walk::default()
                        };
                        match root_of(path)(&w, &RefCell::new(Trace::default())) {
                            Ok(()) => {}
                            Err(e) if e == format!("missing field `{field}`") => {
                                required.insert(key);
                            }
                            Err(e) => panic!("walking without {key}: {e}"),
                        }
                    }
                }
                Kind::Any => {
                    let w = Walk {
                        pass: node.pass,
                        unit_probe: Some(path.clone()),
                        ..Walk::default()
                    };
                    match root_of(path)(&w, &RefCell::new(Trace::default())) {
                        Ok(()) => {}
                        Err(e) if e.contains("unknown unit") => {
                            let units = e
                                .split_once("(units: ")
                                .and_then(|(_, rest)| rest.split_once(')'))
                                .map(|(list, _)| list.split(", ").map(String::from).collect())
                                .unwrap_or_else(|| panic!("{path}: no unit list in {e:?}"));
                            quantities.insert(path.clone(), units);
                        }
                        Err(e) => panic!("probing {path} with a unit string: {e}"),
                    }
                }
                _ => {}
            }
        }
        Schema {
            nodes,
            required,
            quantities,
            open,
        }
    }

    fn kind(&self, path: &str) -> Option<&Kind> {
        self.nodes.get(path).map(|n| &n.kind)
    }

    /// Whether the enum at `path` has only unit variants (it is written as a string).
    fn unit_enum(&self, path: &str, variants: &[&str]) -> bool {
        variants
            .iter()
            .all(|v| self.kind(&format!("{path}.{v}")) == Some(&Kind::Unit))
    }
}

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
        let Some(rows) = secs.get(path) else {
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
