#!/usr/bin/env bash
# mesh_and_check.sh ANITET IN OUT [mesh options...]
# Runs `anitet mesh IN -o OUT`, then checks OUT against IN with `anitet quality --strict`: valid
# (exact orientation, no face shared by more than two tets) and boundary constrained (every input
# triangle a boundary face, no other boundary face, no Steiner point on the surface); and the
# enclosed volume kept to 1e-9 relative. Unless --no-optimize is among the options, also at most
# $MAX_ROUNDING_FLAT (default 0) tets flat to double rounding (valid for the exact test, but a
# double evaluation of their volume could give zero or less: the optimizer's last pass opens them).
set -u
anitet=$1; in=$2; out=$3; shift 3
rm -f "$out"
"$anitet" mesh "$in" -o "$out" -q "$@" || { echo "FAIL: anitet mesh exited $?"; exit 1; }
"$anitet" quality "$out" --surface "$in" --strict --json > "$out.json" || { echo "FAIL: quality --strict exited $?"; cat "$out.json"; exit 1; }
err=$(grep -o '"volume_rel_error": [^,]*' "$out.json" | head -1 | awk '{print $2}')
awk -v e="$err" 'BEGIN { exit !(e != "" && e + 0 < 1e-9) }' || { echo "FAIL: volume_rel_error $err"; exit 1; }
flat=$(grep -o '"rounding_flat_tets": [0-9]*' "$out.json" | head -1 | awk '{print $2}')
if [[ " $* " != *" --no-optimize "* ]]; then
  [[ -n $flat ]] && (( flat <= ${MAX_ROUNDING_FLAT:-0} )) || { echo "FAIL: rounding_flat_tets ${flat:-missing}"; exit 1; }
fi
echo "PASS: valid, boundary constrained, volume_rel_error $err, rounding_flat_tets $flat"
