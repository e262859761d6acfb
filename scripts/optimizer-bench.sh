#!/usr/bin/env bash
# The refiners in ten, twenty and forty dimensions. Each row is one `slipload optimize`
# with the case's 16-point Halton sweep and one refiner; the objective is the study's own
# number (sweep fidelity). The cases (buildings, studies, rows) are defined once in
# scripts/optimizer_cases.py, which scripts/optimizer_peers.py reads too.
#
# ten: the ten-storey check example (configs/study-ten-story-check.json: 10 free slip
# loads, 2 hazard levels x 11 records x 3 property cases, limits; 66 runs a design), from
# the building file's design and from a neutral start (every slip load 1500 kN, the middle
# of the box: what a study knows with no design in the building file):
#   - model, 48 evaluations (+ its post-check of 22 moves): the example's setting;
#   - trust-region, 12 evaluations: the example's setting before the model refiner;
#   - trust-region and nelder-mead at 70 evaluations: the model row's refinement designs;
#   - model, 120 evaluations, 2 starts: the long run that sets the best-known design.
#   - sqp, 22 evaluations after the example's 4-point sweep (the example's setting), and
#     sqp at the project's default budget, 2 starts of 40 (what `auto` runs here).
# twenty: a twenty-storey yielding frame written here (storey stiffness 900 to 520 MN/m,
# yield at 0.75 % drift, post-yield 2 %, P-Delta, modal damping 2 %, a massless damper per
# floor on a brace as stiff as its storey, slip loads 0-6000 kN) under the example's
# design-level suite with its property bounds and limit (33 runs a design), from the
# neutral start (every slip load 3000 kN): model at 60 evaluations (+ 42 post-check
# moves), trust-region and nelder-mead at its 102, model at 240 as the long run.
# forty: the same frame at forty storeys (storey stiffness 700 to 350 MN/m, bare-frame
# T1 = 3.94 s; slip loads 0-12000 kN, twice what the dampers need: in a 0-6000 kN box the
# optimum pressed most floors against the bound), the same suite, from the neutral start
# (6000 kN, uniform slip loads near their best scale: see scripts/optimizer_cases.py): model at 120
# evaluations (3 a slip load, as in the other cases, + 82 post-check moves), trust-region
# and nelder-mead at its 202, model at 480 as the long run. A forty-storey design takes
# about 2 s on 2 cores, so the long run alone may take up to ~20 min (580 designs if it
# spends its whole budget) and the case about 40 min.
#
# Writes results/optimizer/{ten-story-check,twenty-story,forty-story}.{md,json}
# (objective, its gap to the best known, refinement designs, simulations, wall time, why
# it stopped, the post-check) and best-known.json (each case's best design with its
# objective, what found it and the digest of the case it holds for: a later run keeps it
# while the case is the same and no row does better). Builds into $CARGO_TARGET_DIR when
# it is set, else target/.
# Usage: scripts/optimizer-bench.sh [ten|twenty|forty]...   (from anywhere; about 15, 8
# and 40 min; no argument: ten and twenty)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=${CARGO_TARGET_DIR:-$PWD/target}/release/slipload
out=results/optimizer
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cases=${*:-ten twenty}

for case in $cases; do
    mkdir -p "$tmp/$case"
    python3 - "$PWD" "$tmp/$case" "$case" <<'EOF'
import json, os, sys
root, tmp, case = sys.argv[1:4]
sys.path.insert(0, os.path.join(root, "scripts"))
from optimizer_cases import write_case
study, starts, rows = write_case(root, case, tmp)
only = os.environ.get("ONLY")
for start, path in starts.items():
    for method, evals, n_starts, points in rows:
        if only and method != only:
            continue
        x = json.loads(json.dumps(study))
        x["building"] = path
        x["sweep"]["points"] = points
        x["refine"].update(method=method, max_evaluations=evals, starts=n_starts)
        json.dump(x, open(os.path.join(tmp, f"{start}.{method}.{evals}.json"), "w"), indent=1)
