#!/usr/bin/env python3
"""anitet from Python: build a surface in memory, mesh it to an analytic metric (a Python
function), print the quality report. Prints the same text and writes the same files as
examples/c/mesh_sphere.c and examples/fortran/mesh_sphere.f90.

    mesh_sphere.py [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.mesh and OUTPUT_PREFIX.sol when given

Needs the package of bindings/python on PYTHONPATH (or pip-installed) and libanitet where the
loader finds it (or ANITET_LIBRARY=/path/to/libanitet.so).
"""
import math
import sys

import anitet

NLAT, NLON = 8, 16
NPOINTS, NTRI = 2 + (NLAT - 1) * NLON, 2 * NLON * (NLAT - 1)


def ring_point(k, j):
    return 1 + (k - 1) * NLON + j % NLON


def sphere():
    """The sphere of examples/c/sphere_surface.h, with the same operations in the same order
    (sqrt and divisions only), so the points are the same doubles; 0-based."""
    q = NLON // 4
    points = [(0.0, 0.0, -1.0)]
    for k in range(1, NLAT):
        zd = float(2 * k - NLAT) / float(NLAT)
        rd = 1.0 - abs(zd)
        h = math.sqrt(rd * rd + zd * zd)
        r, z = rd / h, zd / h
        for j in range(NLON):
            u = float(j % q) / float(q)
            side = j // q
            if side == 0:
                xd, yd = 1.0 - u, u
            elif side == 1:
                xd, yd = -u, 1.0 - u
            elif side == 2:
                xd, yd = -(1.0 - u), -u
            else:
                xd, yd = u, -(1.0 - u)
            g = math.sqrt(xd * xd + yd * yd)
            points.append((r * (xd / g), r * (yd / g), z))
    points.append((0.0, 0.0, 1.0))
    triangles, patches = [], []
    for j in range(NLON):
        triangles.append((0, ring_point(1, j + 1), ring_point(1, j)))
        patches.append(1)
    for k in range(1, NLAT - 1):
        for j in range(NLON):
            a, b = ring_point(k, j), ring_point(k, j + 1)
            c, d = ring_point(k + 1, j + 1), ring_point(k + 1, j)
            triangles += [(a, b, c), (a, c, d)]
            patches += [2, 2]
    for j in range(NLON):
        triangles.append((ring_point(NLAT - 1, j), ring_point(NLAT - 1, j + 1), NPOINTS - 1))
        patches.append(3)
    return points, triangles, patches


def stretched_metric(x, y, z, hx=0.25):
    """The sizing a solver would supply: edges of hx along x and of hx + 0.2 |z| across it.
    Not defined outside the box [-2, 2]^3 (an exception there fails the evaluation)."""
    if abs(x) > 2.0 or abs(y) > 2.0 or abs(z) > 2.0:
        raise ValueError("outside the metric's box")
    h = hx + 0.2 * abs(z)
    return (1.0 / (hx * hx), 0.0, 1.0 / (h * h), 0.0, 0.0, 1.0 / (h * h))


def main(argv):
    points, triangles, patches = sphere()
    surface = anitet.Surface.from_arrays(points, triangles, patches)
    metric = anitet.Metric.analytic(stretched_metric)
    mesh = anitet.mesh_surface(surface, metric, layers=2)
    np_, nt, nb = mesh.counts()
    print("surface: %d points, %d triangles" % (NPOINTS, NTRI))
    print("mesh: %d vertices, %d tets, %d boundary triangles, metric of %d components"
          % (np_, nt, nb, mesh.metric_components))
    print("quality: %s" % mesh.quality_json(surface))
    if len(argv) > 1:
        mesh.write(argv[1] + ".mesh")
        mesh.write_metric(argv[1] + ".sol")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
