#!/usr/bin/env bash
# The pipeline on a real SLURM: a one-node test cluster on this machine, the smoke config
# through profiles/slurm, the same config locally, and every dataset of the two runs compared.
#
#   sudo tests/slurm/run_single_node.sh          # from anywhere; needs root, Debian/Ubuntu
#
# What it does (see tests/slurm/README.md):
#   1. apt-get install slurm-wlm munge (if slurmctld, slurmd or munged is missing);
#   2. writes a one-node /etc/slurm/slurm.conf (an existing one is moved aside and put back on
#      exit): this host with the CPUs and memory of `slurmd -C`, no accounting, no cgroups
#      (proctrack/linuxproc, task/none: works in containers), select/cons_tres, on private
#      ports (16817/16818); state and logs in $VINES_SLURM_DIR (default /tmp/vines-slurm).
#      Not a private SLURM_CONF: the plugin's job step drops SLURM_* variables before its
#      nested `srun`, which then only finds the default path;
#   3. starts munged (unless one runs), slurmctld and slurmd, waits until the node is idle;
#   4. pip install snakemake-executor-plugin-slurm (if missing);
#   5. snakemake all --profile profiles/slurm --configfile config/smoke.yaml --config run=smoke_slurm
#      (plus --cores <the node's CPUs> and --slurm-status-command squeue: no accounting here),
#      then snakemake -c2 all --configfile config/smoke.yaml --config run=smoke_local;
#   6. compares every dataset (*.nc) of results/smoke_slurm and results/smoke_local: the same
#      files, variables, dimensions and values (NaN == NaN), except the wall-clock timings
#      `seconds`, `run_time`, `impacts_per_second`, `calls` of the workprecision and
#      convergence datasets; prints `slurm vs local: N datasets, M identical, K differ` and
#      exits 1 if any differ (2: the setup or a run failed).
# On exit (also on failure, Ctrl-C or kill) it stops a running snakemake, cancels the jobs of
# the test cluster, stops the daemons it started, restores /etc/slurm/slurm.conf and removes
# results/smoke_slurm and results/smoke_local (KEEP_RESULTS=1 keeps them).
#
# Environment: VINES_SLURM_DIR (state and logs), LOCAL_CORES (cores of the local run, default
# 2), KEEP_RESULTS=1, PYTHON (the interpreter that has snakemake; default python3).
set -euo pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
STATE=${VINES_SLURM_DIR:-/tmp/vines-slurm}
LOCAL_CORES=${LOCAL_CORES:-2}
RUN_SLURM=smoke_slurm
RUN_LOCAL=smoke_local
PY=${PYTHON:-python3}
CONF=/etc/slurm/slurm.conf
MARK="# one-node test cluster written by tests/slurm/run_single_node.sh"

log() { printf '[slurm-test %(%H:%M:%S)T] %s\n' -1 "$*"; }
die() { log "ERROR: $*"; exit 2; }

[ "$(id -u)" -eq 0 ] || die "run as root (installs packages, starts munged/slurmctld/slurmd)"
command -v snakemake >/dev/null || die "snakemake not found (pip install -e '.[pipeline]')"

