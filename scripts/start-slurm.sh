#!/usr/bin/env bash
# Starts a one-machine Slurm cluster (munged, slurmctld, slurmd; no systemd), for CI and for
# trying scripts/slurm-sweep.sh: one node with this machine's CPUs and memory, one partition.
# Writes /etc/slurm/slurm.conf unless one not written by this script is there (then the cluster
# that has it is used as it is). Idempotent: a cluster that answers is left alone. Needs root
# (or sudo). Waits until the node is idle; exits non-zero when it does not come up.
set -euo pipefail

conf=/etc/slurm/slurm.conf
marker="# written by conicloc scripts/start-slurm.sh"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"

node_state() { sinfo --noheader --node="$(hostname -s)" --format=%t 2>/dev/null | head -n1; }

if [ -n "$(node_state)" ] && [ "$(node_state)" != "down" ] && [ "$(node_state)" != "down*" ]; then
  echo "start-slurm: the cluster answers ($(hostname -s): $(node_state))"
  exit 0
fi
for program in munged slurmctld slurmd sinfo; do
  command -v "$program" >/dev/null || PATH=$PATH:/usr/sbin
  command -v "$program" >/dev/null || { echo "start-slurm: no $program (apt-get install slurm-wlm munge)" >&2; exit 1; }
done

# munge: a key, then the daemon, as the munge user.
if [ ! -s /etc/munge/munge.key ]; then
  $sudo mungekey --create --keyfile=/etc/munge/munge.key 2>/dev/null ||
    $sudo dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
  $sudo chown munge:munge /etc/munge/munge.key
  $sudo chmod 400 /etc/munge/munge.key
fi
$sudo mkdir -p /run/munge /var/log/munge /var/lib/munge
$sudo chown munge:munge /run/munge /var/log/munge /var/lib/munge
if ! munge -n </dev/null >/dev/null 2>&1; then
  $sudo runuser -u munge -- munged
fi

if [ ! -e "$conf" ] || grep -qF "$marker" "$conf"; then
  host=$(hostname -s)
  cpus=$(nproc)
  memory_mb=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
  $sudo mkdir -p /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
  $sudo tee "$conf" >/dev/null <<CONF
$marker: one node, this machine
ClusterName=conicloc
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
NodeName=$host CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
fi

pgrep -x slurmctld >/dev/null || $sudo slurmctld
pgrep -x slurmd >/dev/null || $sudo slurmd
for _ in $(seq 60); do
  case "$(node_state)" in
    idle|mix|alloc) echo "start-slurm: $(hostname -s) is $(node_state)"; exit 0 ;;
    down*|drain*) $sudo scontrol update nodename="$(hostname -s)" state=resume 2>/dev/null || true ;;
  esac
  sleep 1
done
echo "start-slurm: the node did not come up; see /var/log/slurm/" >&2
sinfo >&2 || true
exit 1
