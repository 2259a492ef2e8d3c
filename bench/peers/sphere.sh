#!/usr/bin/env bash
# The unit sphere of issue 6: Gmsh meshes its surface (`-2`, size 0.02: about 75,000 triangles),
# then bench/peers/run.sh meshes the volume with anitet, Gmsh HXT (1 and 2 threads, surface kept),
# Gmsh's Delaunay and TetGen back to back and checks each with meshcheck.py.
#
#   bench/peers/sphere.sh [-o OUTDIR] [SIZE]
#
# OUTDIR defaults to out/bench-sphere; SIZE (default 0.02) is Gmsh's surface mesh size. Not run by CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/out/bench-sphere
if [[ ${1:-} == "-o" ]]; then out=$2; shift 2; fi
size=${1:-0.02}
command -v gmsh >/dev/null || { sudo=""; [[ $(id -u) == 0 ]] || sudo=sudo; $sudo apt-get install -y gmsh; }
mkdir -p "$out"
cat > "$out/sphere.geo" <<GEO
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMin = $size;
Mesh.MeshSizeMax = $size;
GEO
gmsh "$out/sphere.geo" -2 -format msh4 -o "$out/sphere-surface.msh" > "$out/sphere-surface.log" 2>&1
# As OFF, every coordinate in full double precision (the peers get the same numbers from it).
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
"$root/bench/peers/run.sh" -o "$out" "$out/sphere.off"
