#!/usr/bin/env python3
"""boundary_elements_check.py INPUT.mesh DIR

Reads the meshes `anitet mesh INPUT.mesh` wrote to DIR (x.mesh, x.msh, x.vtu, x.su2, x.cgns,
x.exo and case/constant/polyMesh) with readers that are not anitet's: meshio for the first four,
h5py (CGNS boundary sections), netCDF4 (Exodus side sets) and a small parser of OpenFOAM's ASCII
files. For each file: every boundary element is a face of the file's tetrahedra, the boundary
faces of the tetrahedra are covered exactly once, and each patch holds exactly the input's
triangles of its label (compared by coordinates: the surface is kept). A file that is absent
(a build without CGNS or Exodus II) is reported and skipped only when SKIP_MISSING=1.
Exit 0 when every check passes.
"""
import os
import re
import sys
import warnings

import numpy as np

warnings.simplefilter("ignore")


def read_medit(path):
    """The input, read by this script's own parser: points, tets, boundary triangles, refs."""
    toks = " ".join(line.split("#")[0] for line in open(path)).split()
    out, i = {}, 0
    sizes = {"Vertices": 4, "Triangles": 4, "Tetrahedra": 5}
    while i < len(toks):
        t = toks[i]
        if t in ("MeshVersionFormatted", "Dimension"):
            i += 2
        elif t in sizes:
            n = int(toks[i + 1])
            out[t] = np.array(toks[i + 2:i + 2 + n * sizes[t]], dtype=float).reshape(n, sizes[t])
            i += 2 + n * sizes[t]
        elif t == "End":
            break
        else:
            raise ValueError("unknown keyword " + t)
    tri = out["Triangles"]
    return out["Vertices"][:, :3], tri[:, :3].astype(int) - 1, tri[:, 3].astype(int)


def key(points, tri):
    """A triangle by the sorted coordinates of its corners."""
    return tuple(sorted(tuple(points[v]) for v in tri))


def tet_faces(tets):
    count = {}
    for t in tets:
        for i in range(4):
            f = tuple(sorted(int(t[j]) for j in range(4) if j != i))
            count[f] = count.get(f, 0) + 1
    return count


def check(name, points, tets, patches, expected):
    """patches: label -> list of triangles (vertex ids of this file)."""
    faces = tet_faces(tets)
    covered = {}
    problems = []
    for label, tris in patches.items():
        for tri in tris:
            f = tuple(sorted(int(v) for v in tri))
            if f not in faces:
                problems.append(f"patch {label}: triangle {[v + 1 for v in tri]} is no face of the tets")
            covered[f] = covered.get(f, 0) + 1
    boundary = [f for f, n in faces.items() if n == 1]
    uncovered = [f for f in boundary if covered.get(f, 0) == 0]
    twice = [f for f in boundary if covered.get(f, 0) > 1]
    if uncovered:
        problems.append(f"{len(uncovered)} of {len(boundary)} boundary faces of the tets are in no patch")
    if twice:
        problems.append(f"{len(twice)} boundary faces are in two patches or twice in one")
    got = {label: sorted(key(points, t) for t in tris) for label, tris in patches.items()}
    if sorted(got) != sorted(expected):
        problems.append(f"patch labels {sorted(got)}, expected {sorted(expected)}")
    else:
        for label in expected:
            if got[label] != expected[label]:
                problems.append(f"patch {label}: its triangles are not the input's of that label")
    nb = sum(len(t) for t in patches.values())
    print(f"{name}: {len(points)} points, {len(tets)} tets, {nb} boundary elements in {len(patches)} patches: "
          + ("OK" if not problems else "; ".join(problems[:5])))
    return not problems


def by_label(tris, labels):
    out = {}
    for t, l in zip(tris, labels):
        out.setdefault(int(l), []).append(t)
    return out


def label_of(name):
    assert name.startswith("patch"), name
    return int(name[5:].replace("_m", "-"))


def meshio_file(path, label_key):
    import meshio
    m = meshio.read(path)
    tets = np.vstack([c.data for c in m.cells if c.type == "tetra"])
    tris, labels = [], []
    for i, c in enumerate(m.cells):
        if c.type == "triangle":
            tris.append(c.data)
            labels.append(np.asarray(m.cell_data[label_key][i]).ravel())
    return m.points, tets, by_label(np.vstack(tris), np.concatenate(labels))


def su2_file(path):
    """meshio reads the points and tets; the markers by name from the text (meshio numbers them)."""
    import meshio
    m = meshio.read(path)
    tets = np.vstack([c.data for c in m.cells if c.type == "tetra"])
    lines = open(path).read().split("\n")
    patches = {}
    for i, line in enumerate(lines):
        if line.startswith("MARKER_TAG="):
            name = line.split("=")[1].strip()
            n = int(lines[i + 1].split("=")[1])
            rows = [list(map(int, lines[i + 2 + k].split())) for k in range(n)]
            assert all(r[0] == 5 for r in rows), "not all SU2 marker elements are triangles"
            patches[label_of(name)] = [r[1:4] for r in rows]
    return m.points, tets, patches


