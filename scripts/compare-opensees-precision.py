#!/usr/bin/env python3
"""slipload against OpenSees at equal accuracy: a work-precision comparison.

scripts/compare-opensees.py times both programs at the same time step, where their peak
drifts differ by about 0.1 %. This script asks instead what each program costs to reach a
given accuracy of the peak drifts, on the same building (configs/benchmark-3story-massless.json,
m' = 0: each brace + friction damper an elastic-perfectly plastic element) and records:

* reference: slipload `exact` (event-driven, each stick/slip mode integrated exactly, the
  drift peaks those of the continuous solution) at its default step; the script checks that
  its peaks do not depend on its output step (coarsest, default and finest step of the
  ladder agree within EXACT_CONSISTENCY) and stops otherwise;
* OpenSees (openseespy), the model and analysis exactly as compare-opensees.py builds them
  (Newmark average acceleration, full Newton to 1e-12 m, ProfileSPD), and slipload
  `newmark`, each at a ladder of time steps: the record's step (at most LADDER_START) halved
  down to LADDER_END; when a program's finest step has not reached the smallest target, the
  ladder grows by halvings (at most --max-extra-halvings);
* slipload `exact` itself, timed at its default step and at the ladder's coarsest step
  (its peaks are the same, only its output grid differs).

Error of a run: max over storeys of |peak drift - exact peak drift| / exact peak drift
(each program's peaks as it reports them: at its steps for OpenSees and `newmark`).
Time of a run, the scope of compare-opensees.py: OpenSees, the wall-clock of the analysis
set-up + one analyze(steps, dt) call with an EnvelopeElement recorder of the storey drifts
(model build, record included, excluded and reported apart); slipload, `cpu_seconds` of
`slipload simulate --format json --repeat 5` (the median of 5 runs in one warm process;
plan compiled and record read beforehand), peaks only. Figures are medians over repeats
after an untimed first run of each (which also gives the errors); the programs and the
steps are interleaved round by round (round r: for each step, OpenSees then slipload
newmark; then slipload exact). Repeats per step: --repeats, fewer for the costly OpenSees
steps (as many as fit in --point-budget seconds of OpenSees time, at least --min-repeats);
the same count for `newmark` at that step.

Time to reach a target error (1e-2, 1e-3, 1e-4): errors are not always monotone in the
step, so the step that reaches it is the first, coarse to fine, from which on every finer
step stays at or below the target; the time is interpolated linearly in log(time) against
log(error) between that step and the coarser one before it. When that step is the ladder's
coarsest, the time is an upper bound (the time of the coarsest step, written "≤"); when
the finest step is above the target, it is not reached. `exact` reaches every target at
its own cost.

Writes, atomically and only once every run has succeeded: results/performance/
opensees-precision.json (every point, the targets table, the machine),
opensees-precision.md, and per record opensees-precision-<record>.png and .svg (figures of
records no longer in the run are removed).

Usage: [SLIPLOAD_BIN=path] scripts/compare-opensees-precision.py [--record FILE|synthetic ...] [--repeats R]
Uses the environment of scripts/compare-opensees.py (scripts/.venv with openseespy, numpy
and matplotlib, created on first use), whose helpers it imports.
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.util
import io
import json
import math
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def load_base():
    """scripts/compare-opensees.py as a module: its environment, OpenSees model, analysis
    and timed run, model checks, records, slipload binary, scenes and runs, atomic writes
    and machine description."""
    spec = importlib.util.spec_from_file_location("compare_opensees", ROOT / "scripts" / "compare-opensees.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


base = load_base()

STEM = "opensees-precision"
TARGETS = (1e-2, 1e-3, 1e-4)
# The ladder: the record's step, halved until it is at most LADDER_START, then halved down
# to LADDER_END (0.02 ... 0.0003125 s on a record sampled at 0.02 s: T1/50 ... T1/3200 of the
# bare frame, about). No step is coarser than the record's: slipload refuses one, and OpenSees would
# skip samples.
LADDER_START = 0.02
LADDER_END = 0.0003125
# exact's continuous peaks at different output steps must agree to this (its contract is
# 1e-8; measured ~1e-14): otherwise the reference itself is in doubt and the script stops.
EXACT_CONSISTENCY = 1e-9
# What the figures say of exact's own error: crates/sim/tests/exact_reference.rs holds exact
# to 1e-10 of an independent piecewise-analytic solution accurate to ~1e-13 (measured
# agreement ~1e-15) on a one-storey frame with an elastic-perfectly plastic dissipator.
EXACT_DOCUMENTED_ERROR = 1e-13
ALGORITHM = "Newton"
SYSTEM = "ProfileSPD"
# Timed runs must reproduce the untimed first run's peaks (both programs are deterministic).
SAME_PEAKS = 1e-12
PROGRAMS = ("opensees", "newmark", "exact")
NAMES = {"opensees": "OpenSees", "newmark": "slipload newmark", "exact": "slipload exact"}


# ---------------------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------------------


def slipload(binary: Path, scene: Path, *extra: str) -> dict:
    """compare-opensees.py's slipload run, its failure reported with slipload's message."""
    try:
        return base.slipload_run(binary, scene, *extra)
    except subprocess.CalledProcessError as e:
        raise SystemExit(f"slipload simulate {scene.name} {' '.join(extra)} failed (exit {e.returncode}): {(e.stderr or '').strip()}")


def scene(tmp: Path, rec: dict, method: str, dt: float | None) -> Path:
    """compare-opensees.py's scene (peaks only) with `method` at step dt (None: the method's
    default step)."""
    tag = f"{rec['slug']}-{method}-{dt!r}" if dt else f"{rec['slug']}-{method}-default"
    path = base.slipload_scene(tmp, tag, rec["path"], rec["units"], dt if dt else rec["dt"])
    s = json.loads(path.read_text())
    s["method"] = {"name": method, **({"dt": dt} if dt else {})}
    path.write_text(json.dumps(s, indent=2))
    return path


def record_name(record: Path) -> str:
    """The record's path in the repository (records/NAME), as the other scripts write it,
    also when records/ is a link to the records elsewhere."""
    for top in (ROOT, base.RECORDS.resolve().parent):
        if record.is_relative_to(top):
            return str(record.relative_to(top))
    return str(record)


def rel_errors(peaks: list[float], ref: list[float]) -> list[float]:
    return [abs(p - r) / r for p, r in zip(peaks, ref)]


def ladder(dt_rec: float, start: float, end: float) -> list[float]:
    """The record's step halved until at most `start`, then down to `end` (each divides
    the record's step)."""
    dt = dt_rec
    while dt > start * (1 + 1e-9):
        dt /= 2
    out = []
    while dt >= end * (1 - 1e-9):
        out.append(dt)
        dt /= 2
    if not out:
        raise SystemExit(f"the ladder is empty: the record's step {dt_rec} s halved to at most {start} s is already below {end} s")
    return out


