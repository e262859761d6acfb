"""Peers of the model refiner on the optimizer benchmark's cases, at equal simulations.

CMA-ES (pycma), pymoo's genetic algorithm and nevergrad's recommended general optimizer
(NGOpt) minimise a case's own objective (scripts/optimizer_cases.py: the study
scripts/optimizer-bench.sh runs; mean peak storey drift ratio, worst of the three property
cases, averaged over the case's hazard levels; a design that misses a limit or collapses
scores +inf, as the refiners see it) through the Python package: each design is the
study's simulations at its sweep fidelity (`slipload.evaluate_objectives`, whose first
objective, the study's drift objective, is checked below against the number `optimize`
reported for the model refiner's optimum). Each peer gets as many designs as the model
refiner's row of the case's benchmark file (results/optimizer/<case>.json) from the
neutral start used in all (sweep and refinement designs, its post-check included; the
finalists' check and the design table not counted), and starts from what it needs, not
from a design: CMA-ES and NGOpt from the middle of the box, the GA from a random
population. Seeds 1, 2, 3.

A design asked again (the same slip loads to the bit) is not simulated again: the
objective is deterministic, so it is read from the earlier evaluation; it still counts
as one of the peer's designs. The evaluations are also appended to
target/optimizer-peers/<case>-<study hash>.jsonl, so a run that was stopped continues
where it stopped (the seeds replay the same designs); the hash covers the study (but for
its refiner's and sweep's settings, which no evaluation reads) with its building's content
and the package version. The check of the model refiner's number
always simulates.

Writes results/optimizer/peers.{json,md} for the ten case and
results/optimizer/peers-<case>.{json,md} for the others. Usage (with the package and cma,
pymoo, nevergrad installed; scripts/optimizer-peers.sh does that):
python3 scripts/optimizer_peers.py [ten|twenty|forty]   (default ten);
python3 scripts/optimizer_peers.py CASE --regrade rewrites a case's files from their own
runs against the best design and the model row its bench file now has (no peer simulated:
a new model row at the same number of designs is simulated once, to check the package
gives its number).
"""

import hashlib
import json
import math
import os
import statistics
import sys
import tempfile

import numpy as np

import slipload

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "results", "optimizer")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from optimizer_cases import CASES, MODEL_ROW, SWEEP_DESIGNS, write_case  # noqa: E402

SEEDS = [1, 2, 3]
# a design the refiners reject (+inf) is this much, a drift ratio of 100 %, for the peers
# that need finite values; worse than every design that passes
REJECTED = 1.0
# what each case's table calls its study
LABEL = {"ten": "ten-storey check example", "twenty": "twenty-storey yielding frame",
         "forty": "forty-storey yielding frame"}


def study_dict(case, folder):
    """The case's study as the benchmark runs it, with the study's objective as the first
    of two objectives (the second is not read)."""
    study, starts, _ = write_case(ROOT, case, folder)
    # ten: the example's own building file, as this script has used from the start (every
    # design's slip loads replace its own); the other cases have only the neutral one
    study["building"] = starts.get("file", starts["neutral"])
    study["objectives"] = [
        {"metric": "peak_drift_ratio", "statistic": "mean"},
        {"metric": "peak_floor_acceleration", "statistic": "mean"},
    ]
    return study


