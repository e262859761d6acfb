"""What the Python front costs beside the command line, measured in one run on one machine.

1. simulate: the benchmark building under a 15 s synthetic record at the default step,
   per call from Python (wall clock around `slipload.simulate`, median of N calls) against
   the command line's in-process time for the same run (`slipload simulate --repeat N`,
   median `cpu_seconds`). Target: at most 5 % more.
2. batch: `slipload.batch_designs` over the designs × records of a sweep against
   `slipload sweep` on the same study, same fidelity (the sweep's method and step), same
   thread count: simulations per second. Target: at least 90 % of the sweep's.
3. GIL: one batch on one worker thread, then two such batches from two Python threads at
   once: with the GIL released the two finish in about one batch's time on two cores,
   far below twice it.
4. Memory: 10,000 `simulate` calls with histories: the process RSS before and after.

Prints a table and writes it with the figures as JSON: python bench/bench_python.py OUT_DIR
(scripts/bench-python.sh runs it and writes results/performance/python.{json,txt}).
"""

import json
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np

import slipload

ROOT = pathlib.Path(__file__).resolve().parents[3]
CLI = pathlib.Path(os.environ.get("SLIPLOAD_BIN", ROOT / "target" / "release" / "slipload"))
REPEAT = 200


def rss_mib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def simulate_overhead():
    cli = json.loads(
        subprocess.run(
            [str(CLI), "simulate", "--duration", "15", "--repeat", str(REPEAT), "--format", "json"],
            capture_output=True, text=True, check=True, cwd=ROOT,
        ).stdout
    )
    scene = slipload.load_scene(duration=15.0)
    for _ in range(10):
        slipload.simulate(scene)  # warm caches, as --repeat's first runs do
    walls, cpus = [], []
    for _ in range(REPEAT):
        t = time.perf_counter()
        r = slipload.simulate(scene)
        walls.append(time.perf_counter() - t)
        cpus.append(r.cpu_seconds)
    py_call = statistics.median(walls)
    return {
        "scene": scene.name + ", 15 s, " + scene.method + f", dt = {scene.dt} s, {scene.steps} steps",
        "calls": REPEAT,
        "cli_in_process_s": cli["cpu_seconds"],
        "python_per_call_s": py_call,
        "python_engine_s": statistics.median(cpus),
        "overhead": py_call / cli["cpu_seconds"] - 1.0,
        "target_overhead": 0.05,
    }


def bench_study(tmp):
    """The benchmark study with a larger sweep (400 designs x 10 records), written with
    absolute paths so it runs from a temporary folder."""
    study = json.loads((ROOT / "configs" / "study-benchmark.json").read_text())
    study["building"] = str(ROOT / "configs" / "benchmark-3story.json")
    study["sweep"]["points"] = 400
    study["name"] = "benchmark-3story-bench"
    path = pathlib.Path(tmp) / "study.json"
    path.write_text(json.dumps(study))
    return path


def batch_vs_sweep(threads):
    with tempfile.TemporaryDirectory() as tmp:
        study_path = bench_study(tmp)
        out = pathlib.Path(tmp) / "sweep"
        err = subprocess.run(
            [str(CLI), "--threads", str(threads), "sweep", str(study_path), "--out", str(out), "--quiet"],
            capture_output=True, text=True, check=True,
        ).stderr
        m = re.search(r"(\d+) run in ([0-9.]+) s, ([0-9.]+) tasks/s", err)
        if not m:
            raise RuntimeError(f"no rate in the sweep's output:\n{err}")
        sweep_rate = float(m.group(3))
        manifest = json.loads((out / "manifest.json").read_text())
        designs = np.array([d["slip_loads_n"] for d in manifest["designs"]], dtype=float)
        if manifest["dt_s"] is not None or manifest["energies"]:
            raise RuntimeError("the bench study's sweep runs at the default step without energies")
        study = slipload.load_study(str(study_path))
        records = study.records
        scene = str(ROOT / "configs" / "benchmark-3story.json")
        method = manifest["method"]
        slipload.batch_designs(scene, records[:1], designs[:4], method=method, threads=threads, progress=False)
        t = time.perf_counter()
        b = slipload.batch_designs(scene, records, designs, method=method, outputs=[], threads=threads, progress=False)
        wall = time.perf_counter() - t
        sims = b["peak_base_shear"].size
        return {
            "threads": threads,
            "simulations": sims,
            "sweep_sims_per_s": sweep_rate,
            "batch_sims_per_s": sims / wall,
            "ratio": (sims / wall) / sweep_rate,
            "target_ratio": 0.9,
            "method": method,
        }


