#!/usr/bin/env python3
"""to_medit.py IN OUT.mesh: a triangulated surface as a Medit .mesh with every coordinate written
in full double precision (repr), for Gmsh's Merge and TetGen. OBJ ('v' and 'f' lines, polygons
fanned) and OFF are read here (meshio stumbles on OBJ normals); other formats through meshio."""
import sys

import meshio


def read_obj(path):
    points, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                points.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(points) + i for i in ids]
                tris += [(ids[0], ids[k], ids[k + 1]) for k in range(1, len(ids) - 1)]
    return points, tris


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    assert words[0].endswith("OFF"), path + ": not an OFF file"
    nv, nf = int(words[1]), int(words[2])
    points = [[float(x) for x in words[4 + 3 * i:7 + 3 * i]] for i in range(nv)]
    tris, at = [], 4 + 3 * nv
    for _ in range(nf):
        n = int(words[at])
        ids = [int(x) for x in words[at + 1:at + 1 + n]]
        tris += [(ids[0], ids[k], ids[k + 1]) for k in range(1, n - 1)]
        at += 1 + n
    return points, tris


def read_surface(path):
    """(points, triangles) of a surface file: OBJ and OFF here, other formats through meshio."""
    if path.lower().endswith(".obj"):
        return read_obj(path)
    if path.lower().endswith(".off"):
        return read_off(path)
    m = meshio.read(path)
    return m.points, m.cells_dict["triangle"]


def write_medit(path, points, tris):
    """The surface as a Medit .mesh, every coordinate in full double precision (repr)."""
    with open(path, "w") as f:
        f.write(f"MeshVersionFormatted 2\nDimension 3\nVertices\n{len(points)}\n")
        for p in points:
            f.write(f"{float(p[0])!r} {float(p[1])!r} {float(p[2])!r} 0\n")
        f.write(f"Triangles\n{len(tris)}\n")
        for t in tris:
            f.write(f"{t[0] + 1} {t[1] + 1} {t[2] + 1} 1\n")
        f.write("End\n")


def main():
    points, tris = read_surface(sys.argv[1])
    write_medit(sys.argv[2], points, tris)


if __name__ == "__main__":
    main()
