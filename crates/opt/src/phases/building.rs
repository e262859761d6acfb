//! The building as the study ran it, kept in the study folder so that a report states
//! what was designed ([`BuildingPage`]):
//! - `building.json`: a building file (`slipload simulate` and `explain` take it) holding
//!   the building the study ran, every quantity a number in SI units (kg, N/m, N·s/m, m,
//!   N): its masses, stiffnesses, heights and damping as the file gives them (Rayleigh by
//!   its ratios and modes stays so), its dampers with their slip loads, and what the file
//!   leaves to defaults or the study overrides made explicit — each yielding storey's
//!   stiffness, yield shear and post-yield ratio, the P-Δ gravity loads, and the collapse
//!   limit (the study's `collapse_drift_ratio` in place of the file's, or the default for a
//!   yielding or P-Δ frame). Loaded again it is the same building to the bit.
//! - `building.md`: its inputs as a person reads them, the first page of the report
//!   (`slipload report`): the frame per storey (height, floor mass, storey stiffness, yield
//!   law, P-Δ load), the inherent damping as given with the ratio it gives each mode, the
//!   collapse limit, the dampers (brace stiffness and, where the study states it, the
//!   braces' configuration; dissipator mass, brace damping, the file's slip load), in t,
//!   kg, kN, kN/m, kN·s/m, m and % as the rest of the report states them.

use crate::base::error::OptError;
use crate::model::check::md_text;
use crate::model::study::Study;
use crate::store::folder::StudyFolder;
use serde_json::{Map, Value, json};
use slipload_sim::building::{DEFAULT_COLLAPSE_DRIFT_RATIO, DampingConfig, storey_stiffness};
use slipload_sim::units::short_number;
use slipload_sim::{Building, BuildingConfig};
use std::fmt::Write as _;

/// The modes whose period and damping ratio `building.md` lists (the first).
const MODES_LISTED: usize = 6;

/// The building the study ran, as the folder keeps it: `building.json` and `building.md`.
#[derive(Debug, Clone, PartialEq)]
pub struct BuildingPage {
    /// `building.json`.
    pub json: String,
    /// `building.md`.
    pub markdown: String,
}

/// How the collapse limit was set: a drift ratio (whose source is named) or a drift.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Collapse {
    /// A drift ratio, and where it comes from.
    Ratio(f64, &'static str),
    /// A drift, m, every storey.
    Drift(f64),
}

impl BuildingPage {
    /// The files [`BuildingPage::write_files`] writes.
    pub const FILES: [&str; 2] = ["building.json", "building.md"];

    /// The page of `study`'s building.
    pub fn of(study: &Study) -> Result<BuildingPage, OptError> {
        let b = &study.building;
        let collapse = collapse(study);
        let mut json =
            serde_json::to_string_pretty(&building_json(b, &study.building_config, collapse)?)
                .map_err(|source| OptError::Json {
                    path: "building.json".into(),
                    source,
                })?;
        json.push('\n');
        Ok(BuildingPage {
            json,
            markdown: markdown(study, collapse),
        })
    }

    /// Writes `building.json` and `building.md` into the study folder.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("building.json", self.json.as_bytes())?;
        folder.write("building.md", self.markdown.as_bytes())
    }
}

/// The collapse limit the study runs with, and how it was set; `None` without one.
fn collapse(study: &Study) -> Option<Collapse> {
    study.building.collapse_drift.as_ref()?;
    let cfg = &study.building_config;
    Some(
        match (study.config.collapse_drift_ratio, cfg.collapse_drift_ratio) {
            (Some(r), _) => Collapse::Ratio(r, "the study's `collapse_drift_ratio`"),
            (None, Some(r)) => Collapse::Ratio(r, "the building file's `collapse_drift_ratio`"),
            (None, None) => match &cfg.collapse_drift {
                Some(d) => Collapse::Drift(d.0),
                None => Collapse::Ratio(
                    DEFAULT_COLLAPSE_DRIFT_RATIO,
                    "the default for a frame that yields or feels P-Δ",
                ),
            },
        },
    )
}

