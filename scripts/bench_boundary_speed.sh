#!/usr/bin/env bash
# Whole-stage timing of mcws_boundary (load, filter, save), median of R runs, on validation clouds:
# 2-D disk of 200000 and 1000000 points, 3-D ball of 1000000; with the default grid search and
# with every point searched in the KdTreeFLANN (--tree-search) for comparison.
# Usage: scripts/bench_boundary_speed.sh [RUNS]   (default 5; needs a release build in build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/apps
runs=${1:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/mcws_sample" --shape disk --samples 200000 --output "$work/disk200k.pcd" 2>/dev/null
"$bin/mcws_sample" --shape disk --samples 1000000 --output "$work/disk1m.pcd" 2>/dev/null
"$bin/mcws_sample" --shape ball --samples 1000000 --output "$work/ball1m.pcd" 2>/dev/null
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}'; }
run() {  # label, cloud, flags...
  local label=$1 cloud=$2
  shift 2
  local times=()
  for _ in $(seq "$runs"); do
    local start end
    start=$(date +%s.%N)
    "$bin/mcws_boundary" --input "$work/$cloud" --output "$work/out.pcd" "$@" 2>/dev/null
    end=$(date +%s.%N)
    times+=("$(echo "$end - $start" | bc)")
  done
  printf '| %s | %s s |\n' "$label" "$(printf '%s\n' "${times[@]}" | median)"
}
echo "| cloud, search | whole stage, median of $runs |"
echo "|---|---|"
run "disk 200000, grid" disk200k.pcd --plane xy
run "disk 1000000, grid" disk1m.pcd --plane xy
run "ball 1000000, grid" ball1m.pcd
run "disk 200000, tree" disk200k.pcd --plane xy --tree-search
run "disk 1000000, tree" disk1m.pcd --plane xy --tree-search
run "ball 1000000, tree" ball1m.pcd --tree-search
