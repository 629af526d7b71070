#!/usr/bin/env bash
# Collision-checked sampling benchmarks for BENCHMARKS.md: (1) Google Benchmark of
# LabelledRobotSampler on ta1400 (capsules) and ta1400_mesh (triangle meshes), file writing
# excluded, with the ablations (capsules through fcl::collide, no bounding spheres); (2) timed
# whole runs of mcws_sample --collision --threads 2 (2 million capsule samples, 500000 mesh
# samples). Medians of 5 in one run of this script; the load average is printed because the
# machine may be shared.
# Usage: scripts/bench_collision.sh [BUILD_DIR]   (needs a release build)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" 5 "${1:-}"
echo
echo "## Google Benchmark (median of 5)"
benchmark_medians "$build/bench/bench_collision"
echo

echo "## Whole runs, mcws_sample --collision --threads 2 (median of 5)"
echo "| robot | samples | wall s | samples/s |"
echo "|---|---|---|---|"
for run in "ta1400 2000000" "ta1400_mesh 500000"; do
  set -- $run
  : >"$tmp/wall"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/wall" "$build/apps/mcws_sample" --robot "$root/robots/$1.yaml" --collision \
      --samples "$2" --threads 2 --output "$tmp/c.pcd" 2>/dev/null
    rm -f "$tmp/c.pcd"
  done
  wall=$(median <"$tmp/wall")
  awk -v r="$1" -v n="$2" -v w="$wall" 'BEGIN {printf "| %s | %d | %.2f | %.0f |\n", r, n, w, n / w}'
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
