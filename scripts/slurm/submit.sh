#!/usr/bin/env bash
# Runs an ambisim sweep on a Slurm cluster: an array job with one shard per task
# (sweep_array.sbatch) and a merge job that starts once every shard succeeded (merge.sbatch,
# --dependency=afterok). Run it on a login node; OUT_DIR must be on storage every node shares.
#
# Usage: scripts/slurm/submit.sh SWEEP.json OUT_DIR [-n TASKS] [-c CPUS_PER_TASK] [--wait]
#                                [-- SBATCH_OPTIONS...]
#   -n TASKS          shards, one array task each [4]
#   -c CPUS           CPUs per task; each shard runs that many runs at once (-j) [1]
#   --wait            block until the merge job has finished; exit with its status
#   SBATCH_OPTIONS    passed to both sbatch calls (e.g. --partition=cpu --time=2:00:00)
# The ambisim binary is $AMBISIM_BIN, else build/ambisim of this repository.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
usage() {
  sed -n '6,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
[ $# -ge 2 ] || usage
sweep="$1"
out="$2"
shift 2
tasks=4
cpus=1
wait=()
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -n) tasks="${2:?-n needs a number}"; shift 2 ;;
    -c) cpus="${2:?-c needs a number}"; shift 2 ;;
    --wait) wait=(--wait); shift ;;
    --) shift; extra=("$@"); break ;;
    *) echo "submit.sh: unknown option $1" >&2; usage ;;
  esac
done
[[ "$tasks" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: -n must be a positive whole number, got $tasks" >&2; exit 2; }
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: -c must be a positive whole number, got $cpus" >&2; exit 2; }
bin="${AMBISIM_BIN:-$root/build/ambisim}"
[ -x "$bin" ] || { echo "submit.sh: no ambisim binary at $bin (build it, or set AMBISIM_BIN)" >&2; exit 2; }
[ -f "$sweep" ] || { echo "submit.sh: $sweep: no such sweep file" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "submit.sh: sbatch not found (run this where Slurm's commands are)" >&2; exit 2; }
# The jobs run elsewhere, later: every path absolute.
bin="$(realpath "$bin")"
sweep="$(realpath "$sweep")"
mkdir -p "$out/slurm"
out="$(realpath "$out")"

array="$(sbatch --parsable --array="1-$tasks" --cpus-per-task="$cpus" --job-name=ambisim-shard \
  --output="$out/slurm/shard-%A_%a.out" "${extra[@]}" "$here/sweep_array.sbatch" "$bin" "$sweep" "$out")"
array="${array%%;*}"  # "jobid;cluster" on multi-cluster setups
echo "ambisim: array job $array: shards 1..$tasks of $sweep, logs $out/slurm/shard-${array}_K.out" >&2
# The merge waits for every task of the array to succeed; if one fails it is cancelled.
set +e
merge="$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --cpus-per-task="$cpus" --job-name=ambisim-merge --output="$out/slurm/merge-%j.out" \
  "${wait[@]}" "${extra[@]}" "$here/merge.sbatch" "$bin" "$sweep" "$out")"
status=$?
set -e
merge="${merge%%;*}"
echo "ambisim: merge job ${merge:-?} after every shard of $array succeeded -> $out/summary.csv" >&2
echo "$array $merge"
exit $status
