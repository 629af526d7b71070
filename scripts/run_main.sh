#!/usr/bin/env bash
# The main job, from a fresh Debian 12 machine: install the dependencies, build, sample the
# de-icing arm of seed 000 (its X-Z plane workspace, Fig. 5, and its 3-D workspace, Fig. 6; 6000
# samples each), and write the clouds and their pictures.
# Usage: scripts/run_main.sh [OUTPUT_DIR]   (default: out/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out}
bin=$root/build/apps

"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" "$root/build"
mkdir -p "$out"

robot=$root/robots/deicing.yaml
# JSON summaries are written beside the clouds, under a temporary name until complete.
"$bin/mcws_sample" --robot "$robot" --samples 6000 --seed 1 --fix theta3=0 \
  --output "$out/deicing_xz.pcd" --json >"$out/.deicing_xz.json.tmp"
mv "$out/.deicing_xz.json.tmp" "$out/deicing_xz.json"
"$bin/mcws_sample" --robot "$robot" --samples 6000 --seed 1 \
  --output "$out/deicing_3d.pcd" --json >"$out/.deicing_3d.json.tmp"
mv "$out/.deicing_3d.json.tmp" "$out/deicing_3d.json"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_xz.pcd" --output "$out/deicing_xz.png" \
  --view xz --unit cm --title "De-icing arm: workspace in the X-Z plane (6000 samples)"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_3d.pcd" --output "$out/deicing_3d.png" \
  --view 3d --unit cm --title "De-icing arm: 3-D workspace (6000 samples)"

echo "mcws: de-icing arm workspace written to $out:"
for f in deicing_xz.pcd deicing_xz.png deicing_3d.pcd deicing_3d.png; do echo "  $out/$f"; done
