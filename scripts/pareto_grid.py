#!/usr/bin/env python3
"""The grid check of a two-objective front (scripts/pareto.sh): reads the responses of a
grid sweep (responses.csv) and a study's pareto.csv/pareto.json, takes every grid
design's (mean peak drift ratio, mean peak floor acceleration) over the records, the
grid's front and the search's front, and prints as JSON both fronts, the reference point
(the grid front's nadir plus 10 % of its range in each objective, as docs/MODEL.md
states), both hypervolumes and their ratio. crates/opt/tests/pareto_grid_check.rs
recomputes the hypervolumes of the committed fronts with slipload's own code."""
import csv
import json
import sys

MARGIN = 0.1


def front(points):
    """The non-dominated points (minimisation), sorted by the first objective."""
    pts = sorted(set(points))
    out = []
    best = float("inf")
    for p in pts:
        if p[1] < best:
            out.append(p)
            best = p[1]
    return out


def hypervolume(points, ref):
    area, prev = 0.0, ref[1]
    for p in sorted(points):
        if p[0] < ref[0] and p[1] < prev:
            area += (ref[0] - p[0]) * (prev - p[1])
            prev = p[1]
    return area


def main(responses, pareto_csv, pareto_json):
    rows = {}
    with open(responses, newline="") as f:
        for r in csv.DictReader(f):
            drift = max(float(v) for k, v in r.items() if k.startswith("drift_ratio_"))
            acc = float(r["peak_floor_acceleration_m_s2"])
            rows.setdefault(int(r["design"]), []).append((drift, acc))
    records = len(rows[0])
    # the mean as slipload sums it: in record order, divided by the count
    grid = []
    for d in sorted(rows):
        if d < 2:
            continue  # the bare frame and the file's design are not grid points
        rs = rows[d]
        grid.append((sum(r[0] for r in rs) / len(rs), sum(r[1] for r in rs) / len(rs)))
    grid_front = front(grid)
    # the search's own front: the sweep's and the search's designs (the file's and the
    # refinement's, candidates of the study's front too, cost simulations the search's
    # count does not hold)
    search = []
    with open(pareto_csv, newline="") as f:
        for r in csv.DictReader(f):
            if r["source"] in ("sweep", "search"):
                v = (r["mean_peak_drift_ratio"], r["mean_peak_floor_acceleration"])
                if "collapsed" not in v:  # a design that collapsed has no point
                    search.append((float(v[0]), float(v[1])))
    search_front = front(search)
    ref = []
    for m in range(2):
        lo = min(p[m] for p in grid_front)
        hi = max(p[m] for p in grid_front)
        ref.append(hi + MARGIN * (hi - lo))
    hv_grid = hypervolume(grid_front, ref)
    hv_search = hypervolume(search_front, ref)
    meta = json.load(open(pareto_json))
    print(json.dumps({
        "objectives": ["mean peak_drift_ratio", "mean peak_floor_acceleration"],
        "reference_point": ref,
        "reference_rule": "the grid front's nadir plus 10 % of its range in each objective",
        "grid": {
            "levels": 21,
            "designs": len(grid),
            "simulations": len(grid) * records,
            "front": [list(p) for p in grid_front],
            "hypervolume": hv_grid,
        },
        "search": {
            "simulations": meta["sweep_fidelity_simulations"],
            "front": [list(p) for p in search_front],
            "hypervolume": hv_search,
        },
        "ratio": hv_search / hv_grid,
    }, indent=1))


if __name__ == "__main__":
    main(*sys.argv[1:4])
