//! Resolving a scene: [`Scene::load`], [`Scene::from_json`] and [`Scene::from_config`]
//! load the building and the ground motion, apply the overrides and run the rules of
//! `check` in a fixed order (the first refusal is the one reported).

use super::check::{
    apply_window, check_exclusive_fields, check_harmonic, check_harmonic_sampling,
    check_loop_settings, check_method_options, check_overrides, check_step_against_record,
    pad_note, target_pga_expected, target_pga_in_band, vec_or_zero,
};
use super::config::{BuildingRef, SceneConfig, SceneOverrides, SyntheticConfig};
use super::method::{MethodName, MethodSettings, default_dt};
use super::resolved::{Harmonic, InitialState, Scene};
use crate::building::Building;
use crate::error::SimError;
use crate::units::is_positive;
use slipload_motion::{G, Record, Units};
use std::path::Path;
use std::sync::Arc;

/// The record a [`SyntheticConfig`] names, scaled to its PGA (the override's first).
fn synthetic_record(
    syn: &SyntheticConfig,
    path: &Path,
    over: &SceneOverrides,
) -> Result<Record, SimError> {
    let field = "excitation.synthetic";
    let pga_g = over
        .scale_pga_g
        .or(syn.pga_g)
        .unwrap_or(slipload_motion::DEFAULT_SUITE_PGA_G);
    if !target_pga_in_band(pga_g) {
        return Err(SimError::invalid(
            path,
            format!("{field}.pga_g"),
            target_pga_expected(pga_g),
        ));
    }
    let record = match (syn.index, syn.seed) {
        (Some(_), Some(_)) => {
            return Err(SimError::invalid(
                path,
                field,
                "give either index (a member of the embedded suite) or seed, not both",
            ));
        }
        (_, Some(seed)) => {
            let mut params = slipload_motion::Synthetic::default();
            if let Some(d) = syn.duration {
                params.duration_s = d.0;
            }
            if let Some(dt) = syn.dt {
                params.dt_s = dt.0;
            }
            params
                .validate()
                .map_err(|e| SimError::invalid(path, field, e.to_string()))?;
            params.generate(seed, &format!("synthetic seed {seed}"))?
        }
        (index, None) => {
            if syn.duration.is_some() || syn.dt.is_some() {
                return Err(SimError::invalid(
                    path,
                    field,
                    "duration and dt apply to a seeded record: give seed too",
                ));
            }
            let index = index.unwrap_or(0);
            let mut suite = slipload_motion::default_suite();
            if index >= suite.len() {
                return Err(SimError::invalid(
                    path,
                    format!("{field}.index"),
                    format!(
                        "the embedded suite has {} records (0..{}), got {index}",
                        suite.len(),
                        suite.len() - 1
                    ),
                ));
            }
            suite.swap_remove(index)
        }
    };
    Ok(record.scaled_to_pga(pga_g * G)?)
}

