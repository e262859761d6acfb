//! The rules a scene is held to (the module docs list them): the overrides' values,
//! exclusive fields, method options, windows, target PGAs, harmonic forces, initial
//! states, loop settings and the step against the record's sample interval. Each refusal
//! names the file, the field (or flag) and what was expected.

use super::config::{HarmonicConfig, MethodConfig, SceneConfig, SceneOverrides};
use super::method::MethodName;
use super::resolved::Harmonic;
use crate::building::{Building, MAX_HARMONIC_FORCE_PER_WEIGHT};
use crate::error::SimError;
use crate::units::is_positive;
use slipload_motion::{G, Record};
use std::path::Path;

/// Most iterations of each `delacruz` fixed-point loop a scene may ask for
/// (`method.max_iterations`): the loops converge in a handful when they converge at all.
pub const MAX_LOOP_ITERATIONS: u32 = 10_000;

/// The band of a target peak ground acceleration, g (`scale_pga_g`, a synthetic record's
/// `pga_g`, `--scale-pga-g`): from about the threshold of perceptible shaking (below it
/// no damper slips and every response is the bare frame's at a scale no study needs, a
/// units slip) to the largest ground acceleration any record holds
/// ([`slipload_motion::MAX_ABS_ACCEL_G`]).
pub const TARGET_PGA_BAND_G: (f64, f64) = (1e-3, slipload_motion::MAX_ABS_ACCEL_G);

/// Whether `pga_g` lies in [`TARGET_PGA_BAND_G`].
pub fn target_pga_in_band(pga_g: f64) -> bool {
    pga_g.is_finite() && (TARGET_PGA_BAND_G.0..=TARGET_PGA_BAND_G.1).contains(&pga_g)
}

/// What [`TARGET_PGA_BAND_G`] asks for, for error messages.
pub(super) fn target_pga_expected(pga_g: f64) -> String {
    format!(
        "must be positive and finite, within {} … {} g (perceptible shaking to the strongest ground motion recorded), got {} g",
        TARGET_PGA_BAND_G.0,
        TARGET_PGA_BAND_G.1,
        slipload_motion::readable(pga_g)
    )
}

/// Largest |initial displacement| (m) or |initial velocity| (m/s) of a floor or
/// dissipator: no structure moves a kilometre or at a kilometre per second.
pub const MAX_INITIAL_STATE: f64 = 1e3;

/// The overrides' own values (the CLI's flags), before anything is read: a target PGA in
/// [`TARGET_PGA_BAND_G`], a positive duration and a positive time step.
pub(super) fn check_overrides(over: &SceneOverrides) -> Result<(), SimError> {
    if let Some(pga) = over.scale_pga_g
        && !target_pga_in_band(pga)
    {
        return Err(SimError::Scene(format!(
            "--scale-pga-g {}",
            target_pga_expected(pga)
        )));
    }
    if let Some(f) = over.scale {
        if over.scale_pga_g.is_some() {
            return Err(SimError::Scene(
                "--scale and --scale-pga-g: give one way of scaling the ground motion, not both"
                    .into(),
            ));
        }
        if !is_positive(f) {
            return Err(SimError::Scene(format!(
                "--scale {f}: a scale factor must be finite and > 0"
            )));
        }
    }
    if let Some(d) = over.duration
        && !is_positive(d)
    {
        return Err(SimError::Scene(format!(
            "--duration: the simulated time must be positive, got {d} (give a finite number of seconds)"
        )));
    }
    if let Some(dt) = over.dt
        && !is_positive(dt)
    {
        return Err(SimError::Scene(format!(
            "--dt: time step {dt} s must be positive and finite"
        )));
    }
    Ok(())
}

/// The excitation's exclusive fields: a record or a synthetic ground motion, and a
/// record's `scale` or its `scale_pga_g`.
pub(super) fn check_exclusive_fields(cfg: &SceneConfig, path: &Path) -> Result<(), SimError> {
    if cfg.excitation.record.is_some() && cfg.excitation.synthetic.is_some() {
        return Err(SimError::invalid(
            path,
            "excitation.synthetic",
            "give either record (a ground-motion file) or synthetic (a generated ground motion), not both",
        ));
    }
    if let Some(rc) = &cfg.excitation.record
        && rc.scale.is_some()
        && rc.scale_pga_g.is_some()
    {
        return Err(SimError::invalid(
            path,
            "excitation.record.scale",
            "give either scale or scale_pga_g, not both",
        ));
    }
    Ok(())
}