/// A JSON value with every `null` left out (the building file's keys are optional).
fn without_nulls(v: Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.into_iter()
                .filter(|(_, v)| !v.is_null())
                .map(|(k, v)| (k, without_nulls(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.into_iter().map(without_nulls).collect()),
        other => other,
    }
}

/// A list of quantities as SI numbers.
fn numbers<Q: Copy + Into<f64>>(v: &[Q]) -> Value {
    json!(v.iter().map(|q| (*q).into()).collect::<Vec<f64>>())
}

/// `building.json`: the building file of the building `b` the study ran, from its file
/// `cfg` as written (see the module).
fn building_json(
    b: &Building,
    cfg: &BuildingConfig,
    collapse: Option<Collapse>,
) -> Result<Value, OptError> {
    let mut m = Map::new();
    m.insert("name".into(), json!(b.name));
    if let Some(d) = &cfg.description {
        m.insert("description".into(), json!(d));
    }
    if let Some(ms) = &cfg.floor_masses {
        m.insert("floor_masses".into(), numbers(ms));
    }
    if let Some(rows) = &cfg.mass_matrix {
        m.insert(
            "mass_matrix".into(),
            Value::Array(rows.iter().map(|r| numbers(r)).collect()),
        );
    }
    if let Some(ks) = &cfg.storey_stiffness {
        m.insert("storey_stiffness".into(), numbers(ks));
    }
    if let Some(rows) = &cfg.stiffness_matrix {
        m.insert(
            "stiffness_matrix".into(),
            Value::Array(rows.iter().map(|r| numbers(r)).collect()),
        );
    }
    if let Some(d) = &cfg.damping {
        let v = serde_json::to_value(d).map_err(|source| OptError::Json {
            path: "building.json".into(),
            source,
        })?;
        m.insert("damping".into(), without_nulls(v));
    }
    if let Some(h) = &b.storey_heights {
        m.insert("storey_heights".into(), json!(h));
    }
    let dissipators: Vec<Value> = b
        .dissipators
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.map(|d| (i, d)))
        .map(|(i, d)| {
            let mut e = json!({
                "floor": i + 1,
                "brace_stiffness": d.brace_stiffness,
                "mass": d.mass,
                "brace_damping": d.brace_damping,
            });
            if d.is_locked() {
                e["slip_load"] = json!("locked");
            } else if d.lower == -d.upper {
                e["slip_load"] = json!(d.upper);
            } else {
                e["bounds"] = json!([d.lower, d.upper]);
            }
            e
        })
        .collect();
    if !dissipators.is_empty() {
        m.insert("dissipators".into(), Value::Array(dissipators));
    }
    let yields: Vec<Value> = b
        .storey_yield
        .iter()
        .enumerate()
        .filter_map(|(i, y)| {
            y.map(|y| {
                json!({
                    "storey": i + 1,
                    "stiffness": y.stiffness,
                    "yield_shear": y.yield_shear,
                    "post_yield_ratio": y.post_yield_ratio,
                })
            })
        })
        .collect();
    if !yields.is_empty() {
        m.insert("storey_yield".into(), Value::Array(yields));
    }
    if let Some(p) = &b.gravity_loads {
        m.insert("p_delta".into(), json!({ "gravity_loads": p }));
    }
    match collapse {
        Some(Collapse::Ratio(r, _)) => {
            m.insert("collapse_drift_ratio".into(), json!(r));
        }
        Some(Collapse::Drift(d)) => {
            m.insert("collapse_drift".into(), json!(d));
        }
        None => {}
    }
    Ok(Value::Object(m))
}

/// A number for the page: six significant digits ([`short_number`]).
fn num(v: f64) -> String {
    short_number(v)
}

/// A ratio in percent of critical (or of the storey height), to six digits.
fn pct(v: f64) -> String {
    format!("{} %", short_number(100.0 * v))
}

/// The inherent damping as the building file gives it, in words.
fn damping_text(cfg: &BuildingConfig) -> String {
    let list = |v: &[f64], f: &dyn Fn(f64) -> String| {
        v.iter().map(|x| f(*x)).collect::<Vec<_>>().join(" and ")
    };
    match &cfg.damping {
        None | Some(DampingConfig::None) => "none".into(),
        Some(DampingConfig::Rayleigh(r)) => {
            if let (Some(a), Some(b)) = (r.alpha, r.beta) {
                return format!(
                    "Rayleigh, C = α M + β K with α = {} 1/s and β = {} s",
                    num(a),
                    num(b)
                );
            }
            let ratios = match (r.ratio, &r.ratios) {
                (Some(z), _) => pct(z),
                (None, Some(zs)) => list(zs, &pct),
                (None, None) => "—".into(),
            };
            let at = match (&r.modes, &r.periods) {
                (Some(ms), _) => format!(
                    "modes {}",
                    ms.iter()
                        .map(usize::to_string)
                        .collect::<Vec<_>>()
                        .join(" and ")
                ),
                (None, Some(ts)) => format!(
                    "periods {} s",
                    list(&ts.iter().map(|t| t.0).collect::<Vec<_>>(), &num)
                ),
                (None, None) => "—".into(),
            };
            format!("Rayleigh, {ratios} of critical at the bare frame's {at}")
        }
        Some(DampingConfig::Modal { ratio, ratios }) => match (ratio, ratios) {
            (Some(z), _) => format!("modal, {} of critical in every mode", pct(*z)),
            (None, Some(zs)) => format!(
                "modal, {} of critical in modes 1 to {} (modes past them take the last)",
                zs.iter().map(|z| pct(*z)).collect::<Vec<_>>().join(", "),
                zs.len()
            ),
            (None, None) => "modal".into(),
        },
        Some(DampingConfig::Storey(_)) => {
            "storey dashpots (the storey damping column, kN·s/m)".into()
        }
        Some(DampingConfig::Matrix(_)) => "a full damping matrix (in building.json, N·s/m)".into(),
    }
}

