#!/usr/bin/env python3
"""slipload against OpenSees on the benchmark three-storey building with massless dissipators.

Builds configs/benchmark-3story-massless.json (m' = 0: each brace + friction damper is an
elastic-perfectly plastic element) in OpenSees through openseespy, runs the same records
at the same time step with Newmark average acceleration (gamma = 1/2, beta = 1/4) in both
programs, and reports:

* model checks: the bare frame's stiffness matrix K of the config (`stiffness_matrix`, the
  paper's full condensed matrix, or `storey_stiffness`, a shear building's chain matrix),
  its periods against slipload's bare T1 and the paper's 1.01/0.33/0.17 s, the stiffness
  matrix OpenSees assembles (read back from its system matrix) against K, the periods of
  the OpenSees model (bare and braced), and the damping matrix OpenSees actually uses (read
  back from its system matrix) against alpha*M + beta*K_frame (the EPP elements must carry
  none);
* physics: peak drifts per storey, peak base shear and the drift / damper-force histories
  of slipload `newmark` against OpenSees, plus both against slipload `exact` (the
  event-located reference) and against an independent return-mapping Newmark written
  here in Python (the discrete equations OpenSees solves);
* timing: the median over R repeats of the time per simulation of each program,
  measured interleaved (OpenSees, slipload, OpenSees, slipload, ...) on the same machine,
  and their ratio.

Timing scope, the same for both programs: the time-stepping only, from a built model to
the peaks. slipload: `cpu_seconds` of `slipload simulate --format json` (wall-clock of the
integrator run, plan compiled and record read beforehand; peaks only, no energies or
histories), run as target/release/slipload after `cargo build --release -p slipload` (the
binary `cargo run --release --` runs; or the binary $SLIPLOAD_BIN names, not rebuilt), one process per repeat that runs the simulation
SLIPLOAD_REPEAT times and reports the median (`simulate --repeat`: a warm process, as
OpenSees is timed in its warm interpreter; a fresh process started right after an
OpenSees analysis runs with cold caches). OpenSees: wall-clock of the
analysis set-up commands (constraints, numberer, system, test, algorithm, integrator,
analysis) plus one `analyze(steps, dt)` call, with an EnvelopeElement recorder of the
storey drifts (the deformations of the EPP elements, each spanning one storey; its peaks); the model (nodes, materials, elements, the record as a Path
time series) is built beforehand and reported separately.

The OpenSees model: the floors as nodes with their masses over a fixed ground node; the
frame as zeroLength Elastic springs that assemble its matrix K exactly: one between every
pair of floors i < j of stiffness -K[i][j] (negative where the off-diagonal term is
positive: OpenSees's Elastic takes a negative E) and one from each floor to the ground of
stiffness sum_j K[i][j] (the row sum), all with Rayleigh damping; each brace + damper a
zeroLength ElasticPP element between floors i-1 and i, without.

Writes results/performance/opensees.json and results/performance/opensees.md atomically.

Usage: [SLIPLOAD_BIN=path] scripts/compare-opensees.py [--repeats R] [--dt DT] [--record FILE|synthetic ...]
Creates scripts/.venv with openseespy + numpy (+ matplotlib, for the figures of
scripts/compare-opensees-precision.py) on first use and re-runs itself inside it.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENV = ROOT / "scripts" / ".venv"
# Simulations per slipload process in the timed repeats (their median is the figure).
SLIPLOAD_REPEAT = 5
# The environment of every OpenSees comparison script (they import this one): matplotlib
# draws the work-precision figures of scripts/compare-opensees-precision.py.
REQUIREMENTS = ["openseespy==3.7.1.2", "numpy", "matplotlib"]
MODULES = ("openseespy", "numpy", "matplotlib")
G = 9.80665  # m/s² per g, as slipload-motion's G
BUILDING = ROOT / "configs" / "benchmark-3story-massless.json"
RECORDS = ROOT / "records"
OUT_DIR = ROOT / "results" / "performance"
SYNTHETIC = "synthetic"
SYNTHETIC_DURATION = 15.0  # s, the issue's benchmark record
SYNTHETIC_DT = 0.01  # s
# Newmark average acceleration, as slipload's `newmark` at alpha = 0.
GAMMA, BETA = 0.5, 0.25
# Newton convergence: norm of the last displacement correction. The response is piecewise
# linear in u_{n+1} (linear springs, EPP return mapping), so a Newton step with the right
# active set lands on the solution and the next correction is round-off (~1e-17 m for
# displacements of ~0.1 m); 1e-12 m (1e-11 of the peak drifts) stops there and no later.
TEST_TOL = 1e-12
TEST_MAX_ITER = 100
# The bare-frame periods the paper prints for the benchmark (De la Cruz, Lopez-Almansa & Oller
# 2007); its matrix gives 1.008 / 0.327 / 0.172 s.
PAPER_BARE_PERIODS = (1.01, 0.33, 0.17)


# ---------------------------------------------------------------------------------------
# Environment: venv with openseespy, numpy and matplotlib, then the OpenSees module itself.
# ---------------------------------------------------------------------------------------


def have_modules() -> bool:
    return all(importlib.util.find_spec(m) is not None for m in MODULES)


def ensure_environment(script: Path | None = None) -> None:
    """Re-executes `script` (default: this script) inside scripts/.venv, creating it and
    installing when missing. The other comparison scripts import this one and pass
    themselves."""
    if have_modules():
        return
    py = VENV / "bin" / "python"
    in_venv = Path(sys.prefix).resolve() == VENV.resolve()
    if not in_venv and not py.exists():
        print(f"creating {VENV.relative_to(ROOT)} ...", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
    check = f"import importlib.util as u,sys; sys.exit(0 if all(u.find_spec(m) for m in {MODULES!r}) else 1)"
    if subprocess.run([str(py), "-c", check]).returncode != 0:
        print(f"installing {' '.join(REQUIREMENTS)} into {VENV.relative_to(ROOT)} ...", file=sys.stderr)
        subprocess.run([str(py), "-m", "pip", "install", "--quiet", *REQUIREMENTS], check=True)
    if in_venv:
        importlib.invalidate_caches()
        return
    os.execv(str(py), [str(py), str((script or Path(__file__)).resolve()), *sys.argv[1:]])


def import_opensees():
    """Imports openseespy.opensees.

    The Linux wheel ships libblas.so.3 in openseespylinux/lib, and opensees.so finds its
    libraries there through its RUNPATH, but the shipped liblapack.so.3 needs libblas.so.3
    too and has no RUNPATH of its own: on a machine without a system BLAS the import
    fails. Loading the shipped BLAS first, globally, satisfies it.
    """
    import ctypes

    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.origin is not None:
        blas = Path(spec.origin).parent / "lib" / "libblas.so.3"
        if blas.exists():
            ctypes.CDLL(str(blas), mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


# ---------------------------------------------------------------------------------------
# Inputs: the building config and the records.
# ---------------------------------------------------------------------------------------

UNIT = {"kg": 1.0, "t": 1e3, "N/m": 1.0, "kN/m": 1e3, "MN/m": 1e6, "GN/m": 1e9, "N": 1.0, "kN": 1e3, "MN": 1e6, "m": 1.0, "cm": 1e-2, "mm": 1e-3, "s": 1.0}


def quantity(value, what: str, source: Path = BUILDING) -> float:
    """A config quantity of `source`: a number (SI) or a string "<number> <unit>"."""
    if isinstance(value, (int, float)):
        return float(value)
    parts = str(value).split()
    if len(parts) == 2 and parts[1] in UNIT:
        return float(parts[0]) * UNIT[parts[1]]
    if len(parts) == 1:
        return float(parts[0])
    raise SystemExit(f"{source}: {what}: cannot read the quantity {value!r}")


def frame_matrix(cfg: dict, path: Path, n: int) -> list[list[float]]:
    """The bare frame's stiffness matrix K (N/m, n x n), the model's source of truth: either
    `stiffness_matrix` (the full condensed matrix, symmetric) or `storey_stiffness` (a shear
    building: springs between consecutive floors, the chain matrix)."""
    if ("stiffness_matrix" in cfg) == ("storey_stiffness" in cfg):
        raise SystemExit(f"{path}: give exactly one of stiffness_matrix and storey_stiffness")
    if "storey_stiffness" in cfg:
        k = [quantity(v, "storey_stiffness") for v in cfg["storey_stiffness"]]
        if len(k) != n:
            raise SystemExit(f"{path}: {len(k)} storey stiffnesses for {n} floors")
        return storey_matrix(k).tolist()
    rows = cfg["stiffness_matrix"]
    if len(rows) != n or any(len(r) != n for r in rows):
        raise SystemExit(f"{path}: stiffness_matrix must be {n} x {n} (one row and column per floor)")
    K = [[quantity(v, f"stiffness_matrix[{i}][{j}]") for j, v in enumerate(r)] for i, r in enumerate(rows)]
    scale = max(abs(x) for r in K for x in r)
    for i in range(n):
        for j in range(i + 1, n):
            if abs(K[i][j] - K[j][i]) > 1e-12 * scale:
                raise SystemExit(f"{path}: stiffness_matrix is not symmetric: [{i}][{j}] = {K[i][j]} N/m, [{j}][{i}] = {K[j][i]} N/m")
            K[j][i] = K[i][j]
    return K


def load_building(path: Path) -> dict:
    cfg = json.loads(path.read_text())
    masses = [quantity(m, "floor_masses") for m in cfg["floor_masses"]]
    n = len(masses)
    K = frame_matrix(cfg, path, n)
    ray = cfg["damping"]["rayleigh"]
    kp = [0.0] * n
    fy = [0.0] * n
    for d in cfg["dissipators"]:
        i = int(d["floor"]) - 1
        if quantity(d.get("mass", 0), "dissipators.mass") != 0.0:
            raise SystemExit(f"{path}: dissipator of floor {i + 1} has mass: the comparison needs m' = 0")
        if quantity(d.get("brace_damping", 0), "dissipators.brace_damping") != 0.0:
            raise SystemExit(f"{path}: dissipator of floor {i + 1} has brace damping: not modelled here")
        kp[i] = quantity(d["brace_stiffness"], "dissipators.brace_stiffness")
        fy[i] = quantity(d["slip_load"], "dissipators.slip_load")
    if any(v == 0.0 for v in kp):
        raise SystemExit(f"{path}: every floor needs a dissipator for this comparison")
    return {"name": cfg["name"], "m": masses, "K": K, "alpha": float(ray["alpha"]), "beta": float(ray["beta"]), "kp": kp, "fy": fy}


def storey_matrix(k: list[float]):
    """Stiffness matrix of springs k[i] between floor i-1 (ground for i = 0) and floor i."""
    import numpy as np

    n = len(k)
    K = np.zeros((n, n))
    for i, ki in enumerate(k):
        K[i, i] += ki
        if i > 0:
            K[i - 1, i - 1] += ki
            K[i - 1, i] -= ki
            K[i, i - 1] -= ki
    return K


def read_at2(path: Path) -> tuple[float, list[float]]:
    """PEER AT2 (values in g): the NPTS/DT header line, then NPTS values."""
    lines = path.read_text().splitlines()
    npts = dt = None
    for i, line in enumerate(lines[:10]):
        mn = re.search(r"NPTS\s*=\s*(\d+)", line, re.I)
        md = re.search(r"DT\s*=\s*([0-9.Ee+-]+)", line, re.I)
        if mn and md:
            npts, dt, start = int(mn.group(1)), float(md.group(1)), i + 1
            break
    if npts is None:
        raise SystemExit(f"{path}: no NPTS=/DT= header line in the first 10 lines")
    vals = [float(t) for line in lines[start:] for t in line.replace(",", " ").split()]
    if len(vals) < npts:
        raise SystemExit(f"{path}: header says NPTS={npts}, found {len(vals)} values")
    return dt, [v * G for v in vals[:npts]]


def read_csv_record(path: Path) -> tuple[float, list[float]]:
    """time_s,accel_m_s2 CSV as written by `slipload record synth` (uniform steps)."""
    rows = [line.split(",") for line in path.read_text().splitlines()[1:] if line.strip()]
    t = [float(r[0]) for r in rows]
    a = [float(r[1]) for r in rows]
    dt = t[1] - t[0]
    for i in range(1, len(t)):
        if abs(t[i] - t[0] - i * dt) > 1e-9 * max(1.0, t[i]):
            raise SystemExit(f"{path}: line {i + 2}: time {t[i]} is not on the uniform grid of dt = {dt}")
    return dt, a


def ground_accel(dt_rec: float, acc: list[float], t: float) -> float:
    """Linear interpolation between samples, zero after the last (OpenSees Path series)."""
    x = t / dt_rec
    i = int(math.floor(x + 1e-9))
    if i >= len(acc) - 1:
        return acc[-1] if abs(x - (len(acc) - 1)) < 1e-9 else 0.0
    f = max(0.0, x - i)
    return acc[i] + f * (acc[i + 1] - acc[i])


# ---------------------------------------------------------------------------------------
# slipload
# ---------------------------------------------------------------------------------------


def slipload_bin() -> Path:
    """$SLIPLOAD_BIN when set (an existing binary, used as is), else target/release/slipload
    after `cargo build --release -p slipload`."""
    given = os.environ.get("SLIPLOAD_BIN")
    if given:
        path = Path(given).resolve()
        if not (path.is_file() and os.access(path, os.X_OK)):
            raise SystemExit(f"SLIPLOAD_BIN={given}: not an executable file")
        return path
    subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "slipload"], cwd=ROOT, check=True)
    return ROOT / "target" / "release" / "slipload"


def slipload_scene(tmp: Path, label: str, record: Path, units: str, dt: float) -> Path:
    scene = {
        "name": f"benchmark-3story-massless, {label}",
        "building": str(BUILDING),
        "excitation": {"record": {"file": str(record.resolve()), "units": units}},
        "method": {"name": "newmark", "dt": dt},
        "outputs": {"energies": False, "histories": False},
    }
    path = tmp / f"scene-{label}.json"
    path.write_text(json.dumps(scene, indent=2))
    return path


def slipload_run(binary: Path, scene: Path, *extra: str) -> dict:
    out = subprocess.run([str(binary), "simulate", str(scene), "--format", "json", *extra], cwd=ROOT, check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def read_history(path: Path) -> dict[str, list[float]]:
    lines = path.read_text().splitlines()
    cols = lines[0].split(",")
    data = {c: [] for c in cols}
    for line in lines[1:]:
        for c, v in zip(cols, line.split(",")):
            data[c].append(float(v))
    return data


# ---------------------------------------------------------------------------------------
# OpenSees
# ---------------------------------------------------------------------------------------

FRAME_TAG = 1  # frame springs: elements (and materials) 1..n(n+1)/2 at most
EPP_TAG = 1001  # brace + damper of storey i (floor i-1 to floor i): element 1001 + i, i = 0..n-1


def frame_springs(K: list[list[float]]) -> list[tuple[int, int, float]]:
    """Springs (node a, node b, stiffness) that assemble exactly the frame matrix K, node 0
    the ground and node i + 1 floor i: one between every pair of floors i < j of stiffness
    -K[i][j] (negative where the off-diagonal term is positive), and one from each floor to
    the ground of stiffness sum_j K[i][j] (the row sum, negative if the row sums below 0).
    A spring of stiffness k between nodes a, b adds k to [a][a], [b][b] and -k to [a][b],
    so the pairs give the off-diagonal terms and the diagonal K[i][i] = ground_i +
    sum_{j != i} (-K[i][j]). Zero springs (to round-off, e.g. the rows of a shear building
    that sum to 0 and the pairs of floors that are not consecutive there) are left out."""
    n = len(K)
    scale = max(abs(x) for r in K for x in r)
    springs = []
    for i in range(n):
        ground = math.fsum(K[i])
        if abs(ground) > 1e-12 * scale:
            springs.append((0, i + 1, ground))
    for i in range(n):
        for j in range(i + 1, n):
            if K[i][j] != 0.0:
                springs.append((i + 1, j + 1, -K[i][j]))
    return springs


def floor_nodes(ops, m: list[float]) -> None:
    """A fresh 1-D model: a fixed ground node 0 and floor nodes 1..n with masses `m`."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(0, 0.0)
    ops.fix(0, 1)
    for i, mi in enumerate(m):
        ops.node(i + 1, 0.0)
        ops.mass(i + 1, mi)


