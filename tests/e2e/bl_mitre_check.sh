#!/usr/bin/env bash
# bl_mitre_check.sh ANITET BODY_IN_BOX_PY WORKDIR: 5 boundary layers on a cube (4 x 4 squares a
# face) in its box, with and without --bl-mitre, columns from --bl-columns. Without it every
# column is h0 (r^n - 1)/(r - 1) long, so that the layers are thinner across the walls at the
# cube's edges and corners (normal share 0.71, 0.58); with it the edge and corner columns are
# 1/share as long (the layers as thick across each wall as on a face) and the face columns as
# before. Every column full in both.
set -uo pipefail
anitet=$1 body_in_box=$2 work=$3
python=/usr/bin/python3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
"$python" - "$work/cube.obj" <<'PY' || fail "cube.obj"
import sys
n, ids, verts, faces = 4, {}, [], []
def vid(p):
    if p not in ids:
        ids[p] = len(verts) + 1
        verts.append(p)
    return ids[p]
for axis in range(3):
    for side in (0, n):
        for i in range(n):
            for j in range(n):
                def pt(a, b):
                    p = [0, 0, 0]
                    p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3] = side, a, b
                    return tuple(p)
                q = [vid(pt(i, j)), vid(pt(i + 1, j)), vid(pt(i + 1, j + 1)), vid(pt(i, j + 1))]
                if side == 0:
                    q.reverse()  # outward normals
                faces += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
with open(sys.argv[1], "w") as f:
    f.writelines(f"v {x / n} {y / n} {z / n}\n" for x, y, z in verts)
    f.writelines(f"f {a} {b} {c}\n" for a, b, c in faces)
PY
"$python" "$body_in_box" "$work/cube.obj" "$work/cube_in_box.mesh" >/dev/null || fail "body_in_box.py"
for mode in plain mitre; do
  extra=()
  [[ $mode == mitre ]] && extra=(--bl-mitre)
  "$anitet" mesh "$work/cube_in_box.mesh" -o "$work/$mode.mesh" -q --bl-patches 1 --bl-first-height 0.005 \
    --bl-growth 1.2 --bl-layers 5 --bl-columns "$work/$mode.csv" "${extra[@]}" || fail "anitet mesh ($mode) exited $?"
done
"$python" - "$work/plain.csv" "$work/mitre.csv" <<'PY' || fail "columns"
import sys
nominal = 0.005 * (1.2 ** 5 - 1) / 0.2
def groups(path):
    rows = [l.strip().split(",") for l in open(path)][1:]
    out = {"corner": [], "edge": [], "face": []}
    for r in rows:
        x, y, z = (float(v) for v in r[:3])
        on = sum(abs(c) < 1e-9 or abs(c - 1) < 1e-9 for c in (x, y, z))
        out[{3: "corner", 2: "edge", 1: "face"}[on]].append((int(r[3]), float(r[5]), float(r[6])))
    return out
plain, mitre = groups(sys.argv[1]), groups(sys.argv[2])
assert [len(plain[k]) for k in ("corner", "edge", "face")] == [8, 36, 54], {k: len(v) for k, v in plain.items()}
for name, g in (("plain", plain), ("mitre", mitre)):
    for k in g:
        assert all(layers == 5 for layers, _, _ in g[k]), (name, k)
        lengths = [t for _, t, _ in g[k]]
        shares = [s for _, _, s in g[k]]
        print(f"{name} {k}: {len(lengths)} columns, length {min(lengths) / nominal:.3f} .. {max(lengths) / nominal:.3f} "
              f"of h0 (r^n - 1)/(r - 1), normal share {min(shares):.3f} .. {max(shares):.3f}")
mean = lambda v: sum(v) / len(v)
for k, stretch in (("corner", 3 ** 0.5), ("edge", 2 ** 0.5), ("face", 1.0)):
    assert abs(mean([t for _, t, _ in plain[k]]) / nominal - 1) < 0.1, ("plain", k)
    assert abs(mean([t for _, t, _ in mitre[k]]) / (stretch * nominal) - 1) < 0.15, ("mitre", k)
# Across the walls: the length times the normal share, near the nominal with --bl-mitre only.
assert mean([t * s for _, t, s in mitre["corner"]]) / nominal > 0.85
assert mean([t * s for _, t, s in plain["corner"]]) / nominal < 0.7
PY
echo PASS
