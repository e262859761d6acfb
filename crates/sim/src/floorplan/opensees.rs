//! A scene in plan written as a self-contained OpenSeesPy script (docs/MODEL.md §
//! Buildings in plan), so a reviewer re-runs it in the tool they trust.
//!
//! The model is the plan's own, in OpenSees' terms: a 2-D model with three DOFs a node
//! (u_x, u_y, θ); each floor a master node at its centre of mass carrying (m, m, J about
//! the centre), and a node per line rigidly linked to it (`rigidLink beam`: a rigid
//! diaphragm); each line's storey a `zeroLength` element along the line between its nodes
//! on the two floors (the ground's fixed for the first) — Elastic αk in parallel with an
//! ElasticPP (1−α)k yielding at (1−α)F_y, or Elastic k — and each massless damper an
//! ElasticPP of its brace stiffness yielding at its bounds beside it; Rayleigh damping
//! α M + β K of the bare frame by regions (α on the masters, β on the lines' initial
//! stiffness); each ground component's acceleration at the integration steps, resolved
//! into x and y, as two `Path` series. Newmark average acceleration at the scene's Δt with
//! full Newton to 1e-12 m: the discrete equations `newmark` solves, in other coordinates,
//! so the two agree to the Newton tolerance. It prints one JSON object: the peak drift of
//! every line at every storey (in the order of the response's `in_plan.drifts`), peaks at
//! the steps.
//!
//! A line's storey dashpot is a zeroLength `Viscous` element (c, exponent 1) along it; a
//! storey's P-Δ a zeroLength element at its gravity load's centroid, between nodes
//! rigidly linked to the two floors, with −P/h along x and y and −Pρ²/h about the
//! vertical (the block the plan subtracts, written as three springs).
//!
//! Refused with a message that says what to change: another method than `newmark` or
//! `bilinear`, modal damping (no element expresses it), a damper with mass under `newmark`
//! (`bilinear` ignores it), a brace dashpot.

use super::model::cos_sin;
use super::scene::FloorPlanScene;
use crate::error::SimError;
use crate::opensees::{NEWTON_MAX_ITERATIONS, NEWTON_TOLERANCE_M};
use crate::py_literal::{comment, py_str};
use crate::scene::MethodName;
use std::fmt::Write as _;

