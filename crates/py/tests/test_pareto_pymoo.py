"""The committed comparison with pymoo (results/pareto/pymoo.json, scripts/pareto-pymoo.sh)
holds its arithmetic: every run's hypervolume is that of its committed front, the medians
are those of the runs, each side kept to its budget of simulations, and the claim in
pymoo.txt — slipload's front is the larger at every budget — follows from the numbers."""

import json
import statistics

import numpy as np

import slipload

from conftest import ROOT

RESULTS = ROOT / "results" / "pareto"


def test_the_committed_pymoo_comparison_holds_its_arithmetic():
    data = json.loads((RESULTS / "pymoo.json").read_text())
    grid = json.loads((RESULTS / "grid-check.json").read_text())
    ref = np.array(data["reference_point"])
    assert data["reference_point"] == grid["reference_point"]
    assert data["grid_hypervolume"] == grid["grid"]["hypervolume"]
    for run in data["runs"]:
        for side in ["slipload", "pymoo"]:
            r = run[side]
            front = np.array(r["front"])
            assert r["simulations"] <= run["budget"], (run["budget"], side)
            assert slipload.nondominated_ranks(front) == [1] * len(front)
            assert slipload.hypervolume(front, ref) == r["hypervolume"]
    text = (RESULTS / "pymoo.txt").read_text()
    for s in data["summary"]:
        runs = [r for r in data["runs"] if r["budget"] == s["budget"]]
        assert len(runs) == 5
        sm = statistics.median(r["slipload"]["hypervolume"] for r in runs) / data["grid_hypervolume"]
        pm = statistics.median(r["pymoo"]["hypervolume"] for r in runs) / data["grid_hypervolume"]
        assert (sm, pm) == (s["slipload_median"], s["pymoo_median"])
        assert s["larger"] == ("slipload" if sm > pm else "pymoo")
        assert f"{s['budget']} | {sm:.4f} | {pm:.4f} | {s['larger']}" in text
    assert all(s["larger"] == "slipload" for s in data["summary"])
