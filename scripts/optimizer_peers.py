"""Peers of the model refiner on the ten-storey check example, at equal simulations.

CMA-ES (pycma) and pymoo's genetic algorithm minimise the study's own objective of
configs/study-ten-story-check.json (mean peak storey drift ratio, worst of the three
property cases, averaged over both hazard levels; a design that misses a limit or
collapses scores +inf, as the refiners see it) through the Python package: each design is
the study's 66 simulations at its sweep fidelity (`slipload.evaluate_objectives`, whose
first objective, the study's drift objective, is checked below against the number
`optimize` reported for the model refiner's optimum). Each peer gets as many designs as
the model refiner's row of results/optimizer/ten-story-check.json from the neutral start
used in all (sweep and refinement designs; the finalists' check and the design table not
counted), and starts from what it needs, not from a design: CMA-ES from the middle of the
box, the GA from a random population. Seeds 1, 2, 3.

Writes results/optimizer/peers.{json,md}. Usage (with the package and cma, pymoo
installed; scripts/optimizer-peers.sh does that): python3 scripts/optimizer_peers.py
"""

import json
import math
import os
import statistics
import sys

import numpy as np

import slipload

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "results", "optimizer")
SEEDS = [1, 2, 3]
# a design the refiners reject (+inf) is this much, a drift ratio of 100 %, for the peers
# that need finite values; worse than every design that passes
REJECTED = 1.0


def study_dict():
    configs = os.path.join(ROOT, "configs")
    study = json.load(open(os.path.join(configs, "study-ten-story-check.json")))
    for s in study["suites"]:
        s["records"] = [os.path.normpath(os.path.join(configs, r)) for r in s["records"]]
    study["building"] = os.path.join(configs, "ten-story-yielding.json")
    # the study's objective as the first of two objectives (the second is not read)
    study["objectives"] = [
        {"metric": "peak_drift_ratio", "statistic": "mean"},
        {"metric": "peak_floor_acceleration", "statistic": "mean"},
    ]
    return study


def main():
    bench = json.load(open(os.path.join(OUT, "ten-story-check.json")))
    model = next(r for r in bench["runs"] if r["start"] == "neutral" and r["refiner"] == "model" and r["max_evaluations"] == 24)
    sweep_designs = 18  # the example's 16 Halton points, the bare frame and the file's design
    budget = sweep_designs + model["refine_designs"]
    best_known = bench["best_known"]["objective"]
    study = slipload.load_study(study_dict())
    upper = 3000e3  # N, every floor's upper bound (lower 0)
    d = 10

    def evaluate(z):
        loads = np.ascontiguousarray(np.clip(np.asarray(z, dtype=float), 0.0, 1.0) * upper)
        return slipload.evaluate_objectives(study, loads, progress=False)[:, 0]

    # the first objective is the study's: the model refiner's optimum gives its number
    check = evaluate([np.array(model["slip_loads_kN"]) * 1e3 / upper])[0]
    same = bool(check == model["objective"])
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
        seen = problem.seen[:budget]
        rows.append({"peer": "GA (pymoo, population 16)", "seed": seed, "designs": len(seen), "objective": min(seen)})
        print(rows[-1], file=sys.stderr)

    for r in rows:
        r["gap_percent"] = 100.0 * (r["objective"] / best_known - 1.0)
    summary = {}
    for peer in sorted({r["peer"] for r in rows}):
        vals = [r["objective"] for r in rows if r["peer"] == peer]
        summary[peer] = {"median": statistics.median(vals), "best": min(vals)}
    result = {
        "case": "configs/study-ten-story-check.json, neutral start",
        "designs_each": budget,
        "best_known": best_known,
        "model_refiner": {"objective": model["objective"], "designs": budget},
        "objective_reproduced_bit_for_bit": same,
        "runs": rows,
        "summary": summary,
    }
    with open(os.path.join(OUT, "peers.json"), "w") as f:
        json.dump(result, f, indent=1)
    with open(os.path.join(OUT, "peers.md"), "w") as f:
        f.write(f"# Peers at equal simulations: ten-storey check example, {budget} designs of 66 simulations each\n\n")
        f.write(f"Best known {best_known:.7f}; the model refiner's row (neutral start, sweep and refinement designs) {model['objective']:.6f} ({100 * (model['objective'] / best_known - 1):+.2f} %). Made by `scripts/optimizer-peers.sh`.\n\n")
        f.write("| optimiser | seed | designs | best objective | vs best known |\n|---|---:|---:|---:|---:|\n")
        f.write(f"| model refiner (slipload) | — | {budget} | {model['objective']:.6f} | {100 * (model['objective'] / best_known - 1):+.2f} % |\n")
        for r in rows:
            f.write(f"| {r['peer']} | {r['seed']} | {r['designs']} | {r['objective']:.6f} | {r['gap_percent']:+.2f} % |\n")
    print(open(os.path.join(OUT, "peers.md")).read())


if __name__ == "__main__":
    main()