/// The text of the OpenSeesPy script of `scene`, or why it cannot be written.
pub fn opensees_script(scene: &FloorPlanScene) -> Result<String, SimError> {
    let refuse = |why: String| SimError::Scene(format!("opensees: {}: {why}", scene.name));
    let method = scene.method.name;
    if !matches!(method, MethodName::Newmark | MethodName::Bilinear) {
        return Err(refuse(format!(
            "the script runs Newmark average acceleration, as newmark and bilinear do; {} is not written",
            method.as_str()
        )));
    }
    let b = &scene.building;
    let plan = super::compile(scene)?;
    crate::simulate::check(&plan)?;
    // Rayleigh α, β of the bare frame: C = αM + βK must hold on the floors' DOFs.
    let (alpha, beta) = rayleigh_of(b).ok_or_else(|| {
        refuse("its damping is not Rayleigh (or none); modal damping has no OpenSees element: give the building `rayleigh` damping to export it".into())
    })?;
    for line in &b.lines {
        for (f, d) in line.dissipators.iter().enumerate() {
            let Some(d) = d else { continue };
            if d.mass > 0.0 && method == MethodName::Newmark {
                return Err(refuse(format!(
                    "the damper {}/{} has mass {} kg; run it with --method bilinear (which ignores damper masses, as frame programs do)",
                    line.name,
                    f + 1,
                    d.mass
                )));
            }
            if d.brace_damping > 0.0 {
                return Err(refuse(format!(
                    "the damper {}/{} has a brace dashpot; the script writes braces without one",
                    line.name,
                    f + 1
                )));
            }
        }
    }
    crate::limits::check(
        &format!(
            "an OpenSees script of {} steps",
            crate::limits::count(plan.steps as f64)
        ),
        (plan.steps as f64 + 1.0) * 48.0,
        crate::opensees::MAX_SCRIPT_BYTES,
        &crate::limits::bytes,
    )?;
    let mut s = String::new();
    let _ = writeln!(s, "#!/usr/bin/env python3");
    // PEP 263 reads the first two lines only: fixed text, and the script is ASCII.
    let _ = writeln!(s, "# -*- coding: utf-8 -*-");
    let _ = writeln!(
        s,
        "# {} (a building in plan) in OpenSees: written by slipload {} (`slipload opensees`).",
        comment(&scene.name),
        env!("CARGO_PKG_VERSION")
    );
    s.push_str("# Prints the peak drift of every line at every storey (m) as JSON; compare with\n# `slipload simulate --format json` of the same scene at the same --dt.\n");
    s.push_str("import ctypes\nimport importlib.util\nimport json\nimport pathlib\nimport sys\n\n");
    let _ = writeln!(s, "SCENE = {}", py_str(&scene.name));
    let _ = writeln!(s, "BUILDING = {}", py_str(&b.name));
    let _ = writeln!(s, "DT = {:?}", plan.method.dt);
    let _ = writeln!(s, "STEPS = {}", plan.steps);
    let _ = writeln!(s, "NEWTON_TOLERANCE = {NEWTON_TOLERANCE_M:?}");
    let _ = writeln!(s, "NEWTON_MAX_ITERATIONS = {NEWTON_MAX_ITERATIONS}");
    let _ = writeln!(s, "RAYLEIGH = ({alpha:?}, {beta:?})");
    let _ = writeln!(
        s,
        "# floors: (mass kg, inertia about the centre kg*m^2, x, y of the centre m)"
    );
    let _ = writeln!(s, "FLOORS = [");
    for f in &b.floors {
        let _ = writeln!(
            s,
            "    ({:?}, {:?}, {:?}, {:?}),",
            f.mass, f.inertia, f.centre[0], f.centre[1]
        );
    }
    let _ = writeln!(s, "]");
    let _ = writeln!(
        s,
        "# lines: (name, cos, sin, x, y of a point, per storey: (elastic k N/m, plastic (k, fy) or None, damper (k', F-, F+) or None, locked brace k' or None, dashpot c N*s/m))"
    );
    let _ = writeln!(s, "LINES = [");
    for line in &b.lines {
        let (c, sn) = cos_sin(line.angle);
        let _ = writeln!(
            s,
            "    ({}, {c:?}, {sn:?}, {:?}, {:?}, [",
            py_str(&line.name),
            line.point[0],
            line.point[1]
        );
        for f in 0..b.storeys() {
            let k = line.stiffness[f];
            let (elastic, plastic) = match line.storey_yield[f] {
                Some(y) => {
                    let kp = (1.0 - y.post_yield_ratio) * y.stiffness;
                    let fp = (1.0 - y.post_yield_ratio) * y.yield_shear;
                    (k - kp, format!("({kp:?}, {fp:?})"))
                }
                None => (k, "None".into()),
            };
            let (damper, locked) = match line.dissipators[f] {
                Some(d) if d.is_free() => ("None".to_string(), "None".to_string()),
                Some(d) if d.is_locked() => {
                    ("None".to_string(), format!("{:?}", d.brace_stiffness))
                }
                Some(d) => (
                    format!("({:?}, {:?}, {:?})", d.brace_stiffness, d.lower, d.upper),
                    "None".to_string(),
                ),
                None => ("None".to_string(), "None".to_string()),
            };
            let dashpot = line.dashpots[f];
            let _ = writeln!(
                s,
                "        ({elastic:?}, {plastic}, {damper}, {locked}, {dashpot:?}),"
            );
        }
        let _ = writeln!(s, "    ]),");
    }
    let _ = writeln!(s, "]");
    // P-Δ: per storey, the block P/h [[1, 0, −ȳ], [0, 1, x̄], [−ȳ, x̄, x̄² + ȳ² + ρ²]] is
    // a spring −P/h along x and one along y at the load's centroid (x̄, ȳ) and a
    // torsional spring −Pρ²/h: three negative stiffnesses of a zeroLength element there.
    let _ = writeln!(
        s,
        "# P-Delta per storey: (x, y of the gravity load's centroid m, -P/h N/m, -P*rho^2/h N*m), or none"
    );
    let _ = writeln!(s, "P_DELTA = [");
    if let Some(pd) = &b.p_delta {
        for block in &pd.blocks {
            let ph = block[0][0];
            let (x, y) = (block[1][2] / ph, -block[0][2] / ph);
            let twist = block[2][2] - ph * (x * x + y * y);
            let _ = writeln!(s, "    ({x:?}, {y:?}, {:?}, {:?}),", -ph, -twist);
        }
    }
    let _ = writeln!(s, "]");
    // The ground at the integration steps, as newmark samples each component, resolved
    // into x and y.
    let dt = plan.method.dt;
    let mut gx = vec![0.0; plan.steps + 1];
    let mut gy = vec![0.0; plan.steps + 1];
    for g in &scene.ground {
        let (c, sn) = cos_sin(g.angle);
        let mut samples = g.record.steps(dt);
        for k in 0..=plan.steps {
            let a = if k == 0 {
                g.record.accel_at(0.0)
            } else {
                samples.next_accel()
            };
            gx[k] += c * a;
            gy[k] += sn * a;
        }
    }
    for (name, v) in [("GROUND_X", &gx), ("GROUND_Y", &gy)] {
        let _ = write!(s, "{name} = [");
        for x in v.iter() {
            let _ = write!(s, "{x:?}, ");
        }
        let _ = writeln!(s, "]");
    }
    s.push_str(BODY);
    Ok(s)
}

