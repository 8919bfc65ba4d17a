#!/usr/bin/env bash
# The main job: installs what is missing, builds, and writes the demo outputs to out/demo/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ambisim_setup
OUT="${1:-$AMBISIM_ROOT/out/demo}"
mkdir -p "$OUT"
AMBISIM="$AMBISIM_BUILD/ambisim"
SCEN="$AMBISIM_ROOT/scenarios"
run() { xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"; }

echo "== world map" >&2
run "$AMBISIM" world "$SCEN/default_world.json" --png "$OUT/world.png" --force
echo "== probes" >&2
while read -r name at; do
  run "$AMBISIM" probe "$SCEN/default_world.json" --at "$at" --above-ground --cube "$OUT/probe_$name.png" \
    --json --force >"$OUT/probe_$name.json"
done <"$SCEN/demo_probes.txt"
echo "ambisim demo: outputs in $OUT" >&2
