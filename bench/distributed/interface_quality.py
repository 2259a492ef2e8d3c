#!/usr/bin/python3
"""Radius ratios of the pieces of anitet-mpi's .pvtu output, near the final interfaces and elsewhere.

    /usr/bin/python3 bench/distributed/interface_quality.py PARTS.pvtu

An interface vertex is in more than one piece (GlobalNodeIds); the tets within two rings of the
interfaces are those with a vertex of an interface vertex's tets. Prints, as one JSON line, the
tets, the radius-ratio mean and min of all, and the share of tets below 0.3 near the interfaces
and elsewhere (issue 51: the interfaces invisible in the quality means the first no higher); the
same shares among the tets with a vertex on the boundary triangles ("surface": in one process they
hold nearly every tet below 0.3) and among the others ("interior"), and the lowest ratio of each.
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np


def radius_ratio(p, t):
    a, b, c, d = (p[t[:, i]] for i in range(4))
    vol = np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))) / 6.0
    area = lambda x, y, z: 0.5 * np.linalg.norm(np.cross(y - x, z - x), axis=1)
    s = area(b, c, d) + area(a, c, d) + area(a, b, d) + area(a, b, c)
    ab, ac, ad = b - a, c - a, d - a
    num = (np.einsum("ij,ij->i", ad, ad)[:, None] * np.cross(ab, ac)
           + np.einsum("ij,ij->i", ac, ac)[:, None] * np.cross(ad, ab)
           + np.einsum("ij,ij->i", ab, ab)[:, None] * np.cross(ac, ad))
    with np.errstate(divide="ignore", invalid="ignore"):
        r_in = 3.0 * vol / s
        r_out = np.linalg.norm(num, axis=1) / (12.0 * vol)
        q = np.nan_to_num(3.0 * r_in / r_out)
    return q


def main(index):
    root = ET.parse(index).getroot()
    pieces = [os.path.join(os.path.dirname(index), p.get("Source")) for p in root.iter("Piece")]
    tets, quality, seen, on_surface = [], [], {}, []
    for k, path in enumerate(pieces):
        with open(path, "rb") as f:
            head = f.read(4096)
        if b'NumberOfCells="0"' in head:
            continue  # a rank that ended with no tet
        m = meshio.read(path)
        gid = np.asarray(m.point_data["GlobalNodeIds"]).astype(np.int64).ravel()
        t = m.cells_dict["tetra"]
        tets.append(gid[t])
        if "triangle" in m.cells_dict:
            on_surface.append(np.unique(gid[m.cells_dict["triangle"]]))
        quality.append(radius_ratio(m.points, t))
        for g in np.unique(gid[t]):
            seen[g] = seen.get(g, 0) + 1
    t = np.concatenate(tets)
    q = np.concatenate(quality)
    n = int(t.max()) + 1
    pieces_of = np.zeros(n, dtype=np.int32)
    for g, c in seen.items():
        pieces_of[g] = c
    near_vertex = pieces_of > 1
    for _ in range(2):  # two rings of tets around the interface vertices
        ring = near_vertex[t].any(axis=1)
        near_vertex = near_vertex.copy()
        near_vertex[t[ring].ravel()] = True
    near = ring
    bad = q < 0.3
    surface_vertex = np.zeros(n, dtype=bool)
    if on_surface:
        surface_vertex[np.concatenate(on_surface)] = True
    touches = surface_vertex[t].any(axis=1)
    share = lambda mask: float(bad[mask].mean()) if mask.any() else 0.0
    lowest = lambda mask: float(q[mask].min()) if mask.any() else 1.0
    out = {
        "pieces": len(pieces), "tets": int(len(q)), "rr_mean": float(q.mean()), "rr_min": float(q.min()),
        "tets_near_interfaces": int(near.sum()),
        "below_0.3_near": float(bad[near].mean()) if near.any() else 0.0,
        "below_0.3_elsewhere": float(bad[~near].mean()) if (~near).any() else 0.0,
        "below_0.3_count_near": int(bad[near].sum()), "below_0.3_count_elsewhere": int(bad[~near].sum()),
    }
    for name, mask in (("surface", touches), ("interior", ~touches)):
        out[name] = {"tets_near": int((near & mask).sum()), "below_0.3_near": share(near & mask),
                     "below_0.3_elsewhere": share(~near & mask), "min_near": lowest(near & mask),
                     "min_elsewhere": lowest(~near & mask)}
    print(json.dumps(out))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