def case_files(case):
    """A case's spec, the command that makes its peers files, their stem, and the model
    refiner's row of its bench file (with the bench file's best known)."""
    spec = CASES[case]
    command = "scripts/optimizer-peers.sh" + ("" if case == "ten" else f" {case}")
    stem = "peers" if case == "ten" else f"peers-{case}"
    bench = json.load(open(os.path.join(OUT, spec["name"] + ".json")))
    model = next(r for r in bench["runs"] if r["start"] == "neutral" and r["refiner"] == "model"
                 and r["max_evaluations"] == MODEL_ROW[case])
    return spec, command, stem, bench, model


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "ten"
    spec, command, stem, bench, model = case_files(case)
    budget = SWEEP_DESIGNS + model["refine_designs"]
    best_known = bench["best_known"]["objective"]
    with tempfile.TemporaryDirectory() as folder:
        raw = study_dict(case, folder)
        study = slipload.load_study(raw)
        # (what an evaluation depends on: not the refiner's or the sweep's settings)
        identity = {k: v for k, v in raw.items() if k not in ("refine", "sweep")}
        identity.update(building=json.load(open(raw["building"])), version=slipload.__version__)
    upper = spec["upper_kn"] * 1e3  # N, every floor's upper bound (lower 0)
    d = spec["n"]
    # evaluations of this study by this script, kept across runs (the key is the design's bytes)
    digest = hashlib.sha256(json.dumps(identity, sort_keys=True).encode()).hexdigest()[:16]
    cache_path = os.path.join(ROOT, "target", "optimizer-peers", f"{case}-{digest}.jsonl")
    os.makedirs(os.path.dirname(cache_path), exist_ok=True)
    seen, asked = {}, set()
    if os.path.exists(cache_path):
        for line in open(cache_path):
            try:
                e = json.loads(line)
            except ValueError:
                continue  # a line torn by a stop
            seen[bytes.fromhex(e["x"])] = float(e["f"])
        print(f"{len(seen)} evaluations read from {cache_path}", file=sys.stderr)
    cache = open(cache_path, "a")

    def simulate(loads):
        return slipload.evaluate_objectives(study, np.ascontiguousarray(loads, dtype=float), progress=False)[:, 0]

    def evaluate_loads(loads):
        loads = np.ascontiguousarray(loads, dtype=float)
        new = [row for row in loads if row.tobytes() not in seen]
        if new:
            fs = simulate(np.array(new))
            for row, f in zip(new, fs):
                seen[row.tobytes()] = float(f)
                cache.write(json.dumps({"x": row.tobytes().hex(), "f": float(f)}) + "\n")
            cache.flush()
        asked.update(row.tobytes() for row in loads)
        return np.array([seen[row.tobytes()] for row in loads])

    def evaluate(z):
        return evaluate_loads(np.clip(np.asarray(z, dtype=float), 0.0, 1.0) * upper)

    # the first objective is the study's: the model refiner's optimum gives its number
    # (its slip loads as optimize wrote them, not through the scaled variables, whose
    # round trip may move the last bit)
    check = simulate([np.array(model["slip_loads_kN"]) * 1e3])[0]
    # (kN as optimize writes them, read back as N, may move a slip load by an ulp, and the
    # objective then by a few ulps: agreement to 1e-12 is agreement)
    same = bool(abs(check - model["objective"]) <= 1e-12 * abs(model["objective"]))
    print(f"the study's objective through evaluate_objectives: {check!r} against optimize's {model['objective']!r}", file=sys.stderr)

    rows = []
    import cma

    for seed in SEEDS:
        es = cma.CMAEvolutionStrategy(
            [0.5] * d, 0.25, {"bounds": [0.0, 1.0], "seed": seed, "verbose": -9, "maxfevals": budget}
        )
        best, used = math.inf, 0
        while used < budget:
            xs = es.ask()[: budget - used]
            fs = evaluate(np.array(xs))
            used += len(xs)
            best = min(best, float(np.min(fs)))
            if len(xs) < es.popsize:
                break
            es.tell(xs, [f if math.isfinite(f) else REJECTED for f in fs])
        rows.append({"peer": "CMA-ES (pycma)", "seed": seed, "designs": used, "objective": best})
        print(rows[-1], file=sys.stderr)

    from pymoo.algorithms.soo.nonconvex.ga import GA
    from pymoo.core.problem import Problem
    from pymoo.optimize import minimize
    from pymoo.termination import get_termination

    class Drift(Problem):
        def __init__(self):
            super().__init__(n_var=d, n_obj=1, xl=0.0, xu=1.0)
            self.seen = []

        def _evaluate(self, x, out, *args, **kwargs):
            fs = evaluate(x)
            self.seen.extend(fs.tolist())
            out["F"] = np.where(np.isfinite(fs), fs, REJECTED)

    for seed in SEEDS:
        problem = Drift()
        minimize(problem, GA(pop_size=16), get_termination("n_eval", budget), seed=seed, verbose=False)
        got = problem.seen[:budget]
        rows.append({"peer": "GA (pymoo, population 16)", "seed": seed, "designs": len(got), "objective": min(got)})
        print(rows[-1], file=sys.stderr)

    import nevergrad as ng

    for seed in SEEDS:
        param = ng.p.Array(init=np.full(d, 0.5), lower=0.0, upper=1.0)
        param.random_state = np.random.RandomState(seed)
        opt = ng.optimizers.NGOpt(parametrization=param, budget=budget, num_workers=1)
        best, chose = math.inf, None
        for _ in range(budget):
            x = opt.ask()
            if chose is None:
                # the optimizer NGOpt chose for this dimension, budget and one worker
                inner = opt
                while getattr(inner, "optim", None) is not None:
                    inner = inner.optim
                chose = getattr(inner, "name", type(inner).__name__)
            f = float(evaluate([x.value])[0])
            best = min(best, f)
            opt.tell(x, f if math.isfinite(f) else REJECTED)
        rows.append({"peer": f"NGOpt (nevergrad, chose {chose})", "seed": seed, "designs": budget, "objective": best})
        print(rows[-1], file=sys.stderr)

    write(case, spec, command, stem, budget, best_known, model, rows, same, check,
          len(asked) * spec["runs"], regraded=False)


