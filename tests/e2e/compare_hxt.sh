#!/bin/sh
# Side by side, in one script on the same machine: anitet mesh and Gmsh's HXT (-algo hxt, one
# thread, the surface kept) on the same surfaces; times, tets per second, and meshcheck.py's
# quality split (tets touching S / the rest). Not run by ctest (it needs gmsh and takes minutes).
# usage: compare_hxt.sh ANITET OUTDIR SURFACE...
set -u
anitet=$1; out=$2; shift 2
mkdir -p "$out"
py=/usr/bin/python3
check=/work/shared/tools/meshcheck.py
summary() {  # meshcheck JSON on stdin -> one line per part
  $py -c '
import json, sys
d = json.load(sys.stdin)
print("   valid %s boundary_constrained %s tets %d" % (d["valid"], d["boundary_constrained"], d["tets"]))
for k in ("quality_touching_surface", "quality_interior"):
    q = d[k]; r = q["radius_ratio"]
    print("   %-25s tets %7d  rr mean %.3f min %.3f  min dihedral %5.2f  good %.2f%%  bad %.4f%%" % (
        k, q["tets"], r["mean"], r["min"], q["min_dihedral_deg"], 100 * q["good_fraction_rr_gt_0.4"],
        100 * q["bad_fraction_rr_lt_0.1"]))'
}
for s in "$@"; do
  name=$(basename "$s"); stem=${name%.*}
  echo "== $name"
  t0=$(date +%s.%N)
  if "$anitet" mesh "$s" -o "$out/$stem.mesh" --front-layers 1 -q; then
    t1=$(date +%s.%N)
    echo "  anitet: $(echo "$t1 - $t0" | bc) s"
    $py $check "$out/$stem.mesh" --surface "$s" | summary
  else
    echo "  anitet: failed"
  fi
  $py -c '
import sys, meshio, numpy as np
if sys.argv[1].lower().endswith(".obj"):  # meshio refuses OBJ files whose normals outnumber points
    pts, tri = [], []
    for line in open(sys.argv[1]):
        f = line.split()
        if f and f[0] == "v": pts.append([float(x) for x in f[1:4]])
        elif f and f[0] == "f":
            ids = [int(x.split("/")[0]) for x in f[1:]]
            ids = [i - 1 if i > 0 else len(pts) + i for i in ids]
            tri += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    pts, tri = np.array(pts), np.array(tri)
else:
    m = meshio.read(sys.argv[1])
    pts, tri = m.points, np.vstack([c.data for c in m.cells if c.type == "triangle"])
meshio.write(sys.argv[2], meshio.Mesh(pts, [("triangle", tri)]), file_format="gmsh22", binary=False)' "$s" "$out/$stem.surf.msh"
  printf 'Merge "%s";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\nMesh.Algorithm3D = 10;\nGeneral.NumThreads = 1;\n' \
    "$stem.surf.msh" > "$out/$stem.geo"
  t0=$(date +%s.%N)
  if (cd "$out" && gmsh "$stem.geo" -3 -nt 1 -o "$stem.hxt.msh" > "$stem.hxt.log" 2>&1); then
    t1=$(date +%s.%N)
    echo "  gmsh hxt: $(echo "$t1 - $t0" | bc) s (whole gmsh run, reading included)"
    $py $check "$out/$stem.hxt.msh" --surface "$s" | summary
  else
    echo "  gmsh hxt: failed ($(grep -m1 Error "$out/$stem.hxt.log"))"
  fi
done
