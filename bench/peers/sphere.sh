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
"$root/bench/peers/unit_sphere.sh" "$out" "$size"
"$root/bench/peers/run.sh" -o "$out" "$out/sphere.off"
