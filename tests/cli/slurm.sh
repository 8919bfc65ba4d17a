#!/usr/bin/env bash
# A sweep on a real scheduler: starts a one-node Slurm cluster on localhost (munged with a key
# generated here, slurmctld and slurmd in the foreground, every file in a temporary directory,
# ports picked free), submits tests/data/small_sweep.json with scripts/slurm/submit.sh as a
# 4-task array job plus its dependent merge, and checks that each task ran its own shard, that
# the merge started after every shard had finished, and that summary.csv is byte-identical to
# a local -j2 run of the same sweep. Everything it starts is stopped at the end, on failure too.
# Installs slurm-wlm and munge the way scripts/setup.sh installs packages. Needs root (slurmd
# starts jobs as their user); exits 77 (skipped) otherwise.
# Usage: slurm.sh AMBISIM_BINARY SOURCE_DIR
set -u
bin="$(realpath "$1")"
src="$(cd "$2" && pwd)"
t_start=$(date +%s)
fail() {
  echo "FAIL $*"
  exit 1
}
# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local seconds="$1"
  shift
  local end=$(($(date +%s) + seconds))
  until "$@" >/dev/null 2>&1; do
    [ "$(date +%s)" -lt "$end" ] || return 1
    sleep 0.2
  done
}

if [ "$(id -u)" -ne 0 ]; then
  echo "skip: the one-node Slurm cluster needs root (slurmd runs jobs as their user)"
  exit 77
fi
(
  source "$src/scripts/setup.sh"
  ambisim_install_packages "${AMBISIM_SLURM_PACKAGES[@]}"
) || fail "cannot install slurm-wlm and munge (apt-get failed; see above)"
for cmd in munged mungekey munge slurmctld slurmd sbatch squeue scontrol sinfo scancel; do
  command -v "$cmd" >/dev/null || fail "$cmd not found after installing slurm-wlm and munge"
done

tmp="$(mktemp -d)"
chmod 755 "$tmp"  # munged wants the directories above its socket reachable
pids=()
cleanup() {
  if [ -f "$tmp/slurm.conf" ] && [ -n "${SLURM_CONF:-}" ]; then
    scancel --quiet --user=root 2>/dev/null
    wait_for 20 sh -c '[ -z "$(squeue -h 2>/dev/null)" ]'
  fi
  local p
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${pids[@]}"; do
    for _ in $(seq 1 50); do
      kill -0 "$p" 2>/dev/null || break
      sleep 0.1
    done
    kill -9 "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  rm -rf "$tmp"
}
trap cleanup EXIT
# On failure, the daemons' logs say why.
show_logs() {
  local f
  for f in "$tmp"/log/*; do
    [ -f "$f" ] || continue
    echo "---- $(basename "$f") (last 25 lines)"
    tail -n 25 "$f"
  done
}
fail_with_logs() {
  echo "FAIL $*"
  show_logs
  exit 1
}

mkdir -p "$tmp/munge" "$tmp/munge-run" "$tmp/state" "$tmp/spool" "$tmp/log" "$tmp/out"
chmod 700 "$tmp/munge" "$tmp/state" "$tmp/spool"
chmod 755 "$tmp/munge-run"
free_ports="$(python3 -c '
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks: s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in socks))')" || fail "cannot pick free ports"
read -r ctld_port slurmd_port <<<"$free_ports"

# munge: a fresh key, a private socket.
mungekey --create --keyfile="$tmp/munge/munge.key" --bits=1024 >/dev/null 2>&1 ||
  fail "mungekey could not create a key"
sock="$tmp/munge-run/munge.socket"
munged --foreground --force --socket="$sock" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge-run/munged.pid" --seed-file="$tmp/munge/munged.seed" \
  --log-file="$tmp/log/munged.log" >>"$tmp/log/munged.out" 2>&1 &
pids+=($!)
wait_for 10 sh -c "munge -S '$sock' -n | unmunge -S '$sock'" ||
  fail_with_logs "munged did not start (munge -n | unmunge failed)"

# The node as slurmd sees it (CPUs, sockets, cores, threads, memory), named localhost.
node="$(slurmd -C 2>/dev/null | head -1 | sed 's/^NodeName=[^ ]*/NodeName=localhost/')"
case "$node" in NodeName=localhost*CPUs=*) ;; *) fail "slurmd -C gave no node description: $node" ;; esac
cat >"$tmp/slurm.conf" <<EOF
ClusterName=ambisim_test
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
$node State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" >>"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
wait_for 30 scontrol ping || fail_with_logs "slurmctld did not answer scontrol ping"
slurmd -D -N localhost -f "$SLURM_CONF" >>"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
wait_for 30 sh -c 'sinfo -h -N -o "%t" | grep -qx "idle"' ||
  fail_with_logs "the node did not become idle: $(sinfo -N 2>&1)"
t_cluster=$(date +%s)
echo "cluster up in $((t_cluster - t_start)) s: $(scontrol ping | head -1); $(sinfo -h -N -o '%N %t %c CPUs')"

# The sweep on the cluster: 4 shards (12 runs, 3 each) and the merge.
sweep="$src/tests/data/small_sweep.json"
ids="$(AMBISIM_BIN="$bin" timeout 150 bash "$src/scripts/slurm/submit.sh" "$sweep" "$tmp/out/slurm_sweep" \
  -n 4 --wait 2>"$tmp/log/submit.err")" || {
  cat "$tmp/log/submit.err"
  for f in "$tmp"/out/slurm_sweep/slurm/*.out; do echo "---- $f"; cat "$f"; done
  fail_with_logs "the Slurm sweep failed (submit.sh --wait)"
}
read -r array_id merge_id <<<"$ids"
t_slurm=$(date +%s)
logs="$tmp/out/slurm_sweep/slurm"
for k in 1 2 3 4; do
  log="$logs/shard-${array_id}_$k.out"
  [ -f "$log" ] || fail "no log for array task $k ($log)"
  grep -q "ambisim shard $k/4:" "$log" || fail "task $k did not run shard $k/4: $(cat "$log")"
  grep -q "3 runs in this shard, 3 run, 0 resumed" "$log" || fail "task $k: $(cat "$log")"
done
merge_log="$logs/merge-$merge_id.out"
grep -q "12 runs in this shard, 0 run, 12 resumed" "$merge_log" || fail "merge: $(cat "$merge_log")"
# afterok: the merge started after the last shard finished.
last_end="$(grep -h "finished" "$logs"/shard-*.out | awk '{print $NF}' | sort -n | tail -1)"
merge_start="$(grep -h "started" "$merge_log" | awk '{print $NF}')"
python3 -c "import sys; sys.exit(0 if float(sys.argv[2]) >= float(sys.argv[1]) else 1)" \
  "$last_end" "$merge_start" || fail "the merge started at $merge_start, before the last shard ended at $last_end"

# The same sweep locally, -j2: summary.csv byte for byte (timing lives in timing.csv).
"$bin" sweep "$sweep" --out "$tmp/out/local" -j2 2>/dev/null || fail "local sweep -j2"
[ "$(ls "$tmp/out/slurm_sweep/runs" | wc -l)" -eq 12 ] || fail "expected 12 runs from the cluster"
cmp "$tmp/out/local/summary.csv" "$tmp/out/slurm_sweep/summary.csv" ||
  fail "summary.csv from Slurm differs from the local -j2 sweep"
t_end=$(date +%s)
echo "ok: array job $array_id (4 shards) and merge job $merge_id in $((t_slurm - t_cluster)) s;" \
  "summary.csv identical to the local -j2 run; $((t_end - t_start)) s in all"