# ------------------------------------------------------------------ cleanup on exit
STARTED_PIDS=()       # daemons started here, in start order
CHILD=""              # the running snakemake
CREATED_RESULTS=0
WROTE_CONF=0
cleanup() {
    local rc=$?
    set +e
    trap - INT TERM
    if [ -n "$CHILD" ] && kill -0 "$CHILD" 2>/dev/null; then
        log "stopping snakemake (pid $CHILD)"
        kill -TERM "$CHILD"; wait "$CHILD" 2>/dev/null
    fi
    if [ ${#STARTED_PIDS[@]} -gt 0 ]; then     # every job of the test cluster is ours
        jobs_left=$(squeue -h -o %i 2>/dev/null)
        [ -n "$jobs_left" ] && scancel --full $jobs_left 2>/dev/null && sleep 2
    fi
    for (( i=${#STARTED_PIDS[@]}-1; i>=0; i-- )); do     # slurmd, slurmctld, munged
        pid=${STARTED_PIDS[i]}
        if kill -0 "$pid" 2>/dev/null; then
            kill -TERM "$pid"
            for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
            kill -0 "$pid" 2>/dev/null && kill -KILL "$pid"
        fi
    done
    [ ${#STARTED_PIDS[@]} -gt 0 ] && log "stopped the daemons started here (pids ${STARTED_PIDS[*]})"
    if [ "$WROTE_CONF" = 1 ]; then
        if [ -f "$CONF.vines-backup" ]; then mv -f "$CONF.vines-backup" "$CONF"; else rm -f "$CONF"; fi
    fi
    if [ "${KEEP_RESULTS:-0}" != 1 ]; then
        rm -rf "$REPO/results/$RUN_SLURM" "$REPO/results/$RUN_LOCAL"
        [ "$CREATED_RESULTS" = 1 ] && rmdir "$REPO/results" 2>/dev/null
        log "removed results/$RUN_SLURM and results/$RUN_LOCAL"
    fi
    exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# ------------------------------------------------------------------ 1. packages
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
        || ! command -v munged >/dev/null; then
    log "installing slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq slurm-wlm munge >/dev/null
fi

# ------------------------------------------------------------------ 2. slurm.conf
for port in 16817 16818; do
    if (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
        die "port $port is in use (a test cluster still running?)"
    fi
done
mkdir -p "$STATE"/{ctld,spool,log} /etc/slurm
NODE=$(hostname -s)
NODE_LINE=$(slurmd -C | grep '^NodeName=' | sed -E "s/^NodeName=[^ ]+/NodeName=$NODE/")
CPUS=$(sed -E 's/.*CPUs=([0-9]+).*/\1/' <<<"$NODE_LINE")
unset SLURM_CONF
if [ -f "$CONF" ] && ! head -1 "$CONF" | grep -qxF "$MARK"; then
    mv "$CONF" "$CONF.vines-backup"
    log "moved the existing $CONF to $CONF.vines-backup (put back on exit)"
fi
WROTE_CONF=1
cat >"$CONF" <<EOF
$MARK
ClusterName=vines-test
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/spool
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
# no cgroups (containers): plain process tracking, no task binding
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
# no slurmdbd: sacct answers "Slurm accounting storage is disabled"
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
ReturnToService=2
# squeue shows a finished job this long (the plugin polls at most every 180 s)
MinJobAge=300
SlurmdTimeout=300
$NODE_LINE NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
log "wrote $CONF: $NODE_LINE"

# ------------------------------------------------------------------ 3. daemons
if pgrep -x munged >/dev/null; then
    log "munged already runs: using it"
else
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    if [ ! -f /etc/munge/munge.key ]; then
        mungekey --create 2>/dev/null || /usr/sbin/create-munge-key -f
    fi
    chown munge:munge /etc/munge/munge.key && chmod 600 /etc/munge/munge.key
    rm -f /run/munge/munged.pid
    runuser -u munge -- /usr/sbin/munged
    for _ in $(seq 50); do [ -s /run/munge/munged.pid ] && break; sleep 0.1; done
    STARTED_PIDS+=("$(cat /run/munge/munged.pid)")
    log "munged started (pid ${STARTED_PIDS[-1]})"
fi
munge -n | unmunge >/dev/null || die "munge does not work"

slurmctld -D -i >"$STATE/log/slurmctld.out" 2>&1 &
STARTED_PIDS+=($!)
for _ in $(seq 100); do scontrol ping 2>/dev/null | grep -q UP && break; sleep 0.2; done
scontrol ping | grep -q UP || { tail -20 "$STATE/log/slurmctld.log"; die "slurmctld is not up"; }
slurmd -D >"$STATE/log/slurmd.out" 2>&1 &
STARTED_PIDS+=($!)
log "slurmctld (pid ${STARTED_PIDS[-2]}) and slurmd (pid ${STARTED_PIDS[-1]}) started"
state=""
for _ in $(seq 120); do
    state=$(sinfo -h -N -n "$NODE" -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.5
done
[ "$state" = idle ] || { tail -20 "$STATE/log/slurmd.log"; die "node $NODE is '$state', not idle"; }
sinfo -N -l

# ------------------------------------------------------------------ 4. plugin
"$PY" -c "import snakemake_executor_plugin_slurm" 2>/dev/null \
    || "$PY" -m pip install -q snakemake-executor-plugin-slurm
VERSIONS="snakemake $(snakemake --version), $("$PY" -c '
from importlib.metadata import version as v
print("snakemake-executor-plugin-slurm", v("snakemake-executor-plugin-slurm"),
      "(jobstep " + v("snakemake-executor-plugin-slurm-jobstep") + ")")'), $(sinfo -V)"
log "versions: $VERSIONS"

# ------------------------------------------------------------------ 5. the two runs
# run_logged LOG CMD...: CMD in the background (a signal to this script reaches the trap at
# once, which stops CMD), its output into LOG and, unless QUIET=1, onto the terminal
run_logged() {
    local logf=$1 rc=0
    shift
    if [ "${QUIET:-0}" = 1 ]; then
        "$@" >"$logf" 2>&1 &
    else
        "$@" > >(tee "$logf") 2>&1 &
    fi
    CHILD=$!
    wait "$CHILD" || rc=$?
    CHILD=""
    return $rc
}

cd "$REPO"
[ -d results ] || CREATED_RESULTS=1
rm -rf "results/$RUN_SLURM" "results/$RUN_LOCAL"
# --cores: the node's CPUs, the most a job can get here (the profile's set-threads ask 8);
# --slurm-status-command squeue: no accounting here (see profiles/slurm/config.yaml);
# --slurm-init-seconds-before-status-checks 5: the smoke jobs take seconds
log "SLURM run: results/$RUN_SLURM (log: $STATE/log/snakemake_slurm.log)"
t0=$(date +%s)
run_logged "$STATE/log/snakemake_slurm.log" \
    snakemake all --profile profiles/slurm --cores "$CPUS" --slurm-status-command squeue \
    --slurm-init-seconds-before-status-checks 5 \
    --configfile config/smoke.yaml --config run=$RUN_SLURM \
    || die "SLURM run failed (log: $STATE/log/snakemake_slurm.log)"
T_SLURM=$(( $(date +%s) - t0 ))
N_JOBS=$(grep -c "has been submitted with SLURM jobid" "$STATE/log/snakemake_slurm.log" || true)
log "SLURM run: $N_JOBS SLURM jobs, ${T_SLURM} s"

log "local run: results/$RUN_LOCAL (log: $STATE/log/snakemake_local.log)"
t0=$(date +%s)
QUIET=1 run_logged "$STATE/log/snakemake_local.log" \
    snakemake -c"$LOCAL_CORES" all --configfile config/smoke.yaml --config run=$RUN_LOCAL \
    || die "local run failed (log: $STATE/log/snakemake_local.log)"
T_LOCAL=$(( $(date +%s) - t0 ))
# the last progress line: "[84/84] all (0.0 s)" of the logger plugin vines (the default
# profile), or Snakemake's own "84 of 84 steps (100%) done" (--workflow-profile none)
N_LOCAL=$(grep -oE '^\[ *[0-9]+/[0-9]+\]|[0-9]+ of [0-9]+ steps \(100%\) done' \
    "$STATE/log/snakemake_local.log" | tail -1 | grep -oE '[0-9]+' | head -1 || true)
log "local run: ${N_LOCAL:-?} steps, ${T_LOCAL} s"

# ------------------------------------------------------------------ 6. compare
RC=0
"$PY" - "results/$RUN_SLURM" "results/$RUN_LOCAL" <<'EOF' || RC=$?
import sys
from pathlib import Path

import numpy as np
import xarray as xr

TIMING = {"seconds", "run_time", "impacts_per_second", "calls"}
TIMED = {"work_precision", "convergence"}        # folders of the datasets that hold timings


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind in "fc":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


slurm, local = Path(sys.argv[1]), Path(sys.argv[2])
files = sorted({p.relative_to(slurm) for p in slurm.rglob("*.nc")}
               | {p.relative_to(local) for p in local.rglob("*.nc")})
n_same, differ = 0, []
for rel in files:
    a, b = slurm / rel, local / rel
    if not (a.exists() and b.exists()):
        differ.append(f"{rel}: only in the {'SLURM' if a.exists() else 'local'} run")
        continue
    skip = TIMING if rel.parts[0] in TIMED else set()
    with xr.open_dataset(a, decode_times=False) as da, \
            xr.open_dataset(b, decode_times=False) as db:
        names = (set(da.variables) | set(db.variables)) - skip
        bad = sorted(n for n in names
                     if n not in da.variables or n not in db.variables
                     or da[n].dims != db[n].dims or not same(da[n].values, db[n].values))
    if bad:
        differ.append(f"{rel}: {', '.join(bad)}")
    else:
        n_same += 1
for line in differ:
    print("  differs:", line)
print(f"slurm vs local: {len(files)} datasets, {n_same} identical, {len(differ)} differ")
sys.exit(1 if differ or not files else 0)
EOF
log "SLURM run: $N_JOBS SLURM jobs, ${T_SLURM} s; local run (-c$LOCAL_CORES): ${N_LOCAL:-?} steps, ${T_LOCAL} s"
log "versions: $VERSIONS"
exit $RC
