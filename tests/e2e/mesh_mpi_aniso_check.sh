#!/usr/bin/env bash
# mesh_mpi_aniso_check.sh ANITET ANITET_MPI TOOLS UGAWG OUTDIR RANKS [IN_RANGE_POINTS [MEAN_SHARE]]
# Issue 51's anisotropic case in parts: the UGAWG cube (UGAWG/cube-linear-00.mesh) to its linear
# metric (cube-linear-00.sol on that mesh as the background), `anitet mesh` and
# `mpirun --oversubscribe -np RANKS anitet-mpi mesh` with the same options, gathered (-o .mesh)
# and in pieces (-o .pvtu, joined by `anitet merge`). The three meshes checked by the shared
# TOOLS/meshcheck.py (valid, boundary constrained) and measured by TOOLS/ugawg.py's UGAWG measures
# in the analytic linear metric: each MPI mesh's share of edges in [1/sqrt2, sqrt2] at most
# IN_RANGE_POINTS (default 1.5) points below one process's, its mean ratio at least MEAN_SHARE
# (default 0.985) of it.
set -u
anitet=$1; anitet_mpi=$2; tools=$3; ugawg=$4; dir=$5; ranks=$6; points=${7:-1.5}; share=${8:-0.985}
mkdir -p "$dir"
rm -f "$dir/serial.mesh" "$dir/mpi.mesh" "$dir"/parts* "$dir/merged.mesh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
opts=(--metric "$ugawg/cube-linear-00.sol" --background "$ugawg/cube-linear-00.mesh")
in="$ugawg/cube-linear-00.mesh"
"$anitet" mesh "$in" -o "$dir/serial.mesh" -q "${opts[@]}" || { echo "FAIL: anitet mesh exited $?"; exit 1; }
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
mpirun --oversubscribe -np "$ranks" "$anitet_mpi" mesh "$in" -o "$dir/mpi.mesh" "${opts[@]}" > "$dir/mpi.log" 2>&1 ||
  { echo "FAIL: mpirun -np $ranks anitet-mpi exited $?"; cat "$dir/mpi.log"; exit 1; }
grep -q "refine+optimize in parts" "$dir/mpi.log" ||
  { echo "FAIL: the MPI run did not mesh in parts"; cat "$dir/mpi.log"; exit 1; }
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
mpirun --oversubscribe -np "$ranks" "$anitet_mpi" mesh "$in" -o "$dir/parts.pvtu" "${opts[@]}" > "$dir/parts.log" \
  2>&1 ||
  { echo "FAIL: mpirun -np $ranks anitet-mpi (pieces) exited $?"; cat "$dir/parts.log"; exit 1; }
"$anitet" merge "$dir/parts.pvtu" -o "$dir/merged.mesh" > /dev/null || { echo "FAIL: anitet merge exited $?"; exit 1; }
for m in serial mpi merged; do
  /usr/bin/python3 "$tools/meshcheck.py" "$dir/$m.mesh" --surface "$in" > "$dir/$m.json" ||
    { echo "FAIL: meshcheck.py on the $m mesh exited $?"; exit 1; }
done
/usr/bin/python3 - "$tools" "$dir" "$points" "$share" <<'PY'
import json, sys
tools, d, points, share = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
sys.path.insert(0, tools)
import ugawg
def fail(m): sys.exit("FAIL: " + m)
for name in ("serial", "mpi", "merged"):
    r = json.load(open(f"{d}/{name}.json"))
    if not (r["valid"] and r["boundary_constrained"]):
        fail(f"the {name} mesh: valid {r['valid']}, boundary constrained {r['boundary_constrained']}")
s = ugawg.measure(f"{d}/serial.mesh", "linear")
line = f"one process {s['tets']} tets, {s['in_range']}% of edges in range, mean ratio {s['q_mean']}"
for name, what in (("mpi", "gathered"), ("merged", "pieces")):
    m = ugawg.measure(f"{d}/{name}.mesh", "linear")
    line += f"; {what} {m['tets']} tets, {m['in_range']}%, mean ratio {m['q_mean']}"
    if m["in_range"] < s["in_range"] - points or m["q_mean"] < share * s["q_mean"]:
        fail(f"the {what} mesh's UGAWG measures fall short (at most {points} points below, at least {share} of the "
             "mean): " + line)
print("PASS: the three meshes valid and boundary constrained; " + line)
PY