def build_model(ops, b: dict, dt_rec: float, acc: list[float], braces: bool = True) -> None:
    """Floors as nodes with their masses on a fixed ground node 0; the frame as zeroLength
    Elastic springs that assemble its matrix K (`frame_springs`); each brace + damper a
    zeroLength ElasticPP element between floors i-1 and i; the record as a uniform
    excitation. `braces = False`: the bare frame (model checks only)."""
    n = len(b["m"])
    floor_nodes(ops, b["m"])
    springs = frame_springs(b["K"])
    if FRAME_TAG + len(springs) > EPP_TAG:
        raise SystemExit(f"{len(springs)} frame springs: their element tags would reach the EPP elements' {EPP_TAG}")
    for tag, (na, nb, k) in enumerate(springs, start=FRAME_TAG):
        # Frame spring (OpenSees's Elastic takes a negative E): takes part in Rayleigh damping.
        ops.uniaxialMaterial("Elastic", tag, k)
        ops.element("zeroLength", tag, na, nb, "-mat", tag, "-dir", 1, "-doRayleigh", 1)
    for i in range(n if braces else 0):
        # Brace + damper: elastic-perfectly plastic, stiffness k', yield displacement muN/k';
        # no Rayleigh damping (c' = 0 in the config). Its deformation is the storey drift.
        ops.uniaxialMaterial("ElasticPP", EPP_TAG + i, b["kp"][i], b["fy"][i] / b["kp"][i])
        ops.element("zeroLength", EPP_TAG + i, i, i + 1, "-mat", EPP_TAG + i, "-dir", 1, "-doRayleigh", 0)
    # alpha*M on the nodes, beta*K_initial on the elements that take Rayleigh damping: the
    # frame springs only, whose initial stiffnesses sum to K (linear frame).
    ops.rayleigh(b["alpha"], 0.0, b["beta"], 0.0)
    # -useLast: OpenSees accumulates time by adding dt, so the last step may land a few ulps
    # past the last sample, where a Path series is otherwise 0; slipload (and the references
    # here) take the last sample at the record's end.
    ops.timeSeries("Path", 1, "-dt", dt_rec, "-values", *acc, "-useLast")
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    # Start from rest in equilibrium with the first sample, as slipload does: relative
    # accelerations -a_g(0) (OpenSees would otherwise start from zero accelerations).
    for i in range(n):
        ops.setNodeAccel(i + 1, 1, -acc[0], "-commit")


