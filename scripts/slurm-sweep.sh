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
usage="usage: slurm-sweep.sh STUDY OUT_DIR [SHARDS]"
if (($# < 2 || $# > 3)); then
    echo "slurm-sweep.sh: expected 2 or 3 arguments, got $#; $usage" >&2
    exit 2
fi
study=$1
out=$2
shards=${3:-8}
[[ $shards =~ ^[1-9][0-9]*$ ]] || {
    echo "slurm-sweep.sh: SHARDS must be a positive whole number, got '$shards'" >&2
    exit 1
}
[[ -f $study ]] || {
    echo "slurm-sweep.sh: study file $study not found" >&2
    exit 1
}
# A newline in a path would split the merge job's list of shard folders (one a line).
for p in "$study" "$out"; do
    [[ $p != *$'\n'* ]] || {
        echo "slurm-sweep.sh: a path with a newline in it is not supported: give another" >&2
        exit 1
    }
done
# Resolve the caller's paths before moving to the repo root to build.
study=$(realpath "$study")
mkdir -p "$out"
out=$(realpath "$out")
cd "$(dirname "$0")/.."
# SLIPLOAD_BIN: a slipload already built (the check scripts give theirs); else built here.
if [[ -n ${SLIPLOAD_BIN:-} ]]; then
    bin=$(realpath "$SLIPLOAD_BIN")
else
    cargo build --release --quiet -p slipload
    target=$(realpath "${CARGO_TARGET_DIR:-target}")
    bin=$target/release/slipload
fi
threads=${SLIPLOAD_THREADS:-2}
# The job scripts are run by /bin/sh (dash on Debian), which knows no $'…' quoting: quote
# every path in single quotes, a quote inside as '\'' — any byte (spaces, non-ASCII
# letters, quotes, $, `) then reaches the command as it is.
q() { printf "'%s'" "${1//\'/\'\\\'\'}"; }
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_ARGS:-} \
    --job-name=slipload-sweep --array=0-$((shards - 1)) \
    --cpus-per-task="$threads" --time=02:00:00 \
    --output="$out/slurm-%A_%a.log" \
    --wrap="$(q "$bin") --threads $threads sweep $(q "$study") --out $(q "$out")/shard-\$SLURM_ARRAY_TASK_ID --shard auto --resume --quiet")
# The merge job reads its shard folders from a file, one a line: its submission stays a
# few hundred bytes whatever the number of shards (1000 folders on the command line of
# one --wrap would pass the kernel's limit on one argument), and folders of an earlier,
# larger submission in OUT_DIR are not picked up as a glob would.
list=$out/shards.txt
for i in $(seq 0 $((shards - 1))); do printf '%s\n' "$out/shard-$i"; done >"$list"
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_ARGS:-} \
    --job-name=slipload-merge --dependency=afterok:"$array" \
    --time=00:20:00 --output="$out/slurm-merge-%j.log" \
    --wrap="set --; while IFS= read -r d; do set -- \"\$@\" \"\$d\"; done < $(q "$list"); exec $(q "$bin") merge \"\$@\" --out $(q "$out/merged")")
echo "submitted array job $array ($shards shards) and merge job $merge; results in $out/merged"
