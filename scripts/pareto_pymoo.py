"""slipload's front search against pymoo's NSGA-II, both on slipload's own evaluations, at
equal numbers of sweep-fidelity simulations.

The problem is configs/study-pareto.json (the benchmark building, free slip loads
0-2000 kN per floor, mean peak drift ratio and mean peak floor acceleration over the
embedded synthetic suite of 10 records). For each budget of simulations (500, 1000, 2000:
50, 100, 200 designs, each run over every record) and each of 5 seeds:

- slipload: `slipload.optimize` on the study with the sweep and the front search sized to
  the budget (a Halton sweep of half the designs, its seed the run's seed, and the search
  adding the rest); its front is the non-dominated set of every design the sweep and the
  search evaluated, at the sweep fidelity (pareto.csv), before any check;
- pymoo: NSGA-II (population 20, pymoo's defaults otherwise, the run's seed) whose every
  evaluation is `slipload.evaluate_objectives` on the same study; its front is that of
  its first budget-many evaluated designs.

slipload's search may end a few designs short of its budget (it does not evaluate a
design twice); the simulations each side used are recorded.

Both fronts are measured by their hypervolume up to the reference point of the grid check
(results/pareto/grid-check.json: the 21^3 grid front's nadir plus 10 % of its range), as a
fraction of the grid front's hypervolume. Writes pymoo.json (every run) and pymoo.txt (the
medians) into the folder given: python scripts/pareto_pymoo.py results/pareto
"""

import json
import os
import pathlib
import statistics
import sys
import tempfile

import numpy as np

import slipload

ROOT = pathlib.Path(__file__).resolve().parents[1]
STUDY = ROOT / "configs" / "study-pareto.json"
BUDGETS = [500, 1000, 2000]
SEEDS = [1, 2, 3, 4, 5]
POPULATION = 20


def study_for(budget_designs, seed):
    """The Pareto study with its sweep and search sized to a budget of designs."""
    s = json.loads(STUDY.read_text())
    s["building"] = str(STUDY.parent / s["building"])
    sweep_designs = budget_designs // 2
    # the sweep evaluates its points plus the bare frame and the building file's design
    s["sweep"] = {"sampler": "halton", "points": sweep_designs - 2, "seed": seed}
    s["pareto"] = dict(s.get("pareto", {}), designs=budget_designs - sweep_designs)
    s["name"] = f"{s['name']}-{budget_designs}-{seed}"
    return s


def slipload_front(budget, seed, nr):
    designs = budget // nr
    with tempfile.TemporaryDirectory() as tmp:
        report = slipload.optimize(study_for(designs, seed), pathlib.Path(tmp) / "o", progress=False)
        rows = [l.split(",") for l in report.files["pareto.csv"].splitlines()]
        head, rows = rows[0], rows[1:]
        # the search's own designs: the file's and the refinement's, candidates of the
        # study's front too, are simulations outside the budget
        source = head.index("source")
        rows = [r for r in rows if r[source] in ("sweep", "search")]
        cols = [head.index("mean_peak_drift_ratio"), head.index("mean_peak_floor_acceleration")]
        points = np.array([[float(r[c]) for c in cols] for r in rows])
    ranks = slipload.nondominated_ranks(points)
    front = points[[r == 1 for r in ranks]]
    return front, len(points) * nr


def pymoo_front(budget, seed, study, nr):
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem
    from pymoo.optimize import minimize

    lower = np.array(json.loads(STUDY.read_text())["space"]["free"]["lower_kn"], dtype=float) * 1e3
    upper = np.array(json.loads(STUDY.read_text())["space"]["free"]["upper_kn"], dtype=float) * 1e3
    evaluated = []

    class SlipLoads(Problem):
        def __init__(self):
            super().__init__(n_var=len(lower), n_obj=2, xl=lower, xu=upper)

        def _evaluate(self, x, out, *args, **kwargs):
            f = slipload.evaluate_objectives(study, np.ascontiguousarray(x, dtype=float), progress=False)
            evaluated.extend(f.tolist())
            out["F"] = f

    minimize(SlipLoads(), NSGA2(pop_size=POPULATION), ("n_eval", budget // nr), seed=seed, verbose=False)
    # NSGA-II stops after the generation that reaches the budget: its front is that of
    # the designs it had evaluated when it reached it, in evaluation order
    points = np.array(evaluated[: budget // nr])
    ranks = slipload.nondominated_ranks(points)
    return points[[r == 1 for r in ranks]], len(points) * nr


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else None
    grid = json.loads((ROOT / "results" / "pareto" / "grid-check.json").read_text())
    ref = np.array(grid["reference_point"])
    grid_hv = grid["grid"]["hypervolume"]
    study = slipload.load_study(str(STUDY))
    nr = len(study.records)
    runs = []
    for budget in BUDGETS:
        for seed in SEEDS:
            sf, ssims = slipload_front(budget, seed, nr)
            pf, psims = pymoo_front(budget, seed, study, nr)
            run = {
                "budget": budget,
                "seed": seed,
                "slipload": {"simulations": ssims, "front": sf.tolist(), "hypervolume": slipload.hypervolume(sf, ref)},
                "pymoo": {"simulations": psims, "front": pf.tolist(), "hypervolume": slipload.hypervolume(pf, ref)},
            }
            runs.append(run)
            print(f"budget {budget} seed {seed}: slipload {run['slipload']['hypervolume'] / grid_hv:.4f} ({ssims} sims), pymoo {run['pymoo']['hypervolume'] / grid_hv:.4f} ({psims} sims)", file=sys.stderr)
    lines = [
        "slipload's front search vs pymoo NSGA-II (population 20) on slipload's evaluations, configs/study-pareto.json",
        "hypervolume as a fraction of the 21^3 grid front's (reference point of results/pareto/grid-check.json), median over seeds 1-5",
        "",
        "simulations | slipload | pymoo NSGA-II | larger",
    ]
    summary = []
    for budget in BUDGETS:
        rs = [r for r in runs if r["budget"] == budget]
        s_med = statistics.median(r["slipload"]["hypervolume"] for r in rs) / grid_hv
        p_med = statistics.median(r["pymoo"]["hypervolume"] for r in rs) / grid_hv
        larger = "slipload" if s_med > p_med else "pymoo"
        summary.append({"budget": budget, "slipload_median": s_med, "pymoo_median": p_med, "larger": larger})
        lines.append(f"{budget} | {s_med:.4f} | {p_med:.4f} | {larger}")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if out:
        result = {
            "study": str(STUDY.relative_to(ROOT)),
            "reference_point": ref.tolist(),
            "grid_hypervolume": grid_hv,
            "population": POPULATION,
            "seeds": SEEDS,
            "runs": runs,
            "summary": summary,
        }
        for name, data in [("pymoo.json", json.dumps(result, indent=1) + "\n"), ("pymoo.txt", text)]:
            tmp = out / (name + ".tmp")
            tmp.write_text(data)
            os.replace(tmp, out / name)


if __name__ == "__main__":
    main()
