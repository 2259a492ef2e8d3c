#!/usr/bin/env bash
# The CFD example of docs/boundary-layers.md in one command: installs and builds what is missing,
# puts a closed body (default: the shared airplane.obj) in a farfield cube, meshes it with a
# boundary layer whose first height comes from a target y+, writes CGNS, SU2 and Medit files with
# the patches named wall and farfield, and checks them (anitet's quality report, cgnscheck when
# installed, the SU2 markers).
#
#   examples/cfd/run.sh [BODY.obj [OUTDIR]]
#
# Environment: YPLUS (default 100), REYNOLDS (5e6), BL_LAYERS (5), BL_GROWTH (1.2), HGRAD (1.3:
# sizes grow by at most 30% from one cell to the next, from the wall out to the farfield).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
body=${1:-$root/../shared/data/surfaces/airplane.obj}
out=${2:-$root/out/cfd}
[ -f "$body" ] || { echo "run.sh: no body surface '$body' (give an OBJ path)" >&2; exit 2; }

"$root/scripts/setup.sh"
build=${BUILD_DIR:-$root/build}
# A first build skips the tests (faster); an existing build keeps its configuration.
if [ -f "$build/CMakeCache.txt" ]; then "$root/scripts/build.sh"; else "$root/scripts/build.sh" -DANITET_BUILD_TESTS=OFF; fi
anitet=$build/app/anitet

mkdir -p "$out"
name=$(basename "${body%.*}")
domain=$out/${name}_in_box.mesh
# The body reversed as patch 1 inside a cube ten times its size as patch 2; prints the body size.
info=$(python3 "$root/examples/cfd/body_in_box.py" "$body" "$domain")
echo "$info"
size=$(echo "$info" | sed -n 's/.*body size \([0-9.eE+-]*\),.*/\1/p')
[ -n "$size" ] || { echo "run.sh: body_in_box.py did not print the body size" >&2; exit 1; }

# The reference length of the Reynolds number is the body's size (its largest extent).
"$anitet" mesh "$domain" -o "$out/$name.cgns" --also-write "$out/$name.su2" --also-write "$out/$name.mesh" \
    --front-layers 2 --patch-names 1=wall,2=farfield \
    --bl-patches 1 --bl-yplus "${YPLUS:-100}" --bl-reynolds "${REYNOLDS:-5e6}" --bl-ref-length "$size" \
    --bl-layers "${BL_LAYERS:-5}" --bl-growth "${BL_GROWTH:-1.2}" --hgrad "${HGRAD:-1.3}"

echo
echo "SU2 file $out/$name.su2:"
grep -E '^(NDIME|NELEM|NPOIN|NMARK|MARKER_TAG|MARKER_ELEMS)=' "$out/$name.su2"
if command -v cgnscheck >/dev/null 2>&1; then
  echo
  echo "cgnscheck -w3 $out/$name.cgns:"
  cgnscheck -w3 "$out/$name.cgns" | tail -n 3
fi

echo
echo "Cell size away from the wall (examples/cfd/grading.py):"
py=python3; $py -c 'import numpy, meshio' 2>/dev/null || py=/usr/bin/python3
$py "$root/examples/cfd/grading.py" "$out/$name.mesh"
