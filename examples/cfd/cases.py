#!/usr/bin/python3
"""cases.py CASE OUT [options]: domain surfaces of CFD cases whose walls meet other patches, for
`anitet mesh` with boundary layers (docs/boundary-layers.md, "Walls that meet other patches").

  pipe OUT.mesh [--radius 1] [--length 10] [--segments 48]
      A pipe along z: `wall` (label 1) the cylinder's side, `inlet` (2) the cap at z = 0, `outlet`
      (3) the cap at z = length. Built here (numpy): structured side, caps in rings.
  hemisphere OUT.msh [--size 0.06]
      The TMR hemisphere-cylinder half-model: a hemisphere of radius 0.5 (nose at x = 0) on a
      cylinder of radius 0.5 to x = 10.5, closed by a flat base, cut by y = 0, in the half box
      [-20, 30] x [0, 20] x [-20, 20]: `wall` (1) the body, `symmetry` (2) the box's y = 0 face,
      `farfield` (3) its other faces. Meshed by Gmsh's command line (`gmsh`, Debian: gmsh).
  wing OUT.msh [--size 0.03] [--floor-size 1.2]
      An extruded NACA 0012 (chord 1 along x from 0, span 3 along z, blunt trailing edge of
      0.252% chord: the 4-digit formula's own) standing on the floor of the channel
      [-5, 10] x [-5, 5] x [0, 6]: `wing` (1) and `floor` (2) walls, `inlet` (3, x = -5),
      `outlet` (4, x = 10), `sides` (5, y = +-5), `top` (6, z = 6). Gmsh too. The sizes grow
      from the wing's to 1.2 away from it, and from at most --floor-size on the floor, by 0.3 per
      unit of height (checkMesh's aspect ratio of the floor's first layer is about that size
      over h0).

The triangles face out of the fluid (anitet's rule; anitet also reorients Gmsh's when needed).
Medit files name their patches in "# patch LABEL NAME" lines, Gmsh files in $PhysicalNames:
anitet reads both. Prints the triangle count per patch."""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np


def write_medit(path, xyz, tris, labels, names):
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\n")
        for label in sorted(names):
            f.write(f"# patch {label} {names[label]}\n")
        f.write(f"Vertices\n{len(xyz)}\n")
        for p in xyz:
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r} 0\n")
        f.write(f"Triangles\n{len(tris)}\n")
        for t, label in zip(tris, labels):
            f.write(f"{t[0] + 1} {t[1] + 1} {t[2] + 1} {label}\n")
        f.write("End\n")


def disc(rim, center, radius, normal_up):
    """A disc's triangles inside the rim (ids of points on a circle, counter-clockwise about +z)
    as rings of points; returns (new points, triangles over rim ids + new ids offset by the
    caller). Counter-clockwise seen from +z when normal_up, else reversed."""
    n = len(rim)
    rings = max(1, round(radius / (2 * math.pi * radius / n)))
    points, tris = [], []
    outer = list(rim)
    outer_angle = [2 * math.pi * i / n for i in range(n)]
    for k in range(1, rings + 1):
        r = radius * (rings - k) / rings
        if k == rings:
            c = ("new", len(points))
            points.append((center[0], center[1], center[2]))
            for i in range(len(outer)):
                tris.append((outer[i], outer[(i + 1) % len(outer)], c))
            break
        m = max(6, round(n * r / radius))
        shift = math.pi / m
        inner = []
        inner_angle = [2 * math.pi * j / m + shift for j in range(m)]
        for a in inner_angle:
            inner.append(("new", len(points)))
            points.append((center[0] + r * math.cos(a), center[1] + r * math.sin(a), center[2]))
        # Zip the rings by angle, from the edge (outer[0], inner[0]) round to it again.
        i = j = 0
        while i < len(outer) or j < m:
            next_outer = outer_angle[(i + 1) % len(outer)] + (2 * math.pi if i + 1 >= len(outer) else 0)
            next_inner = inner_angle[(j + 1) % m] + (2 * math.pi if j + 1 >= m else 0)
            if i < len(outer) and (j >= m or next_outer <= next_inner):
                tris.append((outer[i % len(outer)], outer[(i + 1) % len(outer)], inner[j % m]))
                i += 1
            else:
                tris.append((outer[i % len(outer)], inner[(j + 1) % m], inner[j % m]))
                j += 1
        outer, outer_angle = inner, inner_angle
    if not normal_up:
        tris = [(a, c, b) for a, b, c in tris]
    return points, tris


