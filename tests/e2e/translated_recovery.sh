#!/usr/bin/env bash
# translated_recovery.sh ANITET TRANSFORM_PY SURFACE OUTDIR
# adis16480.stl translated by 1e6 (issue 11): its S1, rounded there, is not recovered by the split
# strategy with the degeneracy oracle (nor with 3 crossing-edge removals); the retry without the
# oracle recovers it on the first layer count. Stages 1-2 and the coupling only (--no-refine
# --no-optimize: 15 s), then `anitet quality --strict`: valid and boundary constrained.
set -u
anitet=$1; transform=$2; surface=$3; dir=$4
py=python3; $py -c 'import numpy, meshio' 2>/dev/null || py=/usr/bin/python3
in=$dir/translated-in.mesh out=$dir/translated-out.mesh
rm -f "$out"
$py "$transform" "$surface" "$in" translate1e6 || { echo "FAIL: transform.py"; exit 1; }
# Stage 1 one push at a time, in vertex order: the S1 whose recovery needs the retry without the
# oracle (with the two push tasks' order stage 2 recovers this input at once).
log=$("$anitet" mesh "$in" -o "$out" --no-refine --no-optimize --push-tasks-min-vertices 0 -v 2>&1) || { echo "$log"; echo "FAIL: anitet mesh exited"; exit 1; }
echo "$log" | grep -E "Steiner points on S1|notice: stage 2 could not recover"
echo "$log" | grep -q "notice: stage 2 could not recover" && { echo "FAIL: needed another layer count"; exit 1; }
echo "$log" | grep -q "tets flat in exact geometry allowed" || { echo "FAIL: not recovered by the retry without the oracle"; exit 1; }
"$anitet" quality "$out" --surface "$in" --strict > "$dir/translated-quality.txt" || { echo "FAIL: quality --strict exited $?"; exit 1; }
echo "PASS: recovered without the oracle, valid and boundary constrained"