impl Scene {
    /// Loads a scene file — or a building file, which is a scene with no excitation.
    pub fn load(path: &Path, over: &SceneOverrides) -> Result<Scene, SimError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "scene",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        Scene::from_json(&text, path, over)
    }

    /// Parses a scene (or building) from JSON text; `path` names it in errors and anchors
    /// relative paths.
    pub fn from_json(text: &str, path: &Path, over: &SceneOverrides) -> Result<Scene, SimError> {
        Scene::from_config(SceneConfig::from_json(text, path)?, path, over)
    }

    /// Resolves a config: loads the building and the record, applies overrides, validates.
    pub fn from_config(
        cfg: SceneConfig,
        path: &Path,
        over: &SceneOverrides,
    ) -> Result<Scene, SimError> {
        Scene::from_config_with_record(cfg, path, over, None)
    }

    /// As [`Scene::from_config`], with a ground motion already in memory (a record a
    /// notebook built from an array, say): when given, it replaces the scene's excitation
    /// record or synthetic motion as an `over.record` file would, and goes through the
    /// same rules — the window, `over.scale_pga_g`, the default step from its Δt, the
    /// duration from its length.
    pub fn from_config_with_record(
        cfg: SceneConfig,
        path: &Path,
        over: &SceneOverrides,
        given: Option<Arc<Record>>,
    ) -> Result<Scene, SimError> {
        check_overrides(over)?;
        let base = path.parent().unwrap_or(Path::new("."));
        let building = match &cfg.building {
            BuildingRef::Path(p) => Building::load(&base.join(p))?,
            BuildingRef::Inline(b) => Building::from_config(b, path)?,
        };
        let n = building.floors();
        check_exclusive_fields(&cfg, path)?;
        // The window in force: `--window` replaces the scene's record window.
        let scene_window = cfg
            .excitation
            .record
            .as_ref()
            .and_then(|rc| rc.window)
            .map(|[s, d]| (s.0, d.0));
        let window: Option<(f64, f64, String)> = match (over.window, scene_window) {
            (Some((s, d)), _) => Some((s, d, "--window".to_string())),
            (None, Some((s, d))) if over.record.is_none() && given.is_none() => Some((
                s,
                d,
                format!("{}: field `excitation.record.window`", path.display()),
            )),
            _ => None,
        };
        // Set when the window reaches past the record's end: the run then lasts the
        // window's duration, padded with the ground at rest. (A window inside the record
        // lasts what it keeps: whole sample intervals from its start.)
        let past_end = std::cell::Cell::new(false);
        let cut = |r: Record| -> Result<Record, SimError> {
            match &window {
                Some((s, d, what)) => {
                    past_end.set(s + d > r.duration() + 1e-9 * r.dt());
                    apply_window(&r, (*s, *d), what)
                }
                None => Ok(r),
            }
        };
        // Ground motion: the one given in memory, else the override's file, else the scene's
        // record, else its synthetic one.
        let record = if let Some(r) = given {
            let mut r = match &window {
                Some(_) => Arc::new(cut(Record::clone(&r))?),
                None => r,
            };
            if let Some(pga) = over.scale_pga_g {
                r = Arc::new(r.scaled_to_pga(pga * G)?);
            }
            Some(r)
        } else if let Some(file) = &over.record {
            let mut r = cut(slipload_motion::read_record(file, over.units, None)?)?;
            if let Some(pga) = over.scale_pga_g {
                r = r.scaled_to_pga(pga * G)?;
            }
            Some(Arc::new(r))
        } else if let Some(rc) = &cfg.excitation.record {
            let units = match &rc.units {
                None => over.units,
                Some(u) => Some(u.parse::<Units>().map_err(|e| {
                    SimError::invalid(path, "excitation.record.units", e.to_string())
                })?),
            };
            let mut r = cut(slipload_motion::read_record(
                &base.join(&rc.file),
                units,
                rc.dt.map(|d| d.0),
            )?)?;
            if over.scale.is_some() {
                // --scale replaces the scene's own scaling (applied below)
            } else if let Some(f) = rc.scale {
                if !f.is_finite() {
                    return Err(SimError::invalid(
                        path,
                        "excitation.record.scale",
                        "must be finite",
                    ));
                }
                r = r.try_scaled(f)?;
            }
            match over
                .scale_pga_g
                .or(rc.scale_pga_g.filter(|_| over.scale.is_none()))
            {
                Some(pga) if !target_pga_in_band(pga) => {
                    return Err(SimError::invalid(
                        path,
                        "excitation.record.scale_pga_g",
                        target_pga_expected(pga),
                    ));
                }
                Some(pga) => r = r.scaled_to_pga(pga * G)?,
                None => {}
            }
            Some(Arc::new(r))
        } else if let Some(syn) = &cfg.excitation.synthetic {
            // windowed before scaling, as a record is: the PGA is the window's
            let r = synthetic_record(syn, path, over)?;
            let r = match &window {
                Some(_) => {
                    let pga = r.pga();
                    cut(r)?.scaled_to_pga(pga)?
                }
                None => r,
            };
            Some(Arc::new(r))
        } else {
            if window.is_some() {
                return Err(SimError::Scene(format!(
                    "--window: {} has no ground motion to window; give a record (--record) or a duration (--duration)",
                    path.display()
                )));
            }
            None
        };
        let record = match (record, over.scale) {
            (Some(r), Some(f)) => Some(Arc::new(r.try_scaled(f)?)),
            (None, Some(f)) => {
                return Err(SimError::Scene(format!(
                    "--scale {f}: {} has no ground motion to scale; give a record (--record)",
                    path.display()
                )));
            }
            (r, None) => r,
        };
        let harmonic = match &cfg.excitation.harmonic {
            None => None,
            Some(h) => {
                check_harmonic(h, n, &building, path)?;
                Some(Harmonic {
                    floor: h.floor - 1,
                    amplitude: h.amplitude.0,
                    omega: h.omega.0,
                    phase: h.phase.0,
                })
            }
        };
        let initial = match cfg.excitation.initial.clone() {
            None => InitialState::rest(n),
            Some(ic) => InitialState {
                floor_displacement: vec_or_zero(
                    path,
                    "excitation.initial.floor_displacement",
                    ic.floor_displacement
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                floor_velocity: vec_or_zero(
                    path,
                    "excitation.initial.floor_velocity",
                    ic.floor_velocity.map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                dissipator_displacement: vec_or_zero(
                    path,
                    "excitation.initial.dissipator_displacement",
                    ic.dissipator_displacement
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                dissipator_velocity: vec_or_zero(
                    path,
                    "excitation.initial.dissipator_velocity",
                    ic.dissipator_velocity
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
            },
        };
        let mut notes = Vec::new();
        let duration = match over.duration.or(cfg.duration.map(|d| d.0)) {
            Some(d) if !is_positive(d) => {
                return Err(SimError::invalid(
                    path,
                    "duration",
                    format!("must be positive, got {d}"),
                ));
            }
            Some(d) => d,
            None => match (&record, &window) {
                (Some(_), Some((_, d, _))) if past_end.get() => *d,
                (Some(r), _) if r.len() < 2 => {
                    return Err(SimError::Scene(format!(
                        "{}: record {} holds a single sample, which lasts 0 s: give a record of at least two samples, or a duration (--duration) to run free vibration past it",
                        path.display(),
                        r.name()
                    )));
                }
                (Some(r), _) => r.duration(),
                (None, _) if over.plan_only => {
                    let t1 = building.t1();
                    notes.push(format!(
                        "no ground motion and no duration: the steps are planned over one bare-frame period T1 = {t1:.6} s; give a record (--record) or a duration (--duration) to plan a run"
                    ));
                    t1
                }
                (None, _) => {
                    return Err(SimError::Scene(format!(
                        "{}: no record and no duration: give a record (--record) or a duration (--duration)",
                        path.display()
                    )));
                }
            },
        };
        if let Some(r) = &record
            && let Some(note) = pad_note(
                r,
                duration,
                window.as_ref().map(|(s, d, what)| (*s, *d, what.as_str())),
            )
        {
            notes.push(note);
        }
        let name = over.method.unwrap_or(cfg.method.name);
        check_method_options(&cfg.method, name, over.method.is_some(), path)?;
        let alpha = match name {
            MethodName::Newmark
            | MethodName::Bilinear
            | MethodName::Delacruz
            | MethodName::Exact => 0.0,
            MethodName::Hht => cfg.method.alpha.unwrap_or(-0.05),
        };
        if !(-1.0 / 3.0..=0.0).contains(&alpha) {
            return Err(SimError::invalid(
                path,
                "method.alpha",
                format!("HHT α must be in [-1/3, 0], got {alpha}"),
            ));
        }
        let dt = over.dt.or(cfg.method.dt.map(|d| d.0)).unwrap_or_else(|| {
            default_dt(
                name,
                building.t1(),
                record.as_ref().map(|r| r.dt()),
                duration,
            )
        });
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        if let Some(r) = &record {
            check_step_against_record(name, dt, r)?;
        }
        check_harmonic_sampling(harmonic.as_ref(), name, dt, path)?;
        check_loop_settings(&cfg.method, path)?;
        let mut outputs = cfg.outputs;
        if let Some(h) = over.histories {
            outputs.histories = h;
        }
        if let Some(e) = over.energies {
            outputs.energies = e;
        }
        if let Some(d) = over.dampers {
            outputs.dampers = d;
        }
        Ok(Scene {
            name: cfg.name.clone().unwrap_or_else(|| building.name.clone()),
            building,
            record,
            harmonic,
            initial,
            duration,
            method: MethodSettings {
                name,
                dt,
                alpha,
                eps_a: cfg.method.eps_a,
                eps_f: cfg.method.eps_f,
                max_iterations: cfg.method.max_iterations,
            },
            outputs,
            reduce: cfg.reduce,
            notes,
        })
    }
}
