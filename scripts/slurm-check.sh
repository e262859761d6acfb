#!/usr/bin/env bash
# Runs scripts/slurm-sweep.sh on a local single-node Slurm and requires that the folder its
# merge job writes is, file for file, the folder one `slipload sweep` of the same study
# writes: every table and figure byte for byte, the journal (the log of finished tasks, in
# the order they finished) line for line in any order. Then submits the same study again
# into the same folder, where every shard must resume its finished journal and the merge
# must write the same files again.
#
#   scripts/slurm-check.sh [STUDY [SHARDS]]     (as root on Debian; default: the small
#                                                 configs/study-slurm-check.json, 3 shards)
#
# It installs munge, slurmctld, slurmd and slurm-client with apt-get when they are missing,
# writes a single-node slurm.conf (no cgroups, no systemd, no accounting) into a temporary
# folder, starts munged, slurmctld and slurmd in the background on that folder, waits until
# the node is idle, submits the sweep, waits for its jobs (bounded; a failed task fails at
# once), runs the single sweep and diffs.
# Everything it started is stopped when it exits, whatever the outcome; on a failure it
# prints the job and daemon logs. Nothing outside the temporary folder is configured: the
# daemons use their own munge socket and key, and the clients find the cluster through
# SLURM_CONF.
#
#   scripts/slurm-check.sh --fake-sbatch        (anyone, no Slurm: only the checks below)
#
# Before any of that (and alone with --fake-sbatch) it checks slurm-sweep.sh's job
# scripts with a fake sbatch that records what it is given and a fake slipload that
# records its arguments: extra arguments are refused with the usage; paths with spaces,
# non-ASCII letters and quotes reach slipload intact when /bin/sh runs the job scripts;
# 1000 shards keep the merge job's submission small (its shard list is a file) and the
# merge job still names every shard.
#
# Environment: SLURM_CHECK_TIMEOUT (seconds the jobs may take, default 300),
# SLURM_CHECK_PORT (slurmctld's port, default 16817; slurmd takes the next one),
# SLURM_CHECK_KEEP=1 keeps the temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
export PATH=$PATH:/usr/sbin:/sbin

fail() {
    echo "slurm-check: $*" >&2
    exit 1
}

# slurm-sweep.sh's job scripts, run by /bin/sh as Slurm runs them, with fake sbatch and
# slipload programs: no cluster, no build, a few seconds.
fake_sbatch_checks() {
    local fake dir study_copy out_dir args n want got wrap merge_wrap i
    fake=$(mktemp -d /tmp/slurm-fake.XXXXXX)
    mkdir -p "$fake/bin"
    # sbatch: each call's arguments (one a line) and its --wrap script, a job id back
    cat >"$fake/bin/sbatch" <<'EOS'
#!/usr/bin/env bash
n=$(($(cat "$FAKE_SBATCH_DIR/count" 2>/dev/null || echo 0) + 1))
echo "$n" >"$FAKE_SBATCH_DIR/count"
printf '%s\n' "$@" >"$FAKE_SBATCH_DIR/call-$n.args"
for a in "$@"; do
    case $a in --wrap=*) printf '%s' "${a#--wrap=}" >"$FAKE_SBATCH_DIR/call-$n.sh" ;; esac
done
echo $((100 + n))
EOS
    # slipload: its arguments, one a line
    cat >"$fake/bin/slipload" <<'EOS'
