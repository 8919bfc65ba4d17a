#!/usr/bin/env bash
# Regenerates scenarios/levels/lakeside/ (the level scenarios/level_flyover.json imports): the
# default world's lake shore, 1024 x 1024 m from (700, 1900), every second 2 m cell, as a
# 256 x 256 level of 4 m cells. Byte-identical on every run.
# Usage: scripts/make_example_level.sh [AMBISIM_BINARY]   (default build/ambisim)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${1:-$root/build/ambisim}"
mkdir -p "$root/scenarios/levels/lakeside"
"$bin" world "$root/scenarios/default_world.json" --export-level "$root/scenarios/levels/lakeside" \
  --region 700,1900,1724,2924 --stride 2 --force
# The test set's level (scenarios/test_set/shore_skim.json): another world's lake shore (seed 7),
# so no tuning run ever saw its terrain.
mkdir -p "$root/scenarios/levels/westlake"
printf '{"world": {"seed": 7}}' >"${TMPDIR:-/tmp}/ambisim_seed7_world.json"
"$bin" world "${TMPDIR:-/tmp}/ambisim_seed7_world.json" --export-level "$root/scenarios/levels/westlake" \
  --region 300,1500,1324,2524 --stride 2 --force
