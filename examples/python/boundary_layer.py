#!/usr/bin/env python3
"""anitet from Python: a boundary layer. The example sphere (patches 1-3) inside the box
[-3, 3]^3 (patch 4), meshed with a boundary layer on the sphere; the patches named; the run's
boundary-layer report read from Mesh.run_stats and printed. Prints the same text and writes the
same file as examples/c/boundary_layer.c and examples/fortran/boundary_layer.f90.

    boundary_layer.py [OUTPUT_PREFIX]   writes OUTPUT_PREFIX.su2 (markers named) when given

Needs the package of bindings/python on PYTHONPATH (or pip-installed) and libanitet where the
loader finds it (or ANITET_LIBRARY=/path/to/libanitet.so).
"""
import sys

import anitet
from mesh_sphere import sphere  # the examples' sphere, beside this file

BOX_TRIANGLES = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
                 (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
NAMES = {1: "sphere_south", 2: "sphere_band", 3: "sphere_north", 4: "farfield"}


def sphere_in_box():
    """The sphere, then the box's 8 corners (corner i at -3 or 3 by the bits of i: x, y, z) and
    12 triangles (patch 4), 0-based, counter-clockwise seen from outside. The sphere is a cavity
    of the box: the validation's repairs (on by default) turn it inward."""
    points, triangles, patches = sphere()
    n = len(points)
    points += [tuple(3.0 if i & bit else -3.0 for bit in (1, 2, 4)) for i in range(8)]
    triangles += [tuple(n + v for v in t) for t in BOX_TRIANGLES]
    patches += [4] * len(BOX_TRIANGLES)
    return points, triangles, patches


def print_report(s):
    print("boundary layer: %d layers, %d wall vertices, %d full columns, %d nominal columns,"
          " %d reduced vertices, %d tets" % (s.bl_layers, s.bl_wall_vertices, s.bl_full_columns,
                                             s.bl_nominal_columns, s.bl_reduced_vertices, s.bl_tets))
    print("first height: min %.6f, mean %.6f, max %.6f"
          % (s.bl_first_height_min, s.bl_first_height_mean, s.bl_first_height_max))
    print("growth: mean %.6f; max height error %.6f" % (s.bl_growth_mean, s.bl_max_height_error))


def main(argv):
    points, triangles, patches = sphere_in_box()
    surface = anitet.Surface.from_arrays(points, triangles, patches)
    mesh = anitet.mesh_surface(surface, bl_patches=[1, 2, 3], bl_first_height=0.02, bl_growth=1.25,
                               bl_layers=5, hgrad=1.3)
    n, nt, nb = mesh.counts()
    quality = mesh.quality(surface)
    print("surface: %d points, %d triangles" % (len(points), len(triangles)))
    print("mesh: %d vertices, %d tets, %d boundary triangles" % (n, nt, nb))
    print("quality: valid %d, boundary constrained %d"
          % (quality.valid, quality.boundary_constrained))
    print_report(mesh.run_stats)
    for label, name in NAMES.items():
        mesh.patch_names[label] = name
        print("patch %d: %s" % (label, name))
    if len(argv) > 1:
        mesh.write(argv[1] + ".su2")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
