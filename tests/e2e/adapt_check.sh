#!/usr/bin/env bash
# adapt_check.sh ANITET TOOLS_DIR UGAWG_DIR WORK MODE
# `anitet adapt` on the UGAWG cube (cube-linear-00.mesh and its metric .sol), checked by the
# shared tools (meshcheck.py, ugawg.py's measures), not by anitet:
#   pass          one pass with a linear scalar and a vector field: meshcheck.py finds it valid with
#                 the cube's volume, >= 70% of its edges in [1/sqrt2, sqrt2] in the analytic metric
#                 (ugawg.py's measure; 78% measured, Mmg's pass 1 75.7%: the cube's 64-vertex metric
#                 is coarse) and no inverted tet in it,
#                 the fields carried exactly (1e-12); then its output and --write-metric as the
#                 next pass's input (the loop with no other step), valid again
#   keep-surface  --keep-surface: valid and every input boundary triangle in the output
#   wrong-count | non-spd | inverted | other-mesh-field
#                 bad input: exit 4, a message naming the problem, no file written
set -u
anitet=$1; tools=$2; ugawg=$3; work=$4; mode=$5
python=/usr/bin/python3
cube=$ugawg/cube-linear-00
rm -rf "$work"; mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

# meshcheck.py FILE [--surface S]: valid, nothing wrong, volume 1; with a surface, constrained by it.
check_mesh() {
  "$python" "$tools/meshcheck.py" "$@" >"$work/check.json" || fail "meshcheck.py $1 exited $?"
  "$python" - "$work/check.json" "$(basename "$1")" <<'PY' || fail "meshcheck.py: $1"
import json, sys
r = json.load(open(sys.argv[1]))
bad = {k: r[k] for k in ("unused_vertices", "coincident_vertices", "nonpositive_tets", "inverted_tets",
                         "faces_shared_by_more_than_two", "file_triangles_not_tet_faces") if r.get(k, 0) != 0}
constrained = r.get("boundary_constrained", True)
print(f"meshcheck.py {sys.argv[2]}: {r['tets']} tets, valid {r['valid']}, volume {r['volume']:.15g}, "
      f"boundary constrained {constrained}, faults {bad}")
sys.exit(0 if r["valid"] and not bad and constrained and abs(r["volume"] - 1) < 1e-12 else 1)
PY
}

# A .sol of the 64 cube vertices' values: a linear scalar and a linear vector field.
fields_at() {  # MESH OUT.sol
  "$python" - "$1" "$2" <<'PY'
import sys
sys.path.insert(0, __import__("os").environ["TOOLS"])
import ugawg
P, _, _, _ = ugawg.read_mesh(sys.argv[1])
with open(sys.argv[2], "w") as f:
    f.write("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n%d\n2 1 2\n" % len(P))
    for x, y, z in P:
        f.write("%.17g %.17g %.17g %.17g\n" % (1 + x + 2 * y - 3 * z, x - y, 2 * z + 0.5, 3 * x))
    f.write("End\n")
PY
}
export TOOLS=$tools

case $mode in
  pass)
    fields_at "$cube.mesh" "$work/u.sol" || fail "writing u.sol"
    "$anitet" adapt "$cube.mesh" -o "$work/p1.mesh" --metric "$cube.sol" --field "$work/u.sol" \
      --write-metric "$work/p1.metric.sol" -q || fail "anitet adapt (pass 1) exited $?"
    [[ -f $work/p1.u.sol ]] || fail "the carried field p1.u.sol was not written"
    check_mesh "$work/p1.mesh"
    "$python" - "$work/p1.mesh" "$work/p1.u.sol" <<'PY' || fail "UGAWG measure or carried fields"
import os, sys
sys.path.insert(0, os.environ["TOOLS"])
import numpy as np, ugawg
m = ugawg.measure(sys.argv[1], "linear")
print("UGAWG measures of pass 1:", m)
P, _, _, _ = ugawg.read_mesh(sys.argv[1])
toks = open(sys.argv[2]).read().split()
i = toks.index("SolAtVertices"); n = int(toks[i + 1])
assert n == len(P), f"{n} field records for {len(P)} vertices"
assert toks[i + 2:i + 5] == ["2", "1", "2"], toks[i + 2:i + 5]
v = np.array(toks[i + 5:i + 5 + 4 * n], float).reshape(n, 4)
x, y, z = P.T
want = np.stack([1 + x + 2 * y - 3 * z, x - y, 2 * z + 0.5, 3 * x], axis=1)
err = np.abs(v - want).max()
print(f"linear fields carried to {n} vertices: max error {err:.3g}")
sys.exit(0 if m["in_range"] >= 70 and m["q_min"] > 0 and err < 1e-12 else 1)
PY
    "$anitet" adapt "$work/p1.mesh" -o "$work/p2.mesh" --metric "$work/p1.metric.sol" -q \
      || fail "anitet adapt (pass 2, on pass 1's output and metric) exited $?"
    check_mesh "$work/p2.mesh"
    ;;
  keep-surface)
    "$anitet" adapt "$cube.mesh" -o "$work/k1.mesh" --metric "$cube.sol" --keep-surface -q \
      || fail "anitet adapt --keep-surface exited $?"
    check_mesh "$work/k1.mesh" --surface "$cube.mesh"
    ;;
  wrong-count|non-spd|inverted|other-mesh-field)
    mesh=$cube.mesh; metric=$cube.sol; extra=()
    case $mode in
      wrong-count)  # 63 records for 64 vertices
        sed -e 's/^ *64$/63/' "$cube.sol" | awk 'NR < 9 || NR <= 8 + 63 || /End/' >"$work/m.sol"
        metric=$work/m.sol; regex="63 vertex values but mesh .* has 64 vertices" ;;
      non-spd)  # the tensor of vertex 10 (line 18) with xx = -1
        awk 'NR == 18 { $1 = "-1" } { print }' "$cube.sol" >"$work/m.sol"
        metric=$work/m.sol; regex="with metric .*m.sol.: the metric tensor at vertex 10 is not symmetric positive definite" ;;
      inverted)  # the first tet's first two vertices swapped
        awk '/^Tetrahedra/ { at = NR + 2 } NR == at { t = $1; $1 = $2; $2 = t } { print }' "$cube.mesh" >"$work/in.mesh"
        mesh=$work/in.mesh; regex="tet 1 is inverted" ;;
      other-mesh-field)  # a field of 65 records
        { printf 'MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n65\n1 1\n'; seq 65; echo End; } >"$work/f.sol"
        extra=(--field "$work/f.sol"); regex="65 vertex records but mesh .* has 64 vertices: a field on another mesh" ;;
    esac
    out=$("$anitet" adapt "$mesh" -o "$work/out.mesh" --metric "$metric" "${extra[@]}" 2>&1); rc=$?
    echo "$out"
    [[ $rc == 4 ]] || fail "exit status $rc, expected 4 (invalid input)"
    grep -Eq -- "$regex" <<<"$out" || fail "the message does not match /$regex/"
    compgen -G "$work/out*" >/dev/null && fail "a file was written: $(ls "$work"/out*)"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo PASS
