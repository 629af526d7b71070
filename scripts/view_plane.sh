#!/usr/bin/env bash
# view_plane.sh - open a plane cloud (e.g. the de-icing arm's X-Z workspace) in pcl_viewer facing
# its plane. Without -cam, pcl_viewer looks from the cloud's VIEWPOINT along +z, so a cloud in the
# X-Z plane is seen edge-on, as a line. This computes the -cam string from the cloud's extents:
# the camera looks at the centre of the cloud's bounding box along the plane's normal, from far
# enough that the plane fills the window with a 10 % margin (pcl_viewer's 30 deg field of view),
# with the plane's second axis up:
#   xz: camera on -y looking along +y, x to the right, z up
#   xy: camera on +z looking down,     x to the right, y up
#   yz: camera on +x looking along -x, y to the right, z up
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: view_plane.sh [--print] [--size W,H] CLOUD.pcd [xz|xy|yz] [-- PCL_VIEWER_ARGS...]
  CLOUD.pcd  point cloud (binary or ASCII PCD with x, y, z fields)
  xz|xy|yz   the plane to face (default: the plane of the two widest axes, i.e. facing
             along the axis on which the cloud is thinnest)
  --print    print the pcl_viewer command instead of running it
  --size     window size in pixels (default: 1024,768)
  --         the arguments after it go to pcl_viewer, e.g. -- -ps 3 (point size)
The -cam string is clipNear,clipFar/focalX,focalY,focalZ/posX,posY,posZ/
viewUpX,viewUpY,viewUpZ/fovy/winW,winH/winPosX,winPosY (fovy in rad), in the cloud's
length unit. The cloud's VIEWPOINT is assumed to be the identity (as mcws writes it).
Exit status: 0 done, 2 usage error, 1 unreadable cloud (or pcl_viewer's own status).
EOF
}
die() { echo "view_plane: $*" >&2; exit 1; }
usage_err() { echo "view_plane: $*" >&2; exit 2; }

print=0 size="1024,768" cloud="" plane="" viewer_args=()
while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --print) print=1; shift ;;
    --size) (($# >= 2)) || usage_err "--size needs a value"; size=$2; shift 2 ;;
    --) shift; viewer_args=("$@"); break ;;
    -*) usage_err "unknown option: $1 (see --help)" ;;
    *)
      if [[ -z $cloud ]]; then cloud=$1
      elif [[ -z $plane ]]; then plane=$1
      else usage_err "unexpected argument: $1 (see --help)"; fi
      shift ;;
  esac
done
[[ -n $cloud ]] || usage_err "a cloud is required (see --help)"
[[ -z $plane || $plane =~ ^(xz|xy|yz)$ ]] \
  || usage_err "the plane must be xz, xy or yz, not '$plane'"
[[ $size =~ ^[1-9][0-9]*,[1-9][0-9]*$ ]] || usage_err "--size must be W,H in pixels, not '$size'"
[[ -f $cloud && -r $cloud ]] || die "cannot read input file: $cloud"
LC_ALL=C head -c 8192 -- "$cloud" | LC_ALL=C grep -aq '^DATA \(ascii\|binary\|binary_compressed\)' \
  || die "not a PCD file (no DATA line in header): $cloud"

tmpdir=$(mktemp -d)
trap 'rm -rf "$tmpdir"' EXIT
{ pcl_convert_pcd_ascii_binary "$cloud" "$tmpdir/cloud.pcd" 0 >"$tmpdir/conv.log" 2>&1 \
  && [[ -s $tmpdir/cloud.pcd ]]; } \
  || { cat "$tmpdir/conv.log" >&2; die "failed to convert $cloud to ASCII PCD"; }

