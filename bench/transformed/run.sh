#!/bin/bash
# bench/transformed/run.sh ANITET [VARIANTS...] — issue 6's invariance check: every clean shared
# surface rotated by a random rotation, scaled by 1e-4 and by 1e4, and translated by 1e6 (one
# variant at a time), meshed with `anitet mesh` and checked with meshcheck.py against the moved
# surface (the translated ones after an exact shift back): valid, boundary constrained, volume
# kept to 1e-9. With the variant `given` first (the default), every other run's tet count is
# compared with the surface's as given: beyond COUNT_TOL percent (default 5) the run fails; the
# variants scale2p-20 and scale2p20 (by 2^-20 and 2^20, exact in floating point) must give the
# given mesh itself, scaled ("exact"). The variants ulp1, ulp2, ... (not in the default list) move
# every coordinate by at most one ulp, at random: the rounding an inexact transform adds, without
# the transform, so their counts show how far rounding alone moves a surface's count (say
# `SURFACES=adis16480.stl run.sh ANITET given ulp1 ulp2 ulp3 ulp4`). One line per run, then a
# summary and the largest count deviation. Needs python3-numpy and python3-meshio. Not run by CI
# (about 45 minutes on 2 cores).
set -u
anitet=$(realpath "${1:?usage: run.sh ANITET [given rotate scale1e-4 scale1e4 translate1e6 scale2p-20 scale2p20 (default), also scale1e-6 scale1e6 ulp1 ulp2 ...]}"); shift
variants=${*:-given rotate scale1e-4 scale1e4 translate1e6 scale2p-20 scale2p20}
count_tol=${COUNT_TOL:-5}
declare -A given_tets
here=$(cd "$(dirname "$0")" && pwd)
shared=$here/../../../shared
surf=$shared/data/surfaces
py=python3; $py -c 'import numpy, meshio' 2>/dev/null || py=/usr/bin/python3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
clean=${SURFACES:-"decimated-knight.off tray_bottom.stl bimba_low.off kitten.off adis16480.stl femur.off casting.off elephant.obj fandisk.off airplane.obj turbine.off rocker-arm.obj hammer.obj armadillo.obj skull.obj"}
fail=0 runs=0
worst=0
printf '%-20s %-13s %8s %9s %8s %s\n' surface variant seconds tets vs_given verdict
for v in $variants; do
  for f in $clean; do
    in=$tmp/${f%.*}-$v.mesh out=$tmp/${f%.*}-$v-out.mesh
    $py "$here/transform.py" "$surf/$f" "$in" "$v" || { echo "transform failed: $f $v"; fail=1; continue; }
    s=$(date +%s.%N)
    "$anitet" mesh "$in" -o "$out" -q >"$tmp/log" 2>&1; rc=$?
    e=$(date +%s.%N)
    check_mesh=$out check_surface=$in
    rm -f "$tmp"/back-*.mesh  # never check the previous surface's result
    if [[ $v == translate1e6 && -e $out ]]; then
      # Checked shifted back by -1e6: exact (Sterbenz), so the same mesh, where meshcheck's
      # enclosed volume and coordinate matching do not lose their digits to cancellation.
      check_mesh=$tmp/back-out.mesh check_surface=$tmp/back-in.mesh
      $py "$here/transform.py" "$out" "$check_mesh" back1e6 && $py "$here/transform.py" "$in" "$check_surface" back1e6
    fi
    verdict=$($py "$shared/tools/meshcheck.py" "$check_mesh" --surface "$check_surface" 2>/dev/null | $py -c '
import json, sys
try: d = json.load(sys.stdin)
except Exception: print("0 no-mesh"); sys.exit()
ok = d["valid"] and d["boundary_constrained"] and d["volume_rel_error"] < 1e-9
q = d["quality"]
print(d["tets"], "ok" if ok else "FAIL", "nonpositive=%d missing=%d steiner_on_S=%d volerr=%.1e rr_mean=%.3f rr_min=%.3f" % (
  d.get("nonpositive_tets", -1), d.get("input_triangles_missing", -1), d.get("steiner_points_on_boundary", -1),
  d.get("volume_rel_error", -1), q["radius_ratio"]["mean"], q["radius_ratio"]["min"]))')
    runs=$((runs + 1))
    tets=${verdict%% *} dev=-
    [[ $v == given ]] && given_tets[$f]=$tets
    if [[ $v != given && -n ${given_tets[$f]:-} && ${given_tets[$f]} != 0 ]]; then
      dev=$(awk "BEGIN{printf \"%+.1f%%\", 100 * ($tets / ${given_tets[$f]} - 1)}")
      worst=$(awk "BEGIN{d = 100 * ($tets / ${given_tets[$f]} - 1); d = d < 0 ? -d : d; printf \"%.1f\", (d > $worst ? d : $worst)}")
      awk "BEGIN{d = 100 * ($tets / ${given_tets[$f]} - 1); exit !(d > $count_tol || d < -$count_tol)}" &&
        verdict="${verdict/ ok / COUNT }"
    fi
    # Scaled by a power of two the surface is the same in floating point: the mesh must be the
    # given one's, scaled exactly (same points in the same order, same tets).
    if [[ $v == scale2p* && $verdict == *" ok "* && -n ${given_tets[$f]:-} ]]; then
      given_out=$tmp/${f%.*}-given-out.mesh
      same=$($py -c '
import sys, meshio, numpy as np
a, b = meshio.read(sys.argv[1]), meshio.read(sys.argv[2])
s = 2.0 ** int(sys.argv[3])
same = a.points.shape == b.points.shape and np.array_equal(a.points * s, b.points) and \
  np.array_equal(a.cells_dict["tetra"], b.cells_dict["tetra"])
print("same" if same else "differs")' "$given_out" "$out" "${v#scale2p}" 2>/dev/null)
      [[ $same == same ]] && verdict="$verdict exact" || verdict="${verdict/ ok / NOT-EXACT }"
    fi
    [[ $rc == 0 && $verdict == *" ok "* ]] || { fail=$((fail + 1)); verdict="$verdict rc=$rc $(head -c 200 "$tmp/log" | tr '\n' ' ')"; }
    printf '%-20s %-13s %8.2f %9s %8s %s\n' "$f" "$v" "$(awk "BEGIN{print $e - $s}")" "$tets" "$dev" "${verdict#* }"
  done
done
echo "transformed: $((runs - fail)) of $runs runs pass; largest tet count deviation from the surface as given: $worst% (tolerance $count_tol%)"
[[ $fail == 0 ]]
