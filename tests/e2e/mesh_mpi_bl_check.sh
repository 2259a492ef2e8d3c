#!/usr/bin/env bash
# mesh_mpi_bl_check.sh ANITET ANITET_MPI MESHCHECK IN OUTDIR RANKS [BL options...]
# Issue 51's boundary-layer case in parts: `anitet mesh IN BL options --json` and, on RANKS ranks
# (mpirun --oversubscribe), `anitet-mpi mesh` the same way with a gathered .mesh output and with a
# .pvtu (one piece per rank, joined by `anitet merge`). The three meshes: valid and boundary
# constrained (the shared meshcheck.py), as many BL tets (region 1 and up) as one process's
# report says; both MPI reports: every wall vertex's column full, as many nominal columns and
# the same first heights as one process's, bit for bit (the layers are frozen); the gathered
# one's also every layer's heights and no BL vertex moved. --bl-cells prisms: written from the gathered mesh,
# refused with a .pvtu output (exit 5, NotImplemented).
set -u
anitet=$1; anitet_mpi=$2; meshcheck=$3; in=$4; dir=$5; ranks=$6; shift 6
mkdir -p "$dir"
rm -f "$dir"/serial.* "$dir"/mpi.* "$dir"/parts* "$dir"/merged.* "$dir"/prisms.*
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
run_mpi() { mpirun --oversubscribe -np "$ranks" "$anitet_mpi" mesh "$in" "$@"; }
"$anitet" mesh "$in" "$@" -o "$dir/serial.mesh" --json > "$dir/serial.report.json" ||
  { echo "FAIL: anitet mesh exited $?"; exit 1; }
run_mpi "$@" -o "$dir/mpi.mesh" --json > "$dir/mpi.report.json" 2> "$dir/mpi.log" ||
  { echo "FAIL: anitet-mpi (gather) exited $?"; cat "$dir/mpi.log"; exit 1; }
run_mpi "$@" -o "$dir/parts.pvtu" --json > "$dir/parts.report.json" 2> "$dir/parts.log" ||
  { echo "FAIL: anitet-mpi (pieces) exited $?"; cat "$dir/parts.log"; exit 1; }
"$anitet" merge "$dir/parts.pvtu" -o "$dir/merged.mesh" > /dev/null || { echo "FAIL: anitet merge exited $?"; exit 1; }
run_mpi "$@" -o "$dir/prisms.vtu" --bl-cells prisms > "$dir/prisms.log" 2>&1 ||
  { echo "FAIL: anitet-mpi --bl-cells prisms (gather) exited $?"; cat "$dir/prisms.log"; exit 1; }
run_mpi "$@" -o "$dir/parts-prisms.pvtu" --bl-cells prisms -q > "$dir/parts-prisms.log" 2>&1
code=$?
if [[ $code != 5 ]] || ! grep -q "bl-cells prisms is not possible with a .pvtu output" "$dir/parts-prisms.log"; then
  echo "FAIL: --bl-cells prisms with a .pvtu output: exit $code, not 5 with its message"
  cat "$dir/parts-prisms.log"
  exit 1
fi
for m in serial mpi merged; do
  /usr/bin/python3 "$meshcheck" "$dir/$m.mesh" --surface "$in" > "$dir/$m.json" ||
    { echo "FAIL: meshcheck.py on the $m mesh exited $?"; exit 1; }
done
/usr/bin/python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def fail(m): sys.exit("FAIL: " + m)
def bl_tets(path):
    """Tets of region >= 1 in a Medit mesh (the BL's regions; the one body is region 0)."""
    toks = open(path).read().split()
    i = toks.index("Tetrahedra"); n = int(toks[i + 1])
    return sum(1 for k in range(n) if int(toks[i + 2 + 5 * k + 4]) >= 1)
for m in ("serial", "mpi", "merged"):
    r = json.load(open(f"{d}/{m}.json"))
    if not (r["valid"] and r["boundary_constrained"]):
        fail(f"the {m} mesh: valid {r['valid']}, boundary constrained {r['boundary_constrained']}")
s = json.load(open(f"{d}/serial.report.json"))["boundary_layer"]
for name in ("mpi", "parts"):
    b = json.load(open(f"{d}/{name}.report.json"))["boundary_layer"]
    if b["full_columns"] != b["wall_vertices"] or b["wall_vertices"] != s["wall_vertices"]:
        fail(f"{name}: {b['full_columns']} full columns of {b['wall_vertices']} wall vertices (one process: "
             f"{s['full_columns']} of {s['wall_vertices']})")
    # The gathered mesh's report is measured on it after the rounds: every layer's heights and
    # the BL vertices' displacement too (the pieces' report is measured before the rounds).
    keys = ["tets", "nominal_columns", "first_height_min", "first_height_max"]
    if name == "mpi":
        keys += ["max_displacement", "layer_height_min", "layer_height_max"]
    for key in keys:
        if b[key] != s[key]:
            fail(f"{name}: boundary_layer.{key} {b[key]}, one process {s[key]}")
counts = {m: bl_tets(f"{d}/{m}.mesh") for m in ("serial", "mpi", "merged")}
if len(set(counts.values())) != 1 or counts["serial"] != s["tets"]:
    fail(f"BL tets in the meshes {counts}, one process's report {s['tets']}")
print(f"PASS: serial, gathered and merged pieces valid and boundary constrained; {s['wall_vertices']} full columns, "
      f"first height {s['first_height_min']:.4g}, {s['tets']} BL tets in all three")
PY
grep -q "written with --bl-cells prisms: [1-9]" "$dir/prisms.log" ||
  { echo "FAIL: no prisms written from the gathered mesh"; cat "$dir/prisms.log"; exit 1; }
