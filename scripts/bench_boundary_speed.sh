#!/usr/bin/env bash
# Whole-stage timing of mcws_boundary (load, filter, save), median of R runs, on validation clouds:
# 2-D disk of 200000 and 1000000 points, 3-D ball of 1000000; with the default grid search and
# with every point searched in the KdTreeFLANN (--tree-search) for comparison.
# Usage: scripts/bench_boundary_speed.sh [RUNS]   (default 5; needs a release build in build/)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" "${1:-}"
bin=$build/apps
"$bin/mcws_sample" --shape disk --samples 200000 --output "$tmp/disk200k.pcd" 2>/dev/null
"$bin/mcws_sample" --shape disk --samples 1000000 --output "$tmp/disk1m.pcd" 2>/dev/null
"$bin/mcws_sample" --shape ball --samples 1000000 --output "$tmp/ball1m.pcd" 2>/dev/null
run() {  # label, cloud, flags...
  local label=$1 cloud=$2
  shift 2
  : >"$tmp/wall"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/wall" "$bin/mcws_boundary" --input "$tmp/$cloud" --output "$tmp/out.pcd" \
      "$@" 2>/dev/null
  done
  printf '| %s | %s s |\n' "$label" "$(median <"$tmp/wall")"
}
echo
echo "| cloud, search | whole stage, median of $runs |"
echo "|---|---|"
run "disk 200000, grid" disk200k.pcd --plane xy
run "disk 1000000, grid" disk1m.pcd --plane xy
run "ball 1000000, grid" ball1m.pcd
run "disk 200000, tree" disk200k.pcd --plane xy --tree-search
run "disk 1000000, tree" disk1m.pcd --plane xy --tree-search
run "ball 1000000, tree" ball1m.pcd --tree-search
