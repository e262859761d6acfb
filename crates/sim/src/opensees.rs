//! A scene written as a self-contained OpenSeesPy script, so that a reviewer re-runs a
//! design in the tool they trust (docs/MODEL.md § Re-running a design in OpenSees).
//!
//! Contract: [`opensees_script`] returns the text of a Python script that builds the
//! scene's building in OpenSees (openseespy), runs its excitation with Newmark average
//! acceleration (γ = ½, β = ¼) at the scene's Δt with full Newton to 1e-12 m, and prints
//! on stdout one JSON object with the peak interstorey drift per storey, the peak base
//! shear and the collapse (if a storey passes its limit) in SI units, peaks at the steps.
//! Every element is one OpenSees solves with the discrete equations `newmark` solves, so
//! the two agree to the Newton tolerance (well below 1e-6 of the peaks):
//! - the frame's linear stiffness (with the elastic part αk of a yielding storey) and its
//!   damping matrix, whatever form the building gives them (storey springs, a full
//!   condensed matrix; Rayleigh, modal, storey dashpots, a matrix), as `zeroLength` Elastic
//!   springs and dashpots between every pair of floors and from each floor to the ground
//!   that assemble the matrices exactly;
//! - a massless damper without a brace dashpot (m′ = 0, c′ = 0) as one `ElasticPP` of the
//!   brace stiffness k′ yielding at the friction bounds (its return mapping is `newmark`'s
//!   for such an element); a locked one as its brace; one with slip load 0 left out;
//! - a yielding storey's elastic–perfectly plastic part (1−α)k yielding at (1−α)Fy as an
//!   `ElasticPP`; P-Δ as a negative Elastic spring −P/h per storey;
//! - the ground acceleration and the harmonic force at the integration steps, as
//!   `newmark` samples them (the record scaled and windowed as the scene says, linear
//!   between its samples, zero after its end), each a `Path` series.
//!
//! What it cannot express that way is refused with [`SimError::OpenSees`] and an
//! [`OpenSeesGap`] naming the alternative: a dissipator with mass under `newmark`
//! (method `bilinear` ignores it, as frame programs do), a brace dashpot on a massless
//! damper, another method than `newmark` or `bilinear`, a non-diagonal mass matrix, an
//! initial state other than rest, an unreduced plan. Numbers are written with `{:?}`,
//! the shortest text that reads back to the same f64.

use crate::error::{OpenSeesGap, SimError};
use crate::plan::Plan;
use crate::py_literal::{comment, py_str};
use crate::scene::{MethodName, Scene};
use nalgebra::DMatrix;
use std::fmt::Write as _;

/// Newton's convergence test of the script: the norm of the last displacement correction,
/// m. The response is piecewise linear in the step's displacements (linear springs and
/// dashpots, elastic–perfectly plastic return mappings), so Newton with the right yield
/// pattern lands on the solution and the next correction is round-off (about 1e-17 m);
/// 1e-12 m stops there (1e-10 of centimetre drifts, far below the 1e-6 the check asks).
pub const NEWTON_TOLERANCE_M: f64 = 1e-12;

/// Most Newton iterations per step before the script retries the step with line search
/// and then with a modified Newton (and reports the step).
pub const NEWTON_MAX_ITERATIONS: u32 = 100;

/// Largest script [`opensees_script`] writes without `--allow-large`, bytes: the ground
/// acceleration at every step is most of it (about 24 bytes a step), and 256 MiB is ten
/// million steps, more than any check of a design needs.
pub const MAX_SCRIPT_BYTES: f64 = 256.0 * 1024.0 * 1024.0;

/// A spring, dashpot or plastic element between two nodes: node 0 is the ground, node i
/// floor i.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Link {
    /// The lower node.
    a: usize,
    /// The upper node.
    b: usize,
    /// Stiffness (N/m) or damping (N·s/m).
    value: f64,
}

/// What the script builds, in SI units, floors numbered from 1 (node i).
#[derive(Debug, Clone, PartialEq)]
struct Model {
    /// Lumped floor masses (locked dissipators' added), kg.
    masses: Vec<f64>,
    /// Springs assembling the frame's linear stiffness (yielding storeys' αk part).
    frame: Vec<Link>,
    /// −P/h per storey with P-Δ.
    p_delta: Vec<Link>,
    /// Locked braces: (floor, k′ N/m, c′ N·s/m).
    locked: Vec<(usize, f64, f64)>,
    /// Dashpots assembling the frame's damping matrix.
    dashpots: Vec<Link>,
    /// Yielding storeys' plastic parts: (storey, (1−α)k N/m, (1−α)Fy N).
    yielding: Vec<(usize, f64, f64)>,
    /// Dampers: (floor, k′ N/m, F⁻ N, F⁺ N).
    dampers: Vec<(usize, f64, f64, f64)>,
    /// Comments on the floors whose dissipator is left out or locked.
    notes: Vec<String>,
}

