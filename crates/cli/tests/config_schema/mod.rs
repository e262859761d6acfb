//! What the config parsers accept, read from the parsers themselves (shared by
//! `docs_reference.rs` and `config_tracer.rs`). A tracing [`Deserializer`] walks each
//! file type (building, scene, study, candidate designs) as its serde derive asks to be
//! walked: `deserialize_struct` hands over the struct's field names (every struct of the
//! configs denies unknown fields — checked too: each is walked once with an extra key —
//! so these are exactly the keys accepted), `deserialize_enum` its variant names, and
//! each field's value is walked in turn, so nested objects, lists and enum variants (one
//! pass per variant index) are all reached. Two more questions go to the parser field by
//! field: whether a key may be left out (its struct is walked once without it: serde's
//! "missing field" means required), and whether a value accepts a string with a unit
//! (the value is given as `"1 zz"`: a quantity answers "unknown unit", and lists the
//! units it knows). [`Schema::read`] puts the answers together.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset

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
pub enum Kind {
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
pub struct Node {
    pub kind: Kind,
    /// The first pass that reached this path (the variant choices that lead to it).
    pub pass: usize,
}

/// How one walk goes.
#[derive(Debug, Clone, Default)]
pub struct Walk {
    /// Every enum takes its variant number `pass % variants`.
    pub pass: usize,
    /// Leave this key (a full path) out of its object.
    pub omit: Option<String>,
    /// Give `"1 zz"` (a number with an unknown unit) at this path's `deserialize_any`.
    pub unit_probe: Option<String>,
    /// Add the key `zz_unknown` to the object at this path.
    pub unknown_key: Option<String>,
}

#[derive(Debug, Default)]
pub struct Trace {
    pub nodes: BTreeMap<String, Node>,
}

impl Trace {
    fn record(&mut self, path: &str, kind: Kind, pass: usize) {
        self.nodes
            .entry(path.to_string())
            .or_insert(Node { kind, pass });
    }
}

#[derive(Debug)]
pub struct TraceError(String);

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
pub fn walk<T: DeserializeOwned>(
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

fn walk_floor_plan(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_sim::floorplan::FloorPlanConfig>("floor_plan", w, t)
}

fn walk_plan_scene(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_sim::floorplan::FloorPlanSceneConfig>("plan_scene", w, t)
}

fn walk_plan_study(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<slipload_opt::plan::PlanStudyConfig>("plan_study", w, t)
}

fn walk_designs(w: &Walk, t: &RefCell<Trace>) -> Result<(), String> {
    walk::<Vec<slipload_opt::phases::rank::NamedDesign>>("designs", w, t)
}

fn roots() -> [(&'static str, WalkFn); 7] {
    [
        ("building", walk_building as WalkFn),
        ("scene", walk_scene),
        ("study", walk_study),
        ("designs", walk_designs),
        ("floor_plan", walk_floor_plan),
        ("plan_scene", walk_plan_scene),
        ("plan_study", walk_plan_study),
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
pub struct Schema {
    pub nodes: BTreeMap<String, Node>,
    /// Keys (full paths) that may not be left out.
    pub required: BTreeSet<String>,
    /// Paths whose `deserialize_any` accepts a unit string, with the units it lists.
    pub quantities: BTreeMap<String, Vec<String>>,
    /// Objects that accept (and ignore) keys they do not know.
    pub open: Vec<String>,
}

impl Schema {
    pub fn read() -> Schema {
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

    pub fn kind(&self, path: &str) -> Option<&Kind> {
        self.nodes.get(path).map(|n| &n.kind)
    }

    /// Whether the enum at `path` has only unit variants (it is written as a string).
    pub fn unit_enum(&self, path: &str, variants: &[&str]) -> bool {
        variants
            .iter()
            .all(|v| self.kind(&format!("{path}.{v}")) == Some(&Kind::Unit))
    }
}
