#!/usr/bin/env bash
# The de-icing arm's pipeline with the stage tools (issue 13): N joint samples in all, measured
#   plain:   mcws_sample N -> mcws_measure (Efron-corrected)
#   refined: mcws_sample N/2 -> mcws_boundary -> mcws_refine N/2 (--cloud) ->
#            mcws_measure --correction none
# for the 3-D volume and the X-Z area (theta3 fixed at 0), against the closed forms of
# BENCHMARKS.md (2 098 290 cm^3, 16 352.5 cm^2). Prints each measure's error and the refined
# pipeline's whole wall time, median of RUNS runs.
# Usage: scripts/bench_deicing_pipeline.sh [RUNS] [BUILD_DIR] [N]   (default 5, build/, 1000000)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
n=${3:-1000000}
bin=$build/apps
robot=$root/robots/deicing.yaml
exact_volume=2098290
exact_area=16352.5

refined() {  # plane flags for sample / boundary+measure; prints the measure's JSON
  local fix=$1 plane=$2
  # shellcheck disable=SC2086
  "$bin/mcws_sample" --robot "$robot" --samples $((n / 2)) $fix --output "$tmp/plain.pcd" 2>/dev/null
  # shellcheck disable=SC2086
  "$bin/mcws_boundary" --input "$tmp/plain.pcd" $plane --output "$tmp/rim.pcd" 2>/dev/null
  "$bin/mcws_refine" --robot "$robot" --input "$tmp/rim.pcd" --samples $((n - n / 2)) \
    --cloud "$tmp/plain.pcd" --output "$tmp/refined.pcd" 2>/dev/null
  # shellcheck disable=SC2086
  "$bin/mcws_measure" --input "$tmp/refined.pcd" $plane --correction none --json 2>/dev/null
}
plain() {
  # shellcheck disable=SC2086
  "$bin/mcws_sample" --robot "$robot" --samples "$n" $1 --output "$tmp/all.pcd" 2>/dev/null
  # shellcheck disable=SC2086
  "$bin/mcws_measure" --input "$tmp/all.pcd" $2 --json 2>/dev/null
}
error() {  # key, exact: reads JSON on stdin, prints "value (error %)"
  python3 -c 'import json, sys; v = json.load(sys.stdin)[sys.argv[1]]
print("%.1f (%+.3f %%)" % (v, 100 * (v / float(sys.argv[2]) - 1)))' "$1" "$2"
}

echo
echo "| $n joint samples | plain | refined | refined pipeline, wall median of $runs [s] |"
echo "|---|---|---|---|"
for what in volume area; do
  if [[ $what == volume ]]; then fix="" plane="" exact=$exact_volume unit="cm^3"
  else fix="--fix theta3=0" plane="--plane xz" exact=$exact_area unit="cm^2"; fi
  : >"$tmp/wall"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/wall" refined "$fix" "$plane" >"$tmp/refined.json"
  done
  printf '| %s [%s] | %s | %s | %.2f |\n' "$what" "$unit" "$(plain "$fix" "$plane" | error "$what" "$exact")" \
    "$(error "$what" "$exact" <"$tmp/refined.json")" "$(median <"$tmp/wall")"
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
