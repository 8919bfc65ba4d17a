#!/usr/bin/env bash
# The room check must be able to fail: copy the tree's sources and the order, add one include
# of a room above (the world including the simulator), one of a sibling family and one the
# planners may never make, and expect exit 1 naming each.
set -euo pipefail
python="$1"
root="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs"
cp "$root/docs/ARCHITECTURE.md" "$tmp/docs/"
for d in sim policies viz apps; do cp -r "$root/$d" "$tmp/$d"; done
"$python" "$root/scripts/check_rooms.py" "$tmp" >/dev/null  # the copy passes as it is
echo '#include "sim/run/simulator.h"' >>"$tmp/sim/world/terrain_noise.cpp"
echo '#include "policies/thesis/octree.h"' >>"$tmp/policies/ambisim/demand_planner.cpp"
echo '#include "sim/run/reference_track.h"' >>"$tmp/policies/core/default_ambient.cpp"
touch "$tmp/sim/stray.cpp"
if out="$("$python" "$root/scripts/check_rooms.py" "$tmp" 2>&1)"; then
  echo "check_rooms passed a tree with bad includes:"; echo "$out"; exit 1
fi
for want in "sim/world/terrain_noise.cpp:.*a room above (sim/run)" \
  "policies/ambisim/demand_planner.cpp:.*a sibling (policies/thesis)" \
  "policies/core/default_ambient.cpp:.*may never include sim/run" \
  "sim/stray.cpp: stands in no room"; do
  grep -q "$want" <<<"$out" || { echo "missing: $want"; echo "$out"; exit 1; }
done
echo "check_rooms fails as it should:"; echo "$out"
