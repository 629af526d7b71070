#!/usr/bin/env bash
# The tiled boundary for BENCHMARKS.md (issue 18, section 3): mcws_boundary on a 1e7-point ball
# (mcws_sample --shape ball) without --tiles, with --tiles 4 and 16 (2 threads), and under mpirun
# on 2 processes x 1 thread with --tiles 16: wall time and peak RSS, median of RUNS each (runs
# interleaved), the outputs compared with the whole-cloud run's. Then, once, a POINTS-point ball
# (default 1e8, 4.8 GB) in 16 slabs on one process: wall time, peak RSS, the JSON summary.
# Clouds in $TMPDIR (default /tmp). Usage: scripts/bench_tiled_boundary.sh [RUNS] [BUILD_DIR] [POINTS]
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" "${1:-5}" "${2:-}"
big=${3:-100000000}
mpirun=(mpirun --oversubscribe)
[[ $(id -u) -ne 0 ]] || mpirun+=(--allow-run-as-root)
boundary=$build/apps/mcws_boundary

"$build/apps/mcws_sample" --shape ball --samples 10000000 --output "$tmp/ball.pcd" 2>/dev/null
configs=(
  "whole|$boundary --input $tmp/ball.pcd --threads 2"
  "tiles-4|$boundary --input $tmp/ball.pcd --threads 2 --tiles 4"
  "tiles-16|$boundary --input $tmp/ball.pcd --threads 2 --tiles 16"
  "np2-tiles-16|${mpirun[*]} -np 2 $boundary --input $tmp/ball.pcd --threads 1 --tiles 16"
)
for _ in $(seq "$runs"); do
  for config in "${configs[@]}"; do
    name=${config%%|*}
    read -r -a command <<<"${config#*|}"
    time_once "$tmp/$name.wall" "$tmp/$name.rss" "${command[@]}" --output "$tmp/$name.pcd"
    [[ $name == whole ]] || cmp -s "$tmp/whole.pcd" "$tmp/$name.pcd" ||
      { echo "$name: the boundary differs from the whole cloud's" >&2; exit 1; }
  done
done
echo "load average after the timed runs: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "1e7-point ball, boundary byte-identical in every run:"
echo "| configuration | median wall s (of $runs) | median peak RSS MB (np2: the largest process) |"
echo "|---|---|---|"
for config in "${configs[@]}"; do
  name=${config%%|*}
  echo "| $name | $(median <"$tmp/$name.wall") | $(median <"$tmp/$name.rss") |"
done

rm -f "$tmp"/*.pcd
echo
echo "$big-point ball in 16 slabs, one process x 2 threads, once:"
"$build/apps/mcws_sample" --shape ball --samples "$big" --output "$tmp/big.pcd" 2>/dev/null
ls -l "$tmp/big.pcd" | awk '{print "input file: " $5 " bytes"}'
time_once "$tmp/big.wall" "$tmp/big.rss" "$boundary" --input "$tmp/big.pcd" --threads 2 \
  --tiles 16 --json --output "$tmp/big_boundary.pcd"
echo "wall $(cat "$tmp/big.wall") s, peak RSS $(cat "$tmp/big.rss") MB"
cat "$tmp/out"