def analysis(ops, algorithm: str, system: str) -> None:
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system(system)
    ops.test("NormDispIncr", TEST_TOL, TEST_MAX_ITER, 0)
    ops.algorithm(algorithm)
    ops.integrator("Newmark", GAMMA, BETA)
    ops.analysis("Transient")



def analyze_step(ops, s: int, dt: float, algorithm: str, failed: list) -> int:
    """One analysis step s of length dt; a step that does not converge is counted in
    `failed` and retried with line search and with a modified Newton of many iterations
    (the algorithm and test restored after each). Returns its Newton iterations."""
    ok = ops.analyze(1, dt)
    it = ops.testIter()
    if ok != 0:
        failed.append(s)
        for retry in (("NewtonLineSearch",), ("ModifiedNewton", "-initial")):
            ops.algorithm(*retry)
            ops.test("NormDispIncr", TEST_TOL, 10 * TEST_MAX_ITER, 0)
            ok = ops.analyze(1, dt)
            it += ops.testIter()
            ops.algorithm(algorithm)
            ops.test("NormDispIncr", TEST_TOL, TEST_MAX_ITER, 0)
            if ok == 0:
                break
        if ok != 0:
            raise SystemExit(f"OpenSees: step {s} (t = {s * dt:.4f} s) does not converge even with line search / modified Newton")
    return it


