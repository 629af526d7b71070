#!/usr/bin/env bash
# The main job, from a fresh Debian 12 machine: install the dependencies, build the tools it runs,
# sample the de-icing arm of Yin, Wang & Yu 2010 (its X-Z plane workspace, Fig. 5, and its 3-D
# workspace, Fig. 6; 6000 samples each), extract the X-Z boundary from 100000 samples (Fig. 13),
# measure the workspace's area and volume (printed with their relative errors against the closed
# form), and write the clouds and their pictures; then plan the arm of the maintenance-arm patent
# under base sway (chosen path, report, validation) and draw the two-joint configuration space;
# then rehearse the cleaning job of Wang et al. 2018 on a 28-disc string (clean, and with one of
# every fault); then the whole power-line study of studies/maintenance4_line.yaml in one command
# (mcws_study: where to stop, which path, how likely it touches the line; out/study/report.html).
# Usage: scripts/run_main.sh [OUTPUT_DIR]   (default: out/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out}
bin=$root/build/apps

"$root/scripts/install_deps.sh"
# Only the tools this job runs (and the libraries they link): tests, benchmarks and examples are
# built by scripts/run_tests.sh. --target leaves the cache alone, so a later full build in build/
# still builds them.
"$root/scripts/build.sh" "$root/build" --target mcws_sample --target mcws_boundary \
  --target mcws_refine --target mcws_measure --target mcws_plan --target mcws_behave \
  --target mcws_envelope --target mcws_study
mkdir -p "$out"

robot=$root/robots/deicing.yaml
# JSON summaries are written beside the clouds, under a temporary name until complete.
"$bin/mcws_sample" --robot "$robot" --samples 6000 --seed 1 --fix theta3=0 \
  --output "$out/deicing_xz.pcd" --json >"$out/.deicing_xz.json.tmp"
mv "$out/.deicing_xz.json.tmp" "$out/deicing_xz.json"
"$bin/mcws_sample" --robot "$robot" --samples 6000 --seed 1 \
  --output "$out/deicing_3d.pcd" --json >"$out/.deicing_3d.json.tmp"
mv "$out/.deicing_3d.json.tmp" "$out/deicing_3d.json"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_xz.pcd" --output "$out/deicing_xz.png" \
  --view xz --unit cm --label samples \
  --title "De-icing arm: workspace in the X-Z plane (6000 samples)"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_3d.pcd" --output "$out/deicing_3d.png" \
  --view 3d --unit cm --color z --label samples --title "De-icing arm: 3-D workspace (6000 samples)"

# Fig. 13 of Yin, Wang & Yu 2010: the X-Z boundary from 100000 samples.
"$bin/mcws_sample" --robot "$robot" --samples 100000 --seed 1 --fix theta3=0 \
  --output "$out/deicing_xz_100k.pcd"
"$bin/mcws_boundary" --input "$out/deicing_xz_100k.pcd" --plane xz --output "$out/deicing_xz_boundary.pcd"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_xz_100k.pcd" --overlay "$out/deicing_xz_boundary.pcd" \
  --output "$out/deicing_xz_boundary.png" --view xz --unit cm --label samples --overlay-label boundary \
  --title "De-icing arm: X-Z workspace boundary (100000 samples)"

# Area and volume: 50000 samples, their boundary, 50000 refined samples near it (mcws_refine),
# measured without edge correction (the refined samples lie on the edge). The 3-D boundary of the
# first 50000 is drawn too.
refined_measure() {  # name, sample flags, boundary flags
  local name=$1
  "$bin/mcws_sample" --robot "$robot" --samples 50000 --seed 2 $2 --output "$out/$name.pcd"
  "$bin/mcws_boundary" --input "$out/$name.pcd" $3 --output "$out/${name}_boundary.pcd"
  "$bin/mcws_refine" --robot "$robot" --input "$out/${name}_boundary.pcd" --cloud "$out/$name.pcd" \
    --samples 50000 --seed 3 --output "$out/${name}_refined.pcd"
  "$bin/mcws_measure" --input "$out/${name}_refined.pcd" $3 --correction none | awk '{print $2}'
}
area=$(refined_measure deicing_xz_50k "--fix theta3=0" "--plane xz")
volume=$(refined_measure deicing_3d_50k "" "")
# The envelope of the refined 3-D cloud as a mesh (MeshLab, pcl_viewer), in cm and in metres,
# and the working range drawn as a datasheet draws it (side and top view with dimensions).
"$bin/mcws_envelope" --input "$out/deicing_3d_50k_refined.pcd" --correction none \
  --output "$out/deicing_envelope.ply" --plot "$out/deicing_envelope.png" \
  --drawing "$out/deicing_range.png" --json >"$out/.deicing_range.json.tmp"
mv "$out/.deicing_range.json.tmp" "$out/deicing_range.json"
"$bin/mcws_envelope" --input "$out/deicing_3d_50k_refined.pcd" --correction none --unit m \
  --output "$out/deicing_envelope_m.stl" --json >"$out/.deicing_envelope.json.tmp"
