#!/usr/bin/env bash
# Reachability-map speed and memory for BENCHMARKS.md: whole runs of mcws_reach on inspection6
# (200 approach directions, 1 roll bin) at 10 cm and 2 cm voxels, with and without the Jacobian's
# manipulability, 2 threads and 1; beside them, as the peer in the same run, mcws_sample
# writing 10 million samples of the same arm (forward kinematics of the tool point into a PCD).
# Medians of 5 whole-process runs (/usr/bin/time -v: wall time, peak memory).
# Usage: scripts/bench_reach.sh [SAMPLES (100000000)] [BUILD_DIR]   (needs a release build)
set -euo pipefail
samples=${1:-100000000}
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" 5 "${2:-}"
robot=$root/robots/inspection6.yaml

echo
echo "## mcws_reach, inspection6, $samples samples (median of $runs)"
echo "| resolution | manipulability | threads | voxels | wall s | M samples/s | peak RSS MB |"
echo "|---|---|---:|---:|---:|---:|---:|"
for resolution in 10cm 2cm; do
  for manip in yes no; do
    for threads in 2 1; do
      flags=()
      [[ $manip == no ]] && flags+=(--no-manipulability)
      read -r wall rss < <(time_runs "$build/apps/mcws_reach" --robot "$robot" --resolution "$resolution" \
        --samples "$samples" --threads "$threads" --output "$tmp/map.pcd" "${flags[@]}")
      voxels=$(sed -n 's/^POINTS //p' "$tmp/map.pcd")
      awk -v r="$resolution" -v m="$manip" -v t="$threads" -v v="$voxels" -v w="$wall" \
        -v rss="$rss" -v n="$samples" 'BEGIN {
        printf "| %s | %s | %d | %d | %.2f | %.1f | %.0f |\n", r, m, t, v, w, n / w / 1e6, rss }'
    done
  done
done

echo
echo "## Peer in the same run: mcws_sample, inspection6, 10000000 samples, 2 threads (median of $runs)"
read -r wall rss < <(time_runs "$build/apps/mcws_sample" --robot "$robot" --samples 10000000 \
  --threads 2 --output "$tmp/ws.pcd")
awk -v w="$wall" -v rss="$rss" 'BEGIN {
  printf "wall %.2f s, %.1f M samples/s, peak RSS %.0f MB\n", w, 10 / w, rss }'
