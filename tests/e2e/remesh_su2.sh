#!/usr/bin/env bash
# remesh_su2.sh ANITET IN OUT_DIR
# Re-meshing from a solver file: IN (sphere in a box, patches 1 and 2) is meshed to SU2 with the
# patches named, then that .su2 is meshed again. The second mesh must keep the .su2's boundary
# (quality --strict against the .su2 read as a surface) and carry the marker names unasked.
set -u
anitet=$1; in=$2; dir=$3
mkdir -p "$dir"; rm -f "$dir"/first.su2 "$dir"/second.mesh "$dir"/second.su2
"$anitet" mesh "$in" -o "$dir/first.su2" --front-layers 1 --patch-names 1=wall,2=farfield -q || { echo "FAIL: first mesh exited $?"; exit 1; }
"$anitet" mesh "$dir/first.su2" -o "$dir/second.mesh" --also-write "$dir/second.su2" --front-layers 1 -q || { echo "FAIL: mesh from the .su2 exited $?"; exit 1; }
"$anitet" quality "$dir/second.mesh" --surface "$dir/first.su2" --strict > "$dir/quality.txt" || { echo "FAIL: quality --strict exited $?"; cat "$dir/quality.txt"; exit 1; }
grep -q "boundary constrained: YES" "$dir/quality.txt" || { echo "FAIL: not boundary constrained"; exit 1; }
markers=$(grep '^MARKER_TAG=' "$dir/second.su2" | tr -d ' ' | tr '\n' ' ')
[[ "$markers" == "MARKER_TAG=wall MARKER_TAG=farfield " ]] || { echo "FAIL: markers of the second mesh: '$markers'"; exit 1; }
for f in first second; do
  echo "$f: $(grep -A1 'MARKER_TAG= wall' "$dir/$f.su2" | tail -1) wall, $(grep -A1 'MARKER_TAG= farfield' "$dir/$f.su2" | tail -1) farfield"
done
[[ "$(grep -A1 'MARKER_TAG= wall' "$dir/first.su2" | tail -1)" == "$(grep -A1 'MARKER_TAG= wall' "$dir/second.su2" | tail -1)" ]] \
  || { echo "FAIL: the wall's triangle count changed"; exit 1; }
echo "PASS: meshed again from the .su2, boundary kept, markers wall and farfield carried"
