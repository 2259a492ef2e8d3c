#!/usr/bin/env python3
"""Writes the small test meshes of tests/data/io (run from anywhere; standard library only).

The model is one box [0, 1.5] x [0, 0.1] x [-0.25, 2] cut into 6 tets (Kuhn split of a cube),
with 12 boundary triangles oriented outward. Patches: x=min 1, x=max 2, y=min 3, y=max 4,
z=min 5, z=max 6. Regions: tets 0-2 are region 1, tets 3-5 region 2.
The test io_tests checks these files against the same numbers.
"""
import itertools
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
LO = (0.0, 0.0, -0.25)
HI = (1.5, 0.1, 2.0)

VERTS = [tuple(HI[k] if (i >> k) & 1 else LO[k] for k in range(3)) for i in range(8)]


def sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(a[k] * b[k] for k in range(3))


def orient(a, b, c, d):
    return dot(cross(sub(VERTS[b], VERTS[a]), sub(VERTS[c], VERTS[a])), sub(VERTS[d], VERTS[a]))


TETS = []
for perm in itertools.permutations(range(3)):
    path = [0]
    for axis in perm:
        path.append(path[-1] | (1 << axis))
    t = list(path)
    if orient(*t) < 0:
        t[0], t[1] = t[1], t[0]
    TETS.append(t)
REGIONS = [1, 1, 1, 2, 2, 2]

# Boundary triangles: faces used by one tet, oriented away from the tet's fourth vertex.
count = {}
for t in TETS:
    for i in range(4):
        f = tuple(sorted(t[:i] + t[i + 1:]))
        count[f] = count.get(f, 0) + 1
TRIS = []
PATCHES = []
for t in TETS:
    for i in range(4):
        f = [v for k, v in enumerate(t) if k != i]
        if count[tuple(sorted(f))] != 1:
            continue
        if orient(f[0], f[1], f[2], t[i]) > 0:  # the tet is on the positive side: flip outward
            f[1], f[2] = f[2], f[1]
        TRIS.append(f)
        # which box side: the coordinate shared by the 3 corners
        for k in range(3):
            bits = {(v >> k) & 1 for v in f}
            if len(bits) == 1:
                PATCHES.append(2 * k + 1 + bits.pop())
TRIS_SORTED = sorted(zip(PATCHES, TRIS))
PATCHES = [p for p, _ in TRIS_SORTED]
TRIS = [t for _, t in TRIS_SORTED]
assert len(TETS) == 6 and len(TRIS) == 12


def fmt(x):
    return repr(float(x))


def write(name, text, mode="w"):
    with open(os.path.join(HERE, name), mode) as f:
        f.write(text)


# --- surfaces ---
def off_quads():
    # The 6 box sides as quads (fan-triangulated by readers into 12 triangles).
    quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]]
    lines = ["# a box as 6 quads", "OFF", "# counts below", "8 6 0", ""]
    for v in VERTS:
        lines.append(" ".join(fmt(c) for c in v) + "  # vertex")
    for q in quads:
        lines.append("4 " + " ".join(map(str, q)))
    write("box_quads.off", "\n".join(lines) + "\n")


def off_inline():
    lines = ["COFF 8 12 18"]
    for v in VERTS:
        lines.append(" ".join(fmt(c) for c in v) + " 255 0 0 255")
    for t in TRIS:
        lines.append("3 " + " ".join(map(str, t)) + " 0.5 0.5 0.5")
    write("box_inline_header.off", "\r\n".join(lines))  # CRLF, no final line break


def obj_groups():
    lines = ["# OBJ with groups, texture/normal forms and negative indices", "mtllib box.mtl"]
    for v in VERTS:
        lines.append("v " + " ".join(fmt(c) for c in v))
    lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vn 0 0 1"]
    forms = ["{v}", "{v}/1", "{v}//1", "{v}/2/1"]
    last_patch = None
    for i, (p, t) in enumerate(zip(PATCHES, TRIS)):
        if p != last_patch:
            lines.append(("o " if p % 2 else "g ") + "side" + str(p))
            lines.append("usemtl m" + str(p))
            last_patch = p
        refs = []
        for k, v in enumerate(t):
            idx = v + 1 if (i + k) % 3 else v - 8  # negative: relative to the 8 vertices
            refs.append(forms[(i + k) % 4].format(v=idx))
        lines.append("f " + " ".join(refs))
    write("box_groups.obj", "\n".join(lines) + "\n")


