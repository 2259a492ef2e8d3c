#!/usr/bin/env python3
"""grading.py MESH.mesh [--wall LABEL] [--bl-region R]

How the cell size grows away from the wall in a mesh `anitet mesh` wrote with a boundary layer:
the mean edge length of the tets outside the BL region, in bands of distance from the wall
(distance from a tet's centroid to the nearest wall vertex), and the ratio from band to band.
Needs numpy and meshio (Debian python3-numpy, python3-meshio)."""
import argparse

import meshio
import numpy as np

EDGES = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    ap.add_argument("mesh")
    ap.add_argument("--wall", type=int, default=1, help="patch label of the wall (default 1)")
    ap.add_argument("--bl-region", type=int, default=1, help="region of the BL tets (default 1)")
    a = ap.parse_args()
    m = meshio.read(a.mesh)
    pts = m.points
    tets = m.cells_dict["tetra"]
    region = m.cell_data_dict["medit:ref"]["tetra"]
    tri = m.cells_dict["triangle"]
    wall = pts[np.unique(tri[m.cell_data_dict["medit:ref"]["triangle"] == a.wall])]
    rest = tets[region != a.bl_region]
    centre = pts[rest].mean(axis=1)
    length = np.mean([np.linalg.norm(pts[rest[:, i]] - pts[rest[:, j]], axis=1) for i, j in EDGES], axis=0)
    dist = np.empty(len(centre))
    for s in range(0, len(centre), 1000):  # nearest wall vertex, a block at a time
        q = centre[s:s + 1000]
        dist[s:s + 1000] = np.sqrt(((q[:, None, :] - wall[None, :, :]) ** 2).sum(-1).min(1))
    size = np.ptp(wall, axis=0).max()
    bands = [0.0] + [size * f for f in (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10)]
    print(f"{len(rest)} tets outside region {a.bl_region}; wall size {size:.4g}")
    print("distance from the wall | tets | mean edge | 10th-90th percentile | ratio to the band before")
    before = None
    for lo, hi in zip(bands[:-1], bands[1:]):
        pick = (dist >= lo) & (dist < hi)
        if not pick.any():
            continue
        mean = length[pick].mean()
        p10, p90 = np.percentile(length[pick], [10, 90])
        ratio = "" if before is None else f"{mean / before:.2f}"
        print(f"{lo:.3g} - {hi:.3g} | {pick.sum()} | {mean:.4g} | {p10:.4g} - {p90:.4g} | {ratio}")
        before = mean


if __name__ == "__main__":
    main()
