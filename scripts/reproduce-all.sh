#!/usr/bin/env bash
# Regenerates everything under results/ with its figures, then one HTML report per folder:
#   results/paper/        the paper's examples (scripts/reproduce-paper.sh)
#   results/accuracy/     accuracy vs cost, work-precision figures (scripts/accuracy-study.sh)
#   results/benchmark-3story/, results/ten-story/, results/ten-story-mce/  design tables
#                         and study figures
#                         (scripts/design-tables.sh)
#   results/refiners/     the refiners against an exhaustive grid (scripts/refiner-comparison.sh)
#   results/performance/  `slipload bench` and the OpenSees comparisons (same step; equal accuracy)
#   results/opensees-yielding/  the yielding, P-Delta frame against OpenSees
#   results/figures/      the simulation and spectrum figures the README shows
# Usage: scripts/reproduce-all.sh   (from anywhere;
# about 22 minutes on a 2-core machine, most of it the accuracy study and the OpenSees runs).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=target/release/slipload

scripts/reproduce-paper.sh
scripts/accuracy-study.sh
scripts/design-tables.sh
scripts/refiner-comparison.sh
scripts/bench.sh
python3 scripts/compare-opensees.py
python3 scripts/compare-opensees-yielding.py
python3 scripts/compare-opensees-precision.py

fig=results/figures
rm -rf "$fig"
mkdir -p "$fig"
# The benchmark under Sylmar 090 with and without dampers (the paper's Figs. 6-7, 10, 13).
"$bin" simulate configs/paper-benchmark-sylmar.json --plot "$fig/benchmark-sylmar" --compare-bare --format table > "$fig/benchmark-sylmar.txt"
# The yielding ten-storey frame at MCE: storey shear-drift loops beside the dampers'.
"$bin" simulate configs/ten-story-yielding.json --record records/RSN1106_KOBE_KJM000.AT2 --scale-pga-g 0.6 --window 5,25 --plot "$fig/ten-story-yielding-mce" --format table > "$fig/ten-story-yielding-mce.txt"
# The embedded synthetic suite's spectra with the ASCE 7 design spectrum it is scaled near.
"$bin" record spectrum --synthetic 10 --plot "$fig/suite-spectra" > /dev/null

for dir in results/paper results/accuracy results/benchmark-3story results/ten-story results/ten-story-mce "$fig/benchmark-sylmar" "$fig/ten-story-yielding-mce"; do
    "$bin" report "$dir" > /dev/null
done
echo "results/ regenerated; open results/*/report.html"