def stl_ascii(name, blocks, solid_names):
    lines = []
    for solid, tris in zip(solid_names, blocks):
        lines.append("solid " + solid)
        for t in tris:
            lines.append("  facet normal 0 0 0")
            lines.append("    outer loop")
            for v in t:
                lines.append("      vertex " + " ".join("%.9g" % c for c in VERTS[v]))
            lines.append("    endloop")
            lines.append("  endfacet")
        lines.append("endsolid " + solid)
    write(name, "\n".join(lines) + "\n")


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def stl_binary(name, header):
    data = header.ljust(80, b" ")[:80] + struct.pack("<I", len(TRIS))
    for t in TRIS:
        data += struct.pack("<3f", 0, 0, 0)
        for v in t:
            data += struct.pack("<3f", *VERTS[v])
        data += struct.pack("<H", 0x1234)  # an attribute word, not a label
    write(name, data, "wb")


def ply_ascii():
    lines = ["ply", "format ascii 1.0", "comment box with extras", "element vertex 8",
             "property double x", "property double y", "property double z",
             "property uchar red", "element face 11", "property list uchar int vertex_indices",
             "property float quality", "element edge 1", "property int vertex1",
             "property int vertex2", "end_header"]
    for i, v in enumerate(VERTS):
        lines.append(" ".join(fmt(c) for c in v) + " " + str(i * 10))
    # 10 triangles, then the last two (a planar pair: 0 4 6 2 side) as one quad
    quad_side = [[0, 4, 6, 2]]
    kept = [t for p, t in zip(PATCHES, TRIS) if p != 1]
    for t in kept:
        lines.append("3 " + " ".join(map(str, t)) + " 0.5")
    lines.append("4 " + " ".join(map(str, quad_side[0])) + " 1")
    lines.append("0 1")
    write("box_ascii.ply", "\n".join(lines) + "\n")


def ply_binary(name, big):
    e = ">" if big else "<"
    head = ["ply", "format %s 1.0" % ("binary_big_endian" if big else "binary_little_endian"),
            "comment made by make_test_files.py", "element vertex 8"]
    if big:
        head += ["property float x", "property float y", "property float z"]
    else:
        head += ["property float nx", "property double x", "property double y",
                 "property double z", "property list uchar short texture"]
    head += ["element face 12"]
    head += ["property list int uint vertex_indices" if big else "property list uchar int vertex_indices"]
    head += ["element material 2", "property uchar r", "end_header"]
    data = ("\n".join(head) + "\n").encode()
    for v in VERTS:
        if big:
            data += struct.pack(e + "3f", *v)
        else:
            data += struct.pack(e + "f3dB2h", 1.0, *v, 2, 7, 8)
    for t in TRIS:
        if big:
            data += struct.pack(e + "i3I", 3, *t)
        else:
            data += struct.pack(e + "B3i", 3, *t)
    data += b"\x01\x02"
    write(name, data, "wb")


# --- volumes ---
def medit():
    lines = ["MeshVersionFormatted 2", "", "# a comment", "Dimension", "3", "", "Vertices", "8"]
    for v in VERTS:
        lines.append(" ".join(fmt(c) for c in v) + " 0")
    lines += ["", "Corners", "2", "1", "8"]  # an unknown section to skip
    lines += ["", "Triangles", "12"]
    for p, t in zip(PATCHES, TRIS):
        lines.append(" ".join(str(v + 1) for v in t) + " " + str(p))
    lines += ["", "Tetrahedra", "6"]
    for r, t in zip(REGIONS, TETS):
        lines.append(" ".join(str(v + 1) for v in t) + " " + str(r))
    lines += ["", "End"]
    write("box.mesh", "\n".join(lines) + "\n")


# Gmsh: sparse node tags, vertex i has tag 10*(i+1). Volume entity 1 (physical 10) holds
# region 1, volume entity 2 (no physical) region 2. Surface entity s = patch s, and surface 1 has
# physical 101.
NODE_TAG = [10 * (i + 1) for i in range(8)]
VOL_PHYS = {1: [10], 2: []}
SURF_PHYS = {s: ([101] if s == 1 else []) for s in range(1, 7)}


