#!/usr/bin/python3
"""bench/bl/mixed_cells_check.py MESH.vtu: checks a .vtu of tets, wedges and pyramids (anitet mesh
--bl-cells prisms) independently of anitet, as meshcheck.py does for tets: every cell positive
(a tet's volume; a wedge's and a pyramid's tets on either diagonal of each quad), every face of
the cells shared by two cells or on the boundary, a quad never facing triangles, and every
boundary face given by the file's boundary triangles (a quad by two). Prints one JSON object;
exit 1 when a check fails."""
import json, sys
from collections import Counter
import numpy as np
import meshio

# Faces per cell type, outward, in meshio's (VTK's for tets and pyramids, Gmsh's for wedges) order.
FACES = {
    "tetra": [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)],
    "wedge": [(0, 1, 4, 3), (1, 2, 5, 4), (0, 3, 5, 2), (0, 2, 1), (3, 4, 5)],
    "pyramid": [(0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)],
}


def vol6(p, a, b, c, d):
    return np.einsum("ij,ij->i", np.cross(p[b] - p[a], p[c] - p[a]), p[d] - p[a])


def main(path):
    m = meshio.read(path)
    p = np.asarray(m.points, dtype=np.float64)
    cells = {c.type: np.asarray(c.data, dtype=np.int64) for c in m.cells}
    out = {"cells": {k: len(v) for k, v in cells.items()}}
    bad = {}
    if "tetra" in cells:
        t = cells["tetra"]
        bad["tetra"] = int((vol6(p, t[:, 0], t[:, 1], t[:, 2], t[:, 3]) <= 0).sum())
    if "pyramid" in cells:
        y = cells["pyramid"]
        neg = np.zeros(len(y), bool)
        for i in range(4):
            neg |= vol6(p, y[:, i], y[:, (i + 1) % 4], y[:, (i + 2) % 4], y[:, 4]) <= 0
        bad["pyramid"] = int(neg.sum())
    if "wedge" in cells:
        w = cells["wedge"]
        neg = np.zeros(len(w), bool)
        # Each corner's tet (the corner, its two cap neighbours, its column's other end).
        for a, b, c, d in [(0, 1, 2, 3), (1, 2, 0, 4), (2, 0, 1, 5), (3, 5, 4, 0), (4, 3, 5, 1), (5, 4, 3, 2)]:
            neg |= vol6(p, w[:, a], w[:, b], w[:, c], w[:, d]) <= 0
        bad["wedge"] = int(neg.sum())
    out["non_positive_cells"] = bad
    faces = Counter()
    for kind, data in cells.items():
        if kind not in FACES:
            continue
        for f in FACES[kind]:
            for row in data[:, list(f)]:
                faces[tuple(sorted(row))] += 1
    over = sum(1 for n in faces.values() if n > 2)
    boundary = {f for f, n in faces.items() if n == 1}
    tri_halves = Counter()
    for f in faces:
        if len(f) == 4:
            for skip in range(4):
                tri_halves[tuple(v for i, v in enumerate(f) if i != skip)] += 1
    quad_on_tri = sum(1 for f in faces if len(f) == 3 and f in tri_halves)
    given = Counter(tuple(sorted(r)) for r in cells.get("triangle", np.zeros((0, 3), np.int64)))
    missing = 0
    for f in boundary:
        if len(f) == 3:
            missing += given[f] != 1
        else:
            missing += sum(given[tuple(v for i, v in enumerate(f) if i != s)] for s in range(4)) != 2
    out.update({"faces_shared_by_3_or_more": over, "cell_triangles_on_a_quad": quad_on_tri,
                "boundary_faces": len(boundary), "boundary_faces_not_given": missing})
    out["valid"] = not any(bad.values()) and over == 0 and quad_on_tri == 0 and missing == 0
    print(json.dumps(out))
    return 0 if out["valid"] else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
