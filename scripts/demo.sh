#!/usr/bin/env bash
# The main job: installs what is missing, builds, then writes to out/demo/ (or $1):
#   world.png, probe_*.png/json   the default world and a few probes (cube crosses)
#   sweep/                        the default sweep (both thesis scenarios x every planner x
#                                 2 budgets x 3 camera speeds x 5 seeds): runs/, summary.csv,
#                                 timing.csv
#   sweep/compare.{txt,csv,json}  every planner against shgraph+vp over the seeds (means, 95 %
#                                 bootstrap intervals, ratios, wins)
#   sweep/charts/                 accuracy vs cost, error and pops vs speed, coverage vs
#                                 budget, box plots across seeds, time series
#   sweep/runs/<run>/views/       ParaView files and PNG snapshots of two motorway runs
#   film/forest_edge.mp4          the forest edge as the player sees it: ambisim | shgraph+vp |
#                                 truth (20 s, 640x360 panels, 30 fps), with
#                                 forest_edge_contact.png (a frame every 2 s) and a still
# Rerunning resumes the sweep (finished runs are kept) and redraws the pictures.
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
  run "$AMBISIM" probe "$SCEN/default_world.json" --at "$at" --above-ground \
    --cube "$OUT/probe_$name.png" --json --force >"$OUT/probe_$name.json"
done <"$SCEN/demo_probes.txt"
echo "== default sweep (resumable)" >&2
"$AMBISIM" sweep "$SCEN/sweeps/default.json" --out "$OUT/sweep" --resume
echo "== compare over seeds" >&2
"$AMBISIM" compare "$OUT/sweep" --baseline shgraph+vp --csv "$OUT/sweep/compare.csv" \
  --json "$OUT/sweep/compare.json" --force >"$OUT/sweep/compare.txt"
echo "== charts" >&2
run "$AMBISIM" plot "$OUT/sweep" --run motorway__ambisim__b1__v1__s1 --force
echo "== views" >&2
for r in motorway__ambisim__b1__v1__s1 motorway__shgraph+vp__b1__v1__s1 forest_edge__ambisim__b1__v1__s1; do
  run "$AMBISIM" viz "$OUT/sweep/runs/$r" --force
done
echo "== film" >&2
mkdir -p "$OUT/film"
runs="$OUT/sweep/runs"
run "$AMBISIM" film "$runs/forest_edge__ambisim__b1__v1__s1" "$runs/forest_edge__shgraph+vp__b1__v1__s1" \
  --out "$OUT/film/forest_edge.mp4" --force
# A still at 16 s (film frame 480), where the props stand in view.
ffmpeg -hide_banner -loglevel error -y -i "$OUT/film/forest_edge.mp4" -vf "select=eq(n\,480)" \
  -frames:v 1 "$OUT/film/forest_edge_still.png"
echo "ambisim demo: outputs in $OUT (charts in $OUT/sweep/charts)" >&2