def periods_and_tangent(ops, n: int):
    """Of the model just built: its eigen periods (initial tangent) and the stiffness
    matrix OpenSees assembles, the system matrix of one static step with no load (Newton:
    the tangent at rest); the model is wiped after."""
    import numpy as np

    w2 = sorted(ops.eigen("-fullGenLapack", n))
    T = [2.0 * math.pi / math.sqrt(x) for x in w2]
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", TEST_TOL, TEST_MAX_ITER, 0)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise SystemExit("OpenSees: model check static step failed")
    K = np.array(ops.printA("-ret")).reshape(n, n)
    ops.wipe()
    return T, K

def opensees_timed(ops, b, dt_rec, acc, dt, steps, algorithm, system, tmp: Path) -> dict:
    """One simulation: build (timed apart), then set-up + analyze(steps) timed."""
    t0 = time.perf_counter()
    build_model(ops, b, dt_rec, acc)
    env = tmp / "envelope-drift.out"
    n = len(b["m"])
    # The storey drifts: the deformations of the EPP elements, element EPP_TAG + i spanning
    # exactly storey i (node i to node i + 1: u_{i+1} - u_i). The frame springs do not map
    # to storeys (one per pair of floors and one per floor to the ground).
    ops.recorder("EnvelopeElement", "-file", str(env), "-precision", 17, "-ele", *range(EPP_TAG, EPP_TAG + n), "deformation")
    t1 = time.perf_counter()
    analysis(ops, algorithm, system)
    ok = ops.analyze(steps, dt)
    t2 = time.perf_counter()
    ops.wipe()  # flushes the envelope recorder
    if ok != 0:
        raise SystemExit(f"OpenSees analyze({steps}, {dt}) failed (code {ok}) with {algorithm}: see the step-by-step run")
    rows = [[float(v) for v in line.split()] for line in env.read_text().splitlines() if line.strip()]
    # rows: min, max, absmax over time, one column per element (storey).
    return {"build_s": t1 - t0, "run_s": t2 - t1, "peak_drift": rows[2]}


def opensees_stepwise(ops, b, dt_rec, acc, dt, steps, algorithm, system) -> dict:
    """The same analysis one step at a time, recording histories, Newton iterations and
    any step that does not converge (then retried with line search and with a
    modified Newton of many iterations; counted either way)."""
    build_model(ops, b, dt_rec, acc)
    analysis(ops, algorithm, system)
    n = len(b["m"])
    m = b["m"]
    drift = [[0.0] * n]
    force = [[0.0] * n]
    peak_bs = 0.0  # at rest, in equilibrium with a_g(0): no inertia force
    iters = []
    failed = []
    for s in range(1, steps + 1):
        it = analyze_step(ops, s, dt, algorithm, failed)
        iters.append(it)
        u = [ops.nodeDisp(i + 1, 1) for i in range(n)]
        drift.append([u[i] - (u[i - 1] if i > 0 else 0.0) for i in range(n)])
        force.append([ops.eleForce(EPP_TAG + i)[1] for i in range(n)])
        ag = ground_accel(dt_rec, acc, s * dt)
        bs = abs(sum(m[i] * (ops.nodeAccel(i + 1, 1) + ag) for i in range(n)))
        peak_bs = max(peak_bs, bs)
    ops.wipe()
    # Elastic <-> yielded changes of each EPP element (|F| at its yield force, to round-off),
    # the counterpart of slipload's stick <-> slip `transitions`.
    tol = 1e-9
    at_bound = [[abs(f[i]) >= b["fy"][i] * (1.0 - tol) for i in range(n)] for f in force]
    transitions = [sum(1 for p, q in zip(at_bound, at_bound[1:]) if p[i] != q[i]) for i in range(n)]
    return {
        "transitions": transitions,
        "drift": drift,
        "force": force,
        "peak_drift": [max(abs(d[i]) for d in drift) for i in range(n)],
        "peak_base_shear": peak_bs,
        "newton_iterations": {"total": sum(iters), "mean": sum(iters) / len(iters), "max": max(iters)},
        "failed_steps": failed,
    }


def newmark_epp_reference(b, dt_rec, acc, dt, steps) -> dict:
    """Newmark average acceleration on the floors with the EPP elements solved to round-off
    by Newton, written independently of both programs: the return mapping, the plastic slip
    advanced by backward Euler (the slip increment decides the yield direction). What
    OpenSees's ElasticPP does by Newton, and what slipload's `newmark` solves exactly (a box
    QP on the slips of the step) for an EPP element without a brace dashpot.
    """
    import numpy as np

    n = len(b["m"])
    M = np.diag(b["m"])
    K = np.array(b["K"])  # the full frame matrix; the EPP elements are storey elements
    C = b["alpha"] * M + b["beta"] * K
    kp, fy = b["kp"], b["fy"]
    c_a = 1.0 / (BETA * dt * dt)
    c_v = GAMMA / (BETA * dt)
    A0 = K + c_v * C + c_a * M
    u = np.zeros(n)
    v = np.zeros(n)
    a = -acc[0] * np.ones(n)
    sp = np.zeros(n)  # slip of each EPP element (drift minus brace elongation), m
    peak = np.zeros(n)
    drift = [[0.0] * n]
    force = [[0.0] * n]
    for s in range(1, steps + 1):
        ag = ground_accel(dt_rec, acc, s * dt)
        start = sp
        # a(u1), v(u1) by Newmark; residual R(u1) = M a + C v + K u1 + B f(u1) + M r ag.
        ua = u + dt * v + (0.5 - BETA) * dt * dt * a
        va = v + (1.0 - GAMMA) * dt * a
        u1 = u.copy()
        for _ in range(100):
            d = u1 - np.concatenate(([0.0], u1[:-1]))
            trial = [kp[i] * (d[i] - start[i]) for i in range(n)]
            f = np.array([min(max(t, -fy[i]), fy[i]) for i, t in enumerate(trial)])
            kt = [kp[i] if abs(trial[i]) <= fy[i] else 0.0 for i in range(n)]
            a1 = c_a * (u1 - ua)
            v1 = va + GAMMA * dt * a1
            bf = f.copy()
            bf[:-1] -= f[1:]  # element i pulls floor i by -f and floor i-1 by +f
            R = M @ a1 + C @ v1 + K @ u1 + bf + M @ np.full(n, ag)
            du = np.linalg.solve(A0 + storey_matrix(kt), -R)
            u1 = u1 + du
            if np.max(np.abs(du)) < 1e-14:
                break
        else:
            raise SystemExit(f"Newmark EPP reference: step {s} did not converge")
        d = u1 - np.concatenate(([0.0], u1[:-1]))
        f = np.array([min(max(kp[i] * (d[i] - start[i]), -fy[i]), fy[i]) for i in range(n)])
        sp = d - f / np.array(kp)
        a1 = c_a * (u1 - ua)
        v = va + GAMMA * dt * a1
        u, a = u1, a1
        peak = np.maximum(peak, np.abs(d))
        drift.append(d.tolist())
        force.append(f.tolist())
    return {"peak_drift": peak.tolist(), "drift": drift, "force": force}


