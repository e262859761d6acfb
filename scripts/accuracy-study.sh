#!/usr/bin/env bash
# Regenerates results/accuracy/: every method x time step against the exact integrator
# (errors, median CPU time, observed orders) for the cases the README discusses.
# Usage: scripts/accuracy-study.sh   (from anywhere)
set -euo pipefail
cd "$(dirname "$0")/.."

records=records
out=results/accuracy
if [ ! -d "$records" ]; then
    echo "$records is missing: the study reads the repository's earthquake records by path" >&2
    exit 1
fi
cargo build --release --quiet -p slipload
bin=target/release/slipload
mkdir -p "$out"

# One-storey paper case under its harmonic force (dissipator with mass, 5 s).
"$bin" accuracy configs/paper-1story-harmonic.json --out "$out" --name paper-1story-harmonic
# Benchmark (massive, chattering dissipators) on Sylmar 090, first 10 s.
"$bin" accuracy configs/benchmark-3story.json --record "$records/SYL090.AT2" --duration 10 \
    --out "$out" --name benchmark-syl090
# The same with massless dissipators (elastic-perfectly plastic elements).
"$bin" accuracy configs/benchmark-3story-massless.json --record "$records/SYL090.AT2" --duration 10 \
    --out "$out" --name benchmark-massless-syl090
# Ten-storey frame on El Centro (I-ELC180) scaled to 0.40 g.
"$bin" accuracy configs/ten-story.json --record "$records/I-ELC180.AT2" --scale-pga-g 0.40 \
    --out "$out" --name ten-story-elcentro-0.40g
# Benchmark over the embedded synthetic suite (10 records): per record and the median.
"$bin" accuracy configs/benchmark-3story.json --synthetic 10 --out "$out" --name benchmark-synthetic-suite
# Why the default step is T1/400: newmark at T1/200, T1/300, T1/400 over the synthetic suite
# (15 s records), both buildings; the summary gives each step's worst record.
for case in "benchmark-3story:benchmark-suite-default-step" "ten-story:ten-story-suite-default-step"; do
    "$bin" accuracy "configs/${case%%:*}.json" --synthetic 10 --duration 15 --methods newmark \
        --dts T1/200,T1/300,T1/400 --out "$out" --name "${case#*:}"
done
python3 scripts/accuracy_summary.py "$out"
echo "results in $out"
