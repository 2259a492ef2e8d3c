#!/usr/bin/env bash
# Issue 11's determinism check on the shared surfaces: each clean surface is meshed twice by
# `anitet mesh`, once on one core (`taskset -c 0`: TBB then runs one thread) and once on all, and
# the two .mesh files must be identical byte for byte.
#
#   bench/determinism/run.sh ANITET [SURFACE ...]
#
# SURFACE: file names in ../shared/data/surfaces (default: the 15 clean ones). Prints one line per
# surface and exits 1 when any pair differs or a run fails. Not run by CI (about 15 minutes).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
anitet=${1:?usage: bench/determinism/run.sh ANITET [SURFACE ...]}
shift
surfaces=("$@")
[[ ${#surfaces[@]} -gt 0 ]] || surfaces=(decimated-knight.off tray_bottom.stl bimba_low.off kitten.off adis16480.stl
                                         femur.off casting.off elephant.obj fandisk.off airplane.obj turbine.off
                                         rocker-arm.obj hammer.obj armadillo.obj skull.obj)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
printf '%-22s %10s %10s %s\n' surface one_core_s all_cores_s verdict
for s in "${surfaces[@]}"; do
  in=$root/../shared/data/surfaces/$s
  t0=$(date +%s.%N)
  taskset -c 0 "$anitet" mesh "$in" -o "$tmp/one.mesh" -q > "$tmp/one.log" 2>&1; rc1=$?
  t1=$(date +%s.%N)
  "$anitet" mesh "$in" -o "$tmp/all.mesh" -q > "$tmp/all.log" 2>&1; rc2=$?
  t2=$(date +%s.%N)
  if ((rc1 != 0 || rc2 != 0)); then verdict="FAIL (exit $rc1 / $rc2)"; fail=1
  elif cmp -s "$tmp/one.mesh" "$tmp/all.mesh"; then verdict="identical ($(stat -c %s "$tmp/all.mesh") bytes)"
  else verdict="DIFFERENT"; fail=1; fi
  awk -v s="$s" -v a="$t0" -v b="$t1" -v c="$t2" -v v="$verdict" 'BEGIN { printf "%-22s %10.1f %10.1f %s\n", s, b - a, c - b, v }'
  rm -f "$tmp/one.mesh" "$tmp/all.mesh"
done
exit $fail