EOF
    for f in "$tmp/$case"/*.*.*.json; do
        name=$(basename "$f" .json)
        echo "== $case: $name" >&2
        "$bin" --threads 2 optimize "$f" --out "$tmp/$case/out.$name" --quiet > "$tmp/$case/$name.txt"
    done
    python3 - "$tmp/$case" "$out" "$case" "$PWD" <<'EOF'
import json, os, re, sys
tmp, out, case, root = sys.argv[1:5]
sys.path.insert(0, os.path.join(root, "scripts"))
from optimizer_cases import CASES, MODEL_ROW, case_key
name, title = CASES[case]["name"], CASES[case]["title"]
key = case_key(root, case, os.path.join(tmp, "key"))
runs = []
for f in sorted(os.listdir(tmp)):
    if not (f.endswith(".txt") and f.count(".") == 3):
        continue
    start, method, evals, _ = f.split(".")
    text = open(os.path.join(tmp, f)).read()
    opt = json.load(open(os.path.join(tmp, "out." + f[:-4], "optimum.json")))
    sims = re.search(r"^(\d+) simulations run in ([0-9.]+) s", text, re.M)
    sweep = re.search(r"^sweep: (\d+) designs", text, re.M)
    runs.append({
        "start": start, "refiner": method, "max_evaluations": int(evals),
        "sweep_designs": int(sweep.group(1)),
        "refine_designs": opt["refine_evaluations"], "objective": opt["objective_value"],
        "slip_loads_kN": opt["slip_loads_kN"], "stops": opt.get("refine_stops"),
        "stationarity": opt.get("stationarity"), "simulations": int(sims.group(1)),
        "seconds": float(sims.group(2)), "verdict": (opt.get("check") or {}).get("verdict"),
    })
# ONLY=<refiner> ran that refiner's rows alone: the other rows stand as the last full run
# measured them
only = os.environ.get("ONLY")
if only:
    previous = json.load(open(os.path.join(out, name + ".json")))["runs"]
    runs += [r for r in previous if r["refiner"] != only]
for r in runs:
    r.setdefault("sweep_designs", 18)
# the best design known: this run's best, or the one kept from an earlier run of the
# same case (same study, buildings and records) where that one is better
best_run = min(runs, key=lambda r: r["objective"])
known_path = os.path.join(out, "best-known.json")
known = json.load(open(known_path)) if os.path.exists(known_path) else {}
kept = known.get(name)
if kept and kept.get("case_key") == key and kept["objective"] < best_run["objective"]:
    best_known = dict(kept, found_by=kept["found_by"].split("; kept")[0] + "; kept from an earlier run of this script")
else:
    best_known = {"objective": best_run["objective"], "slip_loads_kN": best_run["slip_loads_kN"],
                  "found_by": f'{best_run["refiner"]} {best_run["max_evaluations"]} from the {best_run["start"]} start',
                  "case_key": key}
for r in runs:
    r["gap_percent"] = 100.0 * (r["objective"] / best_known["objective"] - 1.0)
# the model row (the default budget) first, then the others by budget, the long run last
runs.sort(key=lambda r: (r["start"] != "neutral", r["refiner"] != "model" or r["max_evaluations"] != MODEL_ROW[case],
                         r["max_evaluations"], r["refiner"]))
json.dump({"case": name, "best_known": best_known, "runs": runs},
          open(os.path.join(out, name + ".json"), "w"), indent=1)
known[name] = best_known
json.dump(dict(sorted(known.items())), open(known_path, "w"), indent=1)
with open(os.path.join(out, name + ".md"), "w") as f:
    f.write(f"# {title}\n\n")
    f.write(f'Best known: {best_known["objective"]:.7f} ({best_known["found_by"]}); every run has a Halton sweep (the sweep designs count the bare frame and the file\'s design; the sqp rows run the example\'s 4-point sweep, the others the 16-point sweep they were measured with). Made by `scripts/optimizer-bench.sh {case}` (`ONLY=sqp scripts/optimizer-bench.sh {case}` runs the sqp rows alone and keeps the others).\n\n')
    f.write("| start | refiner | evaluations (setting) | sweep designs | refinement designs | objective | vs best known | simulations | wall time | stopped on | stationary |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|\n")
    for r in runs:
        st = r["stationarity"]
        first = st is not None and st.get("polls", 1) == 0
        flagged = st is not None and st.get("screened", 0) > 0 and not first
        how = " (first order)" if first else (f' (screened by the derivatives, the {st["moves"]} flagged moves simulated)' if flagged else "")
        stat = "—" if st is None else ("yes" + how if st["stationary"] else f'no ({st["best_move"]}: {100*st["best_gain"]:.2f} %, {"first order" if first else "taken"})')
        f.write(f'| {r["start"]} | {r["refiner"]} | {r["max_evaluations"]} | {r["sweep_designs"]} | {r["refine_designs"]} | {r["objective"]:.6f} | {r["gap_percent"]:+.2f} % | {r["simulations"]} | {r["seconds"]:.1f} s | {", ".join(r["stops"] or [])} | {stat} |\n')
print(open(os.path.join(out, name + ".md")).read())
EOF
done
