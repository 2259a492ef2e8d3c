#!/usr/bin/env bash
# Issue 8's and 12's wall-time ratios on a shared, noisy machine: rounds that alternate two anitet
# binaries (say the session's first and its last) and Gmsh's HXT, keeping the surface, on the same
# input, one after the other; each line gives the three wall times and each binary's ratio to
# HXT's. The medians over the rounds are what the README quotes.
#
#   bench/peers/alternate.sh [-r ROUNDS] [-t HXT_THREADS] OLD NEW [SURFACE ...]
#
# SURFACE: file names in ../shared/data/surfaces (default: fandisk.off airplane.obj elephant.obj).
# HXT_THREADS (default 1): 1 for issue 8, 2 for issue 12. Outputs under out/bench-alternate.
# Needs gmsh and meshio (bench/peers/run.sh installs both). Not run by CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
rounds=6
threads=1
while [[ ${1:-} == -* ]]; do
  case $1 in
    -r) rounds=$2; shift 2 ;;
    -t) threads=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
old=${1:?usage: bench/peers/alternate.sh [-r ROUNDS] [-t HXT_THREADS] OLD NEW [SURFACE ...]}
new=${2:?usage: bench/peers/alternate.sh [-r ROUNDS] [-t HXT_THREADS] OLD NEW [SURFACE ...]}
shift 2
surfaces=("$@")
[[ ${#surfaces[@]} -gt 0 ]] || surfaces=(fandisk.off airplane.obj elephant.obj)
out=$root/out/bench-alternate
py=/usr/bin/python3
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > /dev/null 2>&1 || return 1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
for s in "${surfaces[@]}"; do
  dir=$out/${s%.*}
  mkdir -p "$dir"
  # Double precision for Gmsh (binary STL would round to float32).
  [[ -f $dir/surface.mesh ]] || $py "$root/bench/peers/to_medit.py" "$root/../shared/data/surfaces/$s" "$dir/surface.mesh"
  printf 'Merge "surface.mesh";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\nMesh.Algorithm3D = 10;\nGeneral.NumThreads = %s;\n' \
    "$threads" > "$dir/hxt.geo"
done
printf '%-5s %-14s %8s %8s %8s %10s %10s\n' round surface old_s new_s hxt_s old/hxt new/hxt
for ((r = 1; r <= rounds; ++r)); do
  for s in "${surfaces[@]}"; do
    dir=$out/${s%.*}
    in=$root/../shared/data/surfaces/$s
    to=$(seconds "$old" mesh "$in" -o "$dir/old.mesh")
    tn=$(seconds "$new" mesh "$in" -o "$dir/new.mesh")
    th=$(seconds gmsh "$dir/hxt.geo" -3 -format msh4 -o "$dir/hxt.msh")
    awk -v r="$r" -v s="$s" -v o="$to" -v n="$tn" -v h="$th" \
      'BEGIN { printf "%-5d %-14s %8.2f %8.2f %8.2f %10.2f %10.2f\n", r, s, o, n, h, o / h, n / h }'
  done
done