def pipe(args):
    n, radius, length = args.segments, args.radius, args.length
    edge = 2 * math.pi * radius / n
    nz = max(1, round(length / edge))
    xyz = []
    for j in range(nz + 1):
        for i in range(n):
            a = 2 * math.pi * i / n
            xyz.append((radius * math.cos(a), radius * math.sin(a), length * j / nz))
    ring = lambda j: [j * n + i for i in range(n)]
    tris, labels = [], []
    for j in range(nz):
        for i in range(n):
            a, b = j * n + i, j * n + (i + 1) % n
            c, d = a + n, b + n
            # Outward (radial) normals: (a, b, d) and (a, d, c).
            tris += [(a, b, d), (a, d, c)]
            labels += [1, 1]
    for label, j, z, up in ((2, 0, 0.0, False), (3, nz, length, True)):
        points, cap = disc(ring(j), (0.0, 0.0, z), radius, up)
        base = len(xyz)
        xyz += points
        fix = lambda v: base + v[1] if isinstance(v, tuple) else v
        for t in cap:
            tris.append(tuple(fix(v) for v in t))
            labels.append(label)
    names = {1: "wall", 2: "inlet", 3: "outlet"}
    write_medit(args.out, xyz, tris, labels, names)
    return labels, names


HEMISPHERE_GEO = """
SetFactory("OpenCASCADE");
Sphere(1) = {{0.5, 0, 0, 0.5}};
Cylinder(2) = {{0.5, 0, 0, 10, 0, 0, 0.5}};
BooleanUnion(3) = {{ Volume{{1}}; Delete; }}{{ Volume{{2}}; Delete; }};
Box(4) = {{-20, 0, -20, 50, 20, 40}};
BooleanDifference(5) = {{ Volume{{4}}; Delete; }}{{ Volume{{3}}; Delete; }};
eps = 1e-6;
body() = Surface In BoundingBox{{-eps, -eps, -0.5 - eps, 10.5 + eps, 0.5 + eps, 0.5 + eps}};
sym() = Surface In BoundingBox{{-20 - eps, -eps, -20 - eps, 30 + eps, eps, 20 + eps}};
all() = Surface{{:}};
far() = all();
far() -= body();
far() -= sym();
Physical Surface("wall", 1) = {{body()}};
Physical Surface("symmetry", 2) = {{sym()}};
Physical Surface("farfield", 3) = {{far()}};
Field[1] = Distance;
Field[1].SurfacesList = {{body()}};
Field[1].NNodesByEdge = 60;
Field[2] = MathEval;
Field[2].F = Sprintf("Min({size} + 0.25 * F1, 4)");
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 24;
Mesh.MeshSizeMax = 4;
Mesh.MeshSizeMin = {size} / 3;
Mesh.Algorithm = 6;
"""

