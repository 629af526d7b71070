#!/usr/bin/env bash
# plot_cloud.sh - render a PCD point cloud to a PNG with gnuplot (pngcairo),
# in the style of the paper's figures: a plane view such as "point cloud of
# workspace in X-Z plane" (Fig. 5) or a 3-D view (Fig. 6). An optional second
# cloud (e.g. boundary points) can be drawn on top in a contrasting colour.
# Binary or ASCII PCD is read via pcl_convert_pcd_ascii_binary (pcl-tools).
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: plot_cloud.sh --input CLOUD.pcd --output OUT.png [--view xz|xy|yz|3d]
                     [--title TEXT] [--unit cm] [--overlay OTHER.pcd] [--size W,H]
  --input    point cloud to draw (binary or ASCII PCD with x, y, z fields)
  --output   PNG to write (written atomically; its directory must exist)
  --view     xz, xy, yz (plane view, equal axes) or 3d (default: 3d)
  --title    plot title (default: none)
  --unit     unit for the axis labels, e.g. cm -> "x [cm]" (default: none)
  --overlay  second cloud drawn on top in red with bigger points
  --size     image size in pixels (default: 900,700)
EOF
}
die() { echo "plot_cloud: $*" >&2; exit 1; }
usage_err() { echo "plot_cloud: $*" >&2; exit 2; }