/// The text of a self-contained OpenSeesPy script that runs `scene` as `newmark` does (see
/// the module documentation for what each element is and what it prints).
///
/// Errors: [`SimError::OpenSees`] for what the script cannot express, and whatever
/// compiling the scene into a plan and checking its start refuse ([`Plan::compile`],
/// [`crate::simulate::check`]), so a scene `simulate` refuses is refused here too;
/// [`SimError::TooLarge`] beyond [`MAX_SCRIPT_BYTES`].
pub fn opensees_script(scene: &Scene) -> Result<String, SimError> {
    let gap = |gap| SimError::OpenSees {
        scene: scene.name.clone(),
        gap,
    };
    let method = scene.method.name;
    if !matches!(method, MethodName::Newmark | MethodName::Bilinear) {
        return Err(gap(OpenSeesGap::Method {
            method: method.as_str(),
        }));
    }
    if !scene.initial.is_rest() {
        return Err(gap(OpenSeesGap::InitialState));
    }
    if !scene.reduce && scene.building.dissipators.iter().any(Option::is_some) {
        return Err(gap(OpenSeesGap::Unreduced));
    }
    let model = model(scene).map_err(gap)?;
    let plan = Plan::compile(scene)?;
    crate::simulate::check(&plan)?;
    let steps = plan.steps;
    crate::limits::check(
        &format!(
            "an OpenSees script of {} steps",
            crate::limits::count(steps as f64)
        ),
        (steps as f64 + 1.0) * if plan.harmonic.is_some() { 48.0 } else { 24.0 },
        MAX_SCRIPT_BYTES,
        &crate::limits::bytes,
    )?;
    let mut s = String::new();
    header(&mut s, scene, &plan, &model);
    data(&mut s, scene, &plan, &model);
    s.push_str(BODY);
    Ok(s)
}

/// The elements of the scene's building, or what cannot be written.
fn model(scene: &Scene) -> Result<Model, OpenSeesGap> {
    let b = &scene.building;
    let n = b.floors();
    for col in 0..n {
        for row in 0..n {
            if row != col && b.mass[(row, col)] != 0.0 {
                return Err(OpenSeesGap::MassMatrix {
                    row: row + 1,
                    col: col + 1,
                    value: b.mass[(row, col)],
                });
            }
        }
    }
    let mut masses: Vec<f64> = (0..n).map(|i| b.mass[(i, i)]).collect();
    // `bilinear` ignores dissipator masses everywhere (the plan's m' -> 0).
    let bilinear = scene.method.name == MethodName::Bilinear;
    let (mut locked, mut dampers, mut notes) = (Vec::new(), Vec::new(), Vec::new());
    for (f, d) in b.dissipators.iter().enumerate() {
        let Some(d) = d else { continue };
        let floor = f + 1;
        let mass = if bilinear { 0.0 } else { d.mass };
        if d.is_free() {
            notes.push(format!(
                "floor {floor}: slip load 0, the brace carries no force: left out (a bare storey)"
            ));
        } else if d.is_locked() {
            masses[f] += mass;
            locked.push((floor, d.brace_stiffness, d.brace_damping));
            notes.push(format!(
                "floor {floor}: locked dissipator: its brace joins floors {f} and {floor} (m' = {mass:?} kg added to the floor)"
            ));
        } else if mass > 0.0 {
            return Err(OpenSeesGap::DissipatorMass { floor, mass });
        } else if d.brace_damping > 0.0 {
            return Err(OpenSeesGap::BraceDamping {
                floor,
                damping: d.brace_damping,
            });
        } else {
            dampers.push((floor, d.brace_stiffness, d.lower, d.upper));
        }
    }
    // The frame's linear stiffness: K less the plastic part (1-alpha)k of every yielding
    // storey (a spring between floors i-1 and i), as the plan splits it.
    let mut frame = b.stiffness.clone();
    let mut yielding = Vec::new();
    for (f, y) in b.storey_yield.iter().enumerate() {
        let Some(y) = y else { continue };
        let kp = (1.0 - y.post_yield_ratio) * y.stiffness;
        let fp = (1.0 - y.post_yield_ratio) * y.yield_shear;
        frame[(f, f)] -= kp;
        if f > 0 {
            frame[(f - 1, f - 1)] -= kp;
            frame[(f, f - 1)] += kp;
            frame[(f - 1, f)] += kp;
        }
        yielding.push((f + 1, kp, fp));
    }
    let p_delta = match (&b.gravity_loads, &b.storey_heights) {
        (Some(p), Some(h)) => p
            .iter()
            .zip(h)
            .enumerate()
            .map(|(f, (p, h))| Link {
                a: f,
                b: f + 1,
                value: -p / h,
            })
            .collect(),
        _ => Vec::new(),
    };
    Ok(Model {
        masses,
        frame: links(&frame),
        p_delta,
        locked,
        dashpots: links(&b.damping),
        yielding,
        dampers,
        notes,
    })
}