mv "$out/.deicing_envelope.json.tmp" "$out/deicing_envelope.json"
"$root/scripts/plot_cloud.sh" --input "$out/deicing_3d_50k_boundary.pcd" \
  --output "$out/deicing_3d_boundary.png" --view 3d --unit cm --color z --label boundary \
  --title "De-icing arm: boundary of the 3-D workspace (50000 samples)"

# The maintenance-arm patent: the arm's path robust to base sway, validated on 10000 fresh base
# poses, and the two-joint picture of the patent's Figures 2 and 3 with P against the base offset.
"$bin/mcws_plan" --scenario "$root/scenarios/maintenance4.yaml" --output "$out/maintenance4_path.csv" \
  >"$out/.maintenance4_plan.txt.tmp"
mv "$out/.maintenance4_plan.txt.tmp" "$out/maintenance4_plan.txt"
"$bin/mcws_plan" --scenario "$root/scenarios/planar2.yaml" --output "$out/planar2_path.csv" \
  --plot "$out/planar2_cspace.png" --plot-offsets "$out/planar2_offsets.png" >/dev/null
behaviors=$root/robots/insulator_cleaner_behaviors.yaml
"$bin/mcws_behave" --model "$behaviors" --insulators 28 --log "$out/cleaning_28.jsonl" \
  --timeline "$out/cleaning_28.csv" --plot "$out/cleaning_28.png" --dot "$out/behaviors" \
  >"$out/.cleaning_28.txt.tmp" 2>/dev/null
mv "$out/.cleaning_28.txt.tmp" "$out/cleaning_28.txt"
"$bin/mcws_behave" --model "$behaviors" --insulators 3 --faults "$root/scenarios/faults/rehearsal.yaml" \
  --log "$out/rehearsal_3.jsonl" --plot "$out/rehearsal_3.png" --plot-all \
  >"$out/.rehearsal_3.txt.tmp" 2>/dev/null
mv "$out/.rehearsal_3.txt.tmp" "$out/rehearsal_3.txt"
# The power-line study in one command: one report (HTML that works offline, and JSON).
"$bin/mcws_study" --study "$root/studies/maintenance4_line.yaml" --output "$out/study" 2>/dev/null

echo "mcws: de-icing arm workspace written to $out:"
for f in deicing_xz.pcd deicing_xz.png deicing_3d.pcd deicing_3d.png deicing_xz_boundary.pcd \
  deicing_xz_boundary.png deicing_3d_50k_boundary.pcd deicing_3d_boundary.png deicing_envelope.ply \
  deicing_envelope.png deicing_envelope_m.stl deicing_envelope.json deicing_range.png \
  deicing_range.json; do echo "  $out/$f"; done
# Relative error [%] of a measure against its closed form (BENCHMARKS.md: the area is known to
# +-1.5 cm^2, 0.009 %, the volume to +-200 cm^3, 0.01 %).
relative_error() {  # value, closed form
  awk -v value="$1" -v exact="$2" 'BEGIN { printf "%+.3f %%", 100 * (value - exact) / exact }'
}
echo "  X-Z plane area ${area} cm^2, $(relative_error "$area" 16352.5) from the closed form" \
  "16352.5 cm^2"
echo "  3-D volume ${volume} cm^3, $(relative_error "$volume" 2098290) from the closed form" \
  "2098290 cm^3"
echo "  (50000 samples + 50000 refined each; closed forms in BENCHMARKS.md)"
json_number() { sed "s/.*\"$1\":\([^,}]*\).*/\1/" "$2"; }  # one number from a JSON object
echo "  envelope mesh: $(json_number triangles "$out/deicing_envelope.json") triangles enclosing" \
  "$(json_number volume "$out/deicing_envelope.json") m^3, closed and oriented:" \
  "$(json_number closed_and_oriented "$out/deicing_envelope.json")"
range_number() { printf "%.${2}f" "$(json_number "$1" "$out/deicing_range.json")"; }
echo "  working range: reach $(range_number max_reach 2) cm (eq. (1): 120), highest" \
  "$(range_number highest 2) cm (105.36), swept $(range_number swept_angle 1) deg (120)"
echo "mcws: planning under base sway (the maintenance-arm patent) written to $out:"
for f in maintenance4_path.csv maintenance4_plan.txt planar2_path.csv planar2_cspace.png \
  planar2_offsets.png; do echo "  $out/$f"; done
sed -n '/^validation/,$p' "$out/maintenance4_plan.txt"
echo "mcws: cleaning rehearsals (Wang et al. 2018) written to $out:"
for f in cleaning_28.txt cleaning_28.jsonl cleaning_28.csv cleaning_28.png behaviors/ rehearsal_3.txt \
  rehearsal_3.jsonl rehearsal_3.png; do echo "  $out/$f"; done
sed -n '1,3p' "$out/cleaning_28.txt"
sed -n '/^faults/,$p' "$out/rehearsal_3.txt"
echo "mcws: the power-line study (mcws_study) written to $out/study: report.html, report.json"
python3 -c 'import json, sys
for a in json.load(open(sys.argv[1]))["view"]["answers"]:
    print("  %s: %.6g %s" % (a["label"], a["value"], a["unit"]))' "$out/study/report.json"