def check_step(rec: dict, dt: float) -> None:
    ratio = rec["dt"] / dt
    if dt <= 0 or dt > rec["dt"] * (1 + 1e-12) or abs(ratio - round(ratio)) > 1e-9:
        raise SystemExit(f"{rec['label']}: dt = {dt} s must divide the record's step {rec['dt']} s")


def first_runs(ops, binary: Path, tmp: Path, b: dict, rec: dict, dts: list[float], ref: list[float], extra_halvings: int) -> dict:
    """The untimed first run of OpenSees and slipload newmark at every step (their peaks,
    errors and steps; OpenSees's time as an estimate for its repeats), halving on past the
    ladder while a program's finest step is above the smallest target."""
    runs = {}

    def run(dt: float) -> None:
        sl = slipload(binary, scene(tmp, rec, "newmark", dt))
        if abs(sl["dt"] - dt) > 1e-15 * max(1.0, dt):
            raise SystemExit(f"{rec['label']}: slipload chose dt = {sl['dt']} s, asked for {dt} s")
        steps = int(sl["steps"])
        os_run = base.opensees_timed(ops, b, rec["dt"], rec["acc"], dt, steps, ALGORITHM, SYSTEM, tmp)
        runs[dt] = {"steps": steps, "newmark": sl["peak_drift"], "opensees": os_run["peak_drift"], "opensees_estimate_s": os_run["run_s"]}
        print(
            f"  dt {dt:<11g} {steps:7d} steps: OpenSees {os_run['run_s'] * 1e3:9.2f} ms, error {max(rel_errors(os_run['peak_drift'], ref)):.2e}; "
            f"newmark error {max(rel_errors(sl['peak_drift'], ref)):.2e}",
            file=sys.stderr,
        )

    for dt in dts:
        run(dt)
    added = 0
    while added < extra_halvings and any(max(rel_errors(runs[min(runs)][p], ref)) > min(TARGETS) for p in ("opensees", "newmark")):
        dt = min(runs) / 2
        print(f"  a program's finest step is above {min(TARGETS):g}: adding dt = {dt:g} s", file=sys.stderr)
        run(dt)
        added += 1
    return runs