def model_checks(ops, b: dict, dt: float, slipload_t1: float | None) -> dict:
    """Periods, stiffness and damping of the OpenSees model against the matrices of the config."""
    import numpy as np

    n = len(b["m"])
    M = np.diag(b["m"])
    K = np.array(b["K"])
    Kb = K + storey_matrix(b["kp"])
    C = b["alpha"] * M + b["beta"] * K

    def periods(Km):
        w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, Km)).real)
        return (2.0 * math.pi / np.sqrt(w2)).tolist()

    def rel_matrix(A, B) -> float:
        return float(np.max(np.abs(A - B)) / np.max(np.abs(B)))

    bare = periods(K)
    braced = periods(Kb)
    zeta = [b["alpha"] / (2.0 * (2.0 * math.pi / T)) + b["beta"] * (2.0 * math.pi / T) / 2.0 for T in bare]

    def opensees_model(braces: bool):
        """Eigen periods (initial tangent) and the stiffness matrix OpenSees assembles: the
        system matrix of one static step with no load (Newton: the tangent at rest)."""
        build_model(ops, b, 1.0, [0.0, 0.0, 0.0], braces=braces)
        return periods_and_tangent(ops, n)

    os_bare, K_os = opensees_model(braces=False)
    os_braced, Kb_os = opensees_model(braces=True)
    # The damping matrix read back from the Newmark system matrix
    # A = K_t + gamma/(beta dt) C + 1/(beta dt^2) M after a first (elastic) step of a tiny
    # pulse, K_t the braced stiffness OpenSees assembled (read back above).
    build_model(ops, b, 1.0, [0.0, 1e-6, 0.0])
    analysis(ops, "Newton", "FullGeneral")
    if ops.analyze(1, dt) != 0:
        raise SystemExit("OpenSees: model check step failed")
    A = np.array(ops.printA("-ret")).reshape(n, n)
    ops.wipe()
    C_os = (A - Kb_os - M / (BETA * dt * dt)) * (BETA * dt / GAMMA)
    return {
        "frame_stiffness_N_m": K.tolist(),
        "frame_springs": [{"nodes": [na, nb], "stiffness_N_m": k} for na, nb, k in frame_springs(b["K"])],
        "bare_periods_s": bare,
        "bare_periods_paper_s": list(PAPER_BARE_PERIODS),
        "bare_T1_slipload_s": slipload_t1,
        "bare_damping_ratios": zeta,
        "bare_periods_opensees_s": os_bare,
        "bare_period_max_rel_diff": max(abs(x - y) / y for x, y in zip(os_bare, bare)),
        "frame_stiffness_opensees_N_m": K_os.tolist(),
        "frame_stiffness_max_rel_diff": rel_matrix(K_os, K),
        "braced_stiffness_max_rel_diff": rel_matrix(Kb_os, Kb),
        "braced_periods_s": braced,
        "braced_periods_opensees_s": os_braced,
        "braced_period_max_rel_diff": max(abs(x - y) / y for x, y in zip(os_braced, braced)),
        "damping_matrix_opensees_N_s_m": C_os.tolist(),
        "damping_matrix_max_rel_diff": rel_matrix(C_os, C),
    }


# ---------------------------------------------------------------------------------------
# The comparison
# ---------------------------------------------------------------------------------------


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def max_rel(xs, ys) -> float:
    return max(rel(x, y) for x, y in zip(xs, ys))


def history_rows(cols: dict[str, list[float]], prefix: str, n: int) -> list[list[float]]:
    """Rows (one per step) of the storey columns `drift<i>_m` or `F<i>_N` of a slipload history."""
    unit = "m" if prefix == "drift" else "N"
    return [list(r) for r in zip(*(cols[f"{prefix}{i + 1}_{unit}"] for i in range(n)))]


def history_gap(rows, ref_rows) -> float:
    """max over steps and storeys of |rows - ref_rows|, over the peak |ref_rows| of that storey."""
    if len(rows) != len(ref_rows):
        raise SystemExit(f"history lengths differ: {len(rows)} and {len(ref_rows)} steps")
    worst = 0.0
    for i in range(len(ref_rows[0])):
        scale = max(abs(r[i]) for r in ref_rows)
        worst = max(worst, max(abs(x[i] - r[i]) for x, r in zip(rows, ref_rows)) / scale)
    return worst