def regrade(case):
    """Rewrites a case's peers files from their own runs against the best design now known
    and the model row now benched (results/optimizer/<case>.json, which a later bench run
    may have changed): no peer is simulated, the peers' designs being the same in number;
    a new model row's optimum is, once, to check the package gives its number. The file
    says it was re-read."""
    spec, command, stem, bench, model = case_files(case)
    old = json.load(open(os.path.join(OUT, stem + ".json")))
    same, check = old["objective_reproduced_bit_for_bit"], model["objective"]
    if old["model_refiner"]["objective"] != model["objective"]:
        # a new model row: the peers' runs still hold at the same number of designs
        # (they never read the model row but for its count), once the package gives the
        # new row's number too (one design simulated)
        budget = SWEEP_DESIGNS + model["refine_designs"]
        if old["designs_each"] != budget:
            sys.exit(f"{stem}.json gave each peer {old['designs_each']} designs, the model row now "
                     f"has {budget}: run {command} again")
        with tempfile.TemporaryDirectory() as folder:
            study = slipload.load_study(study_dict(case, folder))
        check = float(slipload.evaluate_objectives(
            study, np.array([model["slip_loads_kN"]], dtype=float) * 1e3, progress=False)[0, 0])
        same = bool(abs(check - model["objective"]) <= 1e-12 * abs(model["objective"]))
        print(f"the study's objective through evaluate_objectives: {check!r} against optimize's {model['objective']!r}", file=sys.stderr)
    write(case, spec, command, stem, old["designs_each"], bench["best_known"]["objective"], model,
          old["runs"], same, check, old.get("simulations_run"), regraded=True)


def write(case, spec, command, stem, budget, best_known, model, rows, same, check, simulations,
          regraded):
    for r in rows:
        r["gap_percent"] = 100.0 * (r["objective"] / best_known - 1.0)
    summary = {}
    for peer in sorted({r["peer"] for r in rows}):
        vals = [r["objective"] for r in rows if r["peer"] == peer]
        summary[peer] = {"median": statistics.median(vals), "best": min(vals)}
    gap = 100 * (model["objective"] / best_known - 1)
    result = {
        "case": ("configs/study-ten-story-check.json, neutral start" if case == "ten"
                 else f"{spec['name']} (scripts/optimizer_cases.py), neutral start"),
        "command": command,
        "designs_each": budget,
        "best_known": best_known,
        "model_refiner": {"objective": model["objective"], "designs": budget},
        "objective_reproduced_bit_for_bit": same,
        # the distinct designs the peers asked for, each the study's simulations once
        "simulations_run": simulations,
        "runs": rows,
        "summary": summary,
    }
    with open(os.path.join(OUT, stem + ".json"), "w") as f:
        json.dump(result, f, indent=1)
    with open(os.path.join(OUT, stem + ".md"), "w") as f:
        f.write(f"# Peers at equal simulations: {LABEL[case]}, {budget} designs of {spec['runs']} simulations each\n\n")
        again = (f"; the gaps re-read against the best design known since by "
                 f"`python3 scripts/optimizer_peers.py {case} --regrade`" if regraded else "")
        f.write(f"Best known {best_known:.7f}; the model refiner's row (neutral start, sweep and refinement designs) {model['objective']:.6f} ({gap:+.2f} %). Made by `{command}`{again}.\n\n")
        f.write("| optimiser | seed | designs | best objective | vs best known |\n|---|---:|---:|---:|---:|\n")
        f.write(f"| model refiner (slipload) | — | {budget} | {model['objective']:.6f} | {gap:+.2f} % |\n")
        for r in rows:
            f.write(f"| {r['peer']} | {r['seed']} | {r['designs']} | {r['objective']:.6f} | {r['gap_percent']:+.2f} % |\n")
        f.write(f"\nOver the seeds, against the model refiner's {gap:+.2f} %:\n\n| optimiser | best | median |\n|---|---:|---:|\n")
        for peer, s in summary.items():
            f.write(f"| {peer} | {100 * (s['best'] / best_known - 1):+.2f} % | {100 * (s['median'] / best_known - 1):+.2f} % |\n")
        if not same:
            f.write(f"\nThe study's objective through `evaluate_objectives` ({check!r}) is not the number `optimize` reported ({model['objective']!r}) to 1e-12: the peers' numbers are not comparable.\n")
    print(open(os.path.join(OUT, stem + ".md")).read())


if __name__ == "__main__":
    if "--regrade" in sys.argv:
        regrade(sys.argv[1])
    else:
        main()
