#!/usr/bin/env bash
# The Python module against the stage tools on the same work, side by side in one run (issue 34):
#   de-icing: N/2 joint samples of robots/deicing.yaml -> boundary -> N/2 refined samples near it
#             -> volume without edge correction (the README's tour at N samples);
#   ball:     the boundary and the volume of an N-point ball (its PCD made once, read by both).
# The tools pass PCD files from stage to stage, as a shell pipeline does; the Python script keeps
# the arrays in memory and writes nothing. Runs alternate (tools, Python, tools, ...); prints the
# median wall time of each and the ratio Python / tools, and checks that both give the same volume.
# Usage: scripts/bench_python.sh [RUNS] [BUILD_DIR] [N]   (default 5, build/, 1000000)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
n=${3:-1000000}
bin=$build/apps
robot=$root/robots/deicing.yaml
python=${PYTHON:-/usr/bin/python3}
export PYTHONPATH=$build/python

volume() { python3 -c 'import json, sys; print(json.load(sys.stdin)["volume"])'; }

deicing_tools() {
  "$bin/mcws_sample" --robot "$robot" --samples $((n / 2)) --seed 2 --output "$tmp/ws.pcd" 2>/dev/null
  "$bin/mcws_boundary" --input "$tmp/ws.pcd" --output "$tmp/rim.pcd" 2>/dev/null
  "$bin/mcws_refine" --robot "$robot" --input "$tmp/rim.pcd" --cloud "$tmp/ws.pcd" \
    --samples $((n - n / 2)) --seed 3 --output "$tmp/refined.pcd" 2>/dev/null
  "$bin/mcws_measure" --input "$tmp/refined.pcd" --correction none --json 2>/dev/null | volume
}
deicing_python() {
  "$python" - "$robot" "$n" <<'EOF'
import sys
import numpy as np
import mcws
robot, n = mcws.Robot(sys.argv[1]), int(sys.argv[2])
ws = mcws.sample(robot, n // 2, seed=2)
rim = ws[mcws.boundary(ws)]
new = mcws.refine(robot, rim, n - n // 2, seed=3)
print(mcws.measure(np.concatenate([ws, new]), correction="none").volume)
EOF
}
ball_tools() {
  "$bin/mcws_boundary" --input "$tmp/ball.pcd" --output "$tmp/ball_rim.pcd" 2>/dev/null
  "$bin/mcws_measure" --input "$tmp/ball.pcd" --json 2>/dev/null | volume
}
ball_python() {
  "$python" - "$tmp/ball.pcd" <<'EOF'
import sys
import mcws
points = mcws.read_pcd(sys.argv[1])
rim = points[mcws.boundary(points)]
print(mcws.measure(points).volume)
EOF
}

"$bin/mcws_sample" --shape ball --samples "$n" --seed 1 --output "$tmp/ball.pcd" 2>/dev/null
echo
echo "| $n points | tools, median of $runs [s] | Python, median of $runs [s] | Python / tools | same volume |"
echo "|---|---|---|---|---|"
for work in deicing ball; do
  : >"$tmp/tools"; : >"$tmp/python"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/tools" "${work}_tools" >"$tmp/tools.out"
    wall_time "$tmp/python" "${work}_python" >"$tmp/python.out"
  done
  tools=$(median <"$tmp/tools") py=$(median <"$tmp/python")
  same=no
  python3 -c 'import sys; a, b = (float(open(f).read()) for f in sys.argv[1:]); sys.exit(abs(a / b - 1) > 1e-12)' \
    "$tmp/tools.out" "$tmp/python.out" && same=yes
  printf '| %s | %.2f | %.2f | %.3f | %s |\n' "$work" "$tools" "$py" \
    "$(awk -v a="$py" -v b="$tools" 'BEGIN {print a / b}')" "$same"
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
