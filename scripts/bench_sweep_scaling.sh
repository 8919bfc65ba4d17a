#!/usr/bin/env bash
# Sweep scaling (docs/PERFORMANCE.md): the same sweep at -j1 and at -j2, wall-clock and CPU time
# of each, the speed-up, and a check that both wrote byte-identical summaries. Run it on a quiet
# machine: the load average is printed before and after each sweep.
# Usage: scripts/bench_sweep_scaling.sh [BUILD_DIR] [SWEEP_JSON] [OUT_DIR]
#   defaults: build, scenarios/sweeps/default.json, a temporary directory (removed at the end)
set -eu
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
sweep="${2:-$root/scenarios/sweeps/default.json}"
out="${3:-}"
bin="$build/ambisim"
[ -x "$bin" ] || { echo "no $bin: build first" >&2; exit 2; }
if [ -z "$out" ]; then
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
echo "sweep:   ${sweep#"$root"/}"

declare -A wall
for j in 1 2; do
  dir="$out/j$j"
  rm -rf "$dir"
  echo "load before -j$j: $(cut -d' ' -f1-3 /proc/loadavg)"
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$out/time_j$j" "$bin" sweep "$sweep" --out "$dir" -j "$j" \
    >"$out/log_j$j" 2>&1
  end=$(date +%s.%N)
  wall[$j]=$(echo "$end - $start" | bc -l)
  read -r user sys <"$out/time_j$j"
  printf -- "-j%s: wall %.1f s, cpu %.1f s (user %.1f + sys %.1f)\n" "$j" "${wall[$j]}" \
    "$(echo "$user + $sys" | bc -l)" "$user" "$sys"
  echo "load after -j$j:  $(cut -d' ' -f1-3 /proc/loadavg)"
done
cmp -s "$out/j1/summary.csv" "$out/j2/summary.csv" || { echo "FAIL: summaries differ"; exit 1; }
echo "summary.csv identical at -j1 and -j2"
printf "speed-up -j2 vs -j1: %.2fx (target >= 1.8x)\n" "$(echo "${wall[1]} / ${wall[2]}" | bc -l)"
