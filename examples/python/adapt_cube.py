#!/usr/bin/env python3
"""anitet from Python: a solver's adaptation loop. The UGAWG linear cube is adapted three times to
the analytic metric of the UGAWG benchmark, evaluated at the vertices of each new mesh, with a
field carried from mesh to mesh, and the measures printed. Prints the same text and writes the
same files as examples/c/adapt_cube.c and examples/fortran/adapt_cube.f90.

    adapt_cube.py CUBE_MESH [OUTPUT_PREFIX]   CUBE_MESH: ../shared/data/ugawg/cube-linear-00.mesh;
                                              writes OUTPUT_PREFIX.meshb and OUTPUT_PREFIX.solb

Needs the package of bindings/python on PYTHONPATH (or pip-installed) and libanitet where the
loader finds it (or ANITET_LIBRARY=/path/to/libanitet.so). NumPy arrays when NumPy is there.
"""
import sys

import anitet

try:
    import numpy as np
except ImportError:
    np = None


def linear_metric(points):
    """UGAWG's linear metric at the points: h_x = h_y = 0.1, h_z = 0.001 + 2 (0.1 - 0.001) |z - 0.5|,
    as (n, 6) tensors xx xy yy xz yz zz."""
    if np is not None:
        hz = 0.001 + 2.0 * (0.1 - 0.001) * np.abs(points[:, 2] - 0.5)
        m = np.zeros((len(points), 6))
        m[:, 0] = m[:, 2] = 100.0
        m[:, 5] = 1.0 / (hz * hz)
        return m
    return [(100.0, 0.0, 100.0, 0.0, 0.0, 1.0 / (hz * hz))
            for hz in (0.001 + 2.0 * (0.1 - 0.001) * abs(p[2] - 0.5) for p in points)]


def main(argv):
    if len(argv) < 2:
        sys.exit("usage: adapt_cube.py CUBE_MESH [OUTPUT_PREFIX]")
    mesh = anitet.Mesh.read(argv[1])
    # A solver's solution on the first mesh (1 + 2x - y + 3z), carried to every new mesh.
    solution = anitet.Fields.from_arrays(["scalar"], [1.0 + 2.0 * x - y + 3.0 * z for x, y, z in mesh.points()])
    for adapt_pass in (1, 2, 3):
        # The sweeps are serial: one thread for the transfer and the measures too.
        mesh, solution, s = mesh.adapt(linear_metric(mesh.points()), fields=solution, num_threads=1)
        print("pass %d: %d splits, %d collapses, %d swaps, %d moves in %d cycles"
              % (adapt_pass, s.splits, s.collapses, s.swaps, s.moves, s.cycles))
        print("mesh: %d vertices, %d tets, %d boundary triangles" % (s.vertices, s.tets, s.boundary_triangles))
        print("edges in range: %.2f%%, mean ratio min %.3f mean %.3f"
              % (100.0 * s.edges_in_range, s.mean_ratio_min, s.mean_ratio_mean))
    if len(argv) > 2:
        mesh.write(argv[2] + ".meshb")
        solution.write(argv[2] + ".solb")


if __name__ == "__main__":
    main(sys.argv)
