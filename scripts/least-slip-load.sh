#!/usr/bin/env bash
# The least dampers that meet the limits: configs/study-ten-story-least-slip-load.json (the
# ten-storey check example's frame, records, property bounds and limits; objective the
# total slip load in kN) at its own setting (model refiner, 60 evaluations, tolerance
# 0.002, initial radius 0.06, + the post-check), at 120 and 300 evaluations, and at 300
# evaluations with the check example's initial radius 0.15: the long runs set the best
# design known. The residual-drift limit is a rough function of the slip loads, so the
# runs end at different local optima. (The setting's radius: at 60 evaluations an
# initial radius of 0.15 ended at 2237.7 kN and 0.03 at 2399.3 kN, against 2166.1 kN
# with 0.06, measured once each while writing this script.)
#
# Writes results/least-slip-load/summary.md (one row per run: total slip load, its gap to
# the best known, the slip loads, the governing limit at the check fidelity, designs,
# simulations, wall time, why it stopped, the post-check) and summary.json, and the
# default run's printed summary (summary.txt, without its wall-time line and the lines
# naming the scratch folder). Usage: scripts/least-slip-load.sh   (about 15 min)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=${CARGO_TARGET_DIR:-$PWD/target}/release/slipload
out=results/least-slip-load
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 - "$PWD" "$tmp" <<'EOF'
import json, os, sys
root, tmp = sys.argv[1:3]
configs = os.path.join(root, "configs")
study = json.load(open(os.path.join(configs, "study-ten-story-least-slip-load.json")))
for s in study["suites"]:
    s["records"] = [os.path.normpath(os.path.join(configs, r)) for r in s["records"]]
study["building"] = os.path.join(configs, study["building"])
for evals, radius in ((60, 0.06), (120, 0.06), (300, 0.06), (300, 0.15)):
    x = json.loads(json.dumps(study))
    x["refine"]["max_evaluations"] = evals
    x["refine"]["initial_radius"] = radius
    json.dump(x, open(os.path.join(tmp, f"model.{evals}-{radius}.json"), "w"), indent=1)
EOF
for row in 60-0.06 120-0.06 300-0.06 300-0.15; do
    echo "== least slip load: model, $row (evaluations-initial radius)" >&2
    "$bin" --threads 2 optimize "$tmp/model.$row.json" --out "$tmp/out.$row" --quiet > "$tmp/model.$row.txt"
done
grep -v -e ' simulations run in ' -e '^wrote ' -e '^figures ' "$tmp/model.60-0.06.txt" > "$out/summary.txt"

python3 - "$tmp" "$out" <<'EOF'
import json, os, re, sys
tmp, out = sys.argv[1:3]
runs = []
for evals, radius in ((60, 0.06), (120, 0.06), (300, 0.06), (300, 0.15)):
    text = open(os.path.join(tmp, f"model.{evals}-{radius}.txt")).read()
    opt = json.load(open(os.path.join(tmp, f"out.{evals}-{radius}", "optimum.json")))
    sims = re.search(r"^(\d+) simulations run in ([0-9.]+) s", text, re.M)
    runs.append({
        "max_evaluations": evals, "initial_radius": radius, "refine_designs": opt["refine_evaluations"],
        "total_slip_load_kN": opt["objective_value"], "slip_loads_kN": opt["slip_loads_kN"],
        "verdict": (opt.get("check") or {}).get("verdict"), "stops": opt.get("refine_stops"),
        "stationarity": opt.get("stationarity"), "bare_passes": opt.get("bare_passes"),
        "file_objective": opt["file_objective"],
        "simulations": int(sims.group(1)), "seconds": float(sims.group(2)),
    })
best = min(runs, key=lambda r: r["total_slip_load_kN"])
for r in runs:
    r["gap_percent"] = 100.0 * (r["total_slip_load_kN"] / best["total_slip_load_kN"] - 1.0)
json.dump({"case": "ten-story-least-slip-load", "best_known": best, "runs": runs},
          open(os.path.join(out, "summary.json"), "w"), indent=1)
def ratio(v):
    m = re.search(r"ratio ([0-9.]+)", v or "")
    return m.group(1) if m else "—"
def stationary(s):
    if not s:
        return "—"
    if s["stationary"]:
        return "yes"
    return f'no ({s["best_move"]}: {100 * s["best_gain"]:.2f} %, taken)'
lines = [
    "# The least dampers that meet the ten-storey check example's limits",
    "",
    f'Best known: {best["total_slip_load_kN"]:.1f} kN (model, {best["max_evaluations"]} evaluations, initial radius {best["initial_radius"]}); '
    f'the building file\'s design totals {runs[0]["file_objective"]:.1f} kN; the bare frame '
    f'{"meets" if runs[0]["bare_passes"] else "misses"} the limits. Every run has the example\'s 16-point '
    "Halton sweep (18 designs with the bare frame and the file's design), 66 runs a design. "
    "Made by `scripts/least-slip-load.sh`.",
    "",
    "| evaluations (setting) | initial radius | refinement designs | total slip load | vs best known | governing ratio (check) | simulations | wall time | stopped on | stationary |",
    "|---:|---:|---:|---:|---:|---:|---:|---:|---|---|",
]
for r in runs:
    lines.append(
        f'| {r["max_evaluations"]} | {r["initial_radius"]} | {r["refine_designs"]} | {r["total_slip_load_kN"]:.1f} kN | '
        f'{r["gap_percent"]:+.2f} % | {ratio(r["verdict"])} | {r["simulations"]} | {r["seconds"]:.1f} s | '
        f'{", ".join(r["stops"] or [])} | {stationary(r["stationarity"])} |')
lines += ["", "Slip loads per floor (kN), floors 1 to 10:", ""]
for r in runs:
    lines.append(f'- {r["max_evaluations"]} evaluations, initial radius {r["initial_radius"]}: ' + " / ".join(f"{v:.1f}" for v in r["slip_loads_kN"]))
open(os.path.join(out, "summary.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
