#!/usr/bin/env bash
# Sampling benchmarks for BENCHMARKS.md: (1) Google Benchmark of the sampler's forward kinematics
# (file writing excluded) and of the PCD writer alone; (2) timed whole runs of mcws_sample with
# 10 million samples (/usr/bin/time -v: wall time, peak memory) beside dd writing the same number
# of bytes to the same disk, without and with fdatasync (mcws_sample syncs its file to the disk
# before giving it its name). Medians of 5 (benchmarks and whole runs) in one run of this script.
# Usage: scripts/bench_sampling.sh [BUILD_DIR]   (needs a release build)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" 5 "${1:-}"
echo
echo "## Google Benchmark (median of 5)"
benchmark_medians "$build/bench/bench_sampler"
echo

echo "## Whole runs, 10000000 samples, --threads 2 (median of 5)"
echo "| robot | wall s | peak RSS MB | file MB | RSS / file | dd same bytes s | dd + fdatasync s |"
echo "|---|---|---|---|---|---|---|"
write_zeros() {  # bytes, file [dd option]: dd writing as many bytes as mcws_sample wrote
  head -c "$1" /dev/zero | dd of="$2" bs=12M iflag=fullblock status=none ${3:+"$3"}
}
for robot in ta1400 inspection6; do
  : >"$tmp/wall"; : >"$tmp/rss"; : >"$tmp/dd"; : >"$tmp/ddsync"
  for _ in $(seq "$runs"); do
    rm -f "$tmp/ws.pcd"; sync
    /usr/bin/time -v "$build/apps/mcws_sample" --robot "$root/robots/$robot.yaml" \
      --samples 10000000 --threads 2 --output "$tmp/ws.pcd" 2>"$tmp/time.log"
    awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' \
      "$tmp/time.log" >>"$tmp/wall"
    awk -F': ' '/Maximum resident set size/ {print $2 / 1024}' "$tmp/time.log" >>"$tmp/rss"
    bytes=$(stat -c %s "$tmp/ws.pcd")
    rm -f "$tmp/ws.pcd" "$tmp/dd.bin"; sync
    wall_time "$tmp/dd" write_zeros "$bytes" "$tmp/dd.bin"
    rm -f "$tmp/dd.bin"; sync
    wall_time "$tmp/ddsync" write_zeros "$bytes" "$tmp/dd.bin" conv=fdatasync
    rm -f "$tmp/dd.bin"
  done
  wall=$(median <"$tmp/wall"); rss=$(median <"$tmp/rss"); dd_s=$(median <"$tmp/dd")
  dd_sync=$(median <"$tmp/ddsync")
  awk -v r="$robot" -v w="$wall" -v rss="$rss" -v bytes="$bytes" -v d="$dd_s" -v ds="$dd_sync" 'BEGIN {
    mb = bytes / 1048576
    printf "| %s | %.2f | %.0f | %.1f | %.2f | %.2f | %.2f |\n", r, w, rss, mb, rss / mb, d, ds }'
done
