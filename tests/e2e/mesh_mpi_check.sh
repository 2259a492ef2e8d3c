#!/usr/bin/env bash
# mesh_mpi_check.sh ANITET ANITET_MPI MESHCHECK IN OUTDIR [RANKS]
# Issue 12's MPI check: `mpirun --oversubscribe -np RANKS anitet-mpi mesh IN` (default 2 ranks)
# and the serial `anitet mesh IN`, both checked by the independent meshcheck.py: valid, boundary
# constrained, and the MPI mesh's radius ratio mean within 2% of the serial one's.
set -u
anitet=$1; anitet_mpi=$2; meshcheck=$3; in=$4; dir=$5; ranks=${6:-2}
mkdir -p "$dir"
rm -f "$dir/serial.mesh" "$dir/mpi.mesh"
# Open MPI refuses to start as root unless told (CI machines and containers run as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$anitet" mesh "$in" -o "$dir/serial.mesh" -q || { echo "FAIL: anitet mesh exited $?"; exit 1; }
# Under AddressSanitizer, leaks are not checked in the MPI run: Open MPI keeps allocations until
# exit in components it has unloaded by then (unknown modules to LeakSanitizer, so they cannot be
# suppressed by name). The distributed code's own leaks are checked by tests/unit/distributed,
# which runs the same parts as threads; addresses and undefined behaviour are checked here too.
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
mpirun --oversubscribe -np "$ranks" "$anitet_mpi" mesh "$in" -o "$dir/mpi.mesh" > "$dir/mpi.log" 2>&1 ||
  { echo "FAIL: mpirun -np $ranks anitet-mpi exited $?"; cat "$dir/mpi.log"; exit 1; }
grep -q "refine+optimize in parts" "$dir/mpi.log" || { echo "FAIL: the MPI run did not mesh in parts"; cat "$dir/mpi.log"; exit 1; }
for m in serial mpi; do
  /usr/bin/python3 "$meshcheck" "$dir/$m.mesh" --surface "$in" > "$dir/$m.json" ||
    { echo "FAIL: meshcheck.py on the $m mesh exited $?"; exit 1; }
done
/usr/bin/python3 - "$dir/serial.json" "$dir/mpi.json" <<'PY'
import json, sys
s, m = (json.load(open(p)) for p in sys.argv[1:3])
for name, r in (("serial", s), ("mpi", m)):
    if not (r["valid"] and r["boundary_constrained"]):
        sys.exit(f"FAIL: the {name} mesh: valid {r['valid']}, boundary constrained {r['boundary_constrained']}")
sm, mm = s["quality"]["radius_ratio"]["mean"], m["quality"]["radius_ratio"]["mean"]
line = (f"serial {s['tets']} tets, radius ratio mean {sm:.4f} min {s['quality']['radius_ratio']['min']:.4f}; "
        f"MPI {m['tets']} tets, mean {mm:.4f} min {m['quality']['radius_ratio']['min']:.4f}")
if abs(mm - sm) > 0.02 * sm:
    sys.exit("FAIL: means differ by more than 2%: " + line)
print("PASS: both valid and boundary constrained; " + line)
PY
