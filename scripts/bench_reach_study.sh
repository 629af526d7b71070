#!/usr/bin/env bash
# Reach-study and base-placement run times for BENCHMARKS.md: mcws_reach --targets on a wall of
# 400 point-and-normal targets 900 mm in front of the inspection arm (its collision model, 4 IK
# starts per target), threads 2 and 1 in the same run (the ratio is the peer); and mcws_place on
# the maintenance arm's damper targets (a 2e7-sample map at 2 cm, 241 positions, all confirmed by
# IK). Medians of 5 whole-process runs (/usr/bin/time -v).
# Usage: scripts/bench_reach_study.sh [BUILD_DIR]   (needs a release build)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" 5 "${1:-}"

# 20 x 20 targets on the plane x = 900 mm, y in [-600, 600], z in [0, 1200], facing the robot.
awk 'BEGIN { print "x,y,z,normal_x,normal_y,normal_z";
  for (i = 0; i < 20; i++) for (j = 0; j < 20; j++)
    printf "900,%.3f,%.3f,-1,0,0\n", -600 + i * 1200 / 19, j * 1200 / 19 }' >"$tmp/wall.csv"

echo
echo "## mcws_reach --targets: inspection6, 400 wall targets, collision model, 4 IK starts (median of $runs)"
echo "| threads | reached | wall s | ms per target | peak RSS MB |"
echo "|---:|---:|---:|---:|---:|"
for threads in 2 1; do
  read -r wall rss < <(time_runs "$build/apps/mcws_reach" --robot "$root/robots/inspection6.yaml" \
    --targets "$tmp/wall.csv" --threads "$threads" --output "$tmp/heat.pcd" --json)
  reached=$(sed -n 's/.*"reached":\([0-9]*\).*/\1/p' "$tmp/out")
  awk -v t="$threads" -v r="$reached" -v w="$wall" -v rss="$rss" 'BEGIN {
    printf "| %d | %d of 400 | %.3f | %.3f | %.0f |\n", t, r, w, 1000 * w / 400, rss }'
done

echo
echo "## mcws_place: maintenance4, 15 damper targets, map 2e7 samples at 2 cm, 241 positions all confirmed (median of $runs)"
echo "| threads | best offset cm | wall s | peak RSS MB |"
echo "|---:|---:|---:|---:|"
for threads in 2 1; do
  read -r wall rss < <(time_runs "$build/apps/mcws_place" --robot "$root/robots/maintenance4.yaml" \
    --targets "$root/robots/maintenance4_damper_targets.pcd" --standoff 2cm --along "-120 120 1" \
    --resolution 2cm --samples 20000000 --confirm all --threads "$threads" --map-cache off \
    --output "$tmp/bases.pcd" --json)
  best=$(python3 -c "import json; print(json.load(open('$tmp/out'))['best']['offset'][0])")
  awk -v t="$threads" -v b="$best" -v w="$wall" -v rss="$rss" 'BEGIN {
    printf "| %d | %s | %.2f | %.0f |\n", t, b, w, rss }'
done
