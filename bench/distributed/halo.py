#!/usr/bin/env python3
"""Halo sizes of graph partitions, for the design model (bench/distributed/model.py): a mesh cut
by anitet_mesh_partition (METIS, one ghost layer: every tet of another part sharing a vertex) into
each count of parts; per part the own tets, the interface facets (2 x edge cut / parts), the
ghost tets per interface facet, and the interface facets over (own tets)^(2/3).

    bench/distributed/halo.py MESH [PARTS ...]    (default parts: 2 8 64)

Needs anitet's Python binding (PYTHONPATH / LD_LIBRARY_PATH of an installed build) and NumPy.
"""
import sys

import anitet
import numpy as np


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    mesh = anitet.Mesh.read(argv[1])
    counts = [int(a) for a in argv[2:]] or [2, 8, 64]
    print("%s: %d tets" % (argv[1], mesh.num_tets))
    print("%6s %10s %12s %14s %14s %16s %10s" % ("parts", "tets/part", "facets/part", "ghost/own mean",
                                                  "ghost/own max", "ghost per facet", "F/n^(2/3)"))
    for k in counts:
        partition = mesh.partition(k, ghost_layers=1, num_threads=1)
        info = partition.info()
        own = np.zeros(k)
        ghost = np.zeros(k)
        for i in range(k):
            _, _, nt, ot, _, _ = partition[i].counts()
            own[i], ghost[i] = ot, nt - ot
        facets = 2.0 * info.edge_cut / k
        print("%6d %10.0f %12.0f %14.3f %14.3f %16.2f %10.2f" % (
            k, own.mean(), facets, (ghost / own).mean(), (ghost / own).max(), ghost.sum() / (2.0 * info.edge_cut),
            facets / own.mean() ** (2.0 / 3.0)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