def gil():
    scene = slipload.load_scene()
    suite = slipload.synthetic_suite()
    designs = np.linspace(0.2, 2.0, 30)[:, None] * scene.slip_loads[None, :]
    run = lambda: slipload.batch_designs(scene, suite, designs, outputs=[], threads=1, progress=False)  # noqa: E731
    run()
    t = time.perf_counter()
    run()
    one = time.perf_counter() - t
    ts = [threading.Thread(target=run) for _ in range(2)]
    t = time.perf_counter()
    for th in ts:
        th.start()
    for th in ts:
        th.join()
    two = time.perf_counter() - t
    return {"one_batch_s": one, "two_threads_s": two, "ratio_to_one": two / one, "cores": os.cpu_count()}


def memory(calls=10_000):
    scene = slipload.load_scene(duration=2.0)
    for _ in range(100):
        slipload.simulate(scene, outputs=["histories", "energies"]).history.array
    before = rss_mib()
    for _ in range(calls):
        r = slipload.simulate(scene, outputs=["histories", "energies"])
        r.history.array  # the histories reach Python as numpy arrays
    after = rss_mib()
    return {"calls": calls, "steps_per_call": scene.steps, "rss_before_mib": before, "rss_after_mib": after, "growth_mib": after - before}


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else None
    res = {
        "simulate": simulate_overhead(),
        "batch": [batch_vs_sweep(1), batch_vs_sweep(os.cpu_count() or 1)],
        "gil": gil(),
        "memory": memory(),
        "machine": {"cpus": os.cpu_count(), "python": sys.version.split()[0], "slipload": slipload.__version__},
    }
    s = res["simulate"]
    lines = [
        "slipload from Python beside the command line (one run, one machine)",
        "",
        f"simulate: {s['scene']}",
        "  " + f"command line, in process (simulate --repeat {s['calls']}, median):".ljust(64) + f"{1e3 * s['cli_in_process_s']:.3f} ms",
        "  " + f"Python, per call (median of {s['calls']} calls):".ljust(64) + f"{1e3 * s['python_per_call_s']:.3f} ms ({100 * s['overhead']:+.1f} %, target at most +5 %)",
        "  " + "the engine's own time inside those calls (median):".ljust(64) + f"{1e3 * s['python_engine_s']:.3f} ms",
        "",
        "batch_designs vs slipload sweep (same designs x records, fidelity, threads):",
    ]
    for b in res["batch"]:
        lines.append(
            f"  {b['threads']} thread(s), {b['simulations']} simulations ({b['method']}): sweep {b['sweep_sims_per_s']:.1f}/s, batch {b['batch_sims_per_s']:.1f}/s: {100 * b['ratio']:.1f} % of the sweep (target at least 90 %)"
        )
    g = res["gil"]
    lines += [
        "",
        f"GIL: one batch (1 worker thread) {g['one_batch_s']:.3f} s; two at once from two Python threads {g['two_threads_s']:.3f} s = {g['ratio_to_one']:.2f} x one batch ({g['cores']} cores; twice would mean the GIL serialised them)",
        "",
    ]
    m = res["memory"]
    lines.append(
        f"memory: {m['calls']} simulate calls with histories ({m['steps_per_call']} steps each): RSS {m['rss_before_mib']:.1f} MiB before, {m['rss_after_mib']:.1f} MiB after ({m['growth_mib']:+.1f} MiB)"
    )
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if out:
        out.mkdir(parents=True, exist_ok=True)
        for name, data in [("python.json", json.dumps(res, indent=2) + "\n"), ("python.txt", text)]:
            tmp = out / (name + ".tmp")
            tmp.write_text(data)
            os.replace(tmp, out / name)


if __name__ == "__main__":
    main()
