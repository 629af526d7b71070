#!/usr/bin/env bash
# The main job, from a fresh Debian 12 machine: install the dependencies, build, sample the
# de-icing arm of seed 000 (its X-Z plane workspace, Fig. 5, and its 3-D workspace, Fig. 6; 6000
# samples each), extract the X-Z boundary from 100000 samples (Fig. 13), measure the workspace's
# area and volume, and write the clouds and their pictures.
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

# Seed 000 Fig. 13: the X-Z boundary from 100000 samples, and the area and volume (100000 each).
"$bin/mcws_sample" --robot "$robot" --samples 100000 --seed 1 --fix theta3=0 \
  --output "$out/deicing_xz_100k.pcd"
"$bin/mcws_boundary" --input "$out/deicing_xz_100k.pcd" --plane xz --output "$out/deicing_xz_boundary.pcd"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_xz_100k.pcd" --overlay "$out/deicing_xz_boundary.pcd" \
  --output "$out/deicing_xz_boundary.png" --view xz --unit cm \
  --title "De-icing arm: X-Z workspace boundary (100000 samples)"
"$bin/mcws_sample" --robot "$robot" --samples 100000 --seed 1 --output "$out/deicing_3d_100k.pcd"
area=$("$bin/mcws_measure" --input "$out/deicing_xz_100k.pcd" --plane xz --boundary "$out/deicing_xz_boundary.pcd")
volume=$("$bin/mcws_measure" --input "$out/deicing_3d_100k.pcd")

echo "mcws: de-icing arm workspace written to $out:"
for f in deicing_xz.pcd deicing_xz.png deicing_3d.pcd deicing_3d.png deicing_xz_boundary.pcd \
  deicing_xz_boundary.png; do echo "  $out/$f"; done
echo "  X-Z plane ${area} cm^2; 3-D ${volume} cm^3 (mcws_measure, 100000 samples each)"