def timed_rounds(ops, binary: Path, tmp: Path, b: dict, rec: dict, first: dict, exact_scenes: dict, args) -> dict:
    """The timed repeats, interleaved: round r runs, for each step that still has repeats,
    OpenSees then slipload newmark, then slipload exact at each of its steps."""
    dts = sorted(first, reverse=True)
    repeats = {dt: max(args.min_repeats, min(args.repeats, math.ceil(args.point_budget / max(first[dt]["opensees_estimate_s"], 1e-9)))) for dt in dts}
    times = {("opensees", dt): [] for dt in dts} | {("newmark", dt): [] for dt in dts} | {("exact", k): [] for k in exact_scenes}
    build = {dt: [] for dt in dts}
    newmark_scenes = {dt: scene(tmp, rec, "newmark", dt) for dt in dts}
    for r in range(args.repeats):
        for dt in dts:
            if r >= repeats[dt]:
                continue
            t = base.opensees_timed(ops, b, rec["dt"], rec["acc"], dt, first[dt]["steps"], ALGORITHM, SYSTEM, tmp)
            if max(rel_errors(t["peak_drift"], first[dt]["opensees"])) > SAME_PEAKS:
                raise SystemExit(f"{rec['label']}, dt = {dt} s: OpenSees's timed run gives other peaks than its first run: {t['peak_drift']} against {first[dt]['opensees']}")
            times[("opensees", dt)].append(t["run_s"])
            build[dt].append(t["build_s"])
            sl = slipload(binary, newmark_scenes[dt], "--repeat", str(base.SLIPLOAD_REPEAT))
            if max(rel_errors(sl["peak_drift"], first[dt]["newmark"])) > SAME_PEAKS:
                raise SystemExit(f"{rec['label']}, dt = {dt} s: slipload newmark's timed run gives other peaks than its first run")
            times[("newmark", dt)].append(sl["cpu_seconds"])
        for key, sc in exact_scenes.items():
            times[("exact", key)].append(slipload(binary, sc, "--repeat", str(base.SLIPLOAD_REPEAT))["cpu_seconds"])
        print(f"  round {r + 1}/{args.repeats} done", file=sys.stderr)
    return {"times": times, "build": build, "repeats": repeats}


# ---------------------------------------------------------------------------------------
# Time to reach a target
# ---------------------------------------------------------------------------------------


def time_to_reach(points: list[dict], target: float) -> dict:
    """points: one program's steps, coarse to fine, each with error and time_s. The first
    step from which on every finer step is at or below `target`; the time interpolated in
    log-log between it and the coarser step before it."""
    idx = None
    for i in range(len(points)):
        if all(p["error"] <= target for p in points[i:]):
            idx = i
            break
    if idx is None:
        return {"status": "not reached", "time_s": None, "finest_error": points[-1]["error"]}
    hi = points[idx]
    if idx == 0:
        return {"status": "at most", "time_s": hi["time_s"], "dt_s": hi["dt_s"], "note": "the coarsest step is already at or below the target: the time is that step's, an upper bound"}
    lo = points[idx - 1]  # above the target
    if hi["error"] <= 0.0:
        return {"status": "at most", "time_s": hi["time_s"], "dt_s": hi["dt_s"], "bracket_dt_s": [lo["dt_s"], hi["dt_s"]], "note": "error 0 at the finer step: its time, an upper bound"}
    f = (math.log(target) - math.log(lo["error"])) / (math.log(hi["error"]) - math.log(lo["error"]))
    t = math.exp(math.log(lo["time_s"]) + f * (math.log(hi["time_s"]) - math.log(lo["time_s"])))
    dt = math.exp(math.log(lo["dt_s"]) + f * (math.log(hi["dt_s"]) - math.log(lo["dt_s"])))
    return {"status": "interpolated", "time_s": t, "dt_s": dt, "bracket_dt_s": [lo["dt_s"], hi["dt_s"]], "bracket_error": [lo["error"], hi["error"]]}


def ratio(num: dict, den: dict) -> dict:
    """num / den of two times to reach; "at most" on one side makes the ratio a bound."""
    if num["time_s"] is None or den["time_s"] is None:
        return {"value": None, "kind": "not reached"}
    bound_num, bound_den = num["status"] == "at most", den["status"] == "at most"
    if bound_num and bound_den:
        return {"value": None, "kind": "both upper bounds"}
    kind = "at most" if bound_num else "at least" if bound_den else "equal"
    return {"value": num["time_s"] / den["time_s"], "kind": kind}