/// One Markdown table row.
fn row(cells: &[String]) -> String {
    format!("| {} |\n", cells.join(" | "))
}

/// `building.md` (see the module).
fn markdown(study: &Study, collapse: Option<Collapse>) -> String {
    let b = &study.building;
    let cfg = &study.building_config;
    let n = b.floors();
    let mut s = String::new();
    let _ = writeln!(s, "# Building: {}\n", md_text(&b.name));
    if let Some(d) = &cfg.description {
        let _ = writeln!(s, "{}\n", md_text(d));
    }
    s.push_str(
        "The building the study ran: `building.json` in this folder is it as a building file \
         (SI units), with what the file leaves to defaults made explicit. Storey i lies between \
         floor i − 1 and floor i (floor 0 the ground); floor i carries its mass and its damper.\n\n",
    );
    // the frame, per storey
    let given_masses = cfg.floor_masses.is_some();
    let given_storeys = cfg.storey_stiffness.is_some();
    let storey_damping = match &cfg.damping {
        Some(DampingConfig::Storey(cs)) => Some(cs.iter().map(|c| c.0).collect::<Vec<_>>()),
        _ => None,
    };
    let yields = b.storey_yield.iter().any(Option::is_some);
    let mut head = vec![
        "storey".to_string(),
        "height (m)".to_string(),
        if given_masses {
            "floor mass (t)".to_string()
        } else {
            "floor mass (t; row sum of the mass matrix)".to_string()
        },
        if given_storeys {
            "storey stiffness (kN/m)".to_string()
        } else {
            "storey stiffness (kN/m; of the frame's stiffness matrix, shear over drift)".to_string()
        },
    ];
    if storey_damping.is_some() {
        head.push("storey damping (kN·s/m)".into());
    }
    if yields {
        head.extend([
            "yield stiffness k (kN/m)".to_string(),
            "yield shear F_y (kN)".to_string(),
            "yield drift (mm)".to_string(),
            "post-yield ratio α".to_string(),
        ]);
    }
    if b.gravity_loads.is_some() {
        head.push("P-Δ gravity load P (kN)".into());
    }
    s.push_str("## Frame\n\n");
    s.push_str(&row(&head));
    s.push_str(&row(&vec!["---:".to_string(); head.len()]));
    for i in 0..n {
        let mut cells = vec![
            (i + 1).to_string(),
            b.storey_heights.as_ref().map_or("—".into(), |h| num(h[i])),
            num(b.mass.row(i).sum() / 1e3),
            match &cfg.storey_stiffness {
                Some(ks) => num(ks[i].0 / 1e3),
                None => storey_stiffness(&b.stiffness, i).map_or("—".into(), |k| num(k / 1e3)),
            },
        ];
        if let Some(cs) = &storey_damping {
            cells.push(num(cs[i] / 1e3));
        }
        if yields {
            match &b.storey_yield[i] {
                Some(y) => cells.extend([
                    num(y.stiffness / 1e3),
                    num(y.yield_shear / 1e3),
                    num(y.yield_drift() * 1e3),
                    num(y.post_yield_ratio),
                ]),
                None => cells.extend(["elastic".to_string(), "—".into(), "—".into(), "—".into()]),
            }
        }
        if let Some(p) = &b.gravity_loads {
            cells.push(num(p[i] / 1e3));
        }
        s.push_str(&row(&cells));
    }
    s.push('\n');
    let matrices: Vec<&str> = [
        (!given_masses, "`mass_matrix`"),
        (!given_storeys, "`stiffness_matrix`"),
    ]
    .into_iter()
    .filter_map(|(m, name)| m.then_some(name))
    .collect();
    if !matrices.is_empty() {
        let _ = writeln!(
            s,
            "The building file gives the frame's {} as a matrix: it is in `building.json`, and the table states what it gives each floor or storey.\n",
            matrices.join(" and ")
        );
    }
    // damping, modes, P-Δ, collapse
    let _ = writeln!(s, "**Inherent damping:** {}.\n", damping_text(cfg));
    let dynamics = b.dynamics();
    let shown = n.min(MODES_LISTED);
    let modes: Vec<String> = (0..shown)
        .map(|k| {
            format!(
                "mode {}: T = {:.4} s, ζ = {:.2} %",
                k + 1,
                2.0 * std::f64::consts::PI / b.modes.omega[k],
                100.0 * dynamics.damping_ratios[k]
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "**The bare frame's modes** ({}): {}{}.\n",
        if shown < n {
            format!("the first {shown} of {n}")
        } else {
            format!("all {n}")
        },
        modes.join("; "),
        if dynamics.classical {
            ""
        } else {
            " (the damping is not classical: these are the diagonal's ratios)"
        }
    );
    if b.gravity_loads.is_some() {
        let given = cfg
            .p_delta
            .as_ref()
            .is_some_and(|p| p.gravity_loads.is_some());
        let _ = writeln!(
            s,
            "**P-Δ:** a geometric stiffness −P/h on every storey, P the gravity load of the table ({}).\n",
            if given {
                "as the building file gives it"
            } else {
                "g = 9.80665 m/s² times the mass at and above the storey, the default"
            }
        );
    }
    match collapse {
        Some(Collapse::Ratio(r, from)) => {
            let _ = writeln!(
                s,
                "**Collapse:** a run stops when a storey drifts past {} of its height ({from}).\n",
                pct(r)
            );
        }
        Some(Collapse::Drift(d)) => {
            let _ = writeln!(
                s,
                "**Collapse:** a run stops when a storey drifts past {} mm (the building file's `collapse_drift`).\n",
                num(d * 1e3)
            );
        }
        None => s.push_str("**Collapse:** no limit (an elastic frame without P-Δ).\n\n"),
    }
    s.push_str(&dampers(study));
    s
}

/// The dampers' table, with the braces' configuration where the study states it.
fn dampers(study: &Study) -> String {
    let b = &study.building;
    let mut s = String::from("## Dampers\n\n");
    let devices = study.config.devices.as_ref();
    let angle = devices.and_then(|d| d.brace_angle_deg);
    let per = devices.and_then(|d| d.braces_per_damper).unwrap_or(1);
    let rows: Vec<(usize, slipload_sim::Dissipator)> = b
        .dissipators
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.map(|d| (i + 1, d)))
        .collect();
    if rows.is_empty() {
        s.push_str("None in the building file.\n");
        return s;
    }
    let mut head = vec![
        "floor".to_string(),
        "brace stiffness k′ (kN/m, horizontal)".to_string(),
    ];
    if angle.is_some() {
        head.push("axial stiffness per brace (kN/m)".into());
    }
    head.extend([
        "dissipator mass m′ (kg)".to_string(),
        "brace damping c′ (kN·s/m)".to_string(),
        "slip load in the building file (kN)".to_string(),
    ]);
    s.push_str(&row(&head));
    s.push_str(&row(&vec!["---:".to_string(); head.len()]));
    for (floor, d) in &rows {
        let mut cells = vec![floor.to_string(), num(d.brace_stiffness / 1e3)];
        if let Some(a) = angle {
            let c = a.to_radians().cos();
            cells.push(num(d.brace_stiffness / (per as f64 * c * c) / 1e3));
        }
        cells.extend([
            num(d.mass),
            num(d.brace_damping / 1e3),
            if d.is_locked() {
                "locked".to_string()
            } else if d.lower == -d.upper {
                format!("{:.1}", d.upper / 1e3)
            } else {
                format!("{:.1}..{:.1}", d.lower / 1e3, d.upper / 1e3)
            },
        ]);
        s.push_str(&row(&cells));
    }
    s.push('\n');
    let none: Vec<String> = (1..=b.floors())
        .filter(|f| b.dissipators[f - 1].is_none())
        .map(|f| f.to_string())
        .collect();
    if !none.is_empty() {
        let _ = writeln!(s, "No damper on floor {}.\n", none.join(", "));
    }
    s.push_str(
        "**Braces:** k′ is the horizontal (storey-level) stiffness of the bracing in series \
         with each damper. ",
    );
    match angle {
        Some(a) => {
            let _ = writeln!(
                s,
                "The study states {} at {} ° to the horizontal per damper (`devices`): each brace's axial stiffness is k′ / (n cos² θ) with n = {per}.",
                if per == 1 {
                    "one diagonal brace".to_string()
                } else {
                    format!("{per} braces")
                },
                num(a)
            );
        }
        None => s.push_str(
            "The study states no brace configuration (`devices.brace_angle_deg`, \
             `devices.braces_per_damper`).\n",
        ),
    }
    s
}
