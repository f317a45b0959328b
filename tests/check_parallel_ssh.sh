#!/usr/bin/env bash
# GNU parallel's --sshlogin form of a sharded sweep (docs/sharding.md), on a
# private sshd: started on a loopback port with keys made for this run, and
# reached under two host names, so that parallel spreads the shards over two
# "hosts" as it would over a farm. The merged sweep must be byte for byte the
# whole sweep, and each host must have run at least one shard.
# Usage: check_parallel_ssh.sh CDSIM WORKDIR SCENE
set -euo pipefail
cdsim=$1 work=$2 scene=$3
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
# sshd refuses keys in folders others may write; mktemp -d is 0700, which it accepts.
keys=$(mktemp -d /tmp/cdsim-ssh.XXXXXX)
sshd_pid=
cleanup() {
  [[ -n $sshd_pid ]] && kill "$sshd_pid" 2>/dev/null || true
  rm -rf "$keys"
}
trap cleanup EXIT

ssh-keygen -q -t ed25519 -N '' -f "$keys/host_key"
ssh-keygen -q -t ed25519 -N '' -f "$keys/client_key"
cp "$keys/client_key.pub" "$keys/authorized_keys"
port=$((20000 + $$ % 20000))
mkdir -p /run/sshd  # sshd's privilege-separation folder
cat > "$keys/sshd_config" <<EOF
Port $port
ListenAddress 127.0.0.1
HostKey $keys/host_key
PidFile $keys/sshd.pid
AuthorizedKeysFile $keys/authorized_keys
PermitRootLogin prohibit-password
PasswordAuthentication no
KbdInteractiveAuthentication no
UsePAM no
StrictModes no
AcceptEnv SYSTEMC_DISABLE_COPYRIGHT_MESSAGE
EOF
/usr/sbin/sshd -D -e -f "$keys/sshd_config" 2> "$work/sshd.log" &
sshd_pid=$!

user=$(id -un)
cat > "$keys/ssh_config" <<EOF
Host farm-a farm-b
  HostName 127.0.0.1
  Port $port
  User $user
  IdentityFile $keys/client_key
  IdentitiesOnly yes
  StrictHostKeyChecking no
  UserKnownHostsFile /dev/null
  LogLevel ERROR
  BatchMode yes
EOF
for _ in $(seq 1 50); do
  ssh -F "$keys/ssh_config" farm-a true 2>/dev/null && break
  sleep 0.1
done
ssh -F "$keys/ssh_config" farm-a true || { cat "$work/sshd.log"; echo "FAIL: sshd did not start"; exit 1; }

cd "$work"
sweep=(sweep --scene "$scene" --design cd-linear,divide --set g_frac=8:12 --set out_frac=4,8)
"$cdsim" "${sweep[@]}" --out whole > whole.txt
n=6
# Each job prints the host it ran on: ssh runs it there, in --workdir.
parallel --ssh "ssh -F $keys/ssh_config" --sshlogin 1/farm-a,1/farm-b --workdir "$work" \
  --halt now,fail=1 --tag \
  "echo \$PARALLEL_SSHLOGIN; $cdsim ${sweep[*]} --shard {}/$n --out shard-{} > shard-{}.txt" \
  ::: $(seq 1 $n) > hosts.txt
cat hosts.txt
"$cdsim" merge $(seq -f "shard-%g" 1 $n) --out merged > merged.txt
cmp whole/sweep.csv merged/sweep.csv
cmp whole/sweep.json merged/sweep.json
for host in farm-a farm-b; do
  grep -q "$host" hosts.txt || { echo "FAIL: no shard ran on $host"; exit 1; }
done
echo "ok   $n shards over --sshlogin farm-a,farm-b (one sshd on 127.0.0.1:$port): merged byte for byte"
echo PASS
