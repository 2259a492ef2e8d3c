#!/usr/bin/env python3
"""The sphere case's surface figures (issue 46): the points of the ball's surface (label 7, or
every boundary point with |x| < 0.9) and their distance to the sphere of radius R, and the volume
the ball's triangles enclose against the true ball's 4/3 pi R^3.

usage: sphere_surface.py MESH [MESH...] [--radius 0.5] [--label 7]
Prints one JSON line per mesh.
"""
import argparse, json, sys, os
import numpy as np

sys.path.insert(0, '/work/shared/tools')
from ugawg import read_mesh  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('meshes', nargs='+')
    ap.add_argument('--radius', type=float, default=0.5)
    ap.add_argument('--label', type=int, default=7)
    a = ap.parse_args()
    true_v = 4 / 3 * np.pi * a.radius ** 3
    for fn in a.meshes:
        P, _, tr, lab = read_mesh(fn)
        ball = tr[lab == a.label] if np.any(lab == a.label) else tr[np.linalg.norm(P[tr].mean(axis=1), axis=1) < 0.9]
        pts = np.unique(ball.ravel())
        d = np.abs(np.linalg.norm(P[pts], axis=1) - a.radius)
        x0, x1, x2 = P[ball[:, 0]], P[ball[:, 1]], P[ball[:, 2]]
        vol = abs(np.einsum('ij,ij->', x0, np.cross(x1, x2))) / 6
        print(json.dumps(dict(mesh=os.path.basename(fn), ball_triangles=int(len(ball)), ball_points=int(len(pts)),
                              max_distance=float(d.max()), volume=vol, volume_error=vol - true_v,
                              relative_volume_error=(vol - true_v) / true_v)))


if __name__ == '__main__':
    main()
