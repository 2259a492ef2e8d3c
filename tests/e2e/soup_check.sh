#!/usr/bin/env bash
# soup_check.sh ANITET MESHCHECK SURFACE.off WORKDIR
# A closed surface given as a polygon soup (soup.py: duplicated vertices, half the triangles facing
# the other way, shuffled): `anitet check-surface -o` repairs it (merge, reorient, outward) and
# says so; `anitet mesh` meshes it; meshcheck.py finds the mesh valid and boundary constrained
# against the repaired surface. A non-orientable closed surface (the real projective plane) is
# refused, naming an edge.
set -uo pipefail
anitet=$1 meshcheck=$2 surface=$3 work=$4
python=/usr/bin/python3
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"

"$python" "$here/soup.py" "$surface" "$work/soup.obj" 7 || fail "soup.py"
out=$("$anitet" check-surface "$work/soup.obj" -o "$work/repaired.off" 2>&1); rc=$?
printf '%s\n' "$out" | grep -E "repairs|reoriented|merged|result|written"
((rc == 0)) || fail "check-surface exited $rc"
grep -Eq "reoriented [0-9]+ of the [0-9]+ triangles of shell 0 to match their neighbours" <<<"$out" ||
  fail "check-surface did not report the reorientation"
[[ -s $work/repaired.off ]] || fail "check-surface -o did not write the repaired surface"

"$anitet" mesh "$work/soup.obj" -o "$work/soup.mesh" -q || fail "anitet mesh on the soup exited $?"
"$python" "$meshcheck" "$work/soup.mesh" --surface "$work/repaired.off" >"$work/soup.json" || fail "meshcheck.py exited $?"
"$python" - "$work/soup.json" <<'PY' || fail "meshcheck.py: not valid and boundary constrained"
import json, sys
r = json.load(open(sys.argv[1]))
print(f"meshcheck.py: valid {r['valid']}, boundary constrained {r['boundary_constrained']}, "
      f"missing {r['input_triangles_missing']}, tets {r['tets']}")
sys.exit(0 if r["valid"] and r["boundary_constrained"] and r["input_triangles_missing"] == 0 else 1)
PY

# The real projective plane: 6 vertices, 10 triangles, every edge on two of them.
cat >"$work/rp2.off" <<'END_OF_OFF'
OFF
6 10 0
0 0 1
1 0 0
0.3 0.95 0
-0.8 0.6 0.1
-0.8 -0.6 0.2
0.3 -0.95 0.3
3 0 1 2
3 0 2 3
3 0 3 4
3 0 4 5
3 0 5 1
3 1 2 4
3 2 3 5
3 3 4 1
3 4 5 2
3 5 1 3
END_OF_OFF
out=$("$anitet" mesh "$work/rp2.off" -o "$work/rp2.mesh" 2>&1); rc=$?
printf '%s\n' "$out" | head -5
((rc == 4)) || fail "the non-orientable surface: exit $rc, expected 4 (invalid input)"
grep -Eq "not orientable.*at edge \([0-9]+, [0-9]+\)" <<<"$out" || fail "the refusal does not name an edge"
[[ ! -e $work/rp2.mesh ]] || fail "a mesh of the non-orientable surface was written"
echo "PASS"
