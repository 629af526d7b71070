#!/usr/bin/env bash
# Tables 1 and 2 of Yin, Wang & Yu 2010 rerun: area of the unit disk from N uniform samples, mean
# absolute error over 10 seeds, for mcws_measure's default (delaunay) and for the paper's column
# method over the boundary points of mcws_boundary's default (column), of the grid method (grid) and
# of the extremum method (extremum); plus the annulus, ball and cube. Prints markdown rows.
# Usage: scripts/bench_area.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
run=${1:-$root/build}/bench/area_accuracy
echo "| shape | N | method | MAE % | bias % | seconds per run |"
echo "|---|---|---|---|---|---|"
for n in 5000 10000 50000 100000 200000 1000000; do
  for method in delaunay column grid extremum; do "$run" disk "$n" 10 "$method"; done
done
"$run" annulus 100000 10 delaunay
"$run" annulus 100000 10 column
"$run" annulus 100000 10 grid
"$run" annulus 100000 10 extremum
"$run" ball 100000 10 delaunay
"$run" box 100000 10 delaunay
