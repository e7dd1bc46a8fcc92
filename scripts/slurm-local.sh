#!/usr/bin/env bash
# A single-node Slurm cluster on loopback, for `make test` and for trying `shatter submit` on one
# machine: munged, slurmctld and slurmd (node "localhost", partition "debug"), all state in one
# directory, no systemd, nothing in /etc touched.
#
#   scripts/slurm-local.sh start   # idempotent: starts what is not running; prints the env line
#   scripts/slurm-local.sh stop    # idempotent: stops the daemons started from the state dir
#   scripts/slurm-local.sh status  # exit 0 when the node is up and idle/mixed/allocated
#   scripts/slurm-local.sh env     # "export SLURM_CONF=...": eval it before sbatch/squeue/shatter submit
#
# The state directory is $SHATTER_SLURM_DIR (default /tmp/shatter-slurm-$UID). Ports are picked
# free at the first start and kept in its slurm.conf. Needs root (slurmd launches jobs as their
# user) and Debian's slurm-wlm and munge (scripts/install-deps.sh). Exit code 77 when the cluster
# cannot be started here (the reason is on stderr): tests skip on it.
#
# Pitfalls handled (docs/cluster.md): the hostname is not "localhost", so slurmd runs with
# -N localhost; munged gets its own key and socket directory owned by munge; MinJobAge=300 keeps
# finished jobs visible to scontrol, since accounting is off (no sacct).
set -euo pipefail

STATE=${SHATTER_SLURM_DIR:-/tmp/shatter-slurm-$(id -u)}
CONF=$STATE/slurm.conf
MUNGE_SOCKET=$STATE/munge/munge.socket.2

skip() { echo "slurm-local: cannot start a local cluster: $*" >&2; exit 77; }
die() { echo "slurm-local: $*" >&2; exit 1; }

pid_alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

pick_ports() {
    local base
    for _ in $(seq 50); do
        base=$((20000 + RANDOM % 40000))
        if port_free "$base" && port_free $((base + 1)); then echo "$base"; return; fi
    done
    die "no two free ports found on 127.0.0.1"
}

write_conf() {
    local base mem
    base=$(pick_ports)
    mem=1024
    cat >"$CONF.tmp" <<EOF
# Written by scripts/slurm-local.sh: a single-node cluster on loopback.
ClusterName=shatterlocal
SlurmctldHost=localhost
SlurmctldPort=$base
SlurmdPort=$((base + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/slurmd
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/slurmctld.log
SlurmdLogFile=$STATE/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
# Schedule dependent jobs as soon as their dependencies end (the default waits up to 3 s).
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
MpiDefault=none
ReturnToService=2
MinJobAge=300
InactiveLimit=0
KillWait=5
Waittime=0
SlurmdParameters=config_overrides
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
    mv "$CONF.tmp" "$CONF"
}

start_munge() {
    if pid_alive "$STATE/munge/munged.pid"; then return; fi
    command -v munged >/dev/null || skip "munged is missing (fix: make deps, or apt-get install munge)"
    mkdir -p "$STATE/munge"
    if [ ! -f "$STATE/munge/munge.key" ]; then
        dd if=/dev/urandom of="$STATE/munge/munge.key" bs=1024 count=1 status=none
    fi
    chown -R munge:munge "$STATE/munge"
    chmod 0700 "$STATE/munge"
    chmod 0400 "$STATE/munge/munge.key"
    runuser -u munge -- munged --socket="$MUNGE_SOCKET" --key-file="$STATE/munge/munge.key" \
        --pid-file="$STATE/munge/munged.pid" --log-file="$STATE/munge/munged.log" \
        --seed-file="$STATE/munge/munged.seed" --force ||
        skip "munged did not start (see $STATE/munge/munged.log)"
}

start_daemons() {
    if ! pid_alive "$STATE/slurmctld.pid"; then
        slurmctld -f "$CONF" -i >>"$STATE/slurmctld.out" 2>&1 ||
            skip "slurmctld did not start (see $STATE/slurmctld.log)"
    fi
    if ! pid_alive "$STATE/slurmd.pid"; then
        slurmd -f "$CONF" -N localhost >>"$STATE/slurmd.out" 2>&1 ||
            skip "slurmd did not start (see $STATE/slurmd.log)"
    fi
}

node_ready() {
    local state
    state=$(SLURM_CONF=$CONF sinfo -h -n localhost -o %t 2>/dev/null) || return 1
    case "$state" in idle | mix | alloc) return 0 ;; *) return 1 ;; esac
}

cmd_start() {
    [ "$(id -u)" -eq 0 ] || skip "not root (slurmd must run as root to launch jobs)"
    for t in slurmctld slurmd sbatch scontrol squeue sinfo runuser; do
        command -v "$t" >/dev/null || skip "$t is missing (fix: make deps, or apt-get install slurm-wlm)"
    done
    mkdir -p "$STATE/ctld" "$STATE/slurmd"
    chmod 0755 "$STATE"
    [ -f "$CONF" ] || write_conf
    start_munge
    start_daemons
    # slurmd registers within a second or two; a node left DOWN by an earlier stop is resumed.
    for i in $(seq 100); do
        if node_ready; then cmd_env; return; fi
        if [ "$i" -eq 20 ]; then
            SLURM_CONF=$CONF scontrol update NodeName=localhost State=RESUME >/dev/null 2>&1 || true
        fi
        sleep 0.1
    done
    skip "the node did not come up in 10 s (see $STATE/slurmctld.log and $STATE/slurmd.log)"
}

# SIGTERM to every daemon named by a pid file, then wait for all (up to 10 s, then SIGKILL).
stop_pids() {
    local pids=() file pid
    for file in "$@"; do
        if pid_alive "$file"; then pid=$(cat "$file"); kill "$pid" 2>/dev/null || true; pids+=("$pid"); fi
        rm -f "$file"
    done
    for _ in $(seq 200); do
        local alive=0
        for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
        [ "$alive" -eq 0 ] && return 0
        sleep 0.05
    done
    for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
}

cmd_stop() {
    [ -d "$STATE" ] || return 0
    stop_pids "$STATE/slurmd.pid" "$STATE/slurmctld.pid" "$STATE/munge/munged.pid"
    rm -rf "$STATE"
}

cmd_env() { printf 'export SLURM_CONF=%q\n' "$CONF"; }

case "${1:-}" in
    start) cmd_start ;;
    stop) cmd_stop ;;
    status) [ -f "$CONF" ] && node_ready ;;
    env) cmd_env ;;
    *) echo "usage: $0 start|stop|status|env" >&2; exit 2 ;;
esac
