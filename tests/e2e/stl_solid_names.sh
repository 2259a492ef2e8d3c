#!/usr/bin/env bash
# stl_solid_names.sh ANITET STL OUT_DIR
# The `solid` names of an ASCII STL with two blocks ("x ends", "sides": tests/data/io) become the
# patch names: `check-surface` lists them, and the mesh written as SU2 and Gmsh carries them as
# its MARKER_TAGs and physical names ("x ends" made the valid name x_ends).
set -u
anitet=$1; in=$2; dir=$3
mkdir -p "$dir"; rm -f "$dir"/names.su2 "$dir"/names.msh
out=$("$anitet" check-surface "$in") || { echo "FAIL: check-surface exited $?"; echo "$out"; exit 1; }
echo "$out" | grep "patches:"
echo "$out" | grep -q "patches: 1 'x_ends' (4 triangles), 2 'sides' (8 triangles)" ||
  { echo "FAIL: check-surface does not list the solids' names"; exit 1; }
"$anitet" mesh "$in" -o "$dir/names.su2" --also-write "$dir/names.msh" -q || { echo "FAIL: mesh exited $?"; exit 1; }
markers=$(grep '^MARKER_TAG=' "$dir/names.su2" | tr -d ' ' | tr '\n' ' ')
[[ "$markers" == "MARKER_TAG=x_ends MARKER_TAG=sides " ]] || { echo "FAIL: SU2 markers '$markers'"; exit 1; }
# shellcheck disable=SC2016 # the $ of $PhysicalNames is literal
physical=$(sed -n '/^\$PhysicalNames/,/^\$EndPhysicalNames/p' "$dir/names.msh" | grep '^2 ' | tr '\n' ' ')
[[ "$physical" == '2 1 "x_ends" 2 2 "sides" ' ]] || { echo "FAIL: Gmsh physical names '$physical'"; exit 1; }
echo "PASS: SU2 $markers; Gmsh $physical"
