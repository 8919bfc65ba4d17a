#!/usr/bin/env bash
# Copies the pictures the README shows from a demo output (scripts/demo.sh) into docs/images/,
# so they come from a run, never by hand. Usage: scripts/docs_images.sh [DEMO_OUT [DYNAMIC_OUT]]
#   (default out/demo; DYNAMIC_OUT, a run of scenarios/sweeps/dynamic.json plotted with
#   `ambisim plot`, adds the charts of light that changes). Fails if a picture is missing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
demo="${1:-$root/out/demo}"
img="$root/docs/images"
sweep="$demo/sweep"
copy() { [ -f "$1" ] || { echo "docs_images: missing $1 (run scripts/demo.sh first)" >&2; exit 1; }; cp "$1" "$img/$2"; }
copy "$demo/world.png" world.png
copy "$demo/probe_forest_edge.png" probe_forest_edge.png
for sc in motorway forest_edge; do
  copy "$sweep/charts/${sc}_accuracy_cost.png" "${sc}_accuracy_cost.png"
  copy "$sweep/charts/${sc}_speed.png" "${sc}_speed.png"
  copy "$sweep/charts/${sc}_seeds.png" "${sc}_seeds.png"
done
copy "$sweep/charts/motorway__ambisim__b1__v1__s1_series.png" motorway_ambisim_series.png
copy "$sweep/runs/motorway__ambisim__b1__v1__s1/views/snapshot_f000600.png" snapshot_motorway_ambisim.png
copy "$sweep/runs/motorway__shgraph+vp__b1__v1__s1/views/snapshot_f000600.png" snapshot_motorway_shgraph_vp.png
copy "$sweep/runs/forest_edge__ambisim__b1__v1__s1/views/snapshot_f000600.png" snapshot_forest_edge_ambisim.png
copy "$demo/film/forest_edge_still.png" film_forest_edge_still.png
copy "$demo/film/forest_edge_contact.png" film_forest_edge_contact.png
if [ $# -ge 2 ]; then
  for sc in sunset_drive day_cycle cloud_shadows fog_bank; do
    copy "$2/charts/${sc}_light.png" "${sc}_light.png"
  done
fi
echo "docs_images: docs/images/ updated from $demo${2:+ and $2}" >&2
