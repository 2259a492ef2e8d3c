#!/usr/bin/env python3
"""A structured background mesh of the unit cube (11 x 11 nodes in x, y; z nodes one metric length
apart under the UGAWG linear field, 47 of them) with that field written at its vertices:
OUT.mesh and OUT.sol, for `anitet mesh cube-linear-00.mesh --metric OUT.sol --background OUT.mesh`
(the analytic field, where cube-linear-00.sol on its own 64 vertices interpolates h_z coarsely).
usage: ugawg_background.py OUT  (reads ../shared/tools/ugawg.py beside the repository)"""
import os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'shared', 'tools'))
import ugawg  # noqa: E402
h0, b = 0.001, 2 * (0.1 - 0.001)
half = np.log((h0 + 0.5 * b) / h0) / b
n = int(round(half))
u = [h0 * (np.exp(b * half * k / n) - 1) / b for k in range(n + 1)]; u[-1] = 0.5
z = sorted(set([0.5 - x for x in u] + [0.5 + x for x in u]))
xs = np.linspace(0, 1, 11)
P = np.array([(x, y, zz) for zz in z for y in xs for x in xs])
nx = len(xs); nz = len(z)
idx = lambda i, j, k: k * nx * nx + j * nx + i
T = []
for k in range(nz - 1):
    for j in range(nx - 1):
        for i in range(nx - 1):
            c = [idx(i + a, j + bb, k + cc) for cc in (0, 1) for bb in (0, 1) for a in (0, 1)]
            # Kuhn split of the cube into 6 tets along the 0-7 diagonal
            for t in ((0, 1, 3, 7), (0, 3, 2, 7), (0, 2, 6, 7), (0, 6, 4, 7), (0, 4, 5, 7), (0, 5, 1, 7)):
                T.append([c[q] for q in t])
T = np.array(T)
a, bq, cq, d = (P[T[:, q]] for q in range(4))
vol = np.einsum('ij,ij->i', bq - a, np.cross(cq - a, d - a))
T[vol < 0] = T[vol < 0][:, [1, 0, 2, 3]]
with open(sys.argv[1] + '.mesh', 'w') as f:
    f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(P))
    for p in P: f.write('%.17g %.17g %.17g 0\n' % tuple(p))
    f.write('Tetrahedra\n%d\n' % len(T))
    for t in T: f.write('%d %d %d %d 1\n' % tuple(t + 1))
    f.write('End\n')
ugawg.write_sol(sys.argv[1] + '.sol', ugawg.metric(P, 'linear'))
print(len(P), 'vertices', len(T), 'tets', nz, 'z nodes')
