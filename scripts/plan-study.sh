#!/usr/bin/env bash
# The placement question on the ten-storey building in plan (issue 46): the study in plan
# (configs/study-plan-ten-story.json: one slip load per perimeter line) and the planar
# placement of the same building (configs/study-plan-ten-story-planar.json: one slip load
# per direction, split between a direction's lines by stiffness), both over seven
# two-component events at 0 and 90 degrees. Writes each study folder
# (results/plan-ten-story, results/plan-ten-story-planar: plan-summary.txt,
# plan-optimum.json, plan-designs.csv, plan-dampers.{csv,md}, plan-profiles.csv, the
# plan-view and line-drift-profiles figures, the journal) afresh.
# Usage: scripts/plan-study.sh   (about 2 min on two cores)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
bin=${CARGO_TARGET_DIR:-$PWD/target}/release/slipload
for name in plan-ten-story plan-ten-story-planar; do
  "$bin" --quiet optimize "configs/study-$name.json" --out "results/$name" --fresh
done
