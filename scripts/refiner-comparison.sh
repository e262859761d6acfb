#!/usr/bin/env bash
# How many designs each refiner needs to come within 1 % of the best point of an
# exhaustive 21^3 grid over the benchmark study's space (full suite: 10 records), and
# sweep throughput with 1 and 2 threads. Writes results/refiners/summary.md.
# Usage: scripts/refiner-comparison.sh (from the repo root; ~2-4 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-$PWD/target}/release/slipload
out=results/refiners
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
# the benchmark study with a 21-level grid instead of the Halton sample
sed -e 's/"sampler": "halton", "points": 48, "seed": 2007/"sampler": "grid", "levels": 21/' \
    -e 's#"building": "benchmark-3story.json"#"building": "'"$PWD"'/configs/benchmark-3story.json"#' \
    configs/study-benchmark.json > "$tmp/grid.json"
"$bin" --threads 2 sweep "$tmp/grid.json" --out "$tmp/grid" --quiet 2> "$tmp/grid.log"
grid_best=$(awk -F, 'NR > 3 { if (best == "" || $6 < best) best = $6 } END { printf "%.10g", best }' "$tmp/grid/designs.csv")
grid_designs=$(awk 'END { print NR - 3 }' "$tmp/grid/designs.csv")
{
    echo "# Refiners against an exhaustive grid (benchmark study, 10 records)"
    echo
    echo "Grid: 21 levels per floor, $grid_designs designs ($((grid_designs * 10)) simulations); best objective $grid_best (mean peak drift ratio)."
    echo "Every refiner starts from the same 48-point Halton sweep; \"designs\" counts sweep + refinement designs (each is 10 simulations)."
    echo
    echo "| refiner | optimum | vs grid best | designs to within 1 % | to within 0.25 % | designs in all | share of the grid |"
    echo "|---|---:|---:|---:|---:|---:|---:|"
} > "$out/summary.md"
for r in model trust-region nelder-mead random; do
    "$bin" optimize configs/study-benchmark.json --refine "$r" --out "$tmp/$r" --quiet > "$tmp/$r.txt"
    sweep=$(awk 'END { print NR - 3 }' "$tmp/$r/designs.csv")
    awk -F, -v g="$grid_best" -v s="$sweep" -v r="$r" -v n="$grid_designs" -v sw="$tmp/$r/designs.csv" '
        BEGIN { while ((getline line < sw) > 0) { split(line, a, ","); if (a[2] ~ /^s[0-9]/ && (sb == "" || a[6] < sb)) sb = a[6] } }
        NR > 1 { last = $1; if ($4 < best || best == "") best = $4; if (hit == "" && $4 <= 1.01 * g) hit = s + $1; if (hit2 == "" && $4 <= 1.0025 * g) hit2 = s + $1 }
        END {
            if (sb <= 1.01 * g) hit = s; if (sb <= 1.0025 * g) hit2 = s;
            if (best == "" || sb < best) best = sb;
            total = s + last;
            printf "| %s | %.6f | %+.2f %% | %s | %s | %d | %.1f %% |\n", r, best, 100 * (best / g - 1), (hit == "" ? "never" : hit), (hit2 == "" ? "never" : hit2), total, 100 * total / n
        }' "$tmp/$r/refine.csv" >> "$out/summary.md"
done
# throughput: a 9-level grid sweep of the benchmark study (731 designs x 10 records)
sed -e 's/"levels": 21/"levels": 9/' "$tmp/grid.json" > "$tmp/grid9.json"
{
    echo
    echo "Sweep throughput (benchmark study, 9-level grid: 7310 tasks of 20 s records, release build, shared 2-core machine):"
    echo
    for t in 1 2; do
        rm -rf "$tmp/tp$t"
        "$bin" --threads "$t" sweep "$tmp/grid9.json" --out "$tmp/tp$t" --quiet 2>&1 | grep -o '[0-9.]* tasks/s' | sed "s/^/- $t thread(s): /"
    done
} >> "$out/summary.md"
cat "$out/summary.md"
