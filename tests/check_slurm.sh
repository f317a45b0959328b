#!/usr/bin/env bash
# A sweep through Slurm: a private single-node Slurm (Debian's slurm-wlm and
# munge, started on free ports, as root) runs scripts/slurm-sweep's
# job array of 3 shards and its dependent merge, whose files must be byte for
# byte those of the unsharded sweep. The daemons stop when the test ends.
# Usage: check_slurm.sh CDSIM WORKDIR SCENE
set -euo pipefail
cdsim=$(realpath "$1") work=$2 scene=$(realpath "$3")
root=$(realpath "$(dirname "$0")/..")
rm -rf "$work" && mkdir -p "$work" && work=$(realpath "$work")
# The daemons' folder is under /tmp, not WORKDIR: munged refuses a socket below
# a folder that not everyone may enter (a build tree under mktemp -d is 0700).
s=$(mktemp -d /tmp/cdsim-slurm.XXXXXX) && chmod 755 "$s" && mkdir -p "$s/state" "$s/spool"
ln -sfn "$s" "$work/slurm"  # the daemons' logs, for a failed run
stop() {
  local status=$?
  SLURM_CONF=$s/slurm.conf scontrol shutdown > /dev/null 2>&1 || true
  for p in slurmd slurmctld munged; do [[ -f $s/$p.pid ]] && kill "$(cat "$s/$p.pid")" 2> /dev/null || true; done
  sleep 1
  ((status != 0)) || rm -rf "$s"  # kept, with the daemons' logs, after a failure
}
trap stop EXIT
start=$(date +%s)
dd if=/dev/urandom of="$s/munge.key" bs=1024 count=1 status=none && chmod 400 "$s/munge.key"
munged --key-file="$s/munge.key" --socket="$s/munge.socket" --pid-file="$s/munged.pid" \
  --log-file="$s/munged.log" --seed-file="$s/munged.seed"
port=$((20000 + ($$ % 20000)))
host=$(hostname -s)
cat > "$s/slurm.conf" <<CONF
ClusterName=cdsimtest
SlurmctldHost=$host(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$s/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$s/state
SlurmdSpoolDir=$s/spool
SlurmctldPidFile=$s/slurmctld.pid
SlurmdPidFile=$s/slurmd.pid
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
SlurmctldLogFile=$s/slurmctld.log
SlurmdLogFile=$s/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=cdsim Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$s/slurm.conf
slurmctld -i
slurmd
for _ in $(seq 1 60); do sinfo -h -o %T 2> /dev/null | grep -q idle && break; sleep 0.5; done
sinfo -h -o %T | grep -q idle || { echo "FAIL: the node is not idle after 30 s"; tail "$s"/*.log; exit 1; }
echo "ok   single-node Slurm up in $(( $(date +%s) - start )) s"

sweep=(--scene "$scene" --design cd-linear,divide --set g_frac=8:12)
"$cdsim" sweep "${sweep[@]}" --out "$work/whole" > "$work/whole.txt"
timeout 300 "$root/scripts/slurm-sweep" --shards 3 --out "$work/farm" --cdsim "$cdsim" --wait -- "${sweep[@]}" \
  | tee "$work/slurm-sweep.txt"
cmp "$work/whole/sweep.csv" "$work/farm/sweep.csv"
cmp "$work/whole/sweep.json" "$work/farm/sweep.json"
for i in 1 2 3; do [[ -s $work/farm/shards/$i/sweep.csv ]] || { echo "FAIL: shard $i wrote nothing"; exit 1; }; done
echo "ok   3 array tasks and the dependent merge: the unsharded sweep's files, byte for byte ($(( $(date +%s) - start )) s in all)"