/// Refuses a `method` option that `name` does not read: it would be ignored, and the run
/// would not be the one asked for. `from_flag`: the method was chosen with `--method`.
pub(super) fn check_method_options(
    cfg: &MethodConfig,
    name: MethodName,
    from_flag: bool,
    path: &Path,
) -> Result<(), SimError> {
    let takes = name.options();
    let Some(unused) = cfg.given().into_iter().find(|o| !takes.contains(o)) else {
        return Ok(());
    };
    let users: Vec<&str> = MethodName::ALL
        .iter()
        .filter(|m| m.options().contains(&unused))
        .map(|m| m.as_str())
        .collect();
    Err(SimError::invalid(
        path,
        format!("method.{unused}"),
        format!(
            "method {}{} does not use {unused} (it takes {}); {unused} is an option of {}: remove it or choose that method",
            name.as_str(),
            if from_flag { " (from --method)" } else { "" },
            takes.join(", "),
            users.join(", ")
        ),
    ))
}

/// Checks a window `[start, duration]` of a ground motion by itself (before any record is
/// at hand), the one rule of every front (a scene's `window`, `--window`, Python's
/// `window=` and `Record.window`): a start ≥ 0 s and a duration > 0 s, both finite — a
/// window of no length holds no ground motion. `what` names the window in errors.
pub fn check_window(start: f64, duration: f64, what: &str) -> Result<(), SimError> {
    if !(start.is_finite() && start >= 0.0 && duration.is_finite() && duration > 0.0) {
        return Err(SimError::Scene(format!(
            "{what}: a window needs a start >= 0 s and a duration > 0 s, got [{start}, {duration}]"
        )));
    }
    Ok(())
}

/// Cuts `window = (start, duration)` out of `r`, refusing a start at or past the record's
/// end (nothing of it would be left). A window that runs past the end keeps what there is:
/// the simulated duration then defaults to the window's, with the ground at rest after the
/// record ([`pad_note`] says so). `what` names the window in errors.
pub(super) fn apply_window(r: &Record, window: (f64, f64), what: &str) -> Result<Record, SimError> {
    let (start, duration) = window;
    check_window(start, duration, what)?;
    let end = r.duration();
    // at the end to round-off (39.98 against 1999 × 0.02 = 39.980000000000004) is at it
    if start >= end - 1e-9 * r.dt() {
        return Err(SimError::Scene(format!(
            "{what}: the window starts at {} s, at or past the end of {} ({} s long): no ground motion would be left; give a start below {} s",
            secs(start),
            r.name(),
            secs(end),
            secs(end)
        )));
    }
    Ok(r.window(start, duration)?)
}

/// Seconds as people write them: round-off below a nanosecond dropped (39.98, not
/// 39.980000000000004).
fn secs(t: f64) -> String {
    format!("{}", (t * 1e9).round() / 1e9)
}

/// The note of a run longer than its ground motion (a `duration` or a window past the
/// record's end): the ground is at rest for the rest, which is free vibration.
pub(super) fn pad_note(
    record: &Record,
    duration: f64,
    window: Option<(f64, f64, &str)>,
) -> Option<String> {
    let end = record.duration();
    // the same slack as Scene::steps: a duration that is the record's to round-off is it
    if duration <= end * (1.0 + 1e-9) + 1e-12 {
        return None;
    }
    let rest = secs(duration - end);
    Some(match window {
        Some((s, d, what)) => format!(
            "{what} [{} s, {} s] runs past the end of {}: {} s of ground motion from {} s, then the ground at rest for the last {rest} s of the {} s run (free vibration), as with a duration longer than the record",
            secs(s),
            secs(d),
            record.name(),
            secs(end),
            secs(s),
            secs(duration)
        ),
        None => format!(
            "the run lasts {} s but the ground motion {} lasts {} s: the ground is at rest for the last {rest} s (free vibration)",
            secs(duration),
            record.name(),
            secs(end)
        ),
    })
}

/// A harmonic force's floor (from 1 to the `n` floors), its finite amplitude, frequency and
/// phase, and an amplitude of at most [`MAX_HARMONIC_FORCE_PER_WEIGHT`] × the building's
/// weight.
pub(super) fn check_harmonic(
    h: &HarmonicConfig,
    n: usize,
    building: &Building,
    path: &Path,
) -> Result<(), SimError> {
    if h.floor == 0 || h.floor > n {
        return Err(SimError::invalid(
            path,
            "excitation.harmonic.floor",
            format!("must be a floor from 1 to {n}, got {}", h.floor),
        ));
    }
    if !h.amplitude.0.is_finite() || !h.omega.0.is_finite() || !h.phase.0.is_finite() {
        return Err(SimError::invalid(
            path,
            "excitation.harmonic",
            "amplitude, omega and phase must be finite",
        ));
    }
    let weight = building.mass.sum() * G;
    let limit = MAX_HARMONIC_FORCE_PER_WEIGHT * weight;
    if h.amplitude.0.abs() > limit {
        return Err(SimError::invalid(
            path,
            "excitation.harmonic.amplitude",
            format!(
                "{:e} N is more than {} × the building's weight ({weight:.4e} N): no shaker or load comes near it (check the units)",
                h.amplitude.0, MAX_HARMONIC_FORCE_PER_WEIGHT
            ),
        ));
    }
    Ok(())
}

