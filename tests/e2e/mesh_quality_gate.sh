#!/usr/bin/env bash
# mesh_quality_gate.sh ANITET IN OUT [mesh options...]
# The issue-8 acceptance thresholds for inputs whose triangles are of good shape: after
# mesh_and_check.sh's checks (valid, boundary constrained, volume kept), `anitet quality --json`
# must report radius ratio mean >= 0.75 and min >= 0.15, good (> 0.4) >= 99%, bad (< 0.1) = 0 and
# the smallest dihedral angle >= 10 degrees.
set -u
here=$(dirname "$0")
anitet=$1; in=$2; out=$3
"$here/mesh_and_check.sh" "$@" || exit 1
json="$out.json"
field() {  # the first number after "name": in the quality block
  sed -n '/"quality"/,/radius_ratio_histogram/p' "$json" | grep -o "\"$1\": [^,]*" | head -1 | awk '{print $2}'
}
rr_mean=$(sed -n '/"quality"/,/"mean_ratio"/p' "$json" | grep -o '"mean": [^,]*' | head -1 | awk '{print $2}')
rr_min=$(sed -n '/"quality"/,/"mean_ratio"/p' "$json" | grep -o '"min": [^,]*' | head -1 | awk '{print $2}')
good=$(field good_fraction_rr_gt_0.4)
bad=$(field bad_fraction_rr_lt_0.1)
dih=$(field min_dihedral_deg)
echo "radius ratio mean $rr_mean min $rr_min, good $good, bad $bad, min dihedral $dih"
awk -v m="$rr_mean" -v n="$rr_min" -v g="$good" -v b="$bad" -v d="$dih" \
  'BEGIN { exit !(m >= 0.75 && n >= 0.15 && g >= 0.99 && b == 0 && d >= 10) }' \
  || { echo "FAIL: below the acceptance thresholds"; exit 1; }
echo "PASS: quality thresholds met"
