#!/bin/bash
# bench/layers/run.sh ANITET — issue 5's stage 1 check: every clean shared surface with 1, 2 and 3
# layers (`anitet mesh --stop-after layers`), one line per run with the layers audit (T1 valid,
# every input triangle a face of T1, S1 closed and off S, the volume identity) and the epsilon-
# halving figures. Not run by CI (about 12 minutes on 2 cores).
set -u
anitet=$(realpath "${1:?usage: run.sh ANITET}")
here=$(cd "$(dirname "$0")" && pwd)
surf=$here/../../../shared/data/surfaces
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
clean="decimated-knight.off tray_bottom.stl bimba_low.off kitten.off adis16480.stl femur.off casting.off elephant.obj fandisk.off airplane.obj turbine.off rocker-arm.obj hammer.obj armadillo.obj skull.obj"
fail=0 runs=0
for f in $clean; do
  for n in 1 2 3; do
    s=$(date +%s.%N)
    "$anitet" mesh "$surf/$f" --stop-after layers --front-layers "$n" -o "$tmp/out.mesh" >"$tmp/log" 2>&1; rc=$?
    e=$(date +%s.%N)
    audit=$(grep "audit:" "$tmp/log" | sed 's/^ *//')
    eps=$(grep "epsilon halving" "$tmp/log" | sed 's/^ *epsilon halving: //')
    runs=$((runs + 1))
    ok=1
    case "$audit" in "audit: valid,"*) ;; *) ok=0;; esac
    [ "$rc" -eq 0 ] || ok=0
    [ "$ok" -eq 1 ] || fail=$((fail + 1))
    printf '%-22s %d rc=%d %6.1fs | %s | %s\n' "$f" "$n" "$rc" "$(echo "$e - $s" | bc)" "$audit" "$eps"
  done
done
echo "layers: $((runs - fail)) of $runs runs pass"
[ "$fail" -eq 0 ]