def run_case(ops, binary, tmp, b, label, record, units, dt_rec, acc, dt, repeats, algorithms, system) -> dict:
    n = len(b["m"])
    scene = slipload_scene(tmp, label, record, units, dt)
    print(f"\n== {label}: {record.name}, {len(acc)} samples at {dt_rec} s, dt = {dt} s", file=sys.stderr)
    # slipload: one run with histories, one exact run (with histories: its peaks at the steps).
    hist = tmp / f"history-{label}.csv"
    sl = slipload_run(binary, scene, "--history", str(hist))
    steps = int(sl["steps"])
    if abs(sl["dt"] - dt) > 1e-15:
        raise SystemExit(f"slipload chose dt = {sl['dt']}, asked for {dt}")
    sl_hist = read_history(hist)
    sl_drift = history_rows(sl_hist, "drift", n)
    sl_force = history_rows(sl_hist, "F", n)
    ex_hist_path = tmp / f"history-{label}-exact.csv"
    ex = slipload_run(binary, scene, "--method", "exact", "--history", str(ex_hist_path))
    ex_hist = read_history(ex_hist_path)
    ex_sampled = [max(abs(x) for x in ex_hist[f"drift{i + 1}_m"]) for i in range(n)]
    # OpenSees step by step (physics, convergence), and the return-mapping reference.
    st = opensees_stepwise(ops, b, dt_rec, acc, dt, steps, algorithms[0], system)
    ref = newmark_epp_reference(b, dt_rec, acc, dt, steps)
    # Timing, interleaved, after one untimed warm-up run of each.
    for a in algorithms:
        opensees_timed(ops, b, dt_rec, acc, dt, steps, a, system, tmp)
    slipload_run(binary, scene)
    times = {a: [] for a in algorithms}
    build = []
    sl_times = []
    env_peaks = None
    for r in range(repeats):
        for a in algorithms:
            t = opensees_timed(ops, b, dt_rec, acc, dt, steps, a, system, tmp)
            times[a].append(t["run_s"])
            build.append(t["build_s"])
            env_peaks = env_peaks or t["peak_drift"]
        sl_times.append(slipload_run(binary, scene, "--repeat", str(SLIPLOAD_REPEAT))["cpu_seconds"])
        print(f"  repeat {r + 1}/{repeats}: OpenSees " + ", ".join(f"{a} {times[a][-1] * 1e3:.2f} ms" for a in algorithms) + f"; slipload {sl_times[-1] * 1e3:.3f} ms", file=sys.stderr)
    med = {a: statistics.median(v) for a, v in times.items()}
    sl_med = statistics.median(sl_times)
    case = {
        "label": label,
        "record": str(record.relative_to(ROOT)) if record.is_relative_to(ROOT) else str(record),
        "record_samples": len(acc),
        "record_dt_s": dt_rec,
        "dt_s": dt,
        "steps": steps,
        "duration_s": steps * dt,
        "slipload": {
            "method": "newmark",
            "median_s": sl_med,
            "times_s": sl_times,
            "peak_drift_m": sl["peak_drift"],
            "peak_base_shear_N": sl["peak_base_shear"],
            "transitions": sl["transitions"],
        },
        "opensees": {
            "algorithm": algorithms[0],
            "system": system,
            "median_s": med[algorithms[0]],
            "times_s": times[algorithms[0]],
            "model_build_median_s": statistics.median(build),
            "other_algorithms": {a: {"median_s": med[a], "times_s": times[a]} for a in algorithms[1:]},
            "peak_drift_m": st["peak_drift"],
            "envelope_recorder_peak_drift_m": env_peaks,
            "peak_base_shear_N": st["peak_base_shear"],
            "newton_iterations": st["newton_iterations"],
            "failed_steps": st["failed_steps"],
            "transitions": st["transitions"],
        },
        "exact": {
            "peak_drift_continuous_m": ex["peak_drift"],
            "peak_drift_at_steps_m": ex_sampled,
            "peak_base_shear_N": ex["peak_base_shear"],
            "transitions": ex["transitions"],
        },
        "ratio_opensees_over_slipload": med[algorithms[0]] / sl_med,
        "ratio_fastest_opensees_over_slipload": min(med.values()) / sl_med,
        "max_rel_diff_peak_drift": max_rel(st["peak_drift"], sl["peak_drift"]),
        "rel_diff_peak_drift_by_storey": [rel(x, y) for x, y in zip(st["peak_drift"], sl["peak_drift"])],
        "rel_diff_peak_base_shear": rel(st["peak_base_shear"], sl["peak_base_shear"]),
        "max_rel_diff_drift_history": history_gap(st["drift"], sl_drift),
        "max_rel_diff_force_history": history_gap(st["force"], sl_force),
        "opensees_vs_return_mapping_max_rel_diff_peak_drift": max_rel(st["peak_drift"], ref["peak_drift"]),
        "opensees_vs_return_mapping_max_rel_diff_drift_history": history_gap(st["drift"], ref["drift"]),
        "slipload_vs_return_mapping_max_rel_diff_peak_drift": max_rel(sl["peak_drift"], ref["peak_drift"]),
        "slipload_vs_return_mapping_max_rel_diff_drift_history": history_gap(sl_drift, ref["drift"]),
        "slipload_vs_return_mapping_max_rel_diff_force_history": history_gap(sl_force, ref["force"]),
        "opensees_envelope_vs_stepwise_max_rel_diff": max_rel(env_peaks, st["peak_drift"]),
        "slipload_vs_exact_max_rel_diff_peak_drift": max_rel(sl["peak_drift"], ex_sampled),
        "opensees_vs_exact_max_rel_diff_peak_drift": max_rel(st["peak_drift"], ex_sampled),
    }
    print(
        f"  OpenSees {med[algorithms[0]] * 1e3:.2f} ms, slipload {sl_med * 1e3:.3f} ms per simulation: ratio {case['ratio_opensees_over_slipload']:.1f}\n"
        f"  peak drifts: max rel. diff {case['max_rel_diff_peak_drift']:.2e} (by storey "
        + ", ".join(f"{x:.1e}" for x in case["rel_diff_peak_drift_by_storey"])
        + f"), base shear {case['rel_diff_peak_base_shear']:.2e}\n"
        f"  against exact (peaks at the steps): slipload {case['slipload_vs_exact_max_rel_diff_peak_drift']:.2e}, OpenSees {case['opensees_vs_exact_max_rel_diff_peak_drift']:.2e}; "
        f"OpenSees against the return-mapping reference {case['opensees_vs_return_mapping_max_rel_diff_peak_drift']:.1e}\n"
        f"  Newton iterations per step: mean {st['newton_iterations']['mean']:.2f}, max {st['newton_iterations']['max']}; steps that failed to converge: {len(st['failed_steps'])}",
        file=sys.stderr,
    )
    return case


