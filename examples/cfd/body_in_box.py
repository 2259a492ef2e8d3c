#!/usr/bin/env python3
"""body_in_box.py BODY.obj OUT.mesh [--scale S] [--cells N]

Writes the fluid domain around a closed body as one Medit .mesh surface for `anitet mesh`: the
body's triangles reversed (normals out of the fluid, into the body), label 1 (the wall), inside
a cube S times the body's largest extent (default 10) centred on it, each side split in N x N
squares of two triangles (default 3), label 2 (the farfield). Only OBJ 'v' and 'f' lines are
read (polygons are fanned into triangles). Standard library only."""
import argparse


def read_obj(path):
    xyz, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                xyz.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(xyz) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    tris.append((ids[0], ids[k], ids[k + 1]))
    return xyz, tris


def box(lo, hi, n):
    """The cube's surface, n x n squares per side, triangles oriented out of the cube."""
    xyz, index, tris = [], {}, []

    def vertex(g):
        if g not in index:
            index[g] = len(xyz)
            xyz.append(tuple(lo[k] + (hi[k] - lo[k]) * g[k] / n for k in range(3)))
        return index[g]

    for axis in range(3):
        b, c = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, 1):
            u, v = (b, c) if side else (c, b)  # u x v points out of the cube
            for i in range(n):
                for j in range(n):
                    q = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        g = [0, 0, 0]
                        g[axis] = n if side else 0
                        g[u], g[v] = i + di, j + dj
                        q.append(vertex(tuple(g)))
                    tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return xyz, tris


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[1])
    ap.add_argument("body")
    ap.add_argument("out")
    ap.add_argument("--scale", type=float, default=10.0)
    ap.add_argument("--cells", type=int, default=3)
    a = ap.parse_args()
    bxyz, btris = read_obj(a.body)
    lo = [min(p[k] for p in bxyz) for k in range(3)]
    hi = [max(p[k] for p in bxyz) for k in range(3)]
    size = max(hi[k] - lo[k] for k in range(3))
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    half = a.scale * size / 2
    fxyz, ftris = box([c - half for c in centre], [c + half for c in centre], a.cells)
    offset = len(fxyz)
    with open(a.out, "w") as f:
        f.write("MeshVersionFormatted 2\n\nDimension 3\n\n")
        f.write(f"# {a.body} (label 1, wall) in a farfield cube {a.scale} x its size (label 2)\n")
        f.write(f"\nVertices\n{len(fxyz) + len(bxyz)}\n")
        for p in fxyz + bxyz:
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r} 0\n")
        f.write(f"\nTriangles\n{len(ftris) + len(btris)}\n")
        for t in ftris:
            f.write(f"{t[0] + 1} {t[1] + 1} {t[2] + 1} 2\n")
        for t in btris:  # reversed: out of the fluid
            f.write(f"{t[0] + offset + 1} {t[2] + offset + 1} {t[1] + offset + 1} 1\n")
        f.write("\nEnd\n")
    print(f"{a.out}: {len(btris)} wall and {len(ftris)} farfield triangles; body size {size:g}, cube side {2 * half:g}")


if __name__ == "__main__":
    main()
