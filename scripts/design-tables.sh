#!/usr/bin/env bash
# Regenerates results/benchmark-3story/, results/ten-story/ and results/ten-story-mce/
# (the yielding, P-Delta frame at the design level and at MCE): the design tables
# (design-table.{csv,md,json}), the sweep (designs.csv, responses.csv, manifest.json),
# the refinement (refine.csv, optimum.json, candidates.json), the ranking of the
# candidates (rank.{csv,md,json}) and, for the benchmark, the family table
# (family.{csv,md}: optimum by period scale x intensity scale). Usage: scripts/design-tables.sh (from the repo root).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/slipload
for pair in "benchmark-3story:configs/study-benchmark.json" "ten-story:configs/study-ten-story.json" "ten-story-mce:configs/study-ten-story-mce.json"; do
    name=${pair%%:*}
    study=${pair#*:}
    out=results/$name
    rm -rf "$out"
    "$bin" optimize "$study" --out "$out" --quiet | tee "$out.summary.txt"
    "$bin" rank "$study" --designs "$out/candidates.json" --out "$out" --quiet > /dev/null
    mv "$out.summary.txt" "$out/summary.txt"
    # the journals are working state (resume), not results
    rm -f "$out/journal.jsonl" "$out"/refine-*.jsonl "$out/check.jsonl"
done
# the benchmark optimum over a family: periods × 0.8/1/1.25, records × 0.5/1/1.5
"$bin" table configs/study-benchmark.json --out results/benchmark-3story --quiet > /dev/null