pub(super) fn vec_or_zero(
    path: &Path,
    field: &str,
    v: Option<Vec<f64>>,
    n: usize,
) -> Result<Vec<f64>, SimError> {
    match v {
        None => Ok(vec![0.0; n]),
        Some(v) if v.len() != n => Err(SimError::invalid(
            path,
            field,
            format!("has {} values, expected {n} (one per floor)", v.len()),
        )),
        Some(v) => match v.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(SimError::invalid(
                path,
                format!("{field}[{i}]"),
                "must be finite",
            )),
            None => match v.iter().position(|x| x.abs() > MAX_INITIAL_STATE) {
                Some(i) => Err(SimError::invalid(
                    path,
                    format!("{field}[{i}]"),
                    format!(
                        "{:e} is beyond any structure's motion (at most {MAX_INITIAL_STATE:e} m or m/s; check the units)",
                        v[i]
                    ),
                )),
                None => Ok(v),
            },
        },
    }
}

/// A step-by-step method (every method but `exact`) samples the ground motion once per
/// step: a step longer than the record's sample interval skips samples, and with them
/// the peaks of the input, so it is refused ([`SimError::StepTooLong`]). `exact`
/// integrates every sample whatever its output step. (The accuracy study sets coarser
/// steps on purpose, on compiled scenes, to measure exactly that error.)
pub fn check_step_against_record(
    method: MethodName,
    dt: f64,
    record: &Record,
) -> Result<(), SimError> {
    let rdt = record.dt();
    if method != MethodName::Exact && dt > rdt * (1.0 + 1e-9) {
        return Err(SimError::StepTooLong {
            dt,
            what: format!("the sample interval of record {}", record.name()),
            span: rdt,
            consequence: format!(
                "{} samples the ground motion once per step and would skip record samples (and the peaks among them); give a step of at most {rdt} s, or none for the default (T1/400 rounded down to divide the sample interval); `exact` integrates every sample at any step",
                method.as_str()
            ),
        });
    }
    Ok(())
}

/// A step short enough for the harmonic force: a step of half its period or more samples
/// sin(ωt) at the same phase or aliases it (`exact` integrates the force itself).
pub(super) fn check_harmonic_sampling(
    harmonic: Option<&Harmonic>,
    name: MethodName,
    dt: f64,
    path: &Path,
) -> Result<(), SimError> {
    // A step of half the forcing period or more samples sin(ωt) at the same phase or
    // aliases it to a slower force: the run would answer a different load.
    if let Some(h) = harmonic
        && name != MethodName::Exact
        && h.omega.abs() * dt >= std::f64::consts::PI
    {
        return Err(SimError::invalid(
            path,
            "excitation.harmonic.omega",
            format!(
                "{omega:e} rad/s has a period of {period:e} s, at most twice the time step {dt:e} s: {method} would sample the force fewer than twice per period and answer a different load; give a physical frequency (check the units: rad/s, or \"Hz\") or a step below half the period",
                omega = h.omega,
                period = 2.0 * std::f64::consts::PI / h.omega.abs(),
                method = name.as_str(),
            ),
        ));
    }
    Ok(())
}

/// The `delacruz` loop settings: positive finite tolerances, and an iteration cap from 1 to
/// [`MAX_LOOP_ITERATIONS`] (more only with the limits lifted).
pub(super) fn check_loop_settings(method: &MethodConfig, path: &Path) -> Result<(), SimError> {
    for (field, v) in [
        ("method.eps_a", method.eps_a),
        ("method.eps_f", method.eps_f),
    ] {
        if let Some(v) = v
            && !is_positive(v)
        {
            return Err(SimError::invalid(
                path,
                field,
                format!("tolerance must be positive and finite, got {v}"),
            ));
        }
    }
    if let Some(cap) = method.max_iterations
        && cap > MAX_LOOP_ITERATIONS
        && !crate::limits::allow_large()
    {
        return Err(SimError::invalid(
            path,
            "method.max_iterations",
            format!(
                "{cap} iterations per loop per step is more than any converging loop needs (limit {MAX_LOOP_ITERATIONS}; the default is 100): a loop that does not converge would run for days; {}",
                crate::limits::OVERRIDE_HINT
            ),
        ));
    }
    if method.max_iterations == Some(0) {
        return Err(SimError::invalid(
            path,
            "method.max_iterations",
            "must be at least 1, got 0",
        ));
    }
    Ok(())
}