/// α and β with C = αM + βK on the floors' DOFs, when the building's damping is Rayleigh
/// (or none: 0, 0).
fn rayleigh_of(b: &super::FloorPlan) -> Option<(f64, f64)> {
    let n = b.mass.nrows();
    // β from a stiffness entry without mass, α from a mass entry: the damping matrix is
    // αM + βK exactly when both reproduce it everywhere.
    let c = &b.damping;
    if c.iter().all(|x| *x == 0.0) {
        return Some((0.0, 0.0));
    }
    // least squares on the two columns (M, K) flattened
    let (mut mm, mut mk, mut kk, mut mc, mut kc) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let (m, k, d) = (b.mass[(i, j)], b.stiffness[(i, j)], c[(i, j)]);
            mm += m * m;
            mk += m * k;
            kk += k * k;
            mc += m * d;
            kc += k * d;
        }
    }
    let det = mm * kk - mk * mk;
    if det.abs() <= 1e-12 * mm * kk {
        return None;
    }
    let alpha = (mc * kk - kc * mk) / det;
    let beta = (kc * mm - mc * mk) / det;
    let fits = (0..n).all(|i| {
        (0..n).all(|j| {
            let want = alpha * b.mass[(i, j)] + beta * b.stiffness[(i, j)];
            (want - c[(i, j)]).abs() <= 1e-9 * c.amax()
        })
    });
    fits.then_some((alpha, beta))
}

const BODY: &str = r#"