def gmsh41_ascii():
    L = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat",
         "$PhysicalNames", "2", "3 10 \"solid\"", "2 101 \"left\"", "$EndPhysicalNames",
         "$Entities", "1 1 6 2", "1 0 0 -0.25 0", "1 0 0 -0.25 1.5 0 -0.25 0 1 1"]
    for s in range(1, 7):
        ph = SURF_PHYS[s]
        L.append("%d 0 0 0 1 1 1 %d %s 0" % (s, len(ph), " ".join(map(str, ph))))
    for vtag in (1, 2):
        ph = VOL_PHYS[vtag]
        L.append("%d 0 0 0 1 1 1 %d %s 6 1 2 3 4 5 -6" % (vtag, len(ph), " ".join(map(str, ph))))
    L += ["$EndEntities", "$Nodes", "2 8 10 80"]
    # block 1: vertices 0-3 on surface 5, parametric; block 2: vertices 4-7 on volume 1
    L.append("2 5 1 4")
    L += [str(NODE_TAG[i]) for i in range(4)]
    L += [" ".join(fmt(c) for c in VERTS[i]) + " 0.5 0.25" for i in range(4)]
    L.append("3 1 0 4")
    L += [str(NODE_TAG[i]) for i in range(4, 8)]
    L += [" ".join(fmt(c) for c in VERTS[i]) for i in range(4, 8)]
    L += ["$EndNodes", "$Elements"]
    blocks = []
    for s in range(1, 7):
        tris = [t for p, t in zip(PATCHES, TRIS) if p == s]
        blocks.append((2, s, 2, [[NODE_TAG[v] for v in t] for t in tris]))
    for vtag in (1, 2):
        tets = [t for r, t in zip(REGIONS, TETS) if r == vtag]
        blocks.append((3, vtag, 4, [[NODE_TAG[v] for v in t] for t in tets]))
    blocks.append((1, 1, 1, [[NODE_TAG[0], NODE_TAG[1]]]))  # a line element, skipped
    blocks.append((0, 1, 15, [[NODE_TAG[0]]]))  # a point element, skipped
    n = sum(len(b[3]) for b in blocks)
    L.append("%d %d 1 %d" % (len(blocks), n, n))
    tag = 1
    for dim, ent, typ, elems in blocks:
        L.append("%d %d %d %d" % (dim, ent, typ, len(elems)))
        for e in elems:
            L.append(" ".join(map(str, [tag] + e)))
            tag += 1
    L += ["$EndElements", "$NodeData", "1", "\"x\"", "1", "0.0", "3", "0", "1", "0", "$EndNodeData"]
    write("box41.msh", "\n".join(L) + "\n")


def gmsh41_binary():
    out = b"$MeshFormat\n4.1 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n"
    ent = struct.pack("<4Q", 1, 1, 6, 2)
    ent += struct.pack("<i3dQ", 1, 0, 0, -0.25, 0)
    ent += struct.pack("<i6dQQi", 1, 0, 0, -0.25, 1.5, 0, -0.25, 0, 1, 1)
    for s in range(1, 7):
        ph = SURF_PHYS[s]
        ent += struct.pack("<i6dQ", s, 0, 0, 0, 1, 1, 1, len(ph)) + b"".join(struct.pack("<i", p) for p in ph)
        ent += struct.pack("<Q", 0)
    for vtag in (1, 2):
        ph = VOL_PHYS[vtag]
        ent += struct.pack("<i6dQ", vtag, 0, 0, 0, 1, 1, 1, len(ph)) + b"".join(struct.pack("<i", p) for p in ph)
        ent += struct.pack("<Q6i", 6, 1, 2, 3, 4, 5, -6)
    out += b"$Entities\n" + ent + b"\n$EndEntities\n"
    nodes = struct.pack("<4Q", 2, 8, 10, 80)
    nodes += struct.pack("<3iQ", 2, 5, 1, 4) + struct.pack("<4Q", *NODE_TAG[:4])
    for i in range(4):
        nodes += struct.pack("<5d", *VERTS[i], 0.5, 0.25)
    nodes += struct.pack("<3iQ", 3, 1, 0, 4) + struct.pack("<4Q", *NODE_TAG[4:])
    for i in range(4, 8):
        nodes += struct.pack("<3d", *VERTS[i])
    out += b"$Nodes\n" + nodes + b"\n$EndNodes\n"
    blocks = []
    for s in range(1, 7):
        blocks.append((2, s, 2, [[NODE_TAG[v] for v in t] for p, t in zip(PATCHES, TRIS) if p == s]))
    for vtag in (1, 2):
        blocks.append((3, vtag, 4, [[NODE_TAG[v] for v in t] for r, t in zip(REGIONS, TETS) if r == vtag]))
    blocks.append((1, 1, 1, [[NODE_TAG[0], NODE_TAG[1]]]))
    n = sum(len(b[3]) for b in blocks)
    els = struct.pack("<4Q", len(blocks), n, 1, n)
    tag = 1
    for dim, e, typ, elems in blocks:
        els += struct.pack("<3iQ", dim, e, typ, len(elems))
        for el in elems:
            els += struct.pack("<%dQ" % (1 + len(el)), tag, *el)
            tag += 1
    out += b"$Elements\n" + els + b"\n$EndElements\n"
    write("box41_binary.msh", out, "wb")