# ---------------------------------------------------------------------------------------
# One record
# ---------------------------------------------------------------------------------------


def run_record(ops, binary: Path, tmp: Path, b: dict, spec: str, args) -> dict:
    rec = base.load_record(binary, tmp, spec)
    rec["slug"] = re.sub(r"[^A-Za-z0-9._-]+", "-", rec["label"].split()[0] if spec == base.SYNTHETIC else rec["label"]).strip("-")
    dts = sorted(args.dts, reverse=True) if args.dts else ladder(rec["dt"], args.ladder_start, args.ladder_end)
    for dt in dts:
        check_step(rec, dt)
    print(f"\n== {rec['label']}: {len(rec['acc'])} samples at {rec['dt']} s; steps {', '.join(f'{d:g}' for d in dts)} s", file=sys.stderr)
    # The reference, and exact at the ladder's ends: its continuous peaks must not move.
    ex_scene = scene(tmp, rec, "exact", None)
    ex = slipload(binary, ex_scene)
    ref = ex["peak_drift"]
    exact_at = {"default": ex}
    for name, dt in (("coarsest", dts[0]), ("finest", dts[-1])):
        exact_at[name] = slipload(binary, scene(tmp, rec, "exact", dt))
    spread = max(max(rel_errors(e["peak_drift"], ref)) for e in exact_at.values())
    if spread > EXACT_CONSISTENCY:
        raise SystemExit(f"{rec['label']}: exact's peak drifts depend on its output step by {spread:.1e} (> {EXACT_CONSISTENCY:g}): " + "; ".join(f"dt {e['dt']}: {e['peak_drift']}" for e in exact_at.values()))
    print(f"  exact: peak drifts {ref} m (dt {ex['dt']} s); at the ladder's coarsest and finest steps within {spread:.1e}", file=sys.stderr)
    first = first_runs(ops, binary, tmp, b, rec, dts, ref, args.max_extra_halvings)
    exact_scenes = {"default": ex_scene}
    if abs(dts[0] - ex["dt"]) > 1e-15:
        exact_scenes["coarsest"] = scene(tmp, rec, "exact", dts[0])
    # One untimed warm-up of each exact scene (the ladder's steps had theirs above).
    for sc in exact_scenes.values():
        slipload(binary, sc)
    timed = timed_rounds(ops, binary, tmp, b, rec, first, exact_scenes, args)
    points = []
    for dt in sorted(first, reverse=True):
        for prog in ("opensees", "newmark"):
            ts = timed["times"][(prog, dt)]
            errs = rel_errors(first[dt][prog], ref)
            p = {
                "program": prog,
                "dt_s": dt,
                "steps": first[dt]["steps"],
                "time_s": statistics.median(ts),
                "times_s": ts,
                "repeats": len(ts),
                "peak_drift_m": first[dt][prog],
                "error_by_storey": errs,
                "error": max(errs),
            }
            if prog == "opensees":
                p["model_build_median_s"] = statistics.median(timed["build"][dt])
                p["algorithm"], p["system"] = ALGORITHM, SYSTEM
            points.append(p)
    for key in exact_scenes:
        e = exact_at[key]
        ts = timed["times"][("exact", key)]
        errs = rel_errors(e["peak_drift"], ref)
        points.append({
            "program": "exact",
            "role": "the reference: exact at its default step" if key == "default" else "exact at the ladder's coarsest step (the same continuous peaks, a coarser output grid)",
            "dt_s": e["dt"],
            "steps": int(e["steps"]),
            "time_s": statistics.median(ts),
            "times_s": ts,
            "repeats": len(ts),
            "peak_drift_m": e["peak_drift"],
            "error_by_storey": errs,
            "error": max(errs),
            "transitions": e["transitions"],
        })
    exact_default = next(p for p in points if p["program"] == "exact" and p["dt_s"] == ex["dt"])
    targets = []
    for target in TARGETS:
        row = {"target": target}
        for prog in ("opensees", "newmark"):
            row[prog] = time_to_reach([p for p in points if p["program"] == prog], target)
        row["exact"] = {"status": "reference", "time_s": exact_default["time_s"], "dt_s": exact_default["dt_s"]}
        row["ratio_opensees_over_newmark"] = ratio(row["opensees"], row["newmark"])
        row["ratio_opensees_over_exact"] = ratio(row["opensees"], row["exact"])
        targets.append(row)
    record = rec["path"]
    return {
        "label": rec["label"],
        "slug": rec["slug"],
        "record": rec["source"] or record_name(record),
        "record_samples": len(rec["acc"]),
        "record_dt_s": rec["dt"],
        "ladder_s": sorted(first, reverse=True),
        "steps_added_past_the_ladder": len(first) - len(dts),
        "reference": {
            "method": "exact",
            "dt_s": ex["dt"],
            "steps": int(ex["steps"]),
            "peak_drift_m": ref,
            "transitions": ex["transitions"],
            "peaks_at_other_output_steps": {k: {"dt_s": e["dt"], "peak_drift_m": e["peak_drift"]} for k, e in exact_at.items() if k != "default"},
            "max_rel_diff_across_output_steps": spread,
        },
        "repeats_by_dt": {repr(dt): r for dt, r in sorted(timed["repeats"].items(), reverse=True)},
        "points": points,
        "targets": targets,
        "figures": [f"{STEM}-{rec['slug']}.png", f"{STEM}-{rec['slug']}.svg"],
    }


