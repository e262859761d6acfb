//! Scenes: a building, an excitation, what is asked for, and a method with its settings.
//!
//! A scene file names a building (inline or by path relative to the scene file) and may
//! name a record or a synthetic ground motion (not both), a harmonic floor force and an
//! initial state. A building file alone is a valid scene (no excitation: give a record or
//! a duration through [`SceneOverrides`]). Overrides (the CLI's flags) win over the file.
//!
//! Rules a scene is held to (each refusal names the file, the field and what was expected):
//! - **Window.** A record's `window` `[start, duration]` keeps that span of the ground
//!   motion; the `--window` flag ([`SceneOverrides::window`]) *replaces* the scene's
//!   window (it is not applied on top of it), and applies to whichever ground motion the
//!   scene ends up with (a record, `--record`'s file, or a synthetic one). A window that
//!   starts at or past the record's end is refused. One that runs past the end is padded
//!   with the ground at rest, the same rule as a `duration` longer than the record: the
//!   simulated time defaults to the window's duration, and the scene carries a note
//!   ([`Scene::notes`]) that says how many seconds have no ground motion. (A window inside
//!   the record lasts the whole sample intervals it keeps, as before.)
//! - **Quantities with units.** Times (`duration`, `window`, `method.dt`, a record's
//!   `dt`, a synthetic record's `duration` and `dt`) are a number of seconds or a string
//!   with a unit (`"10 s"`, `"5 ms"`); so are a harmonic force's `omega` (`"2.5 Hz"`) and
//!   `phase` (`"90 deg"`) and the initial velocities (`"50 cm/s"`), all parsed by
//!   [`crate::units::parse_quantity`].
//! - **Method options.** Each method reads only some of the `method` fields
//!   ([`MethodName::options`]); one it does not read is refused, naming the option, the
//!   method and the options it takes.
//! - **Exclusive excitation fields.** `record` and `synthetic`; a record's `scale` and
//!   `scale_pga_g`; a synthetic's `index` and `seed`.
//!
//! Files: `method` (the methods and their settings), `config` (the file as written and the
//! overrides), `resolved` (the resolved scene), `check` (the rules), `build` (resolving a
//! config, running the rules).

mod build;
mod check;
mod config;
mod method;
mod resolved;

pub use check::{
    MAX_INITIAL_STATE, MAX_LOOP_ITERATIONS, TARGET_PGA_BAND_G, check_step_against_record,
    check_window, target_pga_in_band,
};
pub use config::{
    BENCHMARK_BUILDING, BENCHMARK_ORIGIN, BuildingRef, ExcitationConfig, HarmonicConfig,
    InitialConfig, MethodConfig, OutputsConfig, RecordConfig, SceneConfig, SceneOverrides,
    SyntheticConfig, benchmark_scene_config,
};
pub use method::{DEFAULT_STEPS_PER_PERIOD, MethodName, MethodSettings, default_dt};
pub use resolved::{Harmonic, InitialState, Scene};