WING_GEO = """
SetFactory("OpenCASCADE");
n = 60;
For i In {{0 : n}}
  x = 0.5 * (1 - Cos(Pi * i / n));
  t = 0.6 * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1015 * x^4);
  up[i] = newp; Point(up[i]) = {{x, t, 0}};
EndFor
For i In {{1 : n}}
  x = 0.5 * (1 - Cos(Pi * i / n));
  t = 0.6 * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1015 * x^4);
  lo[i] = newp; Point(lo[i]) = {{x, -t, 0}};
EndFor
upper = newl; Spline(upper) = {{up[{{n : 0 : -1}}]}};
lower = newl; Spline(lower) = {{up[0], lo[{{1 : n}}]}};
te = newl; Line(te) = {{lo[n], up[n]}};
Curve Loop(1) = {{upper, lower, te}};
Plane Surface(1) = {{1}};
wing[] = Extrude {{0, 0, 3}} {{ Surface{{1}}; }};
Box(10) = {{-5, -5, 0, 15, 10, 6}};
BooleanDifference(11) = {{ Volume{{10}}; Delete; }}{{ Volume{{wing[1]}}; Delete; }};
eps = 1e-6;
floor() = Surface In BoundingBox{{-5 - eps, -5 - eps, -eps, 10 + eps, 5 + eps, eps}};
inlet() = Surface In BoundingBox{{-5 - eps, -5 - eps, -eps, -5 + eps, 5 + eps, 6 + eps}};
outlet() = Surface In BoundingBox{{10 - eps, -5 - eps, -eps, 10 + eps, 5 + eps, 6 + eps}};
s1() = Surface In BoundingBox{{-5 - eps, -5 - eps, -eps, 10 + eps, -5 + eps, 6 + eps}};
s2() = Surface In BoundingBox{{-5 - eps, 5 - eps, -eps, 10 + eps, 5 + eps, 6 + eps}};
top() = Surface In BoundingBox{{-5 - eps, -5 - eps, 6 - eps, 10 + eps, 5 + eps, 6 + eps}};
wing() = Surface In BoundingBox{{-1e-3, -0.07, -1e-3, 1 + 1e-3, 0.07, 3 + 1e-3}};
wing() -= floor();
Physical Surface("wing", 1) = {{wing()}};
Physical Surface("floor", 2) = {{floor()}};
Physical Surface("inlet", 3) = {{inlet()}};
Physical Surface("outlet", 4) = {{outlet()}};
Physical Surface("sides", 5) = {{s1(), s2()}};
Physical Surface("top", 6) = {{top()}};
Field[1] = Distance;
Field[1].SurfacesList = {{wing()}};
Field[1].NNodesByEdge = 80;
Field[2] = MathEval;
Field[2].F = Sprintf("Min(Min({size} + 0.3 * F1, 1.2), {floor_size} + 0.3 * z)");
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 40;
Mesh.MeshSizeMax = 1.2;
Mesh.MeshSizeMin = {size} / 4;
Mesh.Algorithm = 6;
"""


def gmsh_case(args, geo, names):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "case.geo")
        with open(path, "w") as f:
            f.write(geo.format(size=args.size, floor_size=args.floor_size))
        run = subprocess.run(["gmsh", path, "-2", "-format", "msh41", "-o", os.path.abspath(args.out)],
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit("gmsh failed:\n" + run.stdout[-2000:] + run.stderr[-2000:])
    # The triangle count per physical surface, from the file.
    labels = []
    with open(args.out) as f:
        lines = f.read().split("\n")
    entity_tag = {}
    i = lines.index("$Entities") + 1
    npts, ncur, nsurf, _ = map(int, lines[i].split())
    for k in range(nsurf):
        parts = lines[i + 1 + npts + ncur + k].split()
        tag, nphys = int(parts[0]), int(parts[7])
        entity_tag[tag] = int(parts[8]) if nphys else 0
    i = lines.index("$Elements") + 1
    nblocks = int(lines[i].split()[0])
    i += 1
    for _ in range(nblocks):
        dim, tag, etype, count = map(int, lines[i].split())
        if dim == 2 and etype == 2:
            labels += [entity_tag[tag]] * count
        i += 1 + count
    return labels, names


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", choices=["pipe", "hemisphere", "wing"])
    p.add_argument("out")
    p.add_argument("--radius", type=float, default=1.0)
    p.add_argument("--length", type=float, default=10.0)
    p.add_argument("--segments", type=int, default=48)
    p.add_argument("--size", type=float, default=None, help="Gmsh cases: the size at the body")
    p.add_argument("--floor-size", type=float, default=1.2,
                   help="wing: the largest size on the floor (a wall too; its layers' aspect ratio is this over h0)")
    args = p.parse_args()
    if args.case == "pipe":
        labels, names = pipe(args)
    elif args.case == "hemisphere":
        args.size = args.size or 0.06
        labels, names = gmsh_case(args, HEMISPHERE_GEO, {1: "wall", 2: "symmetry", 3: "farfield"})
    else:
        args.size = args.size or 0.03
        labels, names = gmsh_case(args, WING_GEO, {1: "wing", 2: "floor", 3: "inlet", 4: "outlet", 5: "sides", 6: "top"})
    counts = {names[k]: labels.count(k) for k in sorted(names)}
    print(f"{args.out}: " + ", ".join(f"{name} {n}" for name, n in counts.items()) + " triangles")


if __name__ == "__main__":
    main()
