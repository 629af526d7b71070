#!/usr/bin/env bash
# Reachability maps before and after a change, in the same run: mcws_reach of two release builds
# on the inspection arm, 1e8 samples, 200 directions, 2 threads, at 2 cm and 10 cm, with and
# without manipulability; the two builds' runs interleaved, medians of 5 whole runs (wall time
# and peak RSS, /usr/bin/time); then the peer, mcws_sample writing 1e7 samples of the same arm.
# The maps of the two builds must be the same bytes (checked).
# Usage: scripts/bench_reach_ab.sh OLD_BUILD_DIR [NEW_BUILD_DIR (build/)] [SAMPLES (100000000)]
#   (an old build: git worktree add /tmp/old REV && scripts/build.sh /tmp/old/build)
set -euo pipefail
(($# >= 1)) || { echo "usage: $0 OLD_BUILD_DIR [NEW_BUILD_DIR] [SAMPLES]" >&2; exit 2; }
old=$1
[[ -x $old/apps/mcws_reach ]] || { echo "$0: no $old/apps/mcws_reach" >&2; exit 2; }
samples=${3:-100000000}
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" 5 "${2:-}"
robot=$root/robots/inspection6.yaml

echo
echo "## mcws_reach, inspection6, $samples samples, 2 threads (median of $runs, interleaved)"
echo "| resolution | manipulability | before s | after s | after/before | M samples/s after | peak RSS MB before | after |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for resolution in 2cm 10cm; do
  for manip in no yes; do
    flags=()
    [[ $manip == no ]] && flags+=(--no-manipulability)
    for side in before after; do : >"$tmp/wall.$side"; : >"$tmp/rss.$side"; done
    for _ in $(seq "$runs"); do
      for side in before after; do
        dir=$build
        [[ $side == before ]] && dir=$old
        time_once "$tmp/wall.$side" "$tmp/rss.$side" "$dir/apps/mcws_reach" --robot "$robot" \
          --resolution "$resolution" --samples "$samples" --threads 2 \
          --output "$tmp/map.$side.pcd" "${flags[@]}"
      done
    done
    cmp -s "$tmp/map.before.pcd" "$tmp/map.after.pcd" || { echo "the maps differ" >&2; exit 1; }
    awk -v r="$resolution" -v m="$manip" -v n="$samples" -v b="$(median <"$tmp/wall.before")" \
      -v a="$(median <"$tmp/wall.after")" -v rb="$(median <"$tmp/rss.before")" \
      -v ra="$(median <"$tmp/rss.after")" 'BEGIN {
      printf "| %s | %s | %.2f | %.2f | %.2f | %.1f | %.0f | %.0f |\n", r, m, b, a, a / b, n / a / 1e6, rb, ra }'
  done
done

echo
echo "## Peer in the same run: mcws_sample, inspection6, 10000000 samples, 2 threads (median of $runs)"
read -r wall rss < <(time_runs "$build/apps/mcws_sample" --robot "$robot" --samples 10000000 \
  --threads 2 --output "$tmp/ws.pcd")
awk -v w="$wall" -v rss="$rss" 'BEGIN {
  printf "wall %.2f s, %.1f M samples/s, peak RSS %.0f MB\n", w, 10 / w, rss }'
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