def cgns_file(path):
    import h5py
    f = h5py.File(path, "r")
    zone = f["Base"]["Zone1"]
    coords = zone["GridCoordinates"]
    points = np.column_stack([coords[c][" data"][:] for c in ("CoordinateX", "CoordinateY", "CoordinateZ")])
    tets = zone["GridElements"]["ElementConnectivity"][" data"][:].reshape(-1, 4) - 1
    patches = {}
    for name in zone["ZoneBC"]:
        conn = zone[name]["ElementConnectivity"][" data"][:].reshape(-1, 3) - 1
        rng = zone[name]["ElementRange"][" data"][:]
        assert (zone["ZoneBC"][name]["PointRange"][" data"][:].ravel() == rng).all(), name
        patches[label_of(name)] = list(conn)
    return points, tets, patches


def exodus_file(path):
    import netCDF4
    nc = netCDF4.Dataset(path)
    points = np.column_stack([nc.variables[v][:] for v in ("coordx", "coordy", "coordz")])
    blocks = [nc.variables[v][:] - 1 for v in sorted(nc.variables) if v.startswith("connect")]
    tets = np.vstack(blocks)

    def names(var):
        v = nc.variables[var]
        v.set_auto_mask(False)
        return [b"".join(c).decode().rstrip("\x00") for c in v[:]]
    side_nodes = {1: (0, 1, 3), 2: (1, 2, 3), 3: (0, 3, 2), 4: (0, 2, 1)}
    patches = {}
    for i, name in enumerate(names("ss_names")):
        elems = nc.variables[f"elem_ss{i + 1}"][:] - 1
        sides = nc.variables[f"side_ss{i + 1}"][:]
        patches[label_of(name)] = [[tets[e][k] for k in side_nodes[int(s)]] for e, s in zip(elems, sides)]
    return points, tets, patches


def foam_list(path):
    """The list of an OpenFOAM ASCII file: its entries as strings (after the FoamFile header)."""
    text = open(path).read()
    body = text[text.index("}", text.index("FoamFile")) + 1:]
    body = "\n".join(l for l in body.split("\n") if not l.strip().startswith("//"))
    start = body.index("(")
    n = int(body[:start].split()[-1])
    return body[start + 1:body.rindex(")")], n


def polymesh(case):
    d = os.path.join(case, "constant", "polyMesh")
    text, n = foam_list(os.path.join(d, "points"))
    points = np.array([list(map(float, p.strip("() ").split())) for p in text.split("\n") if "(" in p])
    assert len(points) == n
    text, n = foam_list(os.path.join(d, "faces"))
    faces = [list(map(int, f.split("(")[1].strip(") ").split())) for f in text.split("\n") if "(" in f]
    owner = [int(x) for x in foam_list(os.path.join(d, "owner"))[0].split()]
    neighbour = [int(x) for x in foam_list(os.path.join(d, "neighbour"))[0].split()]
    # The cells' vertices, from their faces (each cell is a tet: 4 faces, 4 vertices).
    cells = [set() for _ in range(max(owner) + 1)]
    for f, o in enumerate(owner):
        cells[o].update(faces[f])
    for f, nb in enumerate(neighbour):
        cells[nb].update(faces[f])
    assert all(len(c) == 4 for c in cells), "a cell is not a tetrahedron"
    tets = [sorted(c) for c in cells]
    btext = open(os.path.join(d, "boundary")).read()
    patches = {}
    for m in re.finditer(r"\n\s*(\w+)\s*\n\s*\{([^}]*)\}", btext):
        body = m.group(2)
        if "nFaces" not in body:
            continue  # the FoamFile header
        nf = int(re.search(r"nFaces\s+(\d+);", body).group(1))
        sf = int(re.search(r"startFace\s+(\d+);", body).group(1))
        patches[label_of(m.group(1))] = [faces[f] for f in range(sf, sf + nf)]
    if len(faces) != len(neighbour) + sum(len(t) for t in patches.values()):
        print("polyMesh: the patches do not hold every boundary face")
    return points, tets, patches


def main():
    inp, work = sys.argv[1], sys.argv[2]
    skip_missing = os.environ.get("SKIP_MISSING") == "1"
    points, tris, labels = read_medit(inp)
    expected = {}
    for t, l in zip(tris, labels):
        expected.setdefault(int(l), []).append(key(points, t))
    expected = {l: sorted(v) for l, v in expected.items()}
    files = [("x.mesh", lambda p: meshio_file(p, "medit:ref")),
             ("x.msh", lambda p: meshio_file(p, "gmsh:physical")),
             ("x.vtu", lambda p: meshio_file(p, "patch")),
             ("x.su2", su2_file),
             ("x.cgns", cgns_file),
             ("x.exo", exodus_file),
             ("case", polymesh)]
    ok = True
    for name, reader in files:
        path = os.path.join(work, name)
        if not os.path.exists(path):
            print(f"{name}: not written" + (" (skipped)" if skip_missing else ""))
            ok = ok and skip_missing
            continue
        p, t, patches = reader(path)
        ok = check(name, np.asarray(p, dtype=float), np.asarray(t), patches, expected) and ok
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