def import_opensees():
    """openseespy.opensees (its Linux wheel's BLAS loaded first where it ships one)."""
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.origin is not None:
        blas = pathlib.Path(spec.origin).parent / "lib" / "libblas.so.3"
        if blas.exists():
            ctypes.CDLL(str(blas), mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


def build(ops):
    """Masters at the centres of mass, a node per line and floor rigidly linked to its
    master, the lines' storeys and dampers as zeroLength elements along the lines."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    n = len(FLOORS)
    master = lambda f: 100000 * f
    at = lambda f, l: 100000 * f + l + 1
    for l, (name, c, s, x, y, storeys) in enumerate(LINES):
        ops.node(at(0, l), x, y)
        ops.fix(at(0, l), 1, 1, 1)
    for f, (m, j, xc, yc) in enumerate(FLOORS, start=1):
        ops.node(master(f), xc, yc)
        ops.mass(master(f), m, m, j)
        for l, (name, c, s, x, y, storeys) in enumerate(LINES):
            ops.node(at(f, l), x, y)
            ops.rigidLink("beam", master(f), at(f, l))
    tag = 0
    frame = []
    for l, (name, c, s, x, y, storeys) in enumerate(LINES):
        for f, (k, plastic, damper, locked, dashpot) in enumerate(storeys, start=1):
            a, b = at(f - 1, l), at(f, l)
            mats = []
            if k != 0.0:
                tag += 1
                ops.uniaxialMaterial("Elastic", tag, k)
                mats.append(tag)
            if plastic is not None:
                tag += 1
                kp, fp = plastic
                ops.uniaxialMaterial("ElasticPP", tag, kp, fp / kp)
                mats.append(tag)
            if mats:
                tag += 1
                ops.uniaxialMaterial("Parallel", tag, *mats)
                # Rayleigh on (its beta by the region below): zeroLength default is off
                ops.element("zeroLength", tag, a, b, "-mat", tag, "-dir", 1, "-doRayleigh", 1, "-orient", c, s, 0.0, -s, c, 0.0)
                frame.append(tag)
            for brace in ([("ElasticPP", damper[0], damper[2] / damper[0], damper[1] / damper[0])] if damper else []) + ([("Elastic", locked)] if locked else []):
                tag += 1
                ops.uniaxialMaterial(brace[0], tag, *brace[1:])
                ops.element("zeroLength", tag, a, b, "-mat", tag, "-dir", 1, "-orient", c, s, 0.0, -s, c, 0.0, "-doRayleigh", 0)
            if dashpot > 0.0:
                tag += 1
                ops.uniaxialMaterial("Viscous", tag, dashpot, 1.0)
                ops.element("zeroLength", tag, a, b, "-mat", tag, "-dir", 1, "-orient", c, s, 0.0, -s, c, 0.0, "-doRayleigh", 0)
    # P-Delta: a node at the load's centroid on the storey's two floors (the ground's
    # fixed), each rigidly linked to its floor's master, joined by negative springs
    for f, (x, y, kt, kr) in enumerate(P_DELTA, start=1):
        top, bottom = 100000 * f + 99998, 100000 * (f - 1) + 99999
        ops.node(top, x, y)
        ops.rigidLink("beam", master(f), top)
        ops.node(bottom, x, y)
        if f == 1:
            ops.fix(bottom, 1, 1, 1)
        else:
            ops.rigidLink("beam", master(f - 1), bottom)
        mats = []
        for k in (kt, kt, kr):
            tag += 1
            ops.uniaxialMaterial("Elastic", tag, k)
            mats.append(tag)
        tag += 1
        ops.element("zeroLength", tag, bottom, top, "-mat", *mats, "-dir", 1, 2, 3, "-doRayleigh", 0)
    alpha, beta = RAYLEIGH
    if frame and beta != 0.0:
        ops.region(1, "-ele", *frame, "-rayleigh", 0.0, 0.0, beta, 0.0)
    if alpha != 0.0:
        ops.region(2, "-node", *[master(f) for f in range(1, n + 1)], "-rayleigh", alpha, 0.0, 0.0, 0.0)
    ops.timeSeries("Path", 1, "-dt", DT, "-values", *GROUND_X, "-useLast")
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.timeSeries("Path", 2, "-dt", DT, "-values", *GROUND_Y, "-useLast")
    ops.pattern("UniformExcitation", 2, 2, "-accel", 2)
    for f in range(1, n + 1):
        ops.setNodeAccel(master(f), 1, -GROUND_X[0], "-commit")
        ops.setNodeAccel(master(f), 2, -GROUND_Y[0], "-commit")
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", NEWTON_TOLERANCE, NEWTON_MAX_ITERATIONS, 0)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return at


def run(ops):
    at = build(ops)
    n = len(FLOORS)
    peak = [0.0] * (len(LINES) * n)
    drift = [0.0] * (len(LINES) * n)
    retried = []
    k = 0
    while True:
        for l, (name, c, s, x, y, storeys) in enumerate(LINES):
            for f in range(1, n + 1):
                top = [ops.nodeDisp(at(f, l), d) for d in (1, 2)]
                bottom = [ops.nodeDisp(at(f - 1, l), d) for d in (1, 2)]
                d = c * (top[0] - bottom[0]) + s * (top[1] - bottom[1])
                drift[l * n + f - 1] = d
                peak[l * n + f - 1] = max(peak[l * n + f - 1], abs(d))
        if k == STEPS:
            break
        k += 1
        if ops.analyze(1, DT) != 0:
            retried.append(k)
            ops.algorithm("NewtonLineSearch")
            if ops.analyze(1, DT) != 0:
                sys.exit(f"OpenSees: step {k} (t = {k * DT} s) does not converge")
            ops.algorithm("Newton")
    ops.wipe()
    names = [f"{line[0]}/{f}" for line in LINES for f in range(1, n + 1)]
    return {
        "scene": SCENE,
        "building": BUILDING,
        "dt": DT,
        "steps": k,
        "drifts": names,
        "peak_drift": peak,
        "residual_drift": [abs(d) for d in drift],
        "retried_steps": retried,
    }


if __name__ == "__main__":
    print(json.dumps(run(import_opensees()), indent=2))
"#;
