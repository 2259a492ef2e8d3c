#!/usr/bin/python3
"""readback.py REF.mesh OUT.su2 OUT.cgns NAMES: reads an anitet run's SU2 and CGNS files back
(meshio for points and tets; the SU2 MARKER_TAG lines; the CGNS file's per-patch sections and BCs
with h5py) and compares them with the Medit file of the same run: points, tets, and per patch
(NAMES: LABEL=NAME,... as in --patch-names) the triangle count. Exit 1 on a difference."""
import sys
import warnings

import h5py
import meshio
import numpy as np

warnings.simplefilter("ignore")
ref_path, su2_path, cgns_path, names_arg = sys.argv[1:5]
names = {int(k): v for k, v in (p.split("=") for p in names_arg.split(","))}
ref = meshio.read(ref_path)
count = lambda m, kind: sum(len(c.data) for c in m.cells if c.type == kind)
labels = np.concatenate([ref.cell_data["medit:ref"][i] for i, c in enumerate(ref.cells) if c.type == "triangle"])
want = [(names[k], int((labels == k).sum())) for k in sorted(names)]
ok = True
for path in (su2_path, cgns_path):
    m = meshio.read(path)
    got = (len(m.points), count(m, "tetra"))
    print(f"{path}: {got[0]} points, {got[1]} tets (Medit: {len(ref.points)}, {count(ref, 'tetra')})")
    ok &= got == (len(ref.points), count(ref, "tetra"))
lines = open(su2_path).read().split("\n")
markers = [(l[12:], int(lines[i + 1].split("=")[1])) for i, l in enumerate(lines) if l.startswith("MARKER_TAG= ")]
print(f"SU2 markers: {markers}")
ok &= markers == want
zone = h5py.File(cgns_path, "r")["Base"]["Zone1"]
found = []
for name, _ in want:
    rng = zone[name]["ElementRange"][" data"][:]
    bc = zone["ZoneBC"][name]["PointRange"][" data"][:].ravel()
    found.append((name, int(rng[1] - rng[0] + 1)))
    ok &= bool((bc == rng).all())
print(f"CGNS sections and BCs: {found}")
ok &= found == want
print("read back: " + ("same points, tets and patches as the Medit file" if ok else "DIFFERENT"))
sys.exit(0 if ok else 1)
