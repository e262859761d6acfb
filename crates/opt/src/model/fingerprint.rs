//! A study's fingerprint: a stable 64-bit FNV-1a hash of everything that determines the
//! numbers of its journals, kept per component so that a mismatch can say what changed.
//!
//! Components (each hashed over a canonical byte form, floats as their IEEE bits):
//! - `building`: the validated building — M, C, K of the frame, storey heights and every
//!   floor's dissipator (m′, k′, c′, F⁻, F⁺), i.e. after units and defaults are resolved;
//! - `records`: the number of records, their names and the suites they form;
//! - `record K samples (NAME)`, one per record: its time step and every sample as the
//!   integrators see it (after scaling), a content hash — not its path;
//! - `method/step`: the sweep's method, time step and HHT α, whether energies are
//!   accumulated, the check's method and time-step factor;
//! - `objective`: every term's metric, statistic and weight;
//! - `objectives` (only in a study that names them): the front's objectives and the
//!   settings of its search ([`crate::phases::pareto`]);
//! - `design space`: the space's map from scaled variables to slip loads, its
//!   constraints and the sweep's list of designs (sampler, points, seed resolved);
//! - `integrator version`: [`slipload_sim::NUMERICS_VERSION`].
//!
//! Two studies with equal fingerprints give the same bits in every journal entry; a
//! journal whose fingerprint differs from the study's is never continued or reused.

use serde::{Deserialize, Serialize};

/// FNV-1a, 64 bits: small, stable across platforms and releases (unlike `std`'s hasher).
#[derive(Debug, Clone, Copy)]
pub struct Fnv64(u64);

impl Default for Fnv64 {
    fn default() -> Self {
        Fnv64(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv64 {
    /// Feeds bytes.
    pub fn bytes(&mut self, b: &[u8]) -> &mut Self {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
        self
    }
    /// Feeds a u64 (little-endian).
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.bytes(&v.to_le_bytes())
    }
    /// Feeds a float as its bits.
    pub fn f64(&mut self, v: f64) -> &mut Self {
        self.u64(v.to_bits())
    }
    /// Feeds floats, length first.
    pub fn f64s(&mut self, v: &[f64]) -> &mut Self {
        self.u64(v.len() as u64);
        for &x in v {
            self.f64(x);
        }
        self
    }
    /// Feeds a string, length first.
    pub fn str(&mut self, s: &str) -> &mut Self {
        self.u64(s.len() as u64);
        self.bytes(s.as_bytes())
    }
    /// The hash.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// One component of a fingerprint.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Component {
    /// Stable key (`building`, `record 3`, …): what is compared.
    pub key: String,
    /// What the component is, for messages (`record 3 samples (SYL090.AT2)`).
    pub label: String,
    /// Its hash, 16 hex digits.
    pub hash: String,
}

/// A study's fingerprint: the hash of its components, and the components.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fingerprint {
    /// Hash of every component, 16 hex digits.
    pub hash: String,
    /// The components, in a fixed order.
    pub components: Vec<Component>,
}

impl Fingerprint {
    /// A fingerprint from (key, label, hash) components.
    pub fn new(parts: Vec<(String, String, u64)>) -> Fingerprint {
        let mut all = Fnv64::default();
        let components: Vec<Component> = parts
            .into_iter()
            .map(|(key, label, h)| {
                all.str(&key).u64(h);
                Component {
                    key,
                    label,
                    hash: format!("{h:016x}"),
                }
            })
            .collect();
        Fingerprint {
            hash: format!("{:016x}", all.finish()),
            components,
        }
    }

