#!/usr/bin/env python3
"""slipload against OpenSees on the yielding, P-Delta ten-storey frame with massless dampers.

Builds configs/ten-story-yielding.json in OpenSees through openseespy and runs real
records at the design level (PGA 0.4 g) and at MCE (1.5 x, PGA 0.6 g) with Newmark average
acceleration (gamma = 1/2, beta = 1/4) at slipload's default time step in both programs,
beside slipload `exact` (event-driven: exact between stick / slip / yield events) as the
reference. It reports:

* model checks, before anything is compared (the script stops if one fails): the plan
  `slipload explain` prints (each storey's elastic alpha*k in K and its elastic-perfectly
  plastic (1 - alpha)k with bounds (1 - alpha)Fy, the P-Delta loads P over h, the braces'
  k' and slip loads, the bare T1) against the config read here; the stiffness matrix
  OpenSees assembles (read back from its system matrix) against the bare frame K, against
  K + the P-Delta geometric stiffness -P/h per storey (slipload's plan stiffness with every
  plastic element elastic) and against that + the braces; OpenSees's eigen periods against
  those matrices' and slipload's bare T1; the damping matrix OpenSees uses (read back from
  its system matrix) against slipload's modal C = M Phi diag(2 zeta omega) Phi^T M of the
  bare elastic frame; and the modal damping ratios of C;
* per storey, for each record and level: peak drift, residual drift, peak ductility (peak
  drift / yield drift), plastic (hysteretic) energy of the frame's storeys, friction energy
  of the dampers and whether a storey passes the collapse limit, for slipload `newmark`,
  OpenSees and slipload `exact`, with their relative differences;
* that both programs solve the same discrete equations: OpenSees and slipload `newmark`
  against a return-mapping Newmark written here in Python (the plastic slip advanced by
  backward Euler, as OpenSees's ElasticPP does and slipload's `newmark` does for massless
  elements), and OpenSees's storeys as Steel01 against Elastic + ElasticPP;
* convergence toward `exact` of both programs when the time step halves (the first record
  at MCE, `--halvings` times);
* beyond MCE (the last record at `--collapse-pga`), where a storey ratchets past the
  collapse limit: which storey, when and at what drift each program stops.

The OpenSees model: the floors as nodes with their masses over a fixed ground node; each
storey i, between floor i-1 and floor i, as zeroLength elements in parallel: an Elastic
spring alpha*k (the part of the storey that stays elastic: k - (1 - alpha)k_y), an
ElasticPP spring (1 - alpha)k_y with yield strain Fy/k_y (its yield force (1 - alpha)Fy),
an Elastic spring of negative stiffness -P_i/h_i (the linearised P-Delta geometric
stiffness), and the brace + damper as an ElasticPP spring of stiffness k' and yield strain
(slip load)/k'. slipload's damping matrix C is a full matrix that no Rayleigh combination
reproduces, and OpenSees's modal damping command builds its own from the current model;
so C is assembled explicitly, as the frame matrix is in compare-opensees.py: a zeroLength
linear dashpot (an Elastic material with E = 0 and damping tangent eta) between every pair
of floors, eta = -C[i][j], and one from each floor to the ground, eta = sum_j C[i][j]
(negative dashpots where a term asks for one: Elastic takes a negative eta). No element
takes Rayleigh damping.

Energies: a storey's plastic work and a damper's friction work are the sums over the steps
of the mean force times the slip increment, 1/2 (F_n + F_{n+1}) (s_{n+1} - s_n) with
s = deformation - F/k of the element (the trapezoidal rule on force x deformation, less the
elastic energy left at the end); that is slipload's own accounting of `newmark` (its
per-storey sums equal its energy.plastic and energy.friction, checked). `exact` slips only
at its bound, so its per-storey works are F_y |s_{n+1} - s_n| summed over the steps (the
slip between two steps is monotone), whose sums equal its continuous energy.plastic and
energy.friction (checked).

Writes results/opensees-yielding/README.md and comparison.json atomically; every figure in
them comes from this run.

Usage: [SLIPLOAD_BIN=path] scripts/compare-opensees-yielding.py [--record FILE ...] [--design-pga G] [--halvings N] [--collapse-pga G]
Creates scripts/.venv with openseespy, numpy and matplotlib on first use and re-runs itself inside it
(the environment of scripts/compare-opensees.py, whose helpers it imports).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def load_base():
    """scripts/compare-opensees.py as a module: its environment bootstrap, OpenSees import,
    record reader, record interpolation, chain matrix, spring assembly, analysis settings,
    slipload binary and machine description."""
    spec = importlib.util.spec_from_file_location("compare_opensees", ROOT / "scripts" / "compare-opensees.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


base = load_base()

BUILDING = ROOT / "configs" / "ten-story-yielding.json"
RECORDS = base.RECORDS
OUT_DIR = ROOT / "results" / "opensees-yielding"
# Near-fault and far-field records, two record steps (0.02 s and 0.005 / 0.01 s); the frame
# yields under each at MCE.
DEFAULT_RECORDS = ("SYL090.AT2", "RSN1158_KOCAELI_DZC180.AT2", "Rinaldi228.AT2")
DESIGN_PGA_G = 0.4
MCE_FACTOR = 1.5
G = base.G
GAMMA, BETA = base.GAMMA, base.BETA
TEST_TOL, TEST_MAX_ITER = base.TEST_TOL, base.TEST_MAX_ITER
SYSTEM = "ProfileSPD"
# Slip increments below this (m) are the 10 significant digits of slipload's history files,
# not slip: left out of exact's F_y |ds| sums.
SLIP_NOISE = 1e-10
# The Python references' Newton stops when the largest correction is below this (m).
REF_TOL = 1e-14

UNIT = base.UNIT

# OpenSees element (and material) tags: storey i (0-based) of each kind is TAG + i.
STOREY_ELASTIC_TAG = 100
STOREY_EPP_TAG = 200
STOREY_STEEL01_TAG = 300
PDELTA_TAG = 400
DAMPER_TAG = 500
DASHPOT_TAG = 1000


# ---------------------------------------------------------------------------------------
# The building
# ---------------------------------------------------------------------------------------


def quantity(value, what: str) -> float:
    """A quantity of this script's building (compare-opensees.py's reader)."""
    return base.quantity(value, what, BUILDING)


def load_building(path: Path) -> dict:
    """The config's masses, storeys (stiffness, yield law), P-Delta loads, modal damping,
    massless dampers and collapse limit, in SI units."""
    cfg = json.loads(path.read_text())
    m = [quantity(v, "floor_masses") for v in cfg["floor_masses"]]
    n = len(m)
    if "storey_stiffness" not in cfg or "stiffness_matrix" in cfg:
        raise SystemExit(f"{path}: this comparison builds shear buildings (storey_stiffness)")
    k = [quantity(v, "storey_stiffness") for v in cfg["storey_stiffness"]]
    h = [quantity(v, "storey_heights") for v in cfg.get("storey_heights", [])] or None
    if len(k) != n or (h is not None and len(h) != n):
        raise SystemExit(f"{path}: one storey stiffness and height per floor")
    yields = [None] * n
    for y in cfg.get("storey_yield", []):
        i = int(y["storey"]) - 1
        ky = quantity(y["stiffness"], "storey_yield.stiffness") if "stiffness" in y else k[i]
        if ("yield_shear" in y) == ("yield_drift" in y):
            raise SystemExit(f"{path}: storey {i + 1}: give one of yield_shear and yield_drift")
        fy = quantity(y["yield_shear"], "yield_shear") if "yield_shear" in y else quantity(y["yield_drift"], "yield_drift") * ky
        alpha = float(y.get("post_yield_ratio", 0.0))
        yields[i] = {"k": ky, "fy": fy, "alpha": alpha, "yield_drift": fy / ky}
    # Storey i's springs: what stays elastic, k - (1 - alpha)k_y, and the plastic (1 - alpha)k_y.
    k_elastic = [k[i] - ((1.0 - y["alpha"]) * y["k"] if y else 0.0) for i, y in enumerate(yields)]
    if "p_delta" in cfg:
        if h is None:
            raise SystemExit(f"{path}: P-Delta needs storey_heights")
        given = cfg["p_delta"].get("gravity_loads")
        if given is not None:
            p = [quantity(v, "p_delta.gravity_loads") for v in given]
        else:
            p = [G * math.fsum(m[i:]) for i in range(n)]  # g times the mass at and above storey i
    else:
        p = [0.0] * n
    damping = cfg.get("damping", {})
    if "modal" not in damping:
        raise SystemExit(f"{path}: this comparison builds slipload's modal damping (damping.modal)")
    md = damping["modal"]
    zeta = [float(md["ratio"])] * n if "ratio" in md else [float(md["ratios"][min(i, len(md["ratios"]) - 1)]) for i in range(n)]
    kp = [0.0] * n
    fs = [0.0] * n
    for d in cfg["dissipators"]:
        i = int(d["floor"]) - 1
        if quantity(d.get("mass", 0), "dissipators.mass") != 0.0 or quantity(d.get("brace_damping", 0), "dissipators.brace_damping") != 0.0:
            raise SystemExit(f"{path}: the dissipator of floor {i + 1} has mass or brace damping: the comparison needs m' = 0, c' = 0")
        kp[i] = quantity(d["brace_stiffness"], "dissipators.brace_stiffness")
        fs[i] = quantity(d["slip_load"], "dissipators.slip_load")
    if any(v == 0.0 for v in kp):
        raise SystemExit(f"{path}: every floor needs a dissipator for this comparison")
    if "collapse_drift" in cfg:
        limit = [quantity(cfg["collapse_drift"], "collapse_drift")] * n
    elif h is not None:
        limit = [float(cfg.get("collapse_drift_ratio", 0.10)) * x for x in h]
    else:
        limit = None
    return {"name": cfg["name"], "m": m, "k": k, "h": h, "yields": yields, "k_elastic": k_elastic, "p": p, "zeta": zeta, "kp": kp, "fs": fs, "collapse_limit": limit}


def matrices(b: dict) -> dict:
    """M; the bare frame's K (storey springs), its modes and slipload's modal damping
    C = M Phi diag(2 zeta omega) Phi^T M (Phi mass-normalised); the P-Delta geometric
    stiffness; the linear part of the plan (elastic springs + P-Delta) and the
    elastic-perfectly plastic elements (storey plastic parts, then dampers) as a deformation
    operator D (element e's deformation is (D u)_e) with stiffnesses and yield forces."""
    import numpy as np

    n = len(b["m"])
    M = np.diag(b["m"])
    K_frame = base.storey_matrix(b["k"])
    K_geo = -base.storey_matrix([p / hi for p, hi in zip(b["p"], b["h"])]) if b["h"] else np.zeros((n, n))
    sq = np.sqrt(b["m"])
    lam, psi = np.linalg.eigh(K_frame / np.outer(sq, sq))
    order = np.argsort(lam)
    omega = np.sqrt(lam[order])
    phi = psi[:, order] / sq[:, None]
    C = M @ phi @ np.diag(2.0 * np.array(b["zeta"]) * omega) @ phi.T @ M
    C = 0.5 * (C + C.T)
    storeys = [i for i, y in enumerate(b["yields"]) if y]
    kind = ["storey"] * len(storeys) + ["damper"] * n
    at = storeys + list(range(n))
    ke = [(1.0 - b["yields"][i]["alpha"]) * b["yields"][i]["k"] for i in storeys] + b["kp"]
    fe = [(1.0 - b["yields"][i]["alpha"]) * b["yields"][i]["fy"] for i in storeys] + b["fs"]
    D = np.zeros((len(at), n))
    for e, i in enumerate(at):
        D[e, i] = 1.0
        if i > 0:
            D[e, i - 1] = -1.0
    drift_op = np.eye(n) - np.eye(n, k=-1)
    return {
        "M": M,
        "K_frame": K_frame,
        "K_geo": K_geo,
        "K_lin": base.storey_matrix(b["k_elastic"]) + K_geo,
        "omega": omega,
        "phi": phi,
        "C": C,
        "D": D,
        "drift_op": drift_op,
        "kind": kind,
        "at": at,
        "ke": np.array(ke),
        "fe": np.array(fe),
        "storeys": storeys,
    }


def periods(M, K) -> list[float]:
    import numpy as np

    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    return (2.0 * math.pi / np.sqrt(w2)).tolist()


def building_summary(b: dict) -> str:
    """One sentence on what the config holds (the figures the tables depend on)."""

    def span(xs, unit: str, scale: float = 1.0, spec: str = "g") -> str:
        lo, hi = min(xs) * scale, max(xs) * scale
        return (f"{lo:{spec}} {unit}" if lo == hi else f"{lo:{spec}}–{hi:{spec}} {unit}").rstrip()

    y = [v for v in b["yields"] if v]
    text = f"{len(b['m'])} storeys, {len(y)} of them bilinear with kinematic hardening (yield drift {span([v['yield_drift'] for v in y], 'mm', 1e3)}, α = {span([v['alpha'] for v in y], '')})"
    if any(b["p"]):
        text += ", P-Δ (P = g × the mass above)"
    text += f", modal damping {span(b['zeta'], '%', 100)} of the bare frame, a massless friction damper per storey (brace + damper an elastic–perfectly plastic element)"
    if b["collapse_limit"]:
        text += f"; collapse limit: a storey drift of {span(b['collapse_limit'], 'm', 1.0, '.3g')}"
        if b["h"]:
            text += f" ({span([lim / h for lim, h in zip(b['collapse_limit'], b['h'])], '%', 100, '.3g')} of the storey height)"
    return text


def scaled_record(path: Path, pga_g: float) -> tuple[float, list[float]]:
    """The record in m/s², scaled as slipload's --scale-pga-g does: every sample times
    target / PGA, then the samples clamped to +-target (the peak lands on it exactly)."""
    dt_rec, acc = base.read_at2(path)
    pga = max(abs(a) for a in acc)
    x = pga_g * G
    return dt_rec, [min(max(a * (x / pga), -x), x) for a in acc]


# ---------------------------------------------------------------------------------------
# slipload
# ---------------------------------------------------------------------------------------


def slipload_run(binary: Path, record: Path, pga_g: float, method: str, dt: float | None, history: Path) -> tuple[dict, dict]:
    """One `slipload simulate` of the building (JSON response, with energies) and its
    history file (numpy columns by name)."""
    import numpy as np

    cmd = [str(binary), "simulate", str(BUILDING), "--record", str(record), "--scale-pga-g", repr(pga_g), "--method", method, "--format", "json", "--history", str(history)]
    if dt is not None:
        cmd += ["--dt", repr(dt)]
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    with history.open() as f:
        cols = f.readline().strip().split(",")
    data = np.loadtxt(history, delimiter=",", skiprows=1, ndmin=2)
    history.unlink()
    return json.loads(out.stdout), {c: data[:, j] for j, c in enumerate(cols)}


def slipload_histories(b: dict, mats: dict, h: dict) -> dict:
    """Drifts and element forces (storey plastic parts, dampers) of a slipload history, in
    the element order of `matrices`."""
    import numpy as np

    n = len(b["m"])
    drift = np.column_stack([h[f"drift{i + 1}_m"] for i in range(n)])
    forces = [h[f"Fp{i + 1}_N"] for i in mats["storeys"]] + [h[f"F{i + 1}_N"] for i in range(n)]
    return {"drift": drift, "force": np.column_stack(forces)}


# ---------------------------------------------------------------------------------------
# OpenSees
# ---------------------------------------------------------------------------------------


def build_model(ops, b: dict, mats: dict, dt_rec: float, acc: list[float], pdelta: bool = True, dampers: bool = True, storey: str = "parallel") -> None:
    """Floors as nodes with their masses on a fixed ground node 0; each storey as zeroLength
    elements between node i and node i + 1: Elastic alpha*k + ElasticPP (1 - alpha)k_y
    (`storey = "parallel"`) or Steel01 (Fy, k_y, alpha) + Elastic for any k - k_y
    (`storey = "steel01"`), an Elastic -P/h (P-Delta), an ElasticPP for the brace + damper;
    slipload's damping matrix C as zeroLength linear dashpots; the record as a uniform
    excitation. `pdelta`, `dampers` False leave those out (model checks only)."""
    n = len(b["m"])
    base.floor_nodes(ops, b["m"])

    def spring(tag: int, i: int, *material) -> None:
        ops.uniaxialMaterial(*material[:1], tag, *material[1:])
        ops.element("zeroLength", tag, i, i + 1, "-mat", tag, "-dir", 1, "-doRayleigh", 0)

    for i in range(n):
        y = b["yields"][i]
        if y is None:
            spring(STOREY_ELASTIC_TAG + i, i, "Elastic", b["k"][i])
        elif storey == "parallel":
            # Storey deformation = drift; ElasticPP's yield force is E * epsyP = (1 - alpha)Fy.
            spring(STOREY_ELASTIC_TAG + i, i, "Elastic", b["k_elastic"][i])
            spring(STOREY_EPP_TAG + i, i, "ElasticPP", (1.0 - y["alpha"]) * y["k"], y["fy"] / y["k"])
        else:
            spring(STOREY_STEEL01_TAG + i, i, "Steel01", y["fy"], y["k"], y["alpha"])
            if b["k"][i] != y["k"]:
                spring(STOREY_ELASTIC_TAG + i, i, "Elastic", b["k"][i] - y["k"])
        if pdelta and b["p"][i] != 0.0:
            spring(PDELTA_TAG + i, i, "Elastic", -b["p"][i] / b["h"][i])
        if dampers:
            spring(DAMPER_TAG + i, i, "ElasticPP", b["kp"][i], b["fs"][i] / b["kp"][i])
    # Dashpots that assemble C exactly (the assembly of compare-opensees.py's frame springs):
    # Elastic with E = 0 and damping tangent eta, -C[i][j] between floors i < j, the row sum
    # of C from each floor to the ground.
    for tag, (na, nb, c) in enumerate(base.frame_springs(mats["C"].tolist()), start=DASHPOT_TAG):
        ops.uniaxialMaterial("Elastic", tag, 0.0, c)
        ops.element("zeroLength", tag, na, nb, "-mat", tag, "-dir", 1, "-doRayleigh", 0)
    ops.timeSeries("Path", 1, "-dt", dt_rec, "-values", *acc, "-useLast")
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    # At rest in equilibrium with the first sample, as slipload starts: accelerations -a_g(0).
    for i in range(n):
        ops.setNodeAccel(i + 1, 1, -acc[0], "-commit")


def opensees_run(ops, b: dict, mats: dict, dt_rec: float, acc: list[float], dt: float, steps: int, storey: str = "parallel", stop_at_collapse: bool = False) -> dict:
    """The analysis one step at a time (Newton, NormDispIncr TEST_TOL), recording drifts and
    element forces; a step that does not converge is retried with line search, then with a
    modified Newton of many iterations, and counted. `stop_at_collapse`: the run ends at the
    first step a storey drifts past the collapse limit, as slipload's does."""
    import numpy as np

    build_model(ops, b, mats, dt_rec, acc, storey=storey)
    base.analysis(ops, "Newton", SYSTEM)
    n = len(b["m"])
    storeys = mats["storeys"]
    drift = np.zeros((steps + 1, n))
    force = np.zeros((steps + 1, len(mats["kind"])))
    iters = []
    failed = []
    t0 = time.perf_counter()
    for s in range(1, steps + 1):
        it = base.analyze_step(ops, s, dt, "Newton", failed)
        iters.append(it)
        u = [ops.nodeDisp(i + 1, 1) for i in range(n)]
        d = [u[i] - (u[i - 1] if i > 0 else 0.0) for i in range(n)]
        drift[s] = d
        for e, i in enumerate(storeys):
            if storey == "parallel":
                force[s, e] = ops.eleForce(STOREY_EPP_TAG + i)[1]
            else:
                # Steel01 carries the whole yielding spring k_y: its plastic part is its force
                # less the elastic alpha*k_y d.
                force[s, e] = ops.eleForce(STOREY_STEEL01_TAG + i)[1] - b["yields"][i]["alpha"] * b["yields"][i]["k"] * d[i]
        for i in range(n):
            force[s, len(storeys) + i] = ops.eleForce(DAMPER_TAG + i)[1]
        if stop_at_collapse and any(abs(x) > lim for x, lim in zip(d, b["collapse_limit"])):
            drift, force = drift[: s + 1], force[: s + 1]
            break
    run_s = time.perf_counter() - t0
    ops.wipe()
    return {
        "drift": drift,
        "force": force,
        "run_s": run_s,
        "newton_iterations": {"total": sum(iters), "mean": sum(iters) / len(iters), "max": max(iters)},
        "failed_steps": failed,
    }


def model_checks(ops, b: dict, mats: dict, explain: str, dt: float) -> dict:
    """The plan slipload prints against the config; OpenSees's assembled stiffness and
    damping matrices and its periods against the config's matrices; C's modal ratios."""
    import numpy as np

    n = len(b["m"])
    M, K_frame, K_geo, C = mats["M"], mats["K_frame"], mats["K_geo"], mats["C"]
    K_plan = K_frame + K_geo  # = K_lin + the plastic elements' (1 - alpha)k_y, all elastic
    K_braced = K_plan + base.storey_matrix(b["kp"])

    def rel_matrix(A, B) -> float:
        return float(np.max(np.abs(A - B)) / np.max(np.abs(B)))

    def rel_list(xs, ys) -> float:
        return max(abs(x - y) / abs(y) for x, y in zip(xs, ys))

    # The plan as `slipload explain` prints it (7 significant digits).
    num = r"([-+0-9.eE]+)"
    st = {int(mm.group(1)): mm for mm in re.finditer(rf"storey (\d+): yields \(k = {num} N/m, Fy = {num} N, yield drift {num} m, alpha = {num}\) -> elastic {num} N/m in K \+ elastic-perfectly plastic element between floors \d+ and \d+ \(k = {num} N/m, bounds \+-{num} N\)", explain)}
    fl = {int(mm.group(1)): mm for mm in re.finditer(rf"floor (\d+): m' = 0 -> elastic-perfectly plastic element between floors \d+ and \d+ \(k' = {num} N/m, c' = {num} N\*s/m, bounds \[{num}, {num}\] N\)", explain)}
    pd = re.search(r"P-Delta: geometric stiffness -P/h per storey, P = \[([^\]]*)\] N over h = \[([^\]]*)\] m", explain)
    t1 = re.search(r"bare T1 = ([0-9.]+) s", explain)
    storeys = mats["storeys"]
    if sorted(st) != [i + 1 for i in storeys] or sorted(fl) != list(range(1, n + 1)) or pd is None or t1 is None:
        raise SystemExit("model checks: `slipload explain` does not print the yielding storeys, dampers, P-Delta and bare T1 this script reads:\n" + explain)
    plan = {
        "storey_k": [float(st[i + 1].group(2)) for i in storeys],
        "storey_fy": [float(st[i + 1].group(3)) for i in storeys],
        "storey_alpha": [float(st[i + 1].group(5)) for i in storeys],
        "storey_elastic_in_K": [float(st[i + 1].group(6)) for i in storeys],
        "storey_plastic_k": [float(st[i + 1].group(7)) for i in storeys],
        "storey_plastic_bound": [float(st[i + 1].group(8)) for i in storeys],
        "brace_k": [float(fl[i + 1].group(2)) for i in range(n)],
        "damper_bound": [float(fl[i + 1].group(5)) for i in range(n)],
        "p_delta_P": [float(x) for x in pd.group(1).split(",")],
        "p_delta_h": [float(x) for x in pd.group(2).split(",")],
        "bare_T1": float(t1.group(1)),
    }
    mine = {
        "storey_k": [b["yields"][i]["k"] for i in storeys],
        "storey_fy": [b["yields"][i]["fy"] for i in storeys],
        "storey_alpha": [b["yields"][i]["alpha"] for i in storeys],
        "storey_elastic_in_K": [b["k_elastic"][i] for i in storeys],
        "storey_plastic_k": mats["ke"][: len(storeys)].tolist(),
        "storey_plastic_bound": mats["fe"][: len(storeys)].tolist(),
        "brace_k": b["kp"],
        "damper_bound": b["fs"],
        "p_delta_P": b["p"],
        "p_delta_h": b["h"],
    }
    plan_rel = {key: rel_list(plan[key], mine[key]) for key in mine}
    # slipload's plan stiffness from the printed plan: the elastic parts in K, the plastic
    # elements elastic, P-Delta (and the braces).
    K_plan_printed = base.storey_matrix([plan["storey_elastic_in_K"][storeys.index(i)] + plan["storey_plastic_k"][storeys.index(i)] if i in storeys else b["k"][i] for i in range(n)]) - base.storey_matrix([p / h for p, h in zip(plan["p_delta_P"], plan["p_delta_h"])])
    bare = periods(M, K_frame)
    zeta = (np.diag(mats["phi"].T @ C @ mats["phi"]) / (2.0 * mats["omega"])).tolist()

    def opensees_matrix(pdelta: bool, dampers: bool):
        """Eigen periods (initial tangent) and the stiffness matrix OpenSees assembles: the
        system matrix of one static step with no load (Newton: the tangent at rest)."""
        build_model(ops, b, mats, 1.0, [0.0, 0.0, 0.0], pdelta=pdelta, dampers=dampers)
        return base.periods_and_tangent(ops, n)

    T_bare_os, K_bare_os = opensees_matrix(False, False)
    T_plan_os, K_plan_os = opensees_matrix(True, False)
    T_braced_os, K_braced_os = opensees_matrix(True, True)
    # Damping read back from the Newmark system matrix A = K_t + gamma/(beta dt) C +
    # 1/(beta dt^2) M after a first step of a tiny pulse (every element elastic, K_t the
    # braced stiffness read back above).
    build_model(ops, b, mats, 1.0, [0.0, 1e-6, 0.0])
    base.analysis(ops, "Newton", "FullGeneral")
    if ops.analyze(1, dt) != 0:
        raise SystemExit("OpenSees: model check step failed")
    A = np.array(ops.printA("-ret")).reshape(n, n)
    ops.wipe()
    C_os = (A - K_braced_os - M / (BETA * dt * dt)) * (BETA * dt / GAMMA)
    return {
        "plan_printed_by_slipload": plan,
        "plan_vs_config_max_rel_diff": plan_rel,
        "plan_stiffness_printed_vs_opensees_max_rel_diff": rel_matrix(K_plan_os, K_plan_printed),
        "bare_periods_s": bare,
        "bare_T1_slipload_s": plan["bare_T1"],
        "p_delta_periods_s": periods(M, K_plan),
        "braced_periods_s": periods(M, K_braced),
        "bare_modal_damping_ratios": zeta,
        "bare_stiffness_max_rel_diff": rel_matrix(K_bare_os, K_frame),
        "p_delta_stiffness_max_rel_diff": rel_matrix(K_plan_os, K_plan),
        "braced_stiffness_max_rel_diff": rel_matrix(K_braced_os, K_braced),
        "bare_period_max_rel_diff": rel_list(T_bare_os, bare),
        "p_delta_period_max_rel_diff": rel_list(T_plan_os, periods(M, K_plan)),
        "braced_period_max_rel_diff": rel_list(T_braced_os, periods(M, K_braced)),
        "dashpots": len(base.frame_springs(C.tolist())),
        "damping_matrix_max_rel_diff": rel_matrix(C_os, C),
        "damping_matrix_N_s_m": C.tolist(),
        "p_delta_stiffness_N_m": K_plan.tolist(),
    }


# ---------------------------------------------------------------------------------------
# The Newmark references, written here independently of both programs
# ---------------------------------------------------------------------------------------


def newmark_reference(b: dict, mats: dict, dt_rec: float, acc: list[float], dt: float, steps: int) -> dict:
    """Newmark average acceleration on the floors, M a + C v + K_lin u + D^T f(u) = -M r a_g,
    with every elastic-perfectly plastic element (storey plastic parts, dampers) solved to
    round-off by Newton with the return mapping: the slip advanced by backward Euler (the slip
    increment decides the yield direction), what OpenSees's ElasticPP does and slipload's
    `newmark` solves exactly for massless elements.
    """
    import numpy as np

    n = len(b["m"])
    M, C, K, D = mats["M"], mats["C"], mats["K_lin"], mats["D"]
    ke, fe = mats["ke"], mats["fe"]
    c_a = 1.0 / (BETA * dt * dt)
    c_v = GAMMA / (BETA * dt)
    A0 = K + c_v * C + c_a * M
    mr = M @ np.ones(n)
    u = np.zeros(n)
    v = np.zeros(n)
    a = -acc[0] * np.ones(n)
    s = np.zeros(len(ke))
    drift = np.zeros((steps + 1, n))
    force = np.zeros((steps + 1, len(ke)))
    for step in range(1, steps + 1):
        ag = base.ground_accel(dt_rec, acc, step * dt)
        start = s
        ua = u + dt * v + (0.5 - BETA) * dt * dt * a
        va = v + (1.0 - GAMMA) * dt * a
        u1 = u.copy()
        for _ in range(100):
            trial = ke * (D @ u1 - start)
            f = np.clip(trial, -fe, fe)
            kt = np.where(np.abs(trial) <= fe, ke, 0.0)
            a1 = c_a * (u1 - ua)
            R = M @ a1 + C @ (va + GAMMA * dt * a1) + K @ u1 + D.T @ f + mr * ag
            du = np.linalg.solve(A0 + D.T @ (kt[:, None] * D), -R)
            u1 = u1 + du
            if np.max(np.abs(du)) < REF_TOL:
                break
        else:
            raise SystemExit(f"Newmark reference: step {step} did not converge")
        f = np.clip(ke * (D @ u1 - start), -fe, fe)
        s = D @ u1 - f / ke
        a1 = c_a * (u1 - ua)
        v = va + GAMMA * dt * a1
        u, a = u1, a1
        drift[step] = mats["drift_op"] @ u
        force[step] = f
    return {"drift": drift, "force": force}


# ---------------------------------------------------------------------------------------
# Figures of a run
# ---------------------------------------------------------------------------------------


def figures(b: dict, mats: dict, drift, force, exact: bool = False) -> dict:
    """Per storey: peak and residual drift, peak ductility, peak plastic drift, plastic and
    friction energy; collapse (the first step past the limit)."""
    import numpy as np

    n = len(b["m"])
    ke, fe = mats["ke"], mats["fe"]
    slip = np.column_stack([drift[:, i] for i in mats["at"]]) - force / ke
    ds = np.diff(slip, axis=0)
    if exact:
        work = (fe * np.where(np.abs(ds) > SLIP_NOISE, np.abs(ds), 0.0)).sum(axis=0)
    else:
        work = (0.5 * (force[1:] + force[:-1]) * ds).sum(axis=0)
    plastic = [0.0] * n
    plastic_drift = [0.0] * n
    friction = [0.0] * n
    for e, i in enumerate(mats["at"]):
        if mats["kind"][e] == "storey":
            plastic[i] = float(work[e])
            plastic_drift[i] = float(np.max(np.abs(slip[:, e])))
        else:
            friction[i] = float(work[e])
    peak = np.max(np.abs(drift), axis=0)
    collapse = None
    if b["collapse_limit"] is not None:
        past = np.nonzero(np.any(np.abs(drift) > np.array(b["collapse_limit"]), axis=1))[0]
        if len(past):
            step = int(past[0])
            storey = int(np.argmax(np.abs(drift[step]) > np.array(b["collapse_limit"])))
            collapse = {"step": step, "storey": storey + 1, "drift_m": float(drift[step, storey])}
    return {
        "peak_drift_m": peak.tolist(),
        "residual_drift_m": np.abs(drift[-1]).tolist(),
        "peak_ductility": [float(peak[i]) / y["yield_drift"] if y else None for i, y in enumerate(b["yields"])],
        "peak_plastic_drift_m": plastic_drift,
        "plastic_energy_J": plastic,
        "friction_energy_J": friction,
        "plastic_energy_total_J": math.fsum(plastic),
        "friction_energy_total_J": math.fsum(friction),
        "collapse": collapse,
    }


def max_rel(xs, ys) -> float:
    return max(abs(x - y) / abs(y) for x, y in zip(xs, ys))


def signed_rel(x: float, y: float) -> float:
    return (x - y) / abs(y)


def history_gap(rows, ref_rows) -> float:
    """max over steps and storeys of |rows - ref_rows| over the storey's peak |ref_rows|."""
    import numpy as np

    return float(np.max(np.max(np.abs(rows - ref_rows), axis=0) / np.max(np.abs(ref_rows), axis=0)))


def differences(b: dict, x: dict, ref: dict) -> dict:
    """x against ref: peak drift (and ductility: the same ratio), max over storeys of the
    relative difference; residual drift, max over storeys of the difference over the yield
    drift; plastic and friction energy, the frame totals (signed, relative) and the storeys'
    (max over storeys: plastic over the frame total, friction relative per storey)."""
    # The yield drift of each storey (an elastic storey: the reference's peak drift).
    yd = [y["yield_drift"] if y else p for y, p in zip(b["yields"], ref["peak_drift_m"])]
    yielding = ref["plastic_energy_total_J"] > 0.0 and max(d for d in ref["peak_ductility"] if d is not None) > 1.0
    tot = ref["plastic_energy_total_J"]
    return {
        "peak_drift_max_rel": max_rel(x["peak_drift_m"], ref["peak_drift_m"]),
        "peak_drift_rel_by_storey": [signed_rel(p, q) for p, q in zip(x["peak_drift_m"], ref["peak_drift_m"])],
        "residual_drift_max_over_yield_drift": max(abs(p - q) / d for p, q, d in zip(x["residual_drift_m"], ref["residual_drift_m"], yd)),
        "plastic_energy_total_rel": signed_rel(x["plastic_energy_total_J"], tot) if yielding else None,
        "plastic_energy_storey_max_over_total": max(abs(p - q) for p, q in zip(x["plastic_energy_J"], ref["plastic_energy_J"])) / tot if yielding else None,
        "friction_energy_total_rel": signed_rel(x["friction_energy_total_J"], ref["friction_energy_total_J"]),
        "friction_energy_storey_max_rel": max_rel(x["friction_energy_J"], ref["friction_energy_J"]),
        "collapse": x["collapse"] is not None,
    }


# ---------------------------------------------------------------------------------------
# The comparison
# ---------------------------------------------------------------------------------------


def run_case(ops, binary: Path, tmp: Path, b: dict, mats: dict, record: Path, level: str, pga_g: float, dt: float | None, references: bool, steel01: bool) -> dict:
    dt_rec, acc = scaled_record(record, pga_g)
    label = f"{record.stem} {level}"
    t0 = time.perf_counter()
    sl, sl_h = slipload_run(binary, record, pga_g, "newmark", dt, tmp / "newmark.csv")
    dt = sl["dt"]
    steps = int(sl["steps"])
    ratio = dt_rec / dt
    if abs(ratio - round(ratio)) > 1e-9:
        raise SystemExit(f"{record.name}: dt = {dt} s does not divide the record's dt = {dt_rec} s")
    print(f"\n== {label}: PGA {pga_g:g} g, {len(acc)} samples at {dt_rec} s, dt = {dt:.6g} s, {steps} steps", file=sys.stderr)
    ex, ex_h = slipload_run(binary, record, pga_g, "exact", dt, tmp / "exact.csv")
    if ex["steps"] != steps:
        raise SystemExit(f"{label}: exact ran {ex['steps']} steps, newmark {steps}")
    sl_hist = slipload_histories(b, mats, sl_h)
    ex_hist = slipload_histories(b, mats, ex_h)
    sl_fig = figures(b, mats, sl_hist["drift"], sl_hist["force"])
    ex_fig = figures(b, mats, ex_hist["drift"], ex_hist["force"], exact=True)
    os_run = opensees_run(ops, b, mats, dt_rec, acc, dt, steps)
    os_fig = figures(b, mats, os_run["drift"], os_run["force"])
    case = {
        "label": label,
        "record": str(record.relative_to(ROOT)) if record.is_relative_to(ROOT) else str(record),
        "level": level,
        "pga_g": pga_g,
        "record_dt_s": dt_rec,
        "dt_s": dt,
        "steps": steps,
        "slipload_newmark": {"figures": sl_fig, "energy": sl["energy"], "collapse": sl.get("collapse"), "peak_drift_m": sl["peak_drift"], "peak_ductility": sl.get("peak_ductility")},
        "slipload_exact": {"figures": ex_fig, "energy": ex["energy"], "collapse": ex.get("collapse"), "peak_drift_continuous_m": ex["peak_drift"]},
        "opensees": {"figures": os_fig, "newton_iterations": os_run["newton_iterations"], "failed_steps": os_run["failed_steps"], "run_s": os_run["run_s"]},
        # How the per-storey sums read from the histories close on the programs' own totals.
        "energy_accounting": {
            "newmark_plastic_sum_vs_response": signed_rel(sl_fig["plastic_energy_total_J"], sl["energy"]["plastic"]) if sl["energy"]["plastic"] > 1.0 else None,
            "newmark_friction_sum_vs_response": signed_rel(sl_fig["friction_energy_total_J"], sl["energy"]["friction"]),
            "exact_plastic_sum_vs_response": signed_rel(ex_fig["plastic_energy_total_J"], ex["energy"]["plastic"]) if ex["energy"]["plastic"] > 1.0 else None,
            "exact_friction_sum_vs_response": signed_rel(ex_fig["friction_energy_total_J"], ex["energy"]["friction"]),
            "newmark_plastic_response_J": sl["energy"]["plastic"],
            "exact_plastic_response_J": ex["energy"]["plastic"],
        },
        "newmark_vs_exact": differences(b, sl_fig, ex_fig),
        "opensees_vs_exact": differences(b, os_fig, ex_fig),
        "opensees_vs_newmark": differences(b, os_fig, sl_fig),
        "history_peaks_vs_response_max_rel": max_rel(sl_fig["peak_drift_m"], sl["peak_drift"]),
        "collapse": {"newmark": sl.get("collapse"), "exact": ex.get("collapse"), "opensees": os_fig["collapse"]},
    }
    if references:
        rm = newmark_reference(b, mats, dt_rec, acc, dt, steps)
        rm_fig = figures(b, mats, rm["drift"], rm["force"])
        case["references"] = {
            "opensees_vs_return_mapping_peak_drift_max_rel": max_rel(os_fig["peak_drift_m"], rm_fig["peak_drift_m"]),
            "opensees_vs_return_mapping_drift_history": history_gap(os_run["drift"], rm["drift"]),
            "opensees_vs_return_mapping_plastic_energy_rel": signed_rel(os_fig["plastic_energy_total_J"], rm_fig["plastic_energy_total_J"]) if rm_fig["plastic_energy_total_J"] > 1.0 else None,
            "slipload_vs_return_mapping_peak_drift_max_rel": max_rel(sl_fig["peak_drift_m"], rm_fig["peak_drift_m"]),
            "slipload_vs_return_mapping_drift_history": history_gap(sl_hist["drift"], rm["drift"]),
            "slipload_vs_return_mapping_plastic_energy_rel": signed_rel(sl_fig["plastic_energy_total_J"], rm_fig["plastic_energy_total_J"]) if rm_fig["plastic_energy_total_J"] > 1.0 else None,
        }
    if steel01:
        st = opensees_run(ops, b, mats, dt_rec, acc, dt, steps, storey="steel01")
        st_fig = figures(b, mats, st["drift"], st["force"])
        case["steel01_vs_parallel"] = {
            "drift_history": history_gap(st["drift"], os_run["drift"]),
            "plastic_force_history_max_over_bound": float((abs(st["force"] - os_run["force"]) / mats["fe"]).max()),
            "plastic_energy_rel": signed_rel(st_fig["plastic_energy_total_J"], os_fig["plastic_energy_total_J"]),
        }
    case["wall_s"] = time.perf_counter() - t0
    nve, ove, ovn = case["newmark_vs_exact"], case["opensees_vs_exact"], case["opensees_vs_newmark"]
    print(
        f"  max peak ductility (exact) {max(d for d in ex_fig['peak_ductility'] if d):.3f}, plastic energy {ex['energy']['plastic'] / 1e3:.2f} kJ, friction {ex['energy']['friction'] / 1e3:.1f} kJ\n"
        f"  peak drift max rel. diff: newmark vs exact {nve['peak_drift_max_rel']:.2e}, OpenSees vs exact {ove['peak_drift_max_rel']:.2e}, OpenSees vs newmark {ovn['peak_drift_max_rel']:.2e}\n"
        f"  plastic energy rel. diff: newmark vs exact {fmt(nve['plastic_energy_total_rel'], '+.2e')}, OpenSees vs exact {fmt(ove['plastic_energy_total_rel'], '+.2e')}; "
        f"friction energy: newmark {nve['friction_energy_total_rel']:+.2e}, OpenSees {ove['friction_energy_total_rel']:+.2e}\n"
        f"  Newton iterations per step: mean {os_run['newton_iterations']['mean']:.2f}, max {os_run['newton_iterations']['max']}; unconverged steps {len(os_run['failed_steps'])}",
        file=sys.stderr,
    )
    if references:
        r = case["references"]
        print(f"  OpenSees vs return mapping: peaks {r['opensees_vs_return_mapping_peak_drift_max_rel']:.1e}, history {r['opensees_vs_return_mapping_drift_history']:.1e}; slipload vs return mapping: peaks {r['slipload_vs_return_mapping_peak_drift_max_rel']:.1e}, history {r['slipload_vs_return_mapping_drift_history']:.1e}", file=sys.stderr)
    if steel01:
        s = case["steel01_vs_parallel"]
        print(f"  Steel01 vs Elastic + ElasticPP: drift history {s['drift_history']:.1e}, plastic force {s['plastic_force_history_max_over_bound']:.1e} of the bound, plastic energy {s['plastic_energy_rel']:+.1e}", file=sys.stderr)
    return case


def run_collapse(ops, binary: Path, tmp: Path, b: dict, mats: dict, record: Path, pga_g: float) -> dict:
    """A record scaled beyond MCE, where a storey ratchets past the collapse limit: when and
    where each program stops (slipload's `collapse`; OpenSees: the first step past the limit)."""
    dt_rec, acc = scaled_record(record, pga_g)
    sl, _ = slipload_run(binary, record, pga_g, "newmark", None, tmp / "newmark.csv")
    ex, _ = slipload_run(binary, record, pga_g, "exact", sl["dt"], tmp / "exact.csv")
    print(f"\n== {record.stem} at {pga_g:g} g (collapse check), dt = {sl['dt']:.6g} s", file=sys.stderr)
    os_run = opensees_run(ops, b, mats, dt_rec, acc, sl["dt"], int(sl["steps"]), stop_at_collapse=True)
    os_fig = figures(b, mats, os_run["drift"], os_run["force"])
    c = os_fig["collapse"]
    out = {
        "record": str(record.relative_to(ROOT)) if record.is_relative_to(ROOT) else str(record),
        "label": record.stem,
        "pga_g": pga_g,
        "dt_s": sl["dt"],
        "newmark": sl.get("collapse"),
        "exact": ex.get("collapse"),
        "opensees": None if c is None else {"storey": c["storey"], "time": c["step"] * sl["dt"], "drift": c["drift_m"], "limit": b["collapse_limit"][c["storey"] - 1]},
        "opensees_newton_iterations": os_run["newton_iterations"],
        "opensees_failed_steps": os_run["failed_steps"],
    }
    for who in ("newmark", "exact", "opensees"):
        x = out[who]
        print(f"  {who}: " + ("no collapse" if x is None else f"storey {x['storey']} at t = {x['time']:.4f} s, drift {x['drift']:.5f} m (limit {x['limit']:.3f} m)"), file=sys.stderr)
    return out


def fmt(x, spec: str, none: str = "—") -> str:
    return none if x is None else format(x, spec)


def kj(x: float, digits: int) -> str:
    """Joules as kJ to `digits` decimals; a round-off -0.00 (the plastic work of a storey
    that stays elastic, ~1e-7 J either sign) prints as 0.00."""
    return f"{round(x / 1e3, digits) + 0.0:.{digits}f}"


def convergence(cases: list[dict]) -> dict:
    """Errors against exact at each dt and their ratios from one dt to the next (half)."""
    rows = []
    for c in cases:
        rows.append(
            {
                "dt_s": c["dt_s"],
                "steps": c["steps"],
                **{f"{who}_{what}": c[f"{who}_vs_exact"][key] for who in ("newmark", "opensees") for what, key in (("peak_drift", "peak_drift_max_rel"), ("plastic_energy", "plastic_energy_total_rel"), ("friction_energy", "friction_energy_total_rel"), ("residual_drift", "residual_drift_max_over_yield_drift"))},
            }
        )
    ratios = []
    for p, q in zip(rows, rows[1:]):
        ratios.append({key: abs(p[key]) / abs(q[key]) if q[key] else None for key in p if key.startswith(("newmark_", "opensees_"))})
    return {"label": cases[0]["label"], "rows": rows, "ratios": ratios}


# ---------------------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------------------


def markdown(report: dict) -> str:
    m = report["machine"]
    s = report["settings"]
    chk = report["model_checks"]
    e = lambda x, spec=".1e": fmt(x, spec)  # noqa: E731

    def pair(d: dict, what: str) -> str:
        if what == "plastic":
            total, storey = d["plastic_energy_total_rel"], d["plastic_energy_storey_max_over_total"]
        else:
            total, storey = d["friction_energy_total_rel"], d["friction_energy_storey_max_rel"]
        return "—" if total is None else f"{total:+.1e} / {storey:.1e}"
    lines = [
        "# slipload against OpenSees: yielding storeys and P-Δ",
        "",
        f"Regenerate with `{s['command']}` (this run: {report['run_s']:.0f} s).",
        "",
        f"Building: `{s['building']}`: {s['building_summary']}. Records scaled to the design level and to MCE (×{MCE_FACTOR:g}). Both programs: Newmark average",
        "acceleration (γ = ½, β = ¼), the same scaled record, slipload's default Δt (T1/400 rounded to divide the record's step).",
        f"OpenSees: {s['opensees_model']}; {s['opensees_solution']}. Reference: slipload `exact` (event-driven, exact between",
        "stick / slip / yield events) on the same step grid.",
        "",
        "What the figures are: *peak drift*, the largest over storeys of the relative difference of the storeys' peak drifts",
        "(peaks at the steps; peak ductility is peak drift over the yield drift, so its differences are the same); *plastic",
        "energy*, the signed relative difference of the frame's hysteretic energy (all storeys), then the largest difference",
        "of a storey's over the frame's; *friction energy*, the signed relative difference of the dampers' total, then the",
        "largest relative difference of a storey's; *residual drift*, the largest over storeys of the difference of the final drifts over the storey's",
        "yield drift δy; *collapse*, whether any storey drifted past the collapse limit in newmark / OpenSees / exact. “—”: the",
        "frame stays elastic (exact's peak ductility below 1), no plastic energy to compare.",
        "",
        "| record | level (PGA) | steps × Δt | max peak ductility (exact) | plastic energy (exact, kJ) | friction energy (exact, kJ) | peak drift: newmark vs exact | OpenSees vs exact | OpenSees vs newmark | plastic energy (frame / storey): newmark vs exact | OpenSees vs exact | friction energy (total / storey): newmark vs exact | OpenSees vs exact | residual drift / δy: newmark, OpenSees vs exact | collapse |",
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for c in report["cases"]:
        ex = c["slipload_exact"]
        nve, ove, ovn = c["newmark_vs_exact"], c["opensees_vs_exact"], c["opensees_vs_newmark"]
        mu = max(d for d in ex["figures"]["peak_ductility"] if d is not None)
        col = c["collapse"]
        lines.append(
            f"| {Path(c['record']).stem} | {c['level']} ({c['pga_g']:g} g) | {c['steps']} × {c['dt_s']:.6g} s | {mu:.2f} | {kj(ex['energy']['plastic'], 1)} | {kj(ex['energy']['friction'], 0)} | "
            f"{nve['peak_drift_max_rel']:.1e} | {ove['peak_drift_max_rel']:.1e} | {ovn['peak_drift_max_rel']:.1e} | "
            f"{pair(nve, 'plastic')} | {pair(ove, 'plastic')} | {pair(nve, 'friction')} | {pair(ove, 'friction')} | "
            f"{nve['residual_drift_max_over_yield_drift']:.1e}, {ove['residual_drift_max_over_yield_drift']:.1e} | "
            + " / ".join("yes" if col[k] else "no" for k in ("newmark", "opensees", "exact"))
            + " |"
        )
    conv = report["convergence"]
    lines += [
        "",
        f"Convergence toward `exact` when Δt halves ({conv['label']}): the same figures against exact at each Δt, then the ratio",
        "of each error to the next (second order: 4).",
        "",
        "| Δt (s) | steps | peak drift: newmark | OpenSees | plastic energy: newmark | OpenSees | friction energy: newmark | OpenSees | residual drift / δy: newmark | OpenSees |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in conv["rows"]:
        lines.append(
            f"| {r['dt_s']:.6g} | {r['steps']} | {r['newmark_peak_drift']:.2e} | {r['opensees_peak_drift']:.2e} | {e(r['newmark_plastic_energy'], '+.2e')} | {e(r['opensees_plastic_energy'], '+.2e')} | "
            f"{r['newmark_friction_energy']:+.2e} | {r['opensees_friction_energy']:+.2e} | {r['newmark_residual_drift']:.2e} | {r['opensees_residual_drift']:.2e} |"
        )
    for r, (p, q) in zip(conv["ratios"], zip(conv["rows"], conv["rows"][1:])):
        lines.append(
            f"| ratio {p['dt_s']:.4g} → {q['dt_s']:.4g} | | {e(r['newmark_peak_drift'], '.1f')} | {e(r['opensees_peak_drift'], '.1f')} | {e(r['newmark_plastic_energy'], '.1f')} | {e(r['opensees_plastic_energy'], '.1f')} | "
            f"{e(r['newmark_friction_energy'], '.1f')} | {e(r['opensees_friction_energy'], '.1f')} | {e(r['newmark_residual_drift'], '.1f')} | {e(r['opensees_residual_drift'], '.1f')} |"
        )
    col = report["collapse_check"]
    if col:
        lines += [
            "",
            f"Beyond MCE, {col['label']} scaled to {col['pga_g']:g} g (Δt = {col['dt_s']:.6g} s): a storey ratchets past the collapse limit; where and when each",
            "program stops (slipload: its `collapse` outcome; OpenSees: the first step past the limit).",
            "",
            "| program | storey | time (s) | drift (m) | limit (m) |",
            "|---|---:|---:|---:|---:|",
        ]
        for who, name in (("newmark", "slipload newmark"), ("opensees", "OpenSees"), ("exact", "slipload exact")):
            x = col[who]
            lines.append(f"| {name} | none | | | |" if x is None else f"| {name} | {x['storey']} | {x['time']:.4f} | {x['drift']:.5f} | {x['limit']:.3f} |")
    lines += [
        "",
        "Both programs solve the same discrete equations: each against a return-mapping Newmark written in the script (slip by",
        "backward Euler, as ElasticPP and slipload's `newmark` for massless elements), solved by Newton to round-off on the",
        "config's matrices (peaks: max relative",
        "difference over storeys; histories: max over steps and storeys of the difference over the storey's peak drift). The",
        "per-storey energies read from slipload's histories sum to its own energy.plastic and energy.friction (newmark: the same",
        "trapezoidal sums; exact: F_y |Δs|, against its continuous integrals).",
        "",
        "| record | level | OpenSees vs return mapping (peaks / drift history) | slipload vs return mapping (peaks / drift history) | per-storey sums vs totals: newmark plastic, friction | exact plastic, friction | Newton it./step (max) | unconverged steps |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for c in report["cases"]:
        r = c.get("references")
        acc = c["energy_accounting"]
        o = c["opensees"]
        refs = (
            f"{r['opensees_vs_return_mapping_peak_drift_max_rel']:.0e} / {r['opensees_vs_return_mapping_drift_history']:.0e} | {r['slipload_vs_return_mapping_peak_drift_max_rel']:.0e} / {r['slipload_vs_return_mapping_drift_history']:.0e}"
            if r
            else "— | —"
        )
        lines.append(
            f"| {Path(c['record']).stem} | {c['level']} | {refs} | {e(acc['newmark_plastic_sum_vs_response'], '.0e')}, {acc['newmark_friction_sum_vs_response']:.0e} | "
            f"{e(acc['exact_plastic_sum_vs_response'], '.0e')}, {acc['exact_friction_sum_vs_response']:.0e} | {o['newton_iterations']['mean']:.2f} ({o['newton_iterations']['max']}) | {len(o['failed_steps'])} |"
        )
    st = next((c for c in report["cases"] if "steel01_vs_parallel" in c), None)
    if st:
        x = st["steel01_vs_parallel"]
        lines += [
            "",
            f"Steel01 (Fy, k, b = α) for each storey instead of Elastic αk + ElasticPP (1−α)k, {st['label']}: drift histories agree within"
            f" {x['drift_history']:.0e} of the peaks, the storeys' plastic forces within {x['plastic_force_history_max_over_bound']:.0e} of their bounds, the plastic"
            f" energy within {abs(x['plastic_energy_rel']):.0e}: the two OpenSees models of the bilinear storey are the same.",
        ]
    plan = chk["plan_vs_config_max_rel_diff"]
    lines += [
        "",
        "Model checks (the script stops if one fails): the plan `slipload explain` prints equals the config read by the script"
        f" (storey k, Fy, α, elastic αk in K, plastic (1−α)k and bounds, brace k′ and slip loads, P-Δ loads and heights: within"
        f" {max(plan.values()):.0e}, the 7 digits it prints); the stiffness OpenSees assembles (read back from its system matrix) equals"
        f" the bare frame K within {chk['bare_stiffness_max_rel_diff']:.0e}, K − P/h (slipload's plan stiffness, every plastic element elastic)"
        f" within {chk['p_delta_stiffness_max_rel_diff']:.0e} (the plan as printed: {chk['plan_stiffness_printed_vs_opensees_max_rel_diff']:.0e}), and with the braces"
        f" within {chk['braced_stiffness_max_rel_diff']:.0e}; periods: bare " + ", ".join(f"{t:.4f}" for t in chk["bare_periods_s"][:3])
        + f" … s (slipload's bare T1 {chk['bare_T1_slipload_s']} s), with P-Δ " + ", ".join(f"{t:.4f}" for t in chk["p_delta_periods_s"][:3])
        + " … s, braced " + ", ".join(f"{t:.4f}" for t in chk["braced_periods_s"][:3])
        + f" … s, OpenSees's eigen periods within {max(chk['bare_period_max_rel_diff'], chk['p_delta_period_max_rel_diff'], chk['braced_period_max_rel_diff']):.0e};"
        f" the damping matrix OpenSees uses ({chk['dashpots']} dashpots; read back from its system matrix) equals slipload's modal C within"
        f" {chk['damping_matrix_max_rel_diff']:.0e}, whose ratios in the bare modes are " + f"{100 * min(chk['bare_modal_damping_ratios']):.4f}–{100 * max(chk['bare_modal_damping_ratios']):.4f} %.",
        "",
    ]
    for c in report["cases"]:
        ex, sl, os_ = c["slipload_exact"]["figures"], c["slipload_newmark"]["figures"], c["opensees"]["figures"]
        lines += [
            f"Per storey, {c['label']} ({c['pga_g']:g} g): exact's values; newmark's and OpenSees's relative differences (energies: kJ).",
            "",
            "| storey | peak drift (mm) | newmark | OpenSees | peak ductility | residual drift (mm): exact, newmark, OpenSees | plastic energy (kJ): exact, newmark, OpenSees | friction energy (kJ): exact, newmark, OpenSees |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for i in range(len(ex["peak_drift_m"])):
            lines.append(
                f"| {i + 1} | {ex['peak_drift_m'][i] * 1e3:.2f} | {signed_rel(sl['peak_drift_m'][i], ex['peak_drift_m'][i]):+.1e} | {signed_rel(os_['peak_drift_m'][i], ex['peak_drift_m'][i]):+.1e} | "
                f"{e(ex['peak_ductility'][i], '.3f')} | {ex['residual_drift_m'][i] * 1e3:.2f}, {sl['residual_drift_m'][i] * 1e3:.2f}, {os_['residual_drift_m'][i] * 1e3:.2f} | "
                f"{kj(ex['plastic_energy_J'][i], 2)}, {kj(sl['plastic_energy_J'][i], 2)}, {kj(os_['plastic_energy_J'][i], 2)} | "
                f"{kj(ex['friction_energy_J'][i], 1)}, {kj(sl['friction_energy_J'][i], 1)}, {kj(os_['friction_energy_J'][i], 1)} |"
            )
        lines.append("")
    lines += [
        f"Machine: {m['cpu_model']}, {m['cpus']} CPUs ({m['threads_per_core']} thread per core), shared with other jobs; {m['os']};",
        f"OpenSees {m['opensees']} through openseespy {m['openseespy']} (Python {m['python']}); slipload {m['slipload_commit']} built by {m['rustc']}.",
        "",
    ]
    return "\n".join(lines)


def main() -> None:
    base.ensure_environment(Path(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--record", action="append", help=f"record file (.AT2, in g); repeatable [default: {', '.join(DEFAULT_RECORDS)} from {RECORDS}]")
    ap.add_argument("--design-pga", type=float, default=DESIGN_PGA_G, help=f"design-level PGA, g; MCE is {MCE_FACTOR} times it [default: {DESIGN_PGA_G}]")
    ap.add_argument("--halvings", type=int, default=2, help="time-step halvings of the convergence study (first record, MCE) [default: 2]")
    ap.add_argument("--collapse-pga", type=float, default=2.0, help="PGA, g, of a run beyond MCE of the last record, where the frame collapses: when and where each program stops; 0: none [default: 2.0]")
    ap.add_argument("--out", type=Path, default=OUT_DIR, help="output folder [default: results/opensees-yielding]")
    args = ap.parse_args()
    t_start = time.perf_counter()
    ops = base.import_opensees()
    binary = base.slipload_bin()
    b = load_building(BUILDING)
    mats = matrices(b)
    explain = subprocess.run([str(binary), "explain", str(BUILDING), "--duration", "1"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    dt_check = float(re.search(r"dt = ([0-9.eE+-]+) s", explain).group(1))
    checks = model_checks(ops, b, mats, explain, dt_check)
    print(
        f"model checks: plan vs config {max(checks['plan_vs_config_max_rel_diff'].values()):.1e}; OpenSees stiffness: bare {checks['bare_stiffness_max_rel_diff']:.1e}, "
        f"with P-Delta {checks['p_delta_stiffness_max_rel_diff']:.1e} (printed plan {checks['plan_stiffness_printed_vs_opensees_max_rel_diff']:.1e}), braced {checks['braced_stiffness_max_rel_diff']:.1e}; "
        f"periods {max(checks['bare_period_max_rel_diff'], checks['p_delta_period_max_rel_diff'], checks['braced_period_max_rel_diff']):.1e}; bare T1 {checks['bare_periods_s'][0]:.5f} s "
        f"(slipload {checks['bare_T1_slipload_s']}); damping matrix {checks['damping_matrix_max_rel_diff']:.1e}; modal ratios {min(checks['bare_modal_damping_ratios']):.6f}..{max(checks['bare_modal_damping_ratios']):.6f}",
        file=sys.stderr,
    )
    zeta = b["zeta"]
    failed = [
        what
        for what, bad in (
            ("the plan slipload prints is not the config's", max(checks["plan_vs_config_max_rel_diff"].values()) > 6e-7),
            ("OpenSees's stiffness matrix is not the plan's", max(checks["bare_stiffness_max_rel_diff"], checks["p_delta_stiffness_max_rel_diff"], checks["braced_stiffness_max_rel_diff"]) > 1e-12 or checks["plan_stiffness_printed_vs_opensees_max_rel_diff"] > 1e-6),
            ("OpenSees's eigen periods are not those of the matrices", max(checks["bare_period_max_rel_diff"], checks["p_delta_period_max_rel_diff"], checks["braced_period_max_rel_diff"]) > 1e-10),
            ("slipload's bare T1 (4 decimals) is not K's", abs(checks["bare_T1_slipload_s"] - checks["bare_periods_s"][0]) > 5e-5 * 1.0001),
            ("OpenSees's damping matrix is not slipload's modal C", checks["damping_matrix_max_rel_diff"] > 1e-9),
            ("C's modal ratios are not the config's", max(abs(x - z) for x, z in zip(checks["bare_modal_damping_ratios"], zeta)) > 1e-12),
        )
        if bad
    ]
    if failed:
        raise SystemExit("model checks failed: " + "; ".join(failed))
    summary = building_summary(b)
    records = [Path(r).resolve() for r in args.record] if args.record else [RECORDS / r for r in DEFAULT_RECORDS]
    levels = (("design", args.design_pga), ("MCE", MCE_FACTOR * args.design_pga))
    cases = []
    conv_cases = []
    with tempfile.TemporaryDirectory(prefix="slipload-opensees-yielding-") as td:
        tmp = Path(td)
        for k, record in enumerate(records):
            if not record.exists():
                raise SystemExit(f"{record}: no such record file")
            for level, pga in levels:
                first_mce = k == 0 and level == "MCE"
                cases.append(run_case(ops, binary, tmp, b, mats, record, level, pga, None, references=True, steel01=first_mce))
                if first_mce:
                    conv_cases.append(cases[-1])
        collapse = run_collapse(ops, binary, tmp, b, mats, records[-1], args.collapse_pga) if args.collapse_pga > 0 else None
        dt0 = conv_cases[0]["dt_s"]
        for h in range(1, args.halvings + 1):
            conv_cases.append(run_case(ops, binary, tmp, b, mats, records[0], "MCE", levels[1][1], dt0 / 2**h, references=False, steel01=False))
    conv = convergence(conv_cases)
    for r in conv["ratios"]:
        print("convergence ratios: " + ", ".join(f"{k} {fmt(v, '.2f')}" for k, v in r.items()), file=sys.stderr)
    report = {
        "machine": base.machine(ops),
        "settings": {
            "command": "scripts/compare-opensees-yielding.py" + "".join(f" {a}" for a in sys.argv[1:]),
            "building": str(BUILDING.relative_to(ROOT)),
            "building_summary": summary,
            "records": [str(r.relative_to(ROOT)) if r.is_relative_to(ROOT) else str(r) for r in records],
            "levels": {name: pga for name, pga in levels},
            "integrator": f"Newmark gamma = {GAMMA}, beta = {BETA}",
            "opensees_model": "floors as nodes with their masses; per storey zeroLength Elastic αk ∥ ElasticPP (1−α)k (yield strain Fy/k) ∥ Elastic −P/h (P-Δ) ∥ ElasticPP k′ (yield strain slip load/k′) for the brace + damper; slipload's modal C as zeroLength linear dashpots (Elastic, E = 0, damping tangent −C[i][j] between floors, the row sums to the ground); no Rayleigh damping",
            "opensees_solution": f"Newton, test NormDispIncr {TEST_TOL:g} m, at most {TEST_MAX_ITER} iterations, system {SYSTEM}",
            "energies": "per element Σ ½(Fₙ + Fₙ₊₁)(sₙ₊₁ − sₙ), s = deformation − F/k (newmark, OpenSees, the references); exact: Σ F_y |sₙ₊₁ − sₙ| (slip increments below 1e-10 m are the history files' rounding)",
        },
        "model_checks": checks,
        "cases": [c for c in cases],
        "convergence": conv,
        "convergence_cases": conv_cases[1:],
        "collapse_check": collapse,
    }
    report["run_s"] = time.perf_counter() - t_start
    args.out.mkdir(parents=True, exist_ok=True)
    base.write_atomic(args.out / "comparison.json", json.dumps(report, indent=2) + "\n")
    base.write_atomic(args.out / "README.md", markdown(report))
    print(f"\nwrote {args.out / 'comparison.json'} and {args.out / 'README.md'} in {report['run_s']:.0f} s", file=sys.stderr)
    print(markdown(report))


if __name__ == "__main__":
    main()
