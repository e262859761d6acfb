#!/usr/bin/env bash
# Regenerates results/benchmark-3story/ and results/ten-story/: the design tables
# (design-table.{csv,md,json}), the sweep (designs.csv, responses.csv, manifest.json),
# the refinement (refine.csv, optimum.json, candidates.json) and the ranking of the
# candidates (rank.{csv,md,json}). Usage: scripts/design-tables.sh (from the repo root).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/slipload
for pair in "benchmark-3story:configs/study-benchmark.json" "ten-story:configs/study-ten-story.json"; do
    name=${pair%%:*}
    study=${pair#*:}
    out=results/$name
    rm -rf "$out"
    "$bin" optimize "$study" --out "$out" --quiet | tee "$out.summary.txt"
    "$bin" rank "$study" --designs "$out/candidates.json" --out "$out" --quiet > /dev/null
    mv "$out.summary.txt" "$out/summary.txt"
    # the journal is the sweep's working state, not a result
    rm -f "$out/journal.jsonl"
done