    /// What differs from `other` (`self` is the current study): the labels of changed
    /// components, then those only one side has. Empty when the fingerprints are equal.
    pub fn changes_from(&self, other: &Fingerprint) -> Vec<String> {
        if self == other {
            return Vec::new();
        }
        let mut out = Vec::new();
        for c in &self.components {
            match other.components.iter().find(|o| o.key == c.key) {
                Some(o) if o.hash != c.hash => out.push(c.label.clone()),
                Some(_) => {}
                None => out.push(format!("{} (not in the journal's study)", c.label)),
            }
        }
        for o in &other.components {
            if !self.components.iter().any(|c| c.key == o.key) {
                out.push(format!("{} (no longer in the study)", o.label));
            }
        }
        if out.is_empty() {
            out.push("the fingerprint itself".into());
        }
        out
    }

    /// [`Fingerprint::changes_from`] as one phrase, shortened after 6 items.
    pub fn describe_changes(&self, other: &Fingerprint) -> String {
        let ch = self.changes_from(other);
        if ch.len() > 6 {
            format!("{} and {} more", ch[..6].join(", "), ch.len() - 6)
        } else {
            ch.join(", ")
        }
    }
}

/// The fingerprint of `study` whose sweep samples `designs`.
pub fn of_study(study: &crate::Study, designs: &[crate::model::sampler::Design]) -> Fingerprint {
    use crate::model::fidelity::{Fidelity, hht_alpha};
    let mut parts: Vec<(String, String, u64)> = Vec::new();
    let mut part = |key: &str, label: String, h: &Fnv64| {
        parts.push((key.to_string(), label, h.finish()));
    };
    let b = &study.building;
    let mut h = Fnv64::default();
    for m in [&b.mass, &b.damping, &b.stiffness] {
        h.u64(m.nrows() as u64).u64(m.ncols() as u64);
        // column-major, as stored
        h.f64s(m.as_slice());
    }
    match &b.storey_heights {
        Some(v) => h.u64(1).f64s(v),
        None => h.u64(0),
    };
    h.u64(b.dissipators.len() as u64);
    for d in &b.dissipators {
        match d {
            Some(d) => h
                .u64(1)
                .f64(d.mass)
                .f64(d.brace_stiffness)
                .f64(d.brace_damping)
                .f64(d.lower)
                .f64(d.upper),
            None => h.u64(0),
        };
    }
    // Yield laws, P-Δ loads and the collapse limit, hashed only when present, so an
    // elastic building keeps the fingerprint it had before they existed.
    if b.storey_yield.iter().any(Option::is_some)
        || b.gravity_loads.is_some()
        || b.collapse_drift.is_some()
    {
        h.u64(0x0079_6965_6c64); // "yield": a tag before the frame's nonlinear data
        for y in &b.storey_yield {
            match y {
                Some(y) => h
                    .u64(1)
                    .f64(y.stiffness)
                    .f64(y.yield_shear)
                    .f64(y.post_yield_ratio),
                None => h.u64(0),
            };
        }
        for v in [&b.gravity_loads, &b.collapse_drift] {
            match v {
                Some(v) => h.u64(1).f64s(v),
                None => h.u64(0),
            };
        }
    }
    part("building", "building".into(), &h);

    let mut h = Fnv64::default();
    h.u64(study.records.len() as u64);
    for r in &study.records {
        h.str(r.name());
    }
    h.u64(study.suites.len() as u64);
    for s in &study.suites {
        h.str(&s.name)
            .u64(s.range.start as u64)
            .u64(s.range.end as u64);
        // (a rest after the records changes every run of the suite; none hashes as before)
        if s.free_vibration_s > 0.0 {
            h.f64(s.free_vibration_s);
        }
    }
    part("records", "record names and suites".into(), &h);
    for (i, r) in study.records.iter().enumerate() {
        let mut h = Fnv64::default();
        h.f64(r.dt()).f64s(r.samples());
        // a `worst` pair's orientations; none hashes as before
        for o in study.orientations.get(i).into_iter().flatten() {
            h.f64(o.dt()).f64s(o.samples());
        }
        part(
            &format!("record {}", i + 1),
            format!("record {} samples ({})", i + 1, r.name()),
            &h,
        );
    }

    let mut h = Fnv64::default();
    for fid in [Fidelity::sweep(study), Fidelity::check(study)] {
        h.str(fid.method.as_str());
        match fid.dt_s {
            Some(dt) => h.u64(1).f64(dt),
            None => h.u64(0),
        };
        h.f64(fid.dt_factor).u64(u64::from(fid.energies));
        h.f64(hht_alpha(fid.method));
    }
    part("method/step", "method/step".into(), &h);

    let mut h = Fnv64::default();
    h.u64(study.objective.terms.len() as u64);
    for t in &study.objective.terms {
        h.str(t.metric.as_str())
            .str(t.statistic.as_str())
            .f64(t.weight);
    }
    // (only a cost objective adds its prices: a response objective keeps its fingerprint)
    if let Some(c) = &study.objective.cost {
        h.str("cost").f64(c.per_kn).f64(c.per_device);
    }
    part("objective", "objective".into(), &h);

    // property bounds and limits, only when the study names them: a study without keeps
    // the fingerprint it had before they existed (the bounds change every run, the
    // limits what the refiners minimise)
    if !study.checks.is_empty() {
        let mut h = Fnv64::default();
        h.str(&serde_json::to_string(&study.checks).expect("the checks serialise"));
        part("checks", "property bounds and limits".into(), &h);
    }

    // the front's objectives and search, only when the study names them: a
    // one-objective study keeps the fingerprint it had before they existed
    if !study.objectives.is_empty() {
        let mut h = Fnv64::default();
        h.u64(study.objectives.len() as u64);
        for o in &study.objectives {
            h.str(o.metric.as_str());
            match o.statistic {
                Some(s) => h.u64(1).str(s.as_str()),
                None => h.u64(0),
            };
        }
        let p = study.config.pareto.unwrap_or_default();
        h.u64(p.designs as u64)
            .u64(p.batch as u64)
            .f64(p.initial_radius);
        part(
            "objectives",
            "objectives of the front and its search".into(),
            &h,
        );
    }

    let sp = &study.space;
    let mut h = Fnv64::default();
    h.u64(sp.dampers.len() as u64);
    for &d in &sp.dampers {
        h.u64(d as u64);
    }
    h.f64s(&sp.offset);
    for m in [&sp.basis, &sp.a] {
        h.u64(m.nrows() as u64)
            .u64(m.ncols() as u64)
            .f64s(m.as_slice());
    }
    h.f64s(&sp.b);
    h.u64(designs.len() as u64);
    for d in designs {
        h.str(&d.label).f64s(&d.slip_loads_n);
        match &d.z {
            Some(z) => h.u64(1).f64s(z),
            None => h.u64(0),
        };
    }
    part("design space", "design space/sample".into(), &h);

    let mut h = Fnv64::default();
    h.u64(u64::from(slipload_sim::NUMERICS_VERSION));
    part(
        "integrator version",
        format!(
            "integrator version (now {})",
            slipload_sim::NUMERICS_VERSION
        ),
        &h,
    );
    Fingerprint::new(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_reference_values() {
        // FNV-1a 64 test vectors (Fowler, Noll, Vo)
        assert_eq!(Fnv64::default().finish(), 0xcbf2_9ce4_8422_2325);
        assert_eq!(Fnv64::default().bytes(b"a").finish(), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(
            Fnv64::default().bytes(b"foobar").finish(),
            0x8594_4171_f739_67e8
        );
    }

    #[test]
    fn changes_name_the_components() {
        let a = Fingerprint::new(vec![
            ("building".into(), "building".into(), 1),
            ("record 1".into(), "record 1 samples (A.AT2)".into(), 2),
        ]);
        let b = Fingerprint::new(vec![
            ("building".into(), "building".into(), 1),
            ("record 1".into(), "record 1 samples (A.AT2)".into(), 3),
        ]);
        assert!(a.changes_from(&a).is_empty());
        assert_eq!(
            a.changes_from(&b),
            vec!["record 1 samples (A.AT2)".to_string()]
        );
    }
}