/// Springs (or dashpots) that assemble the symmetric matrix `a` on the floors: one between
/// every pair of floors i < j of value −a[i][j], and one from each floor to the ground of
/// the row sum Σⱼ a[i][j] (a link of value v between nodes p, q adds v to [p][p] and
/// [q][q] and −v to [p][q]). Values may be negative (an off-diagonal term above zero, a
/// row that sums below zero): OpenSees's Elastic material takes them. Pairs with a zero
/// term are left out, and so are row sums that are zero to their own rounding (a shear
/// building's rows above the first), so a chain matrix gives its storey springs.
fn links(a: &DMatrix<f64>) -> Vec<Link> {
    let n = a.nrows();
    let mut out = Vec::new();
    for i in 0..n {
        let row = a.row(i);
        let sum: f64 = row.iter().sum();
        let size: f64 = row.iter().map(|v| v.abs()).sum();
        if sum.abs() > n as f64 * f64::EPSILON * size {
            out.push(Link {
                a: 0,
                b: i + 1,
                value: sum,
            });
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            if a[(i, j)] != 0.0 {
                out.push(Link {
                    a: i + 1,
                    b: j + 1,
                    value: -a[(i, j)],
                });
            }
        }
    }
    out
}

fn header(s: &mut String, scene: &Scene, plan: &Plan, m: &Model) {
    let b = &scene.building;
    let dt = plan.method.dt;
    let _ = writeln!(s, "#!/usr/bin/env python3");
    // Python reads an encoding declaration from the first two lines only (PEP 263): both
    // are fixed text, and the script is ASCII throughout, so no name can declare one.
    let _ = writeln!(s, "# -*- coding: utf-8 -*-");
    let _ = writeln!(
        s,
        "# {} in OpenSees: written by slipload {} (`slipload opensees`).",
        comment(&scene.name),
        env!("CARGO_PKG_VERSION")
    );
    s.push_str(
        "#
# Builds the building in OpenSees through openseespy, runs the excitation with Newmark
# average acceleration (gamma = 1/2, beta = 1/4) at the time step slipload used, and prints
# one JSON object on stdout: peak interstorey drift per storey (m, bottom first), peak
# drift ratio (when storey heights are known), residual drift (m), peak base shear (N),
# the collapse (storey, time, drift, limit) when a storey passes its limit, and Newton's
# iterations. Peaks are taken at the steps, as slipload's `newmark` takes them; compare
# with `slipload simulate --format json` of the same scene at the same --dt
# (method newmark, or bilinear when the scene says so).
#
# How each part is modelled (a 1-D model: node 0 the fixed ground, node i floor i, all
# elements zeroLength along the one direction, none with Rayleigh damping):
# - floors: nodes with their lumped masses;
# - the frame's linear stiffness (a yielding storey's elastic part alpha*k included) and its
#   damping matrix C, whatever form the building file gives them: Elastic springs and
#   dashpots (Elastic, E = 0, damping tangent eta) between every pair of floors (-K[i][j])
#   and from each floor to the ground (the row sum), which assemble the matrices exactly
#   (negative values where a matrix asks for them);
# - P-Delta: an Elastic spring of negative stiffness -P/h per storey;
# - a yielding storey (bilinear, kinematic hardening): Elastic alpha*k (in the frame) in
#   parallel with ElasticPP (1 - alpha)k yielding at (1 - alpha)Fy;
# - a massless friction damper on its brace (m' = 0, c' = 0): brace + contact are one
#   elastic-perfectly plastic spring, ElasticPP of stiffness k' yielding at the friction
#   bounds, between floors i-1 and i. OpenSees advances its plastic slip by the return
#   mapping, which is what slipload's `newmark` solves (exactly) for such an element;
# - a locked damper: its brace (Elastic k', damping c'), its mass added to its floor;
#   a damper of slip load 0: left out;
# - the excitation: the ground acceleration at every step t = k*dt as slipload samples it
#   (linear between the record's samples, zero after its end) in a Path series of a
#   UniformExcitation; the harmonic force likewise, a Path series of a Plain pattern;
# - the start: at rest, accelerations in equilibrium with the first ground acceleration;
# - the solution: Newton, test NormDispIncr (tolerance below), system ProfileSPD; a step
#   that does not converge is retried with line search, then with a modified Newton, and
#   reported in `retried_steps`.
#
",
    );
    let _ = writeln!(
        s,
        "# Building: {} ({} floors; bare T1 = {:.6} s).",
        comment(&b.name),
        b.floors(),
        b.t1()
    );
    if scene.method.name == MethodName::Bilinear {
        let _ = writeln!(
            s,
            "# Method bilinear: dissipator masses ignored (m' -> 0), each brace + damper one elastic-perfectly plastic spring."
        );
    }
    for note in &m.notes {
        let _ = writeln!(s, "# {}", comment(note));
    }
    match &plan.record {
        Some(r) => {
            let _ = writeln!(
                s,
                "# Record: {} ({} samples at dt = {:?} s, PGA {:?} m/s2){}.",
                comment(r.name()),
                r.len(),
                r.dt(),
                r.pga(),
                if r.provenance().is_empty() {
                    String::new()
                } else {
                    format!("; {}", comment(r.provenance()))
                }
            );
        }
        None => {
            let _ = writeln!(s, "# No ground motion.");
        }
    }
    for note in &scene.notes {
        let _ = writeln!(s, "# Note: {}", comment(note));
    }
    let _ = writeln!(
        s,
        "# Time step {dt:?} s, {} steps ({:?} s).",
        plan.steps,
        plan.steps as f64 * dt
    );
    let _ = writeln!(
        s,
        "#\n# Run: python3 this-file.py   (needs openseespy: pip install openseespy)\n"
    );
}