# Extents of the finite points: "xmin xmax ymin ymax zmin zmax".
extents=$(LC_ALL=C awk -v src="$cloud" '
  $1 == "FIELDS" { nf = NF - 1; for (i = 2; i <= NF; i++) name[i-1] = $i; next }
  $1 == "COUNT"  { for (i = 2; i <= NF; i++) cnt[i-1] = $i; next }
  $1 == "VIEWPOINT" && $0 !~ /^VIEWPOINT 0 0 0 1 0 0 0 *$/ {
    print "view_plane: note: " src " has a VIEWPOINT other than the identity; the camera" \
      " ignores it" > "/dev/stderr"
  }
  $1 == "DATA" {
    c = 1
    for (i = 1; i <= nf; i++) { col[name[i]] = c; c += ((i in cnt) ? cnt[i] : 1) }
    if (!("x" in col && "y" in col && "z" in col)) {
      print "view_plane: no x/y/z fields in " src > "/dev/stderr"; exit 3
    }
    xi = col["x"]; yi = col["y"]; zi = col["z"]; data = 1; next
  }
  data && NF && tolower($xi $yi $zi) !~ /nan|inf/ {
    v[1] = $xi + 0; v[2] = $yi + 0; v[3] = $zi + 0
    for (k = 1; k <= 3; k++) {
      if (!n || v[k] < lo[k]) lo[k] = v[k]
      if (!n || v[k] > hi[k]) hi[k] = v[k]
    }
    n++
  }
  END {
    if (n) printf "%.17g %.17g %.17g %.17g %.17g %.17g\n", lo[1], hi[1], lo[2], hi[2], lo[3], hi[3]
  }
' "$tmpdir/cloud.pcd") || exit 1
[[ -n $extents ]] || die "point cloud is empty (0 points with finite x, y, z): $cloud"

cam=$(awk -v e="$extents" -v plane="$plane" -v w="${size%,*}" -v h="${size#*,}" '
  BEGIN {
    split(e, b, " ")
    for (k = 1; k <= 3; k++) { c[k] = (b[2*k-1] + b[2*k]) / 2; half[k] = (b[2*k] - b[2*k-1]) / 2 }
    if (plane == "")   # face along the thinnest axis (ties: y, then z, then x)
      plane = (half[2] <= half[3] && half[2] <= half[1]) ? "xz" : (half[3] <= half[1]) ? "xy" : "yz"
    # horizontal axis, vertical axis, normal axis, and the side of the normal the camera is on
    if (plane == "xz") { ah = 1; av = 3; an = 2; side = -1 }
    if (plane == "xy") { ah = 1; av = 2; an = 3; side = +1 }
    if (plane == "yz") { ah = 2; av = 3; an = 1; side = +1 }
    fovy = 3.14159265358979 / 6    # pcl_viewer (VTK) default, 30 deg
    r = 1.1 * ((half[av] > half[ah] * h / w) ? half[av] : half[ah] * h / w)   # half height seen
    if (r == 0) r = 1                                                         # a single point
    d = r / (sin(fovy / 2) / cos(fovy / 2)) + half[an]
    for (k = 1; k <= 3; k++) { pos[k] = c[k]; up[k] = 0 }
    pos[an] += side * d; up[av] = 1
    for (k = 1; k <= 3; k++) {   # rounding noise (y = 1e-15 in an X-Z cloud) printed as 0
      if (c[k] * c[k] < 1e-18 * d * d) c[k] = 0
      if (pos[k] * pos[k] < 1e-18 * d * d) pos[k] = 0
    }
    printf "%.6g,%.6g/%.6g,%.6g,%.6g/%.6g,%.6g,%.6g/%g,%g,%g/%.6g/%d,%d/0,0\n", d / 100, 10 * d,
           c[1], c[2], c[3], pos[1], pos[2], pos[3], up[1], up[2], up[3], fovy, w, h
  }')

viewer=(pcl_viewer "$cloud" -cam "$cam" "${viewer_args[@]}")
if ((print)); then
  # One line to paste into a shell: words with other characters than these single-quoted.
  quoted=()
  for word in "${viewer[@]}"; do
    if [[ $word =~ ^[A-Za-z0-9_./,:=+@%-]+$ ]]; then quoted+=("$word")
    else quoted+=("'${word//\'/\'\\\'\'}'"); fi
  done
  echo "${quoted[*]}"
  exit 0
fi
command -v pcl_viewer >/dev/null || die "pcl_viewer not found (Debian package pcl-tools)"
exec "${viewer[@]}"
