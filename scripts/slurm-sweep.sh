#!/usr/bin/env bash
# Runs a study's sweep as a Slurm job array, one shard per array task, then merges the
# shards into the files a single run writes.
#
#   scripts/slurm-sweep.sh STUDY OUT_DIR [SHARDS]     (on a login node; paths relative to
#                                                       where it is called from)
#
# Each array task runs `slipload sweep STUDY --shard auto --resume` into OUT_DIR/shard-I
# (the index comes from SLURM_ARRAY_TASK_ID, the count from SLURM_ARRAY_TASK_COUNT);
# `--resume` makes a requeued or restarted task continue its journal instead of starting
# over. A dependent job runs `slipload merge`. Set SBATCH_ARGS for partition/account, e.g.
# SBATCH_ARGS="--partition=short --account=proj".
set -euo pipefail
study=${1:?usage: slurm-sweep.sh STUDY OUT_DIR [SHARDS]}
out=${2:?usage: slurm-sweep.sh STUDY OUT_DIR [SHARDS]}
shards=${3:-8}
[[ $shards =~ ^[1-9][0-9]*$ ]] || {
    echo "slurm-sweep.sh: SHARDS must be a positive whole number, got '$shards'" >&2
    exit 1
}
[[ -f $study ]] || {
    echo "slurm-sweep.sh: study file $study not found" >&2
    exit 1
}
# Resolve the caller's paths before moving to the repo root to build.
study=$(realpath "$study")
mkdir -p "$out"
out=$(realpath "$out")
cd "$(dirname "$0")/.."
cargo build --release --quiet -p slipload
target=$(realpath "${CARGO_TARGET_DIR:-target}")
bin=$target/release/slipload
threads=${SLIPLOAD_THREADS:-2}
# The job scripts are run by sh: quote every path for it (spaces, quotes).
q() { printf '%q' "$1"; }
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_ARGS:-} \
    --job-name=slipload-sweep --array=0-$((shards - 1)) \
    --cpus-per-task="$threads" --time=02:00:00 \
    --output="$out/slurm-%A_%a.log" \
    --wrap="$(q "$bin") --threads $threads sweep $(q "$study") --out $(q "$out")/shard-\$SLURM_ARRAY_TASK_ID --shard auto --resume --quiet")
dirs=$(for i in $(seq 0 $((shards - 1))); do printf '%s ' "$(q "$out/shard-$i")"; done)
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_ARGS:-} \
    --job-name=slipload-merge --dependency=afterok:"$array" \
    --time=00:20:00 --output="$out/slurm-merge-%j.log" \
    --wrap="$(q "$bin") merge $dirs--out $(q "$out/merged")")
echo "submitted array job $array ($shards shards) and merge job $merge; results in $out/merged"
