#!/usr/bin/env bash
# The boundary and measuring stages against their limits, in one run: on the 1e6-point unit ball
# and unit disk (seed 1), whole-process wall time of mcws_boundary and mcws_measure (the
# commands alternate, median of RUNS), and the CGAL alpha shape on the same points
# (build/bench/boundary_peers: Fixed_alpha_shape_3 for the ball, Alpha_shape_2 for the disk; the
# time it reports is the alpha shape alone, without making the cloud or reading a file, so the
# ratio favours CGAL). Prints a markdown table with the ratios CGAL / boundary and measure /
# boundary.
# Usage: scripts/bench_boundary_measure.sh [RUNS] [BUILD_DIR]   (default 5, build/)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
cmake --build "$build" -j2 --target boundary_peers mcws_boundary mcws_measure mcws_sample >/dev/null
bin=$build/apps
"$bin/mcws_sample" --shape ball --samples 1000000 --seed 1 --output "$tmp/ball.pcd" 2>/dev/null
"$bin/mcws_sample" --shape disk --samples 1000000 --seed 1 --output "$tmp/disk.pcd" 2>/dev/null

echo
echo "| cloud | mcws_boundary [s] | mcws_measure [s] | CGAL alpha shape [s] | CGAL / boundary | measure / boundary |"
echo "|---|---|---|---|---|---|"
for shape in ball disk; do
  flags=() peer="CGAL Fixed_alpha_shape_3"
  [[ $shape == disk ]] && flags=(--plane xy) peer="CGAL Alpha_shape_2"
  : >"$tmp/b" ; : >"$tmp/m" ; : >"$tmp/c"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/b" "$bin/mcws_boundary" --input "$tmp/$shape.pcd" --output "$tmp/o.pcd" \
      "${flags[@]}" 2>/dev/null
    wall_time "$tmp/m" "$bin/mcws_measure" --input "$tmp/$shape.pcd" "${flags[@]}" \
      >/dev/null 2>&1
    # One run of the peer a round (it times itself: "| ball | CGAL ... | 14.40 s (1 run) | ...").
    "$build/bench/boundary_peers" 1000000 "$shape" 2 "$peer" 2>/dev/null |
      awk -F'|' '/CGAL/ {split($4, t, " "); print t[1]}' >>"$tmp/c"
  done
  b=$(median <"$tmp/b") m=$(median <"$tmp/m") c=$(median <"$tmp/c")
  awk -v s="$shape" -v b="$b" -v m="$m" -v c="$c" \
    'BEGIN {printf "| %s 1e6 | %.2f | %.2f | %.2f | %.1f | %.2f |\n", s, b, m, c, c / b, m / b}'
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
