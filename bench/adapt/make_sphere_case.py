#!/usr/bin/env python3
"""The curved case of issue 46: the box [-1, 1]^3 minus the ball of radius 0.5 at the origin.

Writes SURFACE.mesh (Medit, boundary triangles only): the box's faces as 8x8 grids (labels 1-6,
normals out of the box) and the ball's surface as an icosphere (the icosahedron's faces divided
into 6x6 triangles, points pushed onto the sphere: edges of 0.08-0.11, mean 0.1; label 7, normals into the
ball, i.e. out of the domain). Mesh it with `anitet mesh SURFACE.mesh -o START.mesh`, then run
`ugawg.py anitet:ANITET START.mesh sphere N`.

usage: make_sphere_case.py SURFACE.mesh [--radius 0.5] [--frequency 5] [--box-cells 8]
"""
import argparse
import numpy as np


def icosphere(radius, freq):
    t = (1 + 5 ** 0.5) / 2
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
         [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    pts, index, tris = [], {}, []

    def point(p):
        p = p / np.linalg.norm(p) * radius
        key = tuple(np.round(p, 12))
        if key not in index:
            index[key] = len(pts)
            pts.append(p)
        return index[key]

    for a, b, c in f:
        A, B, C = v[a], v[b], v[c]
        grid = {}
        for i in range(freq + 1):
            for j in range(freq + 1 - i):
                grid[i, j] = point(A + (B - A) * i / freq + (C - A) * j / freq)
        for i in range(freq):
            for j in range(freq - i):
                tris.append([grid[i, j], grid[i + 1, j], grid[i, j + 1]])
                if i + j + 1 < freq:
                    tris.append([grid[i + 1, j], grid[i + 1, j + 1], grid[i, j + 1]])
    return np.array(pts), np.array(tris)


def box(n):
    pts, index, tris, labels = [], {}, [], []

    def point(p):
        key = tuple(np.round(p, 12))
        if key not in index:
            index[key] = len(pts)
            pts.append(np.array(p, float))
        return index[key]

    for axis in range(3):
        for side, label in ((-1.0, 2 * axis + 1), (1.0, 2 * axis + 2)):
            u, w = (axis + 1) % 3, (axis + 2) % 3
            g = {}
            for i in range(n + 1):
                for j in range(n + 1):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = side
                    p[u] = -1 + 2 * i / n
                    p[w] = -1 + 2 * j / n
                    g[i, j] = point(p)
            for i in range(n):
                for j in range(n):
                    q = [g[i, j], g[i + 1, j], g[i + 1, j + 1], g[i, j + 1]]
                    # (u, w, axis) is right-handed: u x w = axis; on the + side keep, on - reverse.
                    for tri in ([q[0], q[1], q[2]], [q[0], q[2], q[3]]):
                        tris.append(tri if side > 0 else tri[::-1])
                        labels.append(label)
    return np.array(pts), np.array(tris), labels


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('output')
    ap.add_argument('--radius', type=float, default=0.5)
    ap.add_argument('--frequency', type=int, default=6)
    ap.add_argument('--box-cells', type=int, default=8)
    a = ap.parse_args()
    bp, bt, bl = box(a.box_cells)
    sp, st = icosphere(a.radius, a.frequency)
    # The icosahedron's faces turn outwards; the ball's surface faces into the ball (out of the domain).
    st = st[:, ::-1] + len(bp)
    P = np.vstack([bp, sp])
    T = np.vstack([bt, st])
    L = bl + [7] * len(st)
    e = np.concatenate([np.linalg.norm(sp[st[:, i] - len(bp)] - sp[st[:, (i + 1) % 3] - len(bp)], axis=1) for i in range(3)])
    with open(a.output, 'w') as f:
        f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(P))
        for p in P:
            f.write('%.17g %.17g %.17g 0\n' % tuple(p))
        f.write('Triangles\n%d\n' % len(T))
        for t, l in zip(T, L):
            f.write('%d %d %d %d\n' % (t[0] + 1, t[1] + 1, t[2] + 1, l))
        f.write('End\n')
    print('%s: %d points, %d triangles; icosphere edges %.4f-%.4f (mean %.4f)' % (a.output, len(P), len(T), e.min(), e.max(), e.mean()))


if __name__ == '__main__':
    main()
