#!/usr/bin/env bash
# Writes OUTDIR/sphere.off: the unit sphere's surface meshed by Gmsh (`-2`, OpenCASCADE sphere,
# mesh size SIZE), every coordinate in full double precision (so anitet and the peers read the
# same numbers). Shared by bench/peers/sphere.sh and bench/scale/run.sh; needs gmsh and meshio.
#
#   bench/peers/unit_sphere.sh OUTDIR SIZE
set -euo pipefail
out=$1 size=$2
mkdir -p "$out"
cat > "$out/sphere.geo" <<GEO
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMin = $size;
Mesh.MeshSizeMax = $size;
GEO
gmsh "$out/sphere.geo" -2 -format msh4 -o "$out/sphere-surface.msh" > "$out/sphere-surface.log" 2>&1
py=python3; $py -c 'import numpy, meshio' 2>/dev/null || py=/usr/bin/python3
$py - "$out/sphere-surface.msh" "$out/sphere.off" <<'PY'
import sys
import meshio
m = meshio.read(sys.argv[1])
tris = m.cells_dict["triangle"]
used = sorted(set(tris.ravel().tolist()))
index = {v: i for i, v in enumerate(used)}
with open(sys.argv[2], "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(used), len(tris)))
    for v in used:
        f.write("%r %r %r\n" % tuple(float(x) for x in m.points[v]))
    for t in tris:
        f.write("3 %d %d %d\n" % tuple(index[int(v)] for v in t))
print("sphere surface: %d vertices, %d triangles" % (len(used), len(tris)))
PY
