#!/usr/bin/env bash
# The 21 x 21 x 21 grid of configs/study-pareto.json's box at the sweep fidelity (9,261
# designs x the suite), its responses written to DIR/responses.csv by `slipload sweep`;
# the grid check of scripts/pareto.sh and scripts/pareto-seeds.sh compares fronts with it.
# Usage: scripts/pareto-grid-sweep.sh BIN DIR   (from the repository root; minutes)
set -euo pipefail
bin=$1
dir=$2
study=$(mktemp --suffix=.json)
trap 'rm -f "$study"' EXIT
python3 - "$PWD/configs" "$study" <<'PY'
import json, sys
configs, target = sys.argv[1], sys.argv[2]
s = json.load(open(f"{configs}/study-pareto.json"))
s["name"] = "benchmark-3story-pareto-grid"
s["building"] = f"{configs}/{s['building']}"
s.pop("objectives"); s.pop("pareto")
s["sweep"] = {"sampler": "grid", "levels": 21}
json.dump(s, open(target, "w"), indent=1)
PY
rm -rf "$dir"
"$bin" sweep "$study" --out "$dir" --quiet > /dev/null
