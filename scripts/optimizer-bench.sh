#!/usr/bin/env bash
# The refiners on the ten-storey check example (configs/study-ten-story-check.json: 10 free
# slip loads, 2 hazard levels x 11 records x 3 property cases, limits), from the building
# file's design and from a neutral start (every slip load 1500 kN, the middle of the box:
# what a study knows with no design in the building file). Each row is one
# `slipload optimize` with the example's sweep (16 Halton points) and one refiner:
#   - model, 24 evaluations (+ its post-check of 22 moves): the example's setting;
#   - trust-region, 12 evaluations: the example's setting before the model refiner;
#   - trust-region and nelder-mead at 46 evaluations: the model row's refinement designs;
#   - model, 120 evaluations, 2 starts: the long run that sets the best-known design.
# Writes results/optimizer/ten-story-check.{md,json} (objective at the sweep fidelity,
# the study's own number; its gap to the best known; refinement designs; simulations;
# wall time) and best-known.json (the best design of every run, with its objective).
# Usage: scripts/optimizer-bench.sh   (from anywhere; about 15 min on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=$PWD/target/release/slipload
out=results/optimizer
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$PWD" "$tmp" <<'EOF'
import json, os, sys
root, tmp = sys.argv[1], sys.argv[2]
configs = os.path.join(root, "configs")
study = json.load(open(os.path.join(configs, "study-ten-story-check.json")))
for s in study["suites"]:
    s["records"] = [os.path.normpath(os.path.join(configs, r)) for r in s["records"]]
building = json.load(open(os.path.join(configs, "ten-story-yielding.json")))
for d in building["dissipators"]:
    d["slip_load"] = "1500 kN"
building["name"] = "ten-story-yielding, every slip load 1500 kN"
json.dump(building, open(os.path.join(tmp, "neutral-building.json"), "w"), indent=1)
starts = {"file": os.path.join(configs, "ten-story-yielding.json"),
          "neutral": os.path.join(tmp, "neutral-building.json")}
rows = [("model", 24, 1), ("trust-region", 12, 1), ("trust-region", 46, 1),
        ("nelder-mead", 46, 1), ("model", 120, 2)]
for start, path in starts.items():
    for method, evals, n in rows:
        x = json.loads(json.dumps(study))
        x["building"] = path
        x["refine"].update(method=method, max_evaluations=evals, starts=n)
        json.dump(x, open(os.path.join(tmp, f"{start}.{method}.{evals}.json"), "w"), indent=1)
EOF
for f in "$tmp"/*.*.*.json; do
    name=$(basename "$f" .json)
    echo "== $name" >&2
    "$bin" --threads 2 optimize "$f" --out "$tmp/out.$name" --quiet > "$tmp/$name.txt" || true
done
python3 - "$tmp" "$out" <<'EOF'
import csv, json, os, re, sys
tmp, out = sys.argv[1], sys.argv[2]
runs = []
for name in sorted(os.listdir(tmp)):
    if not (name.endswith(".txt") and name.count(".") == 3):
        continue
    start, method, evals, _ = name.split(".")
    text = open(os.path.join(tmp, name)).read()
    folder = os.path.join(tmp, "out." + name[:-4])
    opt = json.load(open(os.path.join(folder, "optimum.json")))
    sims = re.search(r"^(\d+) simulations run in ([0-9.]+) s", text, re.M)
    # the best design the run evaluated at the sweep fidelity (the study's objective)
    best = None
    with open(os.path.join(folder, "refine.csv")) as f:
        for row in csv.DictReader(f):
            try:
                v = float(row["objective"])
            except ValueError:  # "collapsed", "inf": no number
                v = float("inf")
            if best is None or v < best[0]:
                best = (v, [float(row[k]) for k in row if k.startswith("slip_load_kN_")])
    runs.append({
        "start": start, "refiner": method, "max_evaluations": int(evals),
        "refine_designs": opt["refine_evaluations"], "objective": opt["objective_value"],
        "slip_loads_kN": opt["slip_loads_kN"], "stops": opt.get("refine_stops"),
        "stationarity": opt.get("stationarity"), "simulations": int(sims.group(1)),
        "seconds": float(sims.group(2)), "verdict": (opt.get("check") or {}).get("verdict"),
        "best_evaluated": best[0] if best else None,
    })
best_known = min(runs, key=lambda r: r["objective"])
for r in runs:
    r["gap_percent"] = 100.0 * (r["objective"] / best_known["objective"] - 1.0)
order = {("model", 24): 0, ("trust-region", 12): 1, ("trust-region", 46): 2, ("nelder-mead", 46): 3, ("model", 120): 4}
runs.sort(key=lambda r: (r["start"] != "neutral", order[(r["refiner"], r["max_evaluations"])]))
json.dump({"case": "configs/study-ten-story-check.json", "best_known": best_known, "runs": runs},
          open(os.path.join(out, "ten-story-check.json"), "w"), indent=1)
json.dump({"ten-story-check": {"objective": best_known["objective"],
                               "slip_loads_kN": best_known["slip_loads_kN"],
                               "found_by": f'{best_known["refiner"]} {best_known["max_evaluations"]} from the {best_known["start"]} start'}},
          open(os.path.join(out, "best-known.json"), "w"), indent=1)
with open(os.path.join(out, "ten-story-check.md"), "w") as f:
    f.write("# Refiners on the ten-storey check example (10 slip loads, 66 runs per design)\n\n")
    f.write(f'Best known: {best_known["objective"]:.7f} ({best_known["refiner"]}, {best_known["max_evaluations"]} evaluations, {best_known["start"]} start); every run has the example\'s 16-point sweep (18 designs with the bare frame and the file\'s design). Made by `scripts/optimizer-bench.sh`.\n\n')
    f.write("| start | refiner | evaluations (setting) | refinement designs | objective | vs best known | simulations | wall time | stopped on | stationary |\n|---|---|---:|---:|---:|---:|---:|---:|---|---|\n")
    for r in runs:
        st = r["stationarity"]
        stat = "—" if st is None else ("yes" if st["stationary"] else f'no ({st["best_move"]}: {100*st["best_gain"]:.2f} %, taken)')
        f.write(f'| {r["start"]} | {r["refiner"]} | {r["max_evaluations"]} | {r["refine_designs"]} | {r["objective"]:.6f} | {r["gap_percent"]:+.2f} % | {r["simulations"]} | {r["seconds"]:.1f} s | {", ".join(r["stops"] or [])} | {stat} |\n')
print(open(os.path.join(out, "ten-story-check.md")).read())
EOF
