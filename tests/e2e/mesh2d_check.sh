#!/usr/bin/env bash
# mesh2d_check.sh ANITET IN OUT.mesh [mesh2d options...] -- [check2d.py options...]
# Runs `anitet mesh2d IN -o OUT.mesh`, then tests/tools/check2d.py (the independent checker):
# valid, every input segment kept, no point added on one (unless --split), holes empty, plus the
# given thresholds.
set -u
anitet=$1; in=$2; out=$3; shift 3
mesh_opts=(); check_opts=()
while (($#)); do [[ $1 == "--" ]] && { shift; break; }; mesh_opts+=("$1"); shift; done
check_opts=("$@")
here=$(cd "$(dirname "$0")" && pwd)
rm -f "$out"
"$anitet" mesh2d "$in" -o "$out" -q "${mesh_opts[@]}" || { echo "FAIL: anitet mesh2d exited $?"; exit 1; }
/usr/bin/python3 "$here/../tools/check2d.py" "$out" "$in" "${check_opts[@]}" || { echo "FAIL: check2d.py"; exit 1; }
echo PASS