/// Writes `name = [ ... ]` with one entry per line, each entry `entry(item)`.
fn list<T>(s: &mut String, name: &str, what: &str, items: &[T], entry: impl Fn(&T) -> String) {
    let _ = writeln!(s, "# {what}");
    if items.is_empty() {
        let _ = writeln!(s, "{name} = []");
        return;
    }
    let _ = writeln!(s, "{name} = [");
    for item in items {
        let _ = writeln!(s, "    {},", entry(item));
    }
    let _ = writeln!(s, "]");
}

/// Writes `name` as a list of floats read from a block of numbers, five a line (the
/// shortest text that reads back to each f64).
fn series(s: &mut String, name: &str, what: &str, values: &[f64]) {
    let _ = writeln!(s, "# {what}");
    let _ = writeln!(s, "{name} = [float(x) for x in \"\"\"");
    for chunk in values.chunks(5) {
        let line: Vec<String> = chunk.iter().map(|v| format!("{v:?}")).collect();
        let _ = writeln!(s, "{}", line.join(" "));
    }
    let _ = writeln!(s, "\"\"\".split()]");
}

fn data(s: &mut String, scene: &Scene, plan: &Plan, m: &Model) {
    let b = &scene.building;
    let dt = plan.method.dt;
    s.push_str("import ctypes\nimport importlib.util\nimport itertools\nimport json\nimport pathlib\nimport sys\n\n");
    let _ = writeln!(
        s,
        "# The names the script was written from, as ASCII literals (printed back in its JSON)"
    );
    let _ = writeln!(s, "SCENE = {}", py_str(&scene.name));
    let _ = writeln!(s, "BUILDING = {}", py_str(&b.name));
    match &plan.record {
        Some(r) => {
            let _ = writeln!(s, "RECORD = {}", py_str(r.name()));
            let _ = writeln!(s, "RECORD_PROVENANCE = {}", py_str(r.provenance()));
        }
        None => {
            let _ = writeln!(s, "RECORD = None\nRECORD_PROVENANCE = None");
        }
    }
    let _ = writeln!(s, "# Newmark time step, s, and number of steps");
    let _ = writeln!(s, "DT = {dt:?}");
    let _ = writeln!(s, "STEPS = {}", plan.steps);
    let _ = writeln!(
        s,
        "# Newton: the norm of the last displacement correction (m), most iterations per step"
    );
    let _ = writeln!(s, "NEWTON_TOLERANCE = {NEWTON_TOLERANCE_M:?}");
    let _ = writeln!(s, "NEWTON_MAX_ITERATIONS = {NEWTON_MAX_ITERATIONS}\n");
    list(
        s,
        "FLOOR_MASSES",
        "Lumped floor masses, kg, floor 1 (node 1) first",
        &m.masses,
        |v| format!("{v:?}"),
    );
    match &b.storey_heights {
        Some(h) => {
            list(s, "STOREY_HEIGHTS", "Storey heights, m", h, |v| {
                format!("{v:?}")
            });
        }
        None => {
            let _ = writeln!(s, "# Storey heights, m (not given)\nSTOREY_HEIGHTS = None");
        }
    }
    let link = |l: &Link| format!("({}, {}, {:?})", l.a, l.b, l.value);
    list(
        s,
        "FRAME_SPRINGS",
        "The frame's linear stiffness as springs: (node, node, stiffness N/m)",
        &m.frame,
        link,
    );
    list(
        s,
        "DASHPOTS",
        "The frame's damping matrix as dashpots: (node, node, damping N*s/m)",
        &m.dashpots,
        link,
    );
    list(
        s,
        "P_DELTA",
        "P-Delta: (node, node, -P/h N/m) per storey",
        &m.p_delta,
        link,
    );
    list(
        s,
        "YIELDING_STOREYS",
        "Yielding storeys' elastic-perfectly plastic parts: (storey, (1 - alpha)k N/m, (1 - alpha)Fy N)",
        &m.yielding,
        |(i, k, f)| format!("({i}, {k:?}, {f:?})"),
    );
    list(
        s,
        "DAMPERS",
        "Friction dampers on their braces, each one elastic-perfectly plastic spring between floors i-1 and i: (floor i, k' N/m, lower bound F- N, upper bound F+ N)",
        &m.dampers,
        |(i, k, lo, hi)| format!("({i}, {k:?}, {lo:?}, {hi:?})"),
    );
    list(
        s,
        "LOCKED_BRACES",
        "Locked dampers' braces between floors i-1 and i: (floor i, k' N/m, c' N*s/m)",
        &m.locked,
        |(i, k, c)| format!("({i}, {k:?}, {c:?})"),
    );
    match &b.collapse_drift {
        Some(c) => list(
            s,
            "COLLAPSE_DRIFT",
            "Collapse limit: a storey drift (m) past which the run stops, as slipload's does",
            c,
            |v| format!("{v:?}"),
        ),
        None => {
            let _ = writeln!(s, "# Collapse limit: none\nCOLLAPSE_DRIFT = None");
        }
    }
    s.push('\n');
    match &plan.record {
        Some(r) => {
            let mut values = Vec::with_capacity(plan.steps + 1);
            values.push(plan.ground_accel(0.0));
            let mut ground = plan.ground_steps();
            values.extend((0..plan.steps).map(|_| ground.next_accel()));
            series(
                s,
                "GROUND_ACCEL",
                &format!(
                    "Ground acceleration, m/s2, at t = k*DT, k = 0..STEPS: record {} as slipload samples it",
                    comment(r.name())
                ),
                &values,
            );
        }
        None => {
            let _ = writeln!(s, "# Ground acceleration: none\nGROUND_ACCEL = None");
        }
    }
    match &plan.harmonic {
        Some(h) => {
            let values: Vec<f64> = (0..=plan.steps)
                .map(|k| plan.force(k as f64 * dt))
                .collect();
            let _ = writeln!(
                s,
                "# Harmonic force on this floor (node): {:?} N * sin({:?} rad/s * t + {:?} rad)",
                h.amplitude, h.omega, h.phase
            );
            let _ = writeln!(s, "HARMONIC_FLOOR = {}", h.floor + 1);
            series(
                s,
                "HARMONIC_FORCE",
                "Harmonic force, N, at t = k*DT, k = 0..STEPS",
                &values,
            );
        }
        None => {
            let _ = writeln!(
                s,
                "# Harmonic force: none\nHARMONIC_FLOOR = None\nHARMONIC_FORCE = None"
            );
        }
    }
}

