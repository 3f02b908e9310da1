#!/usr/bin/env bash
# A study on a real single-node Slurm (docs/cluster.md): starts munged, slurmctld and slurmd
# on this machine with a minimal slurm.conf in a temporary folder, writes a 2 x 2 study with
# `tribosim study --slurm DIR --submit`, waits for the array, collects it, and checks that
# the summary equals the same study run here with `tribosim study`, every number but the
# wall times exactly. Stops the daemons it started and removes the folder on any exit.
# Needs root and Python 3; installs Debian's slurm-wlm and munge with apt when missing.
# TRIBOSIM_BIN names the binary (target/release/tribosim by default).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(realpath "${TRIBOSIM_BIN:-target/release/tribosim}")"
# Generous: the array's 4 members take seconds, but the machine may be loaded.
patience_s=600

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
    echo "== installing slurm-wlm munge (apt)"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi

work="$(mktemp -d)"
chmod 755 "$work"
daemons=()
job=""
cleanup() {
    status=$?
    if [ -n "$job" ]; then scancel "$job" 2>/dev/null || true; fi
    for pid in "${daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
    for pid in "${daemons[@]}"; do
        for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.3; done
        kill -9 "$pid" 2>/dev/null || true
    done
    if [ "$status" -ne 0 ]; then
        for log in "$work"/slurmctld.log "$work"/slurmd.log; do
            [ -f "$log" ] && { echo "== $log (end)"; tail -n 20 "$log"; }
        done
    fi
    rm -rf "$work"
    exit "$status"
}
trap cleanup EXIT

# munge authenticates Slurm's messages. One already running (a machine with systemd starts
# it on install) is used as it is; otherwise one runs here as its own user, as Debian does.
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    install -d -o munge -g munge -m 755 /run/munge
    setpriv --reuid=munge --regid=munge --init-groups /usr/sbin/munged --foreground 2>/dev/null &
    daemons+=($!)
    for _ in $(seq 50); do munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.2; done
fi

host="$(hostname)"
memory_mb="$(free -m | awk '/^Mem:/ { print $2 }')"
mkdir -p "$work/state" "$work/spool"
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=tribosim-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory_mb State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

echo "== slurmctld and slurmd on $host ($(nproc) CPUs, $memory_mb MB)"
# In the foreground (-D) so that they are this shell's children, with known ids to stop;
# their logs are in $work.
slurmctld -D -f "$SLURM_CONF" 2>/dev/null &
daemons+=($!)
slurmd -D -f "$SLURM_CONF" 2>/dev/null &
daemons+=($!)
for _ in $(seq 60); do
    [ "$(sinfo -h -N -o %t 2>/dev/null)" = idle ] && break
    sleep 1
done
state="$(sinfo -h -N -o %t 2>/dev/null || true)"
[ "$state" = idle ] || { echo "the node is not idle after 60 s: ${state:-no answer}" >&2; exit 1; }

cat >"$work/study.json" <<'EOF'
{
  "base": {
    "preset": "dalmau2018-316l",
    "overrides": { "test": { "cycles": 300 }, "numerics": { "grid": 64 } }
  },
  "axes": {
    "test.load_n": [2, 5],
    "test.speed_rpm": [30, 60]
  }
}
EOF

echo "== the study as a Slurm job array"
started_ms=$(date +%s%3N)
job="$("$bin" study "$work/study.json" --slurm "$work/array" --submit)"
for _ in $(seq "$patience_s"); do
    [ -z "$(squeue -h -j "$job" -o %i 2>/dev/null)" ] && break
    sleep 1
done
[ -z "$(squeue -h -j "$job" -o %i 2>/dev/null)" ] || { echo "array job $job still queued after $patience_s s" >&2; exit 1; }
slurm_ms=$(($(date +%s%3N) - started_ms))
job=""
"$bin" study collect "$work/array" -o "$work/slurm.json" --csv "$work/slurm.csv"

echo "== the same study here"
started_ms=$(date +%s%3N)
"$bin" study "$work/study.json" -o "$work/local.json" --csv "$work/local.csv"
local_ms=$(($(date +%s%3N) - started_ms))

python3 - "$work/slurm.json" "$work/local.json" <<'EOF'
import json, sys

def numbers(path):
    """The summary without what depends on the machine and the moment: wall times,
    workers, and the provenance's date and cores (its version and commit stay)."""
    summary = json.load(open(path))
    for key in ("wall_s", "workers"):
        summary.pop(key)
    for key in ("computed_at", "cores"):
        summary["provenance"].pop(key)
    for member in summary["members"]:
        member["summary"].pop("wall_s")
    return summary

slurm, here = numbers(sys.argv[1]), numbers(sys.argv[2])
if slurm != here:
    sys.exit(f"the collected summary differs from the local one:\n{slurm}\n{here}")
print(f"{len(here['members'])} members: the collected summary equals the local one")
EOF
echo "wall time: ${slurm_ms} ms from submission to an empty queue, ${local_ms} ms here ($(nproc) worker threads)"