def write_atomic(path: Path, text: str | bytes) -> None:
    """Writes `text` (or bytes: a PNG) to a temporary file beside `path` and renames it
    over `path`: a reader sees the old file or the whole new one, never a partial one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(fd, "wb" if isinstance(text, bytes) else "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def machine(ops) -> dict:
    info = {}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            key, _, val = line.partition(":")
            info[key.strip()] = val.strip()
    except OSError:
        pass
    commit = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    from importlib.metadata import version

    return {
        "cpu_model": info.get("Model name", platform.processor()),
        "cpus": info.get("CPU(s)"),
        "threads_per_core": info.get("Thread(s) per core"),
        "os": platform.platform(),
        "python": platform.python_version(),
        "opensees": ops.version() if hasattr(ops, "version") else None,
        "openseespy": version("openseespy"),
        "slipload_commit": commit + ("-dirty" if dirty else ""),
        "rustc": subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip(),
    }


def markdown(report: dict) -> str:
    m = report["machine"]
    s = report["settings"]
    chk = report["model_checks"]
    lines = [
        "# slipload against OpenSees",
        "",
        f"Regenerate with `{s['command']}`.",
        "",
        f"Building: `{s['building']}` (the benchmark three-storey frame, massless dissipators: each brace + damper an",
        "elastic–perfectly plastic element). Both programs: Newmark average acceleration (γ = ½, β = ¼), the same record,",
        f"the same Δt, peaks at the steps. OpenSees: {s['opensees_model']}; {s['opensees_solution']}.",
        "",
        f"Timing: {s['timing']}",
        "",
        "| record | steps × Δt | OpenSees (ms / sim) | slipload (ms / sim) | ratio | fastest OpenSees variant (ms) | rel. diff. peak drift, storeys 1, 2, 3 | rel. diff. peak base shear | max rel. diff. drift history | Newton it./step (max) | unconverged steps |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for c in report["cases"]:
        o = c["opensees"]
        fastest = min([o["median_s"]] + [v["median_s"] for v in o["other_algorithms"].values()])
        lines.append(
            f"| {c['label']} | {c['steps']} × {c['dt_s']} s | {o['median_s'] * 1e3:.2f} | {c['slipload']['median_s'] * 1e3:.3f} | "
            f"**{c['ratio_opensees_over_slipload']:.0f}×** | {fastest * 1e3:.2f} | {', '.join(f'{x:.1e}' for x in c['rel_diff_peak_drift_by_storey'])} | "
            f"{c['rel_diff_peak_base_shear']:.1e} | {c['max_rel_diff_drift_history']:.1e} | "
            f"{o['newton_iterations']['mean']:.2f} ({o['newton_iterations']['max']}) | {len(o['failed_steps'])} |"
        )
    lines += [
        "",
        "Both programs against one reference (max relative differences of the peak drifts over storeys; histories: max over steps",
        "and storeys of the difference over the storey's peak): a Newmark with the EPP elements' *return mapping* (the plastic slip",
        "advanced by backward Euler, as OpenSees's ElasticPP and slipload's `newmark` with m′ = 0 do), solved by Newton to round-off",
        "and written in the script, independently of both programs. Against `exact`: the event-located solution, peaks at the same steps.",
        "",
        "| record | OpenSees vs return mapping (peaks / drift history) | slipload vs return mapping (peaks / drift history) | slipload newmark vs exact | OpenSees vs exact | stick↔slip transitions per storey: slipload / OpenSees / exact |",
        "|---|---:|---:|---:|---:|---|",
    ]
    for c in report["cases"]:
        lines.append(
            f"| {c['label']} | {c['opensees_vs_return_mapping_max_rel_diff_peak_drift']:.0e} / {c['opensees_vs_return_mapping_max_rel_diff_drift_history']:.0e} | "
            f"{c['slipload_vs_return_mapping_max_rel_diff_peak_drift']:.0e} / {c['slipload_vs_return_mapping_max_rel_diff_drift_history']:.0e} | "
            f"{c['slipload_vs_exact_max_rel_diff_peak_drift']:.1e} | {c['opensees_vs_exact_max_rel_diff_peak_drift']:.1e} | "
            f"{c['slipload']['transitions']} / {c['opensees']['transitions']} / {c['exact']['transitions']} |"
        )
    lines += [
        "",
        "Model checks: bare-frame periods from the frame matrix "
        + ", ".join(f"{t:.4f}" for t in chk["bare_periods_s"])
        + f" s (slipload's bare T1: {chk['bare_T1_slipload_s']} s; the paper prints "
        + " / ".join(f"{t:g}" for t in chk["bare_periods_paper_s"]) + " s), "
        + "damping ratios " + ", ".join(f"{100 * z:.2f} %" for z in chk["bare_damping_ratios"])
        + f"; OpenSees's frame springs ({len(chk['frame_springs'])}: a spring between every pair of floors and one to the ground per floor,"
        + " negative where an off-diagonal term is positive or a row sums below zero) assemble the condensed frame matrix:"
        + f" its stiffness matrix (read back from its system matrix) equals K within {chk['frame_stiffness_max_rel_diff']:.1e}"
        + f" (braced: K + the braces' chain matrix within {chk['braced_stiffness_max_rel_diff']:.1e}), its bare eigen periods"
        + f" within {chk['bare_period_max_rel_diff']:.1e}; braced periods " + ", ".join(f"{t:.4f}" for t in chk["braced_periods_s"])
        + f" s, OpenSees eigen within {chk['braced_period_max_rel_diff']:.1e}; the damping matrix OpenSees uses (read back from"
        + f" its system matrix) equals α M + β K_frame within {chk['damping_matrix_max_rel_diff']:.1e} (relative), so the EPP elements carry no damping.",
        "",
        f"Machine: {m['cpu_model']}, {m['cpus']} CPUs ({m['threads_per_core']} thread per core), shared with other jobs; {m['os']};",
        f"OpenSees {m['opensees']} through openseespy {m['openseespy']} (Python {m['python']}); slipload {m['slipload_commit']} built by {m['rustc']}.",
        "",
        "Both solve the same discrete equations, so their peaks agree to the Newton tolerance: see the README section \"Against OpenSees\".",
        "",
    ]
    return "\n".join(lines)


def checked_model(ops, binary: Path, b: dict, dt: float) -> dict:
    """model_checks of the OpenSees model at time step dt, with slipload's bare T1 (from
    `slipload explain`); stops when the model is not the config's, since no comparison
    means anything then. The other comparison scripts on this building call it too."""
    explain = subprocess.run([str(binary), "explain", str(BUILDING), "--duration", "1"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    mt = re.search(r"bare T1 = ([0-9.]+) s", explain)
    checks = model_checks(ops, b, dt, float(mt.group(1)) if mt else None)
    print(
        f"model checks: bare periods {checks['bare_periods_s']} (paper {checks['bare_periods_paper_s']}), slipload bare T1 {checks['bare_T1_slipload_s']}; "
        f"OpenSees: stiffness matrix rel. diff {checks['frame_stiffness_max_rel_diff']:.1e} (braced {checks['braced_stiffness_max_rel_diff']:.1e}), "
        f"bare periods {checks['bare_period_max_rel_diff']:.1e}, braced periods {checks['braced_period_max_rel_diff']:.1e}, damping matrix {checks['damping_matrix_max_rel_diff']:.1e}",
        file=sys.stderr,
    )
    # The comparison means nothing on a model that is not the config's: stop here.
    failed = [
        what
        for what, bad in (
            ("OpenSees's stiffness matrix is not K", checks["frame_stiffness_max_rel_diff"] > 1e-12 or checks["braced_stiffness_max_rel_diff"] > 1e-12),
            ("OpenSees's eigen periods are not those of K", max(checks["bare_period_max_rel_diff"], checks["braced_period_max_rel_diff"]) > 1e-12),
            ("OpenSees's damping matrix is not alpha M + beta K_frame", checks["damping_matrix_max_rel_diff"] > 1e-9),
            ("slipload's bare T1 (4 digits) is not K's", checks["bare_T1_slipload_s"] is None or abs(checks["bare_T1_slipload_s"] - checks["bare_periods_s"][0]) > 5e-5 * 1.0001),
        )
        if bad
    ]
    if failed:
        raise SystemExit("model checks failed: " + "; ".join(failed))
    return checks


def load_record(binary: Path, tmp: Path, spec: str) -> dict:
    """A record of the comparison: SYNTHETIC (written into tmp by `slipload record synth`)
    or an AT2 file (in g). Returns its path, units (for the slipload scene), label, step,
    samples (m/s², as OpenSees gets them) and, for the synthetic one, how it was made."""
    if spec == SYNTHETIC:
        path = tmp / "synthetic-15s.csv"
        subprocess.run([str(binary), "record", "synth", "--duration", str(SYNTHETIC_DURATION), "--dt", str(SYNTHETIC_DT), "--out", str(path)], cwd=ROOT, check=True, capture_output=True)
        dt_rec, acc = read_csv_record(path)
        source = f"`slipload record synth --duration {SYNTHETIC_DURATION:g} --dt {SYNTHETIC_DT}` (seed 2007, PGA 0.4 g)"
        return {"path": path, "units": "m/s2", "label": f"synthetic {SYNTHETIC_DURATION:g} s", "dt": dt_rec, "acc": acc, "source": source}
    record = Path(spec).resolve()
    if not record.exists():
        raise SystemExit(f"{spec}: no such record file")
    dt_rec, acc = read_at2(record)
    return {"path": record, "units": "g", "label": record.stem, "dt": dt_rec, "acc": acc, "source": None}


def main() -> None:
    ensure_environment()
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--record", action="append", help=f"record file (.AT2, in g) or '{SYNTHETIC}' (a {SYNTHETIC_DURATION:g} s record from `slipload record synth`); repeatable [default: synthetic, SYL090.AT2, I-ELC180.AT2]")
    ap.add_argument("--dt", type=float, default=0.0025, help="time step of both programs, s [default: 0.0025, slipload's default T1/400 rounded to divide the records' dt]")
    ap.add_argument("--repeats", type=int, default=21, help="timed repeats per program and record (median) [default: 21]")
    ap.add_argument("--system", default="ProfileSPD", help="OpenSees linear system [default: ProfileSPD, the fastest direct solver measured here]")
    ap.add_argument("--out", type=Path, default=OUT_DIR, help="output folder [default: results/performance]")
    args = ap.parse_args()
    if args.repeats < 1:
        raise SystemExit("--repeats must be at least 1")
    ops = import_opensees()
    binary = slipload_bin()
    b = load_building(BUILDING)
    records = args.record or [SYNTHETIC, str(RECORDS / "SYL090.AT2"), str(RECORDS / "I-ELC180.AT2")]
    # Newton first (the reported figure), ModifiedNewton (tangent of the step start) as a variant.
    algorithms = ["Newton", "ModifiedNewton"]
    checks = checked_model(ops, binary, b, args.dt)
    cases = []
    with tempfile.TemporaryDirectory(prefix="slipload-opensees-") as td:
        tmp = Path(td)
        for spec in records:
            rec = load_record(binary, tmp, spec)
            ratio = rec["dt"] / args.dt
            if abs(ratio - round(ratio)) > 1e-9:
                raise SystemExit(f"{spec}: dt = {args.dt} s does not divide the record's dt = {rec['dt']} s")
            case = run_case(ops, binary, tmp, b, rec["label"], rec["path"], rec["units"], rec["dt"], rec["acc"], args.dt, args.repeats, algorithms, args.system)
            if rec["source"]:
                case["record"] = rec["source"]
            cases.append(case)
    report = {
        "machine": machine(ops),
        "settings": {
            "command": "scripts/compare-opensees.py" + "".join(f" {a}" for a in sys.argv[1:]),
            "building": str(BUILDING.relative_to(ROOT)),
            "dt_s": args.dt,
            "repeats": args.repeats,
            "integrator": f"Newmark gamma = {GAMMA}, beta = {BETA}",
            "opensees_model": "floors as nodes with their masses, the frame as zeroLength Elastic springs, a spring between every pair of floors (−K[i][j]) and one to the ground per floor (the row sum Σⱼ K[i][j]), assembling the condensed frame matrix exactly (negative springs where an off-diagonal term is positive or a row sums below zero), zeroLength ElasticPP (k', yield μN/k') for each brace + damper between floors i−1 and i, rayleigh α on the masses and β K_initial on the frame springs only (-doRayleigh 0 on the EPP elements), the record as a Path series in a UniformExcitation, initial accelerations -a_g(0)",
            "opensees_solution": f"Newton (current tangent: exact for the piecewise-linear EPP response, so it ends in a finite number of steps once the yielding pattern is right), test NormDispIncr {TEST_TOL:g} m, at most {TEST_MAX_ITER} iterations, system {args.system}; ModifiedNewton timed as a variant",
            "timing": f"wall-clock of the time-stepping only, median of the repeats after one warm-up run, the two programs interleaved in one run. OpenSees: analysis set-up + one analyze(steps, dt) call with an EnvelopeElement recorder of the storey drifts, the EPP elements' deformations (model build, including the record as a Path series, excluded and reported apart as model_build_median_s). slipload: cpu_seconds of `slipload simulate --format json --repeat {SLIPLOAD_REPEAT}` (the integrator run, median of that many runs in one process: plan compiled and record read beforehand), newmark, peaks only (no energies, no histories).",
        },
        "model_checks": checks,
        "cases": cases,
    }
    args.out.mkdir(parents=True, exist_ok=True)
    write_atomic(args.out / "opensees.json", json.dumps(report, indent=2) + "\n")
    write_atomic(args.out / "opensees.md", markdown(report))
    print(f"\nwrote {args.out / 'opensees.json'} and {args.out / 'opensees.md'}", file=sys.stderr)
    print(markdown(report))


if __name__ == "__main__":
    main()
