#!/bin/bash
# A single-node Slurm cluster on this machine, for trying `gc2d-rs sweep --slurm` and for the Slurm test
# (crates/gc2d-cli/tests/slurm.rs): installs Debian's slurm-wlm and munge if they are missing (apt-get), writes
# /etc/slurm/slurm.conf for this host (its name, cores and memory as `slurmd -C` reports them, 90 % of the memory),
# creates a munge key and starts munged, slurmctld and slurmd, then waits until the node is idle.
#
#   scripts/slurm-local.sh          start (or check that it is running)
#   scripts/slurm-local.sh stop     stop the three daemons
#
# Needs root. Exits 0 when the node accepts jobs, 77 (the usual "skipped" code) when Slurm cannot be set up here, with
# the reason on stderr: not root, no apt-get, the packages cannot be installed, a daemon does not start.
set -u

skip() {
    echo "slurm-local: $*" >&2
    exit 77
}

pids() { pgrep -x "$1" 2>/dev/null; }

if [ "${1:-start}" = stop ]; then
    for daemon in slurmd slurmctld munged; do
        for pid in $(pids "$daemon"); do kill "$pid"; done
    done
    exit 0
fi

[ "$(id -u)" = 0 ] || skip "needs root (to install packages, write /etc/slurm and start the daemons as root)"

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
    command -v apt-get >/dev/null || skip "slurm-wlm and munge are not installed and there is no apt-get to install them"
    log=/tmp/slurm-local-apt.log
    echo "slurm-local: installing slurm-wlm and munge (apt-get; log in $log)" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y --no-install-recommends slurm-wlm munge >"$log" 2>&1 ||
        { apt-get update >>"$log" 2>&1 && apt-get install -y --no-install-recommends slurm-wlm munge >>"$log" 2>&1; } ||
        skip "apt-get could not install slurm-wlm and munge (no network or no package lists?): see $log"
fi

# munge: a key shared by the daemons and the clients (one host: any random key).
mkdir -p /etc/munge /run/munge /var/lib/munge /var/log/munge
if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null || skip "cannot write a munge key"
fi
if id munge >/dev/null 2>&1; then
    chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge
fi
chmod 700 /etc/munge
chmod 400 /etc/munge/munge.key
if [ -z "$(pids munged)" ]; then
    if id munge >/dev/null 2>&1; then
        runuser -u munge -- munged || skip "munged does not start"
    else
        munged --force || skip "munged does not start"
    fi
fi
munge -n | unmunge >/dev/null 2>&1 || skip "munge does not work (munge -n | unmunge fails)"

# slurm.conf for this host.
host=$(hostname -s)
node=$(slurmd -C 2>/dev/null | head -n 1)
case "$node" in
    NodeName=*) ;;
    *) skip "slurmd -C does not describe this host" ;;
esac
memory=$(echo "$node" | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
node=$(echo "$node" | sed "s/RealMemory=[0-9]*/RealMemory=$((memory * 9 / 10))/")
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
conf=$(
    cat <<EOF
# Written by scripts/slurm-local.sh: a single-node cluster on $host.
ClusterName=gc2d-local
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
KillWait=10
MinJobAge=600
$node State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
)
if [ "$(cat /etc/slurm/slurm.conf 2>/dev/null)" != "$conf" ]; then
    echo "$conf" >/etc/slurm/slurm.conf
    for daemon in slurmd slurmctld; do
        for pid in $(pids "$daemon"); do kill "$pid"; done
    done
    sleep 1
fi
[ -n "$(pids slurmctld)" ] || slurmctld || skip "slurmctld does not start: see /var/log/slurm/slurmctld.log"
[ -n "$(pids slurmd)" ] || slurmd || skip "slurmd does not start: see /var/log/slurm/slurmd.log"

for _ in $(seq 60); do
    state=$(sinfo -h -n "$host" -o %T 2>/dev/null)
    case "$state" in
        idle* | mixed* | allocated*)
            echo "slurm-local: node $host is $state" >&2
            exit 0
            ;;
    esac
    sleep 1
done
skip "the node did not become idle within a minute (state: ${state:-unknown}); see /var/log/slurm/"
