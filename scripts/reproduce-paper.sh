#!/usr/bin/env bash
# Reproduces the examples of De la Cruz, López-Almansa & Oller (2007), Comput. Struct.
# 85:30-42 with every method, into results/paper/: compact CSV histories per case and a
# Markdown table (README.md) of peak drifts, energies, transitions and CPU time per method.
# Run from anywhere; paths are resolved from the repository root. Needs cargo and python3
# (standard library only).
set -euo pipefail

METHODS="delacruz newmark hht bilinear exact"

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
OUT=results/paper
BIN=target/release/slipload
cargo build --release --quiet -p slipload
mkdir -p "$OUT"
RAW="$(mktemp -d)"
trap 'rm -rf "$RAW"' EXIT

# case name | scene file | extra flags
CASES=(
  "1story-free|configs/paper-1story-free.json|"
  "1story-harmonic|configs/paper-1story-harmonic.json|"
  "benchmark-sylmar|configs/paper-benchmark-sylmar.json|"
  "benchmark-sylmar-bare|configs/paper-benchmark-sylmar-bare.json|"
  "ten-story-elcentro|configs/paper-ten-story-elcentro.json|"
)

# run CASE METHOD LABEL SCENE [flags...]: JSON to $RAW/CASE.LABEL.json, history CSV beside
# it, or the error message to $RAW/CASE.LABEL.err (a failing method does not stop the script).
run() {
  local case=$1 method=$2 label=$3 scene=$4
  shift 4
  echo "  $case: $label" >&2
  if "$BIN" simulate "$scene" --method "$method" "$@" --format json \
      --history "$RAW/$case.$label.csv" >"$RAW/$case.$label.json" 2>"$RAW/$case.$label.err"; then
    rm -f "$RAW/$case.$label.err"
  else
    rm -f "$RAW/$case.$label.json"
  fi
}

echo "running the paper's cases with: $METHODS" >&2
for spec in "${CASES[@]}"; do
  IFS='|' read -r case scene flags <<<"$spec"
  for m in $METHODS; do
    # shellcheck disable=SC2086 # flags are words on purpose
    run "$case" "$m" "$m" "$scene" $flags
  done
  # Where delacruz fails at the default step, run it again at the step it suggests.
  if [[ -f "$RAW/$case.delacruz.err" ]]; then
    dt=$(python3 -c 'import re,sys; m=re.search(r"try dt <= ([0-9.eE+-]+) s", open(sys.argv[1]).read()); print(m.group(1) if m else "")' "$RAW/$case.delacruz.err")
    if [[ -n "$dt" ]]; then
      # shellcheck disable=SC2086
      run "$case" delacruz "delacruz-dt$dt" "$scene" --dt "$dt" $flags
    fi
  fi
done

python3 scripts/paper_tables.py "$RAW" "$OUT" "$METHODS"
echo "wrote $OUT/README.md" >&2