# ---------------------------------------------------------------------------------------
# Figure and report
# ---------------------------------------------------------------------------------------


def dt_label(dt: float) -> str:
    return f"{dt * 1e3:g} ms"


def figure(case: dict) -> dict[str, str | bytes]:
    """The work-precision figure of one record: x the peak-drift error, y the time per
    simulation, both log; a line per program; exact (whose error is off any such axis) as a
    horizontal line at its time; the targets as vertical guide lines. Returns the SVG text
    and PNG bytes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    matplotlib.rcParams["svg.hashsalt"] = "slipload"  # stable element ids
    fig, ax = plt.subplots(figsize=(8.0, 6.2))
    style = {"opensees": ("C3", "o", (6, 4)), "newmark": ("C0", "s", (-6, -12))}
    errs = []
    for prog, (color, marker, offset) in style.items():
        pts = [p for p in case["points"] if p["program"] == prog]
        x = [p["error"] for p in pts]
        y = [p["time_s"] * 1e3 for p in pts]
        errs += x
        ax.plot(x, y, color=color, marker=marker, label=f"{NAMES[prog]} (each point labelled with its Δt)")
        for p, xi, yi in zip(pts, x, y):
            ax.annotate(dt_label(p["dt_s"]), (xi, yi), xytext=offset, textcoords="offset points", fontsize=7, color=color, ha="left" if offset[0] > 0 else "right")
    ex = next(p for p in case["points"] if p["program"] == "exact" and p["dt_s"] == case["reference"]["dt_s"])
    ax.axhline(ex["time_s"] * 1e3, color="C2", linestyle="--", marker="<", markevery=[0], label=f"{NAMES['exact']} (error ~{EXACT_DOCUMENTED_ERROR:.0e}, off the axis: drawn at its time)")
    lo, hi = min(min(errs), min(TARGETS)) / 3, max(max(errs), max(TARGETS)) * 3
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.annotate(f"exact, Δt {dt_label(ex['dt_s'])} output step: {ex['time_s'] * 1e3:.2f} ms", (lo, ex["time_s"] * 1e3), xytext=(12, 4), textcoords="offset points", fontsize=7, color="C2")
    for t in TARGETS:
        ax.axvline(t, color="0.55", linestyle=":", linewidth=1)
        ax.annotate(f"{t:.0e}", (t, 1), xycoords=("data", "axes fraction"), xytext=(2, -10), textcoords="offset points", fontsize=7, color="0.4")
    ax.set_xlabel("peak-drift error: max over storeys of |peak − exact| / exact")
    ax.set_ylabel("time per simulation (ms)")
    ax.set_title(f"{case['label']}: benchmark three-storey frame, m′ = 0 — time against accuracy", fontsize=10)
    ax.grid(True, which="major", linewidth=0.4, alpha=0.5)
    # Below the axes: inside, it would hide points or guide lines of some record.
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, frameon=False)
    fig.tight_layout()
    out: dict[str, str | bytes] = {}
    svg, png = io.StringIO(), io.BytesIO()
    fig.savefig(svg, format="svg", metadata={"Date": None})
    fig.savefig(png, format="png", dpi=150, metadata={"Software": None})
    plt.close(fig)
    out["svg"], out["png"] = svg.getvalue(), png.getvalue()
    return out


def fmt_time(t: dict) -> str:
    if t["time_s"] is None:
        return f"not reached (finest {t['finest_error']:.1e})"
    ms = t["time_s"] * 1e3
    s = f"{ms:.3g}" if ms < 100 else f"{ms:.0f}"
    if t["status"] == "at most":
        return f"≤ {s} (Δt {dt_label(t['dt_s'])})"
    if t["status"] == "interpolated":
        return f"{s} (Δt ≈ {t['dt_s'] * 1e3:.2g} ms)"
    return f"{s} (Δt {dt_label(t['dt_s'])} output)"


def fmt_ratio(r: dict) -> str:
    if r["value"] is None:
        return "—"
    sign = {"at most": "≤ ", "at least": "≥ ", "equal": ""}[r["kind"]]
    v = r["value"]
    return f"{sign}{v:.3g}×" if v < 10 else f"{sign}{v:.0f}×"


def markdown(report: dict) -> str:
    s = report["settings"]
    m = report["machine"]
    lines = [
        "# slipload against OpenSees at equal accuracy",
        "",
        f"Regenerate with `{s['command']}` ({s['run_minutes']:.1f} minutes for this run).",
        "",
        f"Building: `{s['building']}` (the benchmark three-storey frame, massless dissipators: each brace + damper an",
        "elastic–perfectly plastic element). OpenSees: the model and analysis of `scripts/compare-opensees.py` (checked there",
        f"and again here: {s['model_checks']}), Newmark average acceleration, {s['opensees_solution']}. slipload `newmark`: the same",
        "Newmark scheme with the friction law solved exactly each step. Both at the same ladder of time steps.",
        "",
        f"**Error** of a run: {s['error']}",
        "",
        f"**Time** per simulation: {s['timing']}",
        "",
        f"**Time to reach a target**: {s['time_to_reach']}",
        "",
        f"**`exact`**: {s['exact']}",
        "",
        "## Time to reach a peak-drift error (ms per simulation)",
        "",
        "| record | target | OpenSees | slipload newmark | slipload exact | OpenSees / newmark | OpenSees / exact |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    for c in report["records"]:
        for row in c["targets"]:
            lines.append(
                f"| {c['label']} | {row['target']:.0e} | {fmt_time(row['opensees'])} | {fmt_time(row['newmark'])} | {fmt_time(row['exact'])} | "
                f"**{fmt_ratio(row['ratio_opensees_over_newmark'])}** | {fmt_ratio(row['ratio_opensees_over_exact'])} |"
            )
    lines += [
        "",
        "Δt ≈ …: the step interpolated (log–log, as the time) between the two ladder steps that bracket the target; ≤ …: the",
        "ladder's coarsest step already reaches the target, so its time is an upper bound (and a ratio with it a bound);",
        "not reached: the finest step is above the target.",
        "",
    ]
    for c in report["records"]:
        ref = c["reference"]
        lines += [
            f"## {c['label']}",
            "",
            f"Record: {c['record']} ({c['record_samples']} samples at {c['record_dt_s']} s). Reference: `exact` at Δt {ref['dt_s']} s"
            f" ({ref['steps']} output steps), peak drifts " + ", ".join(f"{x:.6f}" for x in ref["peak_drift_m"]) + " m; at the"
            f" ladder's coarsest and finest steps its peaks agree within {ref['max_rel_diff_across_output_steps']:.1e}."
            + (f" {c['steps_added_past_the_ladder']} step(s) added past the ladder to reach {min(TARGETS):g}." if c["steps_added_past_the_ladder"] else ""),
            "",
            f"![work-precision, {c['label']}]({c['figures'][0]}) ([SVG]({c['figures'][1]}))",
            "",
            "| Δt (s) | steps | OpenSees (ms) | OpenSees error | slipload newmark (ms) | newmark error | repeats | OpenSees model build (ms, excluded) |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for dt in c["ladder_s"]:
            o = next(p for p in c["points"] if p["program"] == "opensees" and p["dt_s"] == dt)
            n = next(p for p in c["points"] if p["program"] == "newmark" and p["dt_s"] == dt)
            lines.append(
                f"| {dt:g} | {o['steps']} | {o['time_s'] * 1e3:.2f} | {o['error']:.2e} | {n['time_s'] * 1e3:.3f} | {n['error']:.2e} | {o['repeats']} | {o['model_build_median_s'] * 1e3:.2f} |"
            )
        for e in (p for p in c["points"] if p["program"] == "exact"):
            lines.append(f"| exact, output Δt {e['dt_s']:g} | {e['steps']} | — | — | {e['time_s'] * 1e3:.3f} (exact) | {e['error']:.1e} (vs. the reference) | {e['repeats']} | — |")
        lines.append("")
    lines += [
        f"Machine: {m['cpu_model']}, {m['cpus']} CPUs ({m['threads_per_core']} thread per core), shared with other jobs; {m['os']};",
        f"OpenSees {m['opensees']} through openseespy {m['openseespy']} (Python {m['python']}); slipload binary {m['slipload_binary']} ({m['slipload_version']},"
        f" sha256 {m['slipload_binary_sha256']}), repository at {m['slipload_commit']}.",
        "",
    ]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------
# Main
# ---------------------------------------------------------------------------------------


def main() -> None:
    base.ensure_environment(Path(__file__))
    started = time.perf_counter()
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--record", action="append", help=f"record file (.AT2, in g) or '{base.SYNTHETIC}' (the {base.SYNTHETIC_DURATION:g} s record of compare-opensees.py); repeatable [default: synthetic, SYL090.AT2, I-ELC180.AT2]")
    ap.add_argument("--repeats", type=int, default=21, help="timed repeats per program and step, at most (median) [default: 21]")
    ap.add_argument("--min-repeats", type=int, default=5, help="timed repeats of the costliest OpenSees steps, at least [default: 5]")
    ap.add_argument("--point-budget", type=float, default=10.0, help="OpenSees seconds per step that set its repeats between --min-repeats and --repeats [default: 10]")
    ap.add_argument("--ladder-start", type=float, default=LADDER_START, help=f"coarsest step, s: the record's step halved until at most this [default: {LADDER_START}]")
    ap.add_argument("--ladder-end", type=float, default=LADDER_END, help=f"finest step of the ladder, s [default: {LADDER_END}]")
    ap.add_argument("--dts", type=lambda v: [float(x) for x in v.split(",")], help="the ladder, comma-separated steps in s, instead of --ladder-start/--ladder-end (each must divide the record's step)")
    ap.add_argument("--max-extra-halvings", type=int, default=3, help=f"halvings past the ladder while a program's finest step is above {min(TARGETS):g} [default: 3]")
    ap.add_argument("--out", type=Path, default=base.OUT_DIR, help="output folder [default: results/performance]")
    args = ap.parse_args()
    if args.repeats < 1 or args.min_repeats < 1:
        raise SystemExit("--repeats and --min-repeats must be at least 1")
    if args.max_extra_halvings < 0 or args.point_budget <= 0 or args.ladder_end <= 0 or args.ladder_start < args.ladder_end:
        raise SystemExit("need --max-extra-halvings >= 0, --point-budget > 0 and 0 < --ladder-end <= --ladder-start")
    if args.dts is not None and (len(args.dts) < 2 or len(set(args.dts)) != len(args.dts)):
        raise SystemExit("--dts needs at least two different steps")
    args.min_repeats = min(args.min_repeats, args.repeats)
    ops = base.import_opensees()
    binary = base.slipload_bin()
    b = base.load_building(base.BUILDING)
    checks = base.checked_model(ops, binary, b, 0.0025)
    records = args.record or [base.SYNTHETIC, str(base.RECORDS / "SYL090.AT2"), str(base.RECORDS / "I-ELC180.AT2")]
    cases = []
    with tempfile.TemporaryDirectory(prefix="slipload-opensees-precision-") as td:
        for spec in records:
            cases.append(run_record(ops, binary, Path(td), b, spec, args))
    slugs = [c["slug"] for c in cases]
    if len(set(slugs)) != len(slugs):
        raise SystemExit(f"two records share a figure name: {slugs}")
    version = subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()
    mach = base.machine(ops) | {
        "slipload_binary": str(binary),
        "slipload_version": version,
        "slipload_binary_sha256": hashlib.sha256(binary.read_bytes()).hexdigest()[:16],
    }
    command = "scripts/compare-opensees-precision.py" + "".join(f" {a}" for a in sys.argv[1:])
    report = {
        "machine": mach,
        "settings": {
            "command": command,
            "building": str(base.BUILDING.relative_to(ROOT)),
            "targets": list(TARGETS),
            "ladder": f"the record's step halved until at most {args.ladder_start} s, then halved down to {args.ladder_end} s" if not args.dts else f"given: {args.dts}",
            "max_extra_halvings": args.max_extra_halvings,
            "repeats": args.repeats,
            "min_repeats": args.min_repeats,
            "point_budget_s": args.point_budget,
            "integrator": f"Newmark gamma = {base.GAMMA}, beta = {base.BETA} (OpenSees and slipload newmark)",
            "opensees_solution": f"{ALGORITHM}, test NormDispIncr {base.TEST_TOL:g} m, at most {base.TEST_MAX_ITER} iterations, system {SYSTEM}",
            "model_checks": f"stiffness matrix within {max(checks['frame_stiffness_max_rel_diff'], checks['braced_stiffness_max_rel_diff']):.1e} of K, periods within {max(checks['bare_period_max_rel_diff'], checks['braced_period_max_rel_diff']):.1e}, damping matrix within {checks['damping_matrix_max_rel_diff']:.1e}",
            "error": "max over storeys of |peak drift − exact's peak drift| / exact's peak drift, each program's peaks as it reports them (OpenSees and slipload newmark: the largest |drift| at their steps; exact: of the continuous solution).",
            "timing": (
                "the scope of `scripts/compare-opensees.py`, medians over the timed repeats after an untimed first run of each (which also gives the peaks; the timed runs must reproduce them), the programs and steps interleaved round by round "
                "(round r: for each step that still has repeats, OpenSees then slipload newmark; then slipload exact). OpenSees: wall-clock of the analysis set-up + one analyze(steps, dt) call with an EnvelopeElement recorder of the storey drifts "
                "(model build, record included, excluded: in the JSON as model_build_median_s). slipload: cpu_seconds of "
                f"`slipload simulate --format json --repeat {base.SLIPLOAD_REPEAT}` (the median of {base.SLIPLOAD_REPEAT} runs in one warm process; plan compiled and record read beforehand), peaks only. "
                f"Repeats per step: {args.repeats}, fewer for an OpenSees step whose first run says {args.repeats} would take more than {args.point_budget:g} s (as many as fit, at least {args.min_repeats}); slipload newmark as many as OpenSees at that step."
            ),
            "time_to_reach": (
                "errors are not always monotone in Δt, so the step that reaches a target is the first, coarse to fine, from which on every finer step stays at or below it; "
                "its time is interpolated linearly in log(time) against log(error) between that step and the coarser one before it (the Δt likewise). "
                "When that step is the ladder's coarsest the time is an upper bound (≤, that step's time); when the finest step is above the target, not reached. "
                f"If a program's finest step is above {min(TARGETS):g}, the ladder is halved on (at most {args.max_extra_halvings} times). "
                "exact reaches every target at its own time, at its default step."
            ),
            "exact": (
                "the reference, at its default output step (`--method exact`; its cost grows with the output steps, at which it also samples the state: "
                "its time at the ladder's coarsest step is in the tables too, with the same continuous peaks). Its own error is not measurable against itself: "
                f"`crates/sim/tests/exact_reference.rs` holds it to 1e-10 of an independent piecewise-analytic solution accurate to ~{EXACT_DOCUMENTED_ERROR:.0e} (measured agreement ~1e-15) on a one-storey frame with an EPP dissipator; "
                f"here its peaks at the ladder's coarsest, default and finest output steps must agree within {EXACT_CONSISTENCY:g} (the script stops otherwise). "
                f"The figures draw it as a horizontal dashed line at its time (its error, ~{EXACT_DOCUMENTED_ERROR:.0e}, is off the axis to the left), not as a point."
            ),
        },
        "model_checks": checks,
        "records": cases,
    }
    # Everything is computed; render the figures in memory, then write.
    figures = {c["slug"]: figure(c) for c in cases}
    report["settings"]["run_minutes"] = (time.perf_counter() - started) / 60.0
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    for slug, fig in figures.items():
        base.write_atomic(out / f"{STEM}-{slug}.png", fig["png"])
        base.write_atomic(out / f"{STEM}-{slug}.svg", fig["svg"])
    base.write_atomic(out / f"{STEM}.json", json.dumps(report, indent=2) + "\n")
    base.write_atomic(out / f"{STEM}.md", markdown(report))
    # Figures of records this run did not make would contradict the report: remove them.
    keep = {name for c in cases for name in c["figures"]}
    for old in list(out.glob(f"{STEM}-*.png")) + list(out.glob(f"{STEM}-*.svg")):
        if old.name not in keep:
            old.unlink()
    print(f"\nwrote {out / (STEM + '.json')}, {out / (STEM + '.md')} and {len(keep)} figures ({report['settings']['run_minutes']:.1f} min)", file=sys.stderr)
    print(markdown(report))


if __name__ == "__main__":
    main()
