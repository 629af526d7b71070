#!/usr/bin/env bash
# Boundary methods side by side (issue 3, section 4): PCL's BoundaryEstimation and ConcaveHull,
# CGAL's alpha shapes, a plain kd-tree quadrant/octant test, mcws's OrthantBoundary and the grid
# and extremum baselines, on the same 1000000-point disk and ball, 2 threads where a method
# supports them. Prints a markdown table (time, points reported, precision, recall, area/volume
# error).
# Usage: scripts/bench_peers.sh [BUILD_DIR] [N]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cmake --build "$build" -j2 --target boundary_peers >/dev/null
"$build/bench/boundary_peers" "${2:-1000000}" both 2