input="" output="" view="3d" title="" unit="" overlay="" size="900,700"
while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --input|--output|--view|--title|--unit|--overlay|--size)
      (($# >= 2)) || usage_err "$1 needs a value"
      declare "${1#--}=$2"; shift 2 ;;
    *) usage_err "unknown argument: $1 (see --help)" ;;
  esac
done
[[ -n $input ]] || usage_err "--input is required"
[[ -n $output ]] || usage_err "--output is required"
[[ $view =~ ^(xz|xy|yz|3d)$ ]] || usage_err "--view must be xz, xy, yz or 3d, not '$view'"
[[ $size =~ ^[1-9][0-9]*,[1-9][0-9]*$ ]] || usage_err "--size must be W,H in pixels, not '$size'"
outdir=$(dirname -- "$output")
[[ -d $outdir ]] || die "output directory does not exist: $outdir"
[[ ! -d $output ]] || die "output is a directory, expected a PNG file name: $output"

tmpdir=$(mktemp -d) tmppng=""
trap 'rm -rf "$tmpdir"; [[ -z $tmppng ]] || rm -f "$tmppng"' EXIT

# load_xyz IN.pcd OUT.dat: write "x y z" lines of a PCD file, checking it first.
load_xyz() {
  local in=$1 out=$2 ascii="$tmpdir/conv.pcd"
  [[ -f $in && -r $in ]] || die "cannot read input file: $in"
  # Sanity-check the header ourselves: the converter crashes on non-PCD input.
  LC_ALL=C head -c 8192 -- "$in" | LC_ALL=C grep -aq '^DATA \(ascii\|binary\|binary_compressed\)' \
    || die "not a PCD file (no DATA line in header): $in"
  pcl_convert_pcd_ascii_binary "$in" "$ascii" 0 >"$tmpdir/conv.log" 2>&1 && [[ -s $ascii ]] \
    || { cat "$tmpdir/conv.log" >&2; die "failed to convert $in to ASCII PCD"; }
  # Column of each field = 1 + sum of COUNTs of the fields before it.
  LC_ALL=C awk -v src="$in" '
    $1 == "FIELDS" { nf = NF - 1; for (i = 2; i <= NF; i++) name[i-1] = $i; next }
    $1 == "COUNT"  { for (i = 2; i <= NF; i++) cnt[i-1] = $i; next }
    $1 == "DATA" {
      c = 1
      for (i = 1; i <= nf; i++) { col[name[i]] = c; c += ((i in cnt) ? cnt[i] : 1) }
      if (!("x" in col && "y" in col && "z" in col)) { print "plot_cloud: no x/y/z fields in " src > "/dev/stderr"; exit 3 }
      xi = col["x"]; yi = col["y"]; zi = col["z"]; data = 1; next
    }
    data && NF && tolower($xi $yi $zi) !~ /nan/ { print $xi, $yi, $zi }
  ' "$ascii" >"$out" || exit 1
  [[ -s $out ]] || die "point cloud is empty (0 valid points): $in"
}

load_xyz "$input" "$tmpdir/main.dat"
[[ -z $overlay ]] || load_xyz "$overlay" "$tmpdir/overlay.dat"

q() { printf "'%s'" "${1//\'/\'\'}"; }   # quote a string for gnuplot
label() { if [[ -n $unit ]]; then q "$1 [$unit]"; else q "$1"; fi; }
tmppng=$(mktemp -- "$outdir/.plot_cloud.XXXXXX.png")

{
  echo "set terminal pngcairo noenhanced size $size font 'Sans,12'"
  echo "set output $(q "$tmppng")"
  [[ -z $title ]] || echo "set title $(q "$title")"
  echo "set grid; set border lw 1"
  # Legend (file names) only when there is an overlay to tell apart.
  if [[ -z $overlay ]]; then echo "unset key"
  elif [[ $view == 3d ]]; then echo "set key top right box"
  else echo "set key below horizontal height 1"; fi
  if [[ $view == 3d ]]; then
    cols=1:2:3 axes="x y z" frac=0.02
    echo "set view 60,30; set view equal xyz; set xyplane relative 0"
    echo "set xtics offset -0.5,-0.3; set ytics offset 0.5,-0.3"
    echo "set xlabel $(label x) offset -1,-1; set ylabel $(label y) offset 3,-1; set zlabel $(label z) rotate parallel"
  else
    declare -A idx=([x]=1 [y]=2 [z]=3)
    a=${view:0:1} b=${view:1:1} axes="x y" frac=0.05 cols=${idx[$a]}:${idx[$b]}
    echo "set size ratio -1"
    echo "set xlabel $(label "$a"); set ylabel $(label "$b")"
  fi
  # Tight ranges with the same margin on every axis (a fraction of the largest
  # extent); a flat axis (e.g. y of the X-Z cloud) gets +-10% of it instead.
  cat "$tmpdir"/*.dat | awk -v cols="${cols//:/ }" -v axes="$axes" -v frac="$frac" '
    BEGIN { n = split(cols, c, " "); split(axes, ax, " ") }
    { for (i = 1; i <= n; i++) { v = $c[i] + 0
        if (NR == 1 || v < lo[i]) lo[i] = v; if (NR == 1 || v > hi[i]) hi[i] = v } }
    END { for (i = 1; i <= n; i++) if (hi[i] - lo[i] > s) s = hi[i] - lo[i]
      p = (s > 0) ? frac * s : 1
      for (i = 1; i <= n; i++) { q = p; flat = (hi[i] - lo[i] < 0.01 * s)
        if (flat) { q = 0.1 * s; m = (lo[i] + hi[i]) / 2; if (m * m < 1e-12 * s * s) m = 0
                    printf "set %stics (%.4g)\n", ax[i], m }   # one tic at its value
        printf "set %srange [%.10g:%.10g]\n", ax[i], lo[i] - q, hi[i] + q } }'
  # Small dots for dense clouds, a bit bigger for sparse ones; overlay bigger still.
  ps=0.25 ops=0.55
  (( $(wc -l <"$tmpdir/main.dat") >= 2000 )) || ps=0.5 ops=0.8
  cmd=plot; [[ $view != 3d ]] || cmd=splot
  plots="$(q "$tmpdir/main.dat") using $cols title $(q "$(basename -- "$input")")"
  plots+=" with points pt 7 ps $ps lc rgb '#1f77b4'"
  if [[ -n $overlay ]]; then
    plots+=", $(q "$tmpdir/overlay.dat") using $cols title $(q "$(basename -- "$overlay")")"
    plots+=" with points pt 7 ps $ops lc rgb '#d62728'"
  fi
  echo "$cmd $plots"
} >"$tmpdir/plot.gp"

gnuplot "$tmpdir/plot.gp" >"$tmpdir/gnuplot.log" 2>&1 && [[ -s $tmppng ]] \
  || { cat "$tmpdir/gnuplot.log" >&2; die "gnuplot failed to render $output"; }
chmod "$(printf '%o' $((0666 & ~0$(umask))))" "$tmppng"
mv -f -- "$tmppng" "$output"
tmppng=""
