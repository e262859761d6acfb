#!/usr/bin/env bash
# Regenerates results/performance/bench.{json,txt}: every `slipload bench` figure beside its
# target (release build; run it on a quiet machine — the figures are CPU times and the
# sweep's parallel efficiency is wall-clock). Usage: scripts/bench.sh [--quick]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/slipload
out=results/performance
mkdir -p "$out"
"$bin" bench --format json "$@" > "$out/bench.json.tmp"
"$bin" bench --format table "$@" > "$out/bench.txt.tmp"
{ echo; echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"; } >> "$out/bench.txt.tmp"
mv "$out/bench.json.tmp" "$out/bench.json"
mv "$out/bench.txt.tmp" "$out/bench.txt"
