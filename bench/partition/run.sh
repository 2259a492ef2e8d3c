#!/usr/bin/env bash
# Issue 50's partition figures: armadillo's mesh (`anitet mesh armadillo.obj`, made once and kept
# in OUTDIR) cut into 2, 8 and 64 parts by anitet's partitioner (src/partition, one ghost layer),
# each checked by partition_check: edge cut against METIS's own cut of the same dual graph (tets
# sharing a face) with METIS's defaults, imbalance (<= 3%), every tet own in exactly one part,
# every ghost tet own on its owner, the halo lists of each pair of neighbours naming the same
# global ids. Then the same graph, written in METIS's format, through Debian's gpmetis, and the
# comparison of METIS with Scotch (partitioner_compare) that chose METIS. Everything on one core
# (taskset -c 0). Not run by CI (about two minutes with the meshing).
#
#   bench/partition/run.sh [-o OUTDIR] [SURFACE]
#
# OUTDIR defaults to out/bench-partition (results.txt there); SURFACE to the shared armadillo.obj.
# Environment: BUILD_DIR (anitet's build, default build/).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/out/bench-partition
if [[ ${1:-} == "-o" ]]; then out=$2; shift 2; fi
surface=${1:-$root/../shared/data/surfaces/armadillo.obj}
name=$(basename "${surface%.*}")
"$root/scripts/setup.sh" metis libscotch-dev  # gpmetis; Scotch for the comparison only
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DANITET_BUILD_BENCH=ON >/dev/null
cmake --build "$build" -j "${JOBS:-2}" --target anitet partition_check partitioner_compare
mkdir -p "$out"
mesh=$out/$name.mesh
if [[ ! -f $mesh ]]; then
  echo "meshing $surface (once)"
  "$build/app/anitet" mesh "$surface" -o "$mesh" -q
fi
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "anitet: $(cd "$root" && git describe --always --dirty 2>/dev/null || echo unknown)"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores; memory: $(free -g | awk '/^Mem:/ {print $2}') GB"
  echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); one core (taskset -c 0)"
  echo
  echo "== partition_check: anitet_mesh_partition's partitioner, one ghost layer"
  taskset -c 0 "$build/bench/partition/partition_check" "$mesh" --parts 2,8,64 --ghost-layers 1
  echo
  echo "== the same dual graph through Debian's gpmetis (METIS 5.1 defaults)"
  taskset -c 0 "$build/bench/partition/partitioner_compare" "$mesh" --graph "$out/$name.graph" --parts 2,8,64 \
    > "$out/compare.txt"
  for k in 2 8 64; do
    printf '%3d parts: %s\n' "$k" "$(gpmetis "$out/$name.graph" "$k" | grep -E 'Edgecut' | sed 's/^ *- *//')"
  done
  echo
  echo "== METIS against Scotch 7.0 on the same graph (why METIS)"
  cat "$out/compare.txt"
  echo
  echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$out/results.txt"
rm -f "$out/$name.graph" "$out/$name.graph.part."*