#!/usr/bin/env bash
printf '%s\n' "$@" >"$FAKE_SBATCH_DIR/slipload.args"
EOS
    chmod 755 "$fake/bin/sbatch" "$fake/bin/slipload"
    export FAKE_SBATCH_DIR=$fake
    run_sweep() {
        rm -f "$fake"/count "$fake"/call-* "$fake"/slipload.args
        # the C locale, as on many clusters: there bash's printf %q writes é as $'\303\251',
        # which /bin/sh cannot read
        LC_ALL=C PATH=$fake/bin:$PATH SLIPLOAD_BIN=$fake/bin/slipload SLIPLOAD_THREADS=1 \
            "$repo/scripts/slurm-sweep.sh" "$@"
    }

    echo "== slurm-check: extra arguments are refused with the usage"
    if run_sweep a.json out 3 extra 2>"$fake/err"; then
        fail "slurm-sweep.sh took a fourth argument"
    fi
    grep -q 'usage: slurm-sweep.sh STUDY OUT_DIR \[SHARDS\]' "$fake/err" || fail "no usage in: $(cat "$fake/err")"
    [[ ! -e $fake/count ]] || fail "slurm-sweep.sh submitted a job on bad arguments"

    echo "== slurm-check: paths with spaces, non-ASCII letters and quotes"
    dir="$fake/répertoire d'essai \$HOME \`x\`"
    mkdir -p "$dir"
    study_copy="$dir/étude n°1.json"
    cp "$repo/configs/study-slurm-check.json" "$study_copy"
    out_dir="$dir/sortie été"
    run_sweep "$study_copy" "$out_dir" 3 >/dev/null
    [[ $(cat "$fake/count") == 2 ]] || fail "expected 2 submissions (array, merge), got $(cat "$fake/count")"
    SLURM_ARRAY_TASK_ID=2 /bin/sh "$fake/call-1.sh" || fail "/bin/sh refused the array job's script: $(cat "$fake/call-1.sh")"
    want=$(printf '%s\n' --threads 1 sweep "$study_copy" --out "$out_dir/shard-2" --shard auto --resume --quiet)
    got=$(cat "$fake/slipload.args")
    [[ $got == "$want" ]] || fail "the array job ran slipload with"$'\n'"$got"$'\n'"not"$'\n'"$want"
    /bin/sh "$fake/call-2.sh" || fail "/bin/sh refused the merge job's script: $(cat "$fake/call-2.sh")"
    want=$(printf '%s\n' merge "$out_dir/shard-0" "$out_dir/shard-1" "$out_dir/shard-2" --out "$out_dir/merged")
    got=$(cat "$fake/slipload.args")
    [[ $got == "$want" ]] || fail "the merge job ran slipload with"$'\n'"$got"$'\n'"not"$'\n'"$want"

    echo "== slurm-check: 1000 shards"
    run_sweep "$study_copy" "$out_dir" 1000 >/dev/null
    grep -qx -- '--array=0-999' "$fake/call-1.args" || fail "the array is not 0-999: $(cat "$fake/call-1.args")"
    n=$(wc -c <"$fake/call-2.args")
    ((n < 4096)) || fail "the merge job's submission takes $n bytes of arguments for 1000 shards"
    /bin/sh "$fake/call-2.sh" || fail "/bin/sh refused the merge job's script"
    want=$( (
        echo merge
        for i in $(seq 0 999); do echo "$out_dir/shard-$i"; done
        printf '%s\n' --out "$out_dir/merged"
    ))
    got=$(cat "$fake/slipload.args")
    [[ $got == "$want" ]] || fail "the merge job of 1000 shards did not name every shard in order"
    unset FAKE_SBATCH_DIR
    rm -rf "$fake"
    echo "fake sbatch checks: ok"
}
if [[ ${1:-} == --fake-sbatch ]]; then
    (($# == 1)) || fail "--fake-sbatch takes no other argument"
    fake_sbatch_checks
    exit 0
fi
(($# <= 2)) || fail "expected at most STUDY and SHARDS, got $# arguments"
fake_sbatch_checks

study=${1:-configs/study-slurm-check.json}
shards=${2:-3}
job_timeout=${SLURM_CHECK_TIMEOUT:-300}
port=${SLURM_CHECK_PORT:-16817}
keep=${SLURM_CHECK_KEEP:-0}
[[ -f $study ]] || fail "study file $study not found"
[[ $shards =~ ^[1-9][0-9]*$ ]] || fail "SHARDS must be a positive whole number, got '$shards'"
[[ $job_timeout =~ ^[1-9][0-9]*$ ]] || fail "SLURM_CHECK_TIMEOUT must be a positive whole number of seconds, got '$job_timeout'"
if ! [[ $port =~ ^[1-9][0-9]{0,4}$ ]] || ((port >= 65535)); then
    fail "SLURM_CHECK_PORT must be a TCP port below 65535, got '$port'"
fi
study=$(realpath "$study")
[[ $(id -u) == 0 ]] || fail "must run as root: it installs packages and starts munged, slurmctld and slurmd"

echo "== slurm-check: packages"
missing=()
command -v munged >/dev/null || missing+=(munge)
command -v slurmctld >/dev/null || missing+=(slurmctld)
command -v slurmd >/dev/null || missing+=(slurmd)
command -v sbatch >/dev/null || missing+=(slurm-client)
if ((${#missing[@]})); then
    command -v apt-get >/dev/null || fail "missing ${missing[*]} and no apt-get to install them (Debian expected)"
    echo "installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    # The packages' scripts would start the daemons on the system's configuration; this
    # check starts its own. A policy-rc.d that refuses (as container images ship) stops them.
    policy=
    if [[ ! -e /usr/sbin/policy-rc.d ]]; then
        policy=/usr/sbin/policy-rc.d
        printf '#!/bin/sh\nexit 101\n' >"$policy"
        chmod 755 "$policy"
    fi
    apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null ||
        install_failed=1
    [[ -z $policy ]] || rm -f "$policy"
    ((!${install_failed:-0})) || fail "apt-get could not install ${missing[*]}"
fi
slurmctld -V

tmp=$(mktemp -d /tmp/slurm-check.XXXXXX)
# The daemons run as root; munged wants its socket's folder searchable, not writable.
chmod 711 "$tmp"
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/log"
# Where the job array writes; a space in its name keeps the job scripts' quoting honest.
out="$tmp/array run"
single=$tmp/single
pids=()
munged_started=0
jobs_to_cancel=()

print_logs() {
    local f d
    for f in "$out"/slurm-*.log "$tmp/log/munged.log"; do
        [[ -f $f ]] || continue
        echo "---- $f (last 60 lines)" >&2
        tail -n 60 "$f" >&2
    done
    # A daemon in the foreground logs to its log file and to stderr; stderr alone holds
    # what it said before it opened the log file (a configuration it refused, say).
    for d in slurmctld slurmd; do
        f=$tmp/log/$d.log
        [[ -s $f ]] || f=$tmp/log/$d.out
        [[ -f $f ]] || continue
        echo "---- $f (last 60 lines)" >&2
        tail -n 60 "$f" >&2
    done
}

stop_all() {
    status=$?
    trap - EXIT INT TERM
    set +e
    if ((status != 0)); then
        print_logs
    fi
    if ((${#jobs_to_cancel[@]})); then
        scancel "${jobs_to_cancel[@]}" >/dev/null 2>&1
        sleep 1
    fi
    local pid _
    for pid in "${pids[@]}"; do
        kill "$pid" 2>/dev/null
    done
    for pid in "${pids[@]}"; do
        for _ in $(seq 1 50); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.2
        done
        kill -9 "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
    done
    if ((munged_started)); then
        munged --stop --socket="$tmp/munge.sock" >/dev/null 2>&1
    fi
    if [[ $keep == 1 || $status != 0 ]]; then
        echo "slurm-check: files kept in $tmp" >&2
    else
        rm -rf "$tmp"
    fi
    exit "$status"
}
trap stop_all EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

echo "== slurm-check: munged"
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge.key"
# --force: the key and socket live in a folder of root's, not munge's.
munged --force --socket="$tmp/munge.sock" --key-file="$tmp/munge.key" \
    --log-file="$tmp/log/munged.log" --pid-file="$tmp/munged.pid" --seed-file="$tmp/munged.seed" ||
    fail "munged did not start"
munged_started=1
munge --socket="$tmp/munge.sock" -n | unmunge --socket="$tmp/munge.sock" >/dev/null ||
    fail "munged started but a credential does not round-trip through $tmp/munge.sock"

echo "== slurm-check: slurm.conf"
cpus=$(nproc)
export SLURM_CONF=$tmp/slurm.conf
cat >"$SLURM_CONF" <<EOF
# One node, the machine itself, for scripts/slurm-check.sh. No cgroups and no systemd:
# processes are tracked through /proc and tasks are not bound.
ClusterName=slipload-check
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge.sock
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=3600
NodeName=localhost CPUs=$cpus RealMemory=1024 State=UNKNOWN
PartitionName=check Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
# The sweep must see only this cluster and its own arguments (not those of a job or a
# login shell this runs in).
for v in $(compgen -e); do
    case $v in
    SLURM_CONF | SLURM_CHECK_*) ;;
    SBATCH_* | SLURM_* | SQUEUE_* | SINFO_* | SLIPLOAD_*) unset "$v" ;;
    esac
done

echo "== slurm-check: slurmctld, slurmd"
slurmctld -D -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
state=
up=$SECONDS
while ((SECONDS - up < 60)); do
    state=$(timeout 10 sinfo -h -N -n localhost -o %T 2>/dev/null || true)
    [[ $state == idle ]] && break
    kill -0 "${pids[0]}" 2>/dev/null || fail "slurmctld exited before the node came up (its log follows)"
    kill -0 "${pids[1]}" 2>/dev/null || fail "slurmd exited before the node came up (its log follows)"
    sleep 1
done
[[ $state == idle ]] || fail "node localhost not idle after 60 s (sinfo says '${state:-nothing}')"
sinfo

# Submits the study with slurm-sweep.sh and waits for the array and its merge. One thread
# per task, so two shards run side by side on a two-core node; the single run below uses
# every core, so the comparison also covers the thread count. Called from another folder
# with relative paths, as a user on a login node would.
sweep_on_slurm() {
    local submitted array merge listing n start
    submitted=$(cd "$tmp" && SLIPLOAD_THREADS=1 "$repo/scripts/slurm-sweep.sh" \
        "$(realpath --relative-to="$tmp" "$study")" "$(basename "$out")" "$shards")
    echo "$submitted"
    read -r array merge < <(sed -n 's/^submitted array job \([0-9][0-9]*\) .* merge job \([0-9][0-9]*\);.*/\1 \2/p' <<<"$submitted") ||
        true
    [[ -n ${array:-} && -n ${merge:-} ]] || fail "could not read the job ids from slurm-sweep.sh's output"
    jobs_to_cancel=("$array" "$merge")
    echo "waiting for jobs $array (array) and $merge (merge), at most $job_timeout s"
    start=$SECONDS
    while :; do
        # One line per array task and job: id, state, reason.
        listing=$(squeue -h -r -t all -j "$array,$merge" -o '%i %T %r') ||
            fail "squeue failed while waiting for jobs $array and $merge"
        if grep -Eq ' (FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED|SPECIAL_EXIT|REVOKED) |DependencyNeverSatisfied' <<<"$listing"; then
            echo "$listing" >&2
            fail "a job failed or can never run"
        fi
        if [[ -n $listing ]] && ! grep -vq ' COMPLETED ' <<<"$listing"; then
            # Every line COMPLETED: the array's tasks and the merge.
            n=$(grep -c '' <<<"$listing")
            ((n == shards + 1)) || {
                echo "$listing" >&2
                fail "expected $shards array tasks and one merge job, squeue lists $n jobs"
            }
            break
        fi
        if ((SECONDS - start > job_timeout)); then
            echo "$listing" >&2
            fail "jobs not finished after $job_timeout s"
        fi
        sleep 2
    done
    jobs_to_cancel=()
    echo "$listing"
    echo "jobs finished in $((SECONDS - start)) s"
}

# Requires OUT/merged to be the single run's folder: every file byte for byte, except the
# journals: a journal is the log of finished tasks in the order they finished (which the
# thread count and the shard split change); the tables and figures are built from it
# sorted by key. Journals must hold the same lines.
compare_with_single() {
    local files journal_files j differ=0 excludes=()
    [[ -d $out/merged ]] || fail "the merge job wrote no $out/merged"
    files=$(find "$single" -type f -printf '%P\n' | LC_ALL=C sort)
    [[ -n $files ]] || fail "the single sweep wrote no files into $single"
    for j in journal.jsonl check.jsonl 'refine-*.jsonl'; do excludes+=(-x "$j"); done
    if ! diff -r "${excludes[@]}" "$single" "$out/merged" >"$tmp/diff.txt" 2>&1; then
        differ=1
        echo "slurm-check: the merged folder differs from the single run:" >&2
        diff -rq "${excludes[@]}" "$single" "$out/merged" >&2 || true
        head -n 40 "$tmp/diff.txt" >&2
    fi
    journal_files=$(find "$single" "$out/merged" -type f -printf '%P\n' |
        grep -E '(^|/)(journal\.jsonl|check\.jsonl|refine-[^/]*\.jsonl)$' | LC_ALL=C sort -u || true)
    for j in $journal_files; do
        if [[ ! -f $single/$j || ! -f $out/merged/$j ]]; then
            differ=1
            echo "slurm-check: journal $j is in only one of the two folders" >&2
        elif ! cmp -s <(LC_ALL=C sort "$single/$j") <(LC_ALL=C sort "$out/merged/$j"); then
            differ=1
            echo "slurm-check: journal $j holds other lines in the merged folder than in the single run:" >&2
            diff <(LC_ALL=C sort "$single/$j") <(LC_ALL=C sort "$out/merged/$j") | head -n 20 >&2 || true
        fi
    done
    ((differ == 0)) || fail "merged shards != single sweep"
    echo "same files ($(wc -l <<<"$files")): $(tr '\n' ' ' <<<"$files")"
    echo "(byte for byte; the journals, ${journal_files//$'\n'/ }, as sets of lines)"
}

echo "== slurm-check: scripts/slurm-sweep.sh $(basename "$study") ($shards shards)"
sweep_on_slurm

echo "== slurm-check: one sweep of the same study"
"${CARGO_TARGET_DIR:-$repo/target}/release/slipload" --threads "$cpus" sweep "$study" --out "$single" --quiet

echo "== slurm-check: merged folder against the single run"
compare_with_single

echo "== slurm-check: the same submission again (every shard resumes a finished journal)"
# A requeued or resubmitted task continues its shard's journal: finished, it must run
# nothing (its journal keeps the same lines), and the merge must write the same files.
mkdir -p "$tmp/before"
shard_dirs=("$out"/shard-*)
((${#shard_dirs[@]} == shards)) || fail "expected $shards shard folders in $out, found ${#shard_dirs[@]}"
for d in "${shard_dirs[@]}"; do
    LC_ALL=C sort "$d/journal.jsonl" >"$tmp/before/$(basename "$d").jsonl"
done
rm -rf "$out/merged"
sweep_on_slurm
for d in "${shard_dirs[@]}"; do
    cmp -s <(LC_ALL=C sort "$d/journal.jsonl") "$tmp/before/$(basename "$d").jsonl" ||
        fail "resubmitted, $(basename "$d")/journal.jsonl changed: a resumed shard ran tasks again"
done
compare_with_single
echo "slurm-check: ok"
