#!/usr/bin/env bash
# Regenerates results/pareto/: the fronts of configs/study-pareto.json (mean peak drift
# ratio vs mean peak floor acceleration, 1,500 sweep-fidelity simulations) in front-2/
# and configs/study-pareto-3.json (+ mean peak base shear) in front-3/ — each the files
# of `slipload optimize` (pareto.{csv,json}, pareto-table.*, the design table, the front
# figure) and its summary —, then the grid check: the 21 x 21 x 21 grid of the same box
# at the sweep fidelity (9,261 designs x 10 records) and the hypervolume of front-2's
# front against the grid's front (grid-check.json and its one line, grid-check.txt;
# reference point in docs/MODEL.md).
# Usage: scripts/pareto.sh [--skip-grid]   (from anywhere; the grid takes minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=target/release/slipload
out=results/pareto
mkdir -p "$out"
for pair in "front-2:configs/study-pareto.json" "front-3:configs/study-pareto-3.json"; do
    name=${pair%%:*}
    study=${pair#*:}
    dir=$out/$name
    rm -rf "$dir"
    "$bin" optimize "$study" --out "$dir" --quiet | tee "$out/$name.summary.txt"
    mv "$out/$name.summary.txt" "$dir/summary.txt"
    # the journals are working state (resume), not results
    rm -f "$dir/journal.jsonl" "$dir"/refine-*.jsonl "$dir/check.jsonl" "$dir/pareto.jsonl"
done
if [ "${1:-}" = "--skip-grid" ]; then
    exit 0
fi
# the grid: the Pareto study's box, sweep only, 21 levels per floor
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/pareto-grid-sweep.sh "$bin" "$tmp/grid"
python3 scripts/pareto_grid.py "$tmp/grid/responses.csv" "$out/front-2/pareto.csv" "$out/front-2/pareto.json" > "$out/grid-check.json.tmp"
mv "$out/grid-check.json.tmp" "$out/grid-check.json"
python3 -c "import json; d = json.load(open('$out/grid-check.json')); print('hypervolume ratio (search front, %d simulations / 21^3 grid front, %d simulations): %.4f' % (d['search']['simulations'], d['grid']['simulations'], d['ratio']))" | tee "$out/grid-check.txt"
echo "results in $out"