def gmsh22():
    L = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", "8"]
    for i in range(8):
        L.append(str(NODE_TAG[i]) + " " + " ".join(fmt(c) for c in VERTS[i]))
    L += ["$EndNodes", "$Elements"]
    elems = []
    for p, t in zip(PATCHES, TRIS):
        phys = 101 if p == 1 else 0
        elems.append("2 2 %d %d %s" % (phys, p, " ".join(str(NODE_TAG[v]) for v in t)))
    for r, t in zip(REGIONS, TETS):
        phys = 10 if r == 1 else 0
        elems.append("4 3 %d %d 0 %s" % (phys, r, " ".join(str(NODE_TAG[v]) for v in t)))
    elems.append("15 2 0 1 %d" % NODE_TAG[0])
    L.append(str(len(elems)))
    L += ["%d %s" % (i + 1, e) for i, e in enumerate(elems)]
    L.append("$EndElements")
    write("box22.msh", "\n".join(L) + "\n")


def tetgen(base, first):
    L = ["# TetGen files, first index %d" % first, "8 3 0 1"]
    for i, v in enumerate(VERTS):
        L.append("%d %s 0" % (i + first, " ".join(fmt(c) for c in v)))
    write(base + ".node", "\n".join(L) + "\n")
    L = ["6 4 1"]
    for i, (r, t) in enumerate(zip(REGIONS, TETS)):
        L.append("%d %s %d" % (i + first, " ".join(str(v + first) for v in t), r))
    write(base + ".ele", "\n".join(L) + "\n")
    L = ["12 1"]
    for i, (p, t) in enumerate(zip(PATCHES, TRIS)):
        L.append("%d %s %d" % (i + first, " ".join(str(v + first) for v in t), p))
    write(base + ".face", "\n".join(L) + "\n")


def vtu():
    pts = " ".join(fmt(c) for v in VERTS for c in v)
    conn = " ".join(str(v) for t in TETS for v in t) + " " + " ".join(str(v) for t in TRIS for v in t)
    offs = " ".join(str(4 * (i + 1)) for i in range(6)) + " " + " ".join(str(24 + 3 * (i + 1)) for i in range(12))
    types = " ".join(["10"] * 6 + ["5"] * 12)
    region = " ".join(map(str, REGIONS + [-1] * 12))
    patch = " ".join(map(str, [-1] * 6 + PATCHES))
    text = f"""<?xml version="1.0"?>
<!-- written by make_test_files.py -->
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="8" NumberOfCells="18">
      <PointData>
        <DataArray type="Float64" Name="size" format="ascii">1 1 1 1 1 1 1 1</DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">{pts}</DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">{conn}</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">{offs}</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">{types}</DataArray>
      </Cells>
      <CellData>
        <DataArray type="Int32" Name="region" format="ascii">{region}</DataArray>
        <DataArray type="Int32" Name="patch" format="ascii">{patch}</DataArray>
      </CellData>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"""
    write("box.vtu", text)


off_quads()
off_inline()
obj_groups()
stl_ascii("box_ascii.stl", [TRIS], ["block0"])
# Names as CAD exporters write them: "x ends" is read as the patch name x_ends.
stl_ascii("box_two_solids.stl", [TRIS[:4], TRIS[4:]], ["x ends", "sides"])
stl_binary("box_binary_solid_header.stl", b"solid this binary header starts like ASCII")
ply_ascii()
ply_binary("box_binary_le.ply", False)
ply_binary("box_binary_be.ply", True)
medit()
gmsh41_ascii()
gmsh41_binary()
gmsh22()
tetgen("box_base1", 1)
tetgen("box_base0", 0)
vtu()
print("TETS", TETS)
print("TRIS", TRIS)
print("PATCHES", PATCHES)
