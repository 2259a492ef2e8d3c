#!/usr/bin/env bash
# mesh_mpi_pieces_check.sh ANITET ANITET_MPI MESHCHECK IN OUTDIR RANKS [MAX_PIECE_OVER_MEAN]
# Issue 51's no-gather path: `mpirun --oversubscribe -np RANKS anitet-mpi mesh IN -o parts.pvtu`
# (each rank writes its piece), the .pvtu checked against the format's rules (the elements and
# attributes ParaView reads; every piece's arrays declared in the index with the same type and
# components), `anitet merge` joining the pieces, and meshcheck.py on the merged mesh: valid,
# boundary constrained, radius-ratio mean within 1% of the serial run's, min >= 80% of it (PT-Scotch's
# parts change from run to run, and with them the min: 82-99% of the serial one on 2 ranks).
# With MAX_PIECE_OVER_MEAN, the largest piece's tets at most that times the pieces' mean (balance).
set -u
anitet=$1; anitet_mpi=$2; meshcheck=$3; in=$4; dir=$5; ranks=$6; max_over_mean=${7:-0}
mkdir -p "$dir"
rm -f "$dir"/parts* "$dir/merged.mesh" "$dir/serial.mesh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$anitet" mesh "$in" -o "$dir/serial.mesh" -q || { echo "FAIL: anitet mesh exited $?"; exit 1; }
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
mpirun --oversubscribe -np "$ranks" "$anitet_mpi" mesh "$in" -o "$dir/parts.pvtu" > "$dir/mpi.log" 2>&1 ||
  { echo "FAIL: mpirun -np $ranks anitet-mpi exited $?"; cat "$dir/mpi.log"; exit 1; }
/usr/bin/python3 - "$dir/parts.pvtu" "$ranks" "$max_over_mean" <<'PY' || exit 1
import os, sys, xml.etree.ElementTree as ET
index, ranks, max_over_mean = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
root = ET.parse(index).getroot()
def fail(m): sys.exit("FAIL: " + m)
if root.tag != "VTKFile" or root.get("type") != "PUnstructuredGrid": fail("not a PUnstructuredGrid")
grid = root.find("PUnstructuredGrid")
if grid is None or grid.get("GhostLevel") != "0": fail("no PUnstructuredGrid GhostLevel=0")
decl = {}
for sec in ("PPointData", "PCellData", "PPoints"):
    e = grid.find(sec)
    if e is None: fail("no " + sec)
    for a in e.findall("PDataArray"):
        decl[(sec[1:], a.get("Name"))] = (a.get("type"), a.get("NumberOfComponents"))
if grid.find("PPointData").get("GlobalIds") != "GlobalNodeIds": fail("GlobalNodeIds not declared as GlobalIds")
pieces = grid.findall("Piece")
cells = []
if len(pieces) != ranks: fail(f"{len(pieces)} pieces for {ranks} ranks")
for p in pieces:
    path = os.path.join(os.path.dirname(index), p.get("Source"))
    text = open(path, "rb").read()
    head = text[:text.index(b"<AppendedData")].decode() + "</VTKFile>"
    piece = ET.fromstring(head).find("UnstructuredGrid/Piece")
    found = {}
    for sec in ("PointData", "CellData", "Points"):
        for a in piece.find(sec).findall("DataArray"):
            found[(sec, a.get("Name"))] = (a.get("type"), a.get("NumberOfComponents"))
    if found != decl: fail(f"{path}: arrays {found} against the index's {decl}")
    cells.append(int(piece.get("NumberOfCells")))
print(f"PASS: {index}: {ranks} pieces, arrays as declared; tets per piece {cells}")
if max_over_mean > 0 and max(cells) > max_over_mean * sum(cells) / len(cells):
    fail(f"the largest piece has {max(cells)} tets, more than {max_over_mean} times the mean {sum(cells) / len(cells):.0f}")
PY
"$anitet" merge "$dir/parts.pvtu" -o "$dir/merged.mesh" || { echo "FAIL: anitet merge exited $?"; exit 1; }
for m in serial merged; do
  /usr/bin/python3 "$meshcheck" "$dir/$m.mesh" --surface "$in" > "$dir/$m.json" ||
    { echo "FAIL: meshcheck.py on the $m mesh exited $?"; exit 1; }
done
/usr/bin/python3 - "$dir/serial.json" "$dir/merged.json" <<'PY'
import json, sys
s, m = (json.load(open(p)) for p in sys.argv[1:3])
for name, r in (("serial", s), ("merged", m)):
    if not (r["valid"] and r["boundary_constrained"]):
        sys.exit(f"FAIL: the {name} mesh: valid {r['valid']}, boundary constrained {r['boundary_constrained']}")
sq, mq = s["quality"]["radius_ratio"], m["quality"]["radius_ratio"]
line = (f"serial {s['tets']} tets, radius ratio mean {sq['mean']:.4f} min {sq['min']:.4f}; "
        f"pieces {m['tets']} tets, mean {mq['mean']:.4f} min {mq['min']:.4f}")
if abs(mq["mean"] - sq["mean"]) > 0.01 * sq["mean"] or mq["min"] < 0.8 * sq["min"]:
    sys.exit("FAIL: mean not within 1% or min below 80%: " + line)
print("PASS: merged mesh valid and boundary constrained; " + line)
PY