/// The part of every script that does not depend on the scene: the model built from the
/// data above, the run, the JSON it prints.
const BODY: &str = r#"

# ---------------------------------------------------------------------------------------
# The model and the run: everything below is the same for every scene.
# ---------------------------------------------------------------------------------------


def import_opensees():
    """openseespy.opensees. The Linux wheel ships libblas.so.3 beside its liblapack.so.3,
    which finds it only when it is loaded first: on a machine without a system BLAS the
    import fails otherwise."""
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.origin is not None:
        blas = pathlib.Path(spec.origin).parent / "lib" / "libblas.so.3"
        if blas.exists():
            ctypes.CDLL(str(blas), mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


def zero_length(ops, tag, node_a, node_b, *material):
    """A zeroLength element between two nodes along the one direction, with its own
    uniaxial material (type, then its parameters); no Rayleigh damping."""
    ops.uniaxialMaterial(material[0], tag, *material[1:])
    ops.element("zeroLength", tag, node_a, node_b, "-mat", tag, "-dir", 1, "-doRayleigh", 0)


def build(ops):
    """The model, the excitation and the start at rest."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(0, 0.0)
    ops.fix(0, 1)
    for i, m in enumerate(FLOOR_MASSES, start=1):
        ops.node(i, 0.0)
        ops.mass(i, m)
    tags = itertools.count(1)
    for a, b, k in FRAME_SPRINGS + P_DELTA:
        zero_length(ops, next(tags), a, b, "Elastic", k)
    for a, b, c in DASHPOTS:
        zero_length(ops, next(tags), a, b, "Elastic", 0.0, c)
    for storey, k, fy in YIELDING_STOREYS:
        zero_length(ops, next(tags), storey - 1, storey, "ElasticPP", k, fy / k)
    for floor, k, lower, upper in DAMPERS:
        zero_length(ops, next(tags), floor - 1, floor, "ElasticPP", k, upper / k, lower / k)
    for floor, k, c in LOCKED_BRACES:
        zero_length(ops, next(tags), floor - 1, floor, "Elastic", k, c)
    # -useLast: OpenSees adds dt to its time at every step, so the last step may land a
    # few ulps past the last value, where a Path series is otherwise 0.
    if GROUND_ACCEL is not None:
        ops.timeSeries("Path", 1, "-dt", DT, "-values", *GROUND_ACCEL, "-useLast")
        ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    if HARMONIC_FORCE is not None:
        ops.timeSeries("Path", 2, "-dt", DT, "-values", *HARMONIC_FORCE, "-useLast")
        ops.pattern("Plain", 2, 2)
        ops.load(HARMONIC_FLOOR, 1.0)
    # At rest, accelerations in equilibrium with the loads at t = 0 (OpenSees would start
    # from zero accelerations).
    for i, m in enumerate(FLOOR_MASSES, start=1):
        a0 = -ground(0) + (force(0) / m if i == HARMONIC_FLOOR else 0.0)
        ops.setNodeAccel(i, 1, a0, "-commit")
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("ProfileSPD")
    ops.test("NormDispIncr", NEWTON_TOLERANCE, NEWTON_MAX_ITERATIONS, 0)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def ground(k):
    return GROUND_ACCEL[k] if GROUND_ACCEL is not None else 0.0


def force(k):
    return HARMONIC_FORCE[k] if HARMONIC_FORCE is not None else 0.0


def step(ops, k, retried):
    """Step k; one that does not converge is retried with line search, then with a
    modified Newton of many iterations (counted in `retried`). Returns the iterations."""
    ok = ops.analyze(1, DT)
    iterations = ops.testIter()
    if ok == 0:
        return iterations
    retried.append(k)
    for algorithm in (("NewtonLineSearch",), ("ModifiedNewton", "-initial")):
        ops.algorithm(*algorithm)
        ops.test("NormDispIncr", NEWTON_TOLERANCE, 10 * NEWTON_MAX_ITERATIONS, 0)
        ok = ops.analyze(1, DT)
        iterations += ops.testIter()
        ops.algorithm("Newton")
        ops.test("NormDispIncr", NEWTON_TOLERANCE, NEWTON_MAX_ITERATIONS, 0)
        if ok == 0:
            return iterations
    sys.exit(f"OpenSees: step {k} (t = {k * DT} s) does not converge, even with line search and modified Newton")


def run(ops):
    build(ops)
    n = len(FLOOR_MASSES)
    nodes = range(1, n + 1)
    mass = sum(FLOOR_MASSES)
    peak_drift = [0.0] * n
    drift = [0.0] * n
    peak_base_shear = 0.0
    collapse = None
    iterations = []
    retried = []
    k = 0
    while True:
        u = [ops.nodeDisp(i, 1) for i in nodes]
        a = [ops.nodeAccel(i, 1) for i in nodes]
        below = 0.0
        for i in range(n):
            drift[i] = u[i] - below
            below = u[i]
            peak_drift[i] = max(peak_drift[i], abs(drift[i]))
        # base shear: the floors' inertia forces less the applied force, sum m(a + a_g) - P
        shear = mass * ground(k) - force(k)
        for m, ai in zip(FLOOR_MASSES, a):
            shear += m * ai
        peak_base_shear = max(peak_base_shear, abs(shear))
        if COLLAPSE_DRIFT is not None and k > 0:
            past = [i for i in range(n) if abs(drift[i]) > COLLAPSE_DRIFT[i]]
            if past:
                i = past[0]
                collapse = {"storey": i + 1, "time": k * DT, "drift": drift[i], "limit": COLLAPSE_DRIFT[i]}
                break
        if k == STEPS:
            break
        k += 1
        iterations.append(step(ops, k, retried))
    version = ops.version() if hasattr(ops, "version") else None
    ops.wipe()
    result = {
        "program": f"OpenSees {version} (openseespy)" if version else "OpenSees (openseespy)",
        "scene": SCENE,
        "building": BUILDING,
        "record": RECORD,
        "record_provenance": RECORD_PROVENANCE,
        "dt": DT,
        "steps": k,
        "peak_drift": peak_drift,
        "peak_drift_ratio": [d / h for d, h in zip(peak_drift, STOREY_HEIGHTS)] if STOREY_HEIGHTS else None,
        "residual_drift": [abs(d) for d in drift],
        "peak_base_shear": peak_base_shear,
        "collapse": collapse,
        "newton_iterations": {"mean": sum(iterations) / len(iterations), "max": max(iterations)} if iterations else None,
        "retried_steps": retried,
    }
    return result


if __name__ == "__main__":
    print(json.dumps(run(import_opensees()), indent=2))
"#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneOverrides;
    use std::path::Path;

    fn config(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../configs")
            .join(name)
    }

    fn scene(file: &str, method: Option<MethodName>) -> Scene {
        let over = SceneOverrides {
            record: Some(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records/I-ELC180.AT2")),
            duration: Some(1.0),
            method,
            ..Default::default()
        };
        Scene::load(&config(file), &over).unwrap()
    }

    /// The matrix the links assemble on the floors.
    fn assemble(n: usize, links: &[Link]) -> DMatrix<f64> {
        let mut m = DMatrix::zeros(n, n);
        for l in links {
            m[(l.b - 1, l.b - 1)] += l.value;
            if l.a > 0 {
                m[(l.a - 1, l.a - 1)] += l.value;
                m[(l.a - 1, l.b - 1)] -= l.value;
                m[(l.b - 1, l.a - 1)] -= l.value;
            }
        }
        m
    }

    fn rel(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
        (a - b).amax() / b.amax()
    }

    #[test]
    fn links_assemble_the_matrix_and_a_chain_gives_its_storey_springs() {
        let k = DMatrix::from_row_slice(
            3,
            3,
            &[
                436.575, -237.344, 41.445, -237.344, 313.526, -128.931, 41.445, -128.931, 93.585,
            ],
        ) * 1e6;
        let l = links(&k);
        assert_eq!(l.len(), 6, "{l:?}"); // three to the ground, three pairs
        assert!(rel(&assemble(3, &l), &k) < 1e-15);
        // a chain of storey springs: one spring per storey, nothing else
        let chain =
            DMatrix::from_row_slice(3, 3, &[3.0, -1.0, 0.0, -1.0, 1.7, -0.7, 0.0, -0.7, 0.7]) * 1e8;
        let l = links(&chain);
        assert_eq!(
            l,
            vec![
                Link {
                    a: 0,
                    b: 1,
                    value: 2e8
                },
                Link {
                    a: 1,
                    b: 2,
                    value: 1e8
                },
                Link {
                    a: 2,
                    b: 3,
                    value: 0.7e8
                },
            ]
        );
    }

    /// Every storey, damper and the assembled stiffness and damping of the ten-storey
    /// yielding frame with P-Δ are the plan's: the springs, P-Δ and the plastic elements
    /// (elastic) assemble the plan's stiffness with its elastic-perfectly plastic elements,
    /// the dashpots its damping matrix.
    #[test]
    fn the_ten_storey_yielding_frame_is_the_plan() {
        let sc = scene("ten-story-yielding.json", None);
        let plan = Plan::compile(&sc).unwrap();
        let m = model(&sc).unwrap();
        let n = 10;
        assert_eq!(m.masses.len(), n);
        assert_eq!(m.dampers.len(), n);
        assert_eq!(m.p_delta.len(), n);
        assert!(!m.yielding.is_empty());
        let mut k = assemble(n, &m.frame) + assemble(n, &m.p_delta);
        let mut plan_k = plan.stiffness.clone();
        for (f, kp, _) in &m.yielding {
            let l = [Link {
                a: f - 1,
                b: *f,
                value: *kp,
            }];
            k += assemble(n, &l);
        }
        for ct in &plan.contacts {
            if ct.role == crate::plan::ContactRole::Storey {
                let l = [Link {
                    a: ct.floor,
                    b: ct.floor + 1,
                    value: ct.brace_stiffness,
                }];
                plan_k += assemble(n, &l);
            }
        }
        assert!(rel(&k, &plan_k) < 1e-13, "{}", rel(&k, &plan_k));
        assert!(rel(&assemble(n, &m.dashpots), &plan.damping) < 1e-13);
        let storeys: Vec<_> = plan
            .contacts
            .iter()
            .filter(|c| c.role == crate::plan::ContactRole::Storey)
            .map(|c| (c.floor + 1, c.brace_stiffness, c.upper))
            .collect();
        assert_eq!(m.yielding, storeys);
        let script = opensees_script(&sc).unwrap();
        for i in 1..=n {
            let damper = m.dampers[i - 1];
            assert!(
                script.contains(&format!(
                    "    ({i}, {:?}, {:?}, {:?}),",
                    damper.1, damper.2, damper.3
                )),
                "damper {i}"
            );
            assert!(script.contains(&format!(
                "    ({}, {i}, {:?}),",
                i - 1,
                m.p_delta[i - 1].value
            )));
        }
        for (storey, k, f) in &m.yielding {
            assert!(script.contains(&format!("    ({storey}, {k:?}, {f:?}),")));
        }
        assert!(script.contains(&format!("STEPS = {}\n", plan.steps)));
        assert!(script.contains(&format!("DT = {:?}\n", plan.method.dt)));
    }

    /// The benchmark's full frame matrix and Rayleigh damping, its three massless dampers,
    /// the ground acceleration at every step as newmark takes it.
    #[test]
    fn the_benchmark_names_its_dampers_and_every_ground_acceleration() {
        let sc = scene("benchmark-3story-massless.json", None);
        let plan = Plan::compile(&sc).unwrap();
        let script = opensees_script(&sc).unwrap();
        let m = model(&sc).unwrap();
        assert_eq!(m.frame.len(), 6);
        assert!(rel(&assemble(3, &m.frame), &plan.stiffness) < 1e-15);
        assert!(rel(&assemble(3, &m.dashpots), &plan.damping) < 1e-15);
        for (i, d) in sc.building.dissipators.iter().enumerate() {
            let d = d.unwrap();
            let row = format!(
                "    ({}, {:?}, {:?}, {:?}),",
                i + 1,
                d.brace_stiffness,
                d.lower,
                d.upper
            );
            assert!(script.contains(&row), "{row}");
        }
        let block = script
            .split("GROUND_ACCEL = [float(x) for x in \"\"\"\n")
            .nth(1)
            .and_then(|rest| rest.split("\"\"\".split()]").next())
            .unwrap();
        let values: Vec<f64> = block
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(values.len(), plan.steps + 1);
        let mut g = plan.ground_steps();
        assert_eq!(values[0].to_bits(), plan.ground_accel(0.0).to_bits());
        for v in &values[1..] {
            assert_eq!(v.to_bits(), g.next_accel().to_bits());
        }
    }

    #[test]
    fn refusals_are_typed() {
        let gap = |r: Result<String, SimError>| match r {
            Err(SimError::OpenSees { gap, .. }) => gap,
            other => panic!("expected an OpenSees gap, got {other:?}"),
        };
        // the benchmark's dampers have mass: newmark is refused, bilinear written
        let sc = scene("benchmark-3story.json", None);
        assert!(matches!(
            gap(opensees_script(&sc)),
            OpenSeesGap::DissipatorMass { floor: 1, .. }
        ));
        let script =
            opensees_script(&scene("benchmark-3story.json", Some(MethodName::Bilinear))).unwrap();
        assert!(script.contains("Method bilinear"));
        for method in [MethodName::Exact, MethodName::Hht, MethodName::Delacruz] {
            let sc = scene("benchmark-3story-massless.json", Some(method));
            assert_eq!(
                gap(opensees_script(&sc)),
                OpenSeesGap::Method {
                    method: method.as_str()
                }
            );
        }
        let mut sc = scene("benchmark-3story-massless.json", None);
        sc.building.dissipators[1].as_mut().unwrap().brace_damping = 1e5;
        assert_eq!(
            gap(opensees_script(&sc)),
            OpenSeesGap::BraceDamping {
                floor: 2,
                damping: 1e5
            }
        );
        let mut sc = scene("benchmark-3story-massless.json", None);
        sc.initial.floor_displacement[0] = 0.01;
        assert_eq!(gap(opensees_script(&sc)), OpenSeesGap::InitialState);
        let mut sc = scene("benchmark-3story-massless.json", None);
        sc.reduce = false;
        assert_eq!(gap(opensees_script(&sc)), OpenSeesGap::Unreduced);
        let mut sc = scene("benchmark-3story-massless.json", None);
        sc.building.mass[(0, 1)] = 10.0;
        sc.building.mass[(1, 0)] = 10.0;
        assert!(matches!(
            gap(opensees_script(&sc)),
            OpenSeesGap::MassMatrix { row: 2, col: 1, .. }
        ));
    }

    /// A locked damper is its brace, its mass on its floor; a damper of slip load 0 is
    /// left out; names with newlines stay inside their comment.
    #[test]
    fn locked_and_free_dampers_and_hostile_names() {
        let mut sc = scene("benchmark-3story-massless.json", None);
        {
            let d = sc.building.dissipators[0].as_mut().unwrap();
            (d.lower, d.upper) = (f64::NEG_INFINITY, f64::INFINITY);
        }
        {
            let d = sc.building.dissipators[2].as_mut().unwrap();
            (d.lower, d.upper) = (0.0, 0.0);
        }
        sc.name = "a\nname \"\"\" with\r quotes".into();
        let m = model(&sc).unwrap();
        let k1 = sc.building.dissipators[0].unwrap().brace_stiffness;
        assert_eq!(m.locked, vec![(1, k1, 0.0)]);
        assert_eq!(m.dampers.len(), 1);
        assert_eq!(m.dampers[0].0, 2);
        let script = opensees_script(&sc).unwrap();
        assert!(
            script
                .lines()
                .all(|l| !l.starts_with("name") && !l.starts_with(" quotes"))
        );
        assert!(script.contains(r#"SCENE = "a\nname \"\"\" with\r quotes""#));
    }

    /// Names are written as ASCII literals and comments: an encoding declaration in a
    /// name (PEP 263 reads one from the first two lines) never reaches those lines, and no
    /// character of a name can end its line or its literal.
    #[test]
    fn hostile_names_stay_ascii_data_below_the_fixed_first_lines() {
        let mut sc = scene("benchmark-3story-massless.json", None);
        let hostile =
            "# -*- coding: unicode_escape -*-\\nimport os\n\"\"\"'''\0\u{7f}\u{85}\u{2028}é地震😀";
        sc.name = hostile.into();
        sc.building.name = format!("b {hostile}");
        let script = opensees_script(&sc).unwrap();
        assert!(script.is_ascii());
        let lines: Vec<&str> = script.lines().collect();
        assert_eq!(lines[0], "#!/usr/bin/env python3");
        assert_eq!(lines[1], "# -*- coding: utf-8 -*-");
        assert!(script.lines().all(|l| !l.starts_with("import os")));
        let escaped = r#"# -*- coding: unicode_escape -*-\\nimport os\n\"\"\"'''\x00\x7f\x85\u2028\xe9\u5730\u9707\U0001f600"#;
        assert!(script.contains(&format!("SCENE = \"{escaped}\"\n")));
        assert!(script.contains(&format!("BUILDING = \"b {escaped}\"\n")));
        assert!(script.contains(&format!("# Building: b {escaped} (3 floors")));
    }
}
