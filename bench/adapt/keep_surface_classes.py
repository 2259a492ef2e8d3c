#!/usr/bin/env python3
"""UGAWG linear with --keep-surface (issue 46): the misses of the measured edges (no end on the
surface, as ugawg.py measures with --keep-surface) by class, as markdown tables: short/long, the
edge's distance to the cube's faces (the smaller of its ends' and midpoint's), its distance to the
metric's fine plane z = 0.5 (where h_z = 0.001), its direction against z (the metric's strong
axis: z-ward or in-plane within 30 degrees, else oblique), and whether an end is a neighbour of a
kept surface point (one edge from the surface: the layer the kept coarse faces constrain).

usage: keep_surface_classes.py MESH   (TOOLS: the directory of ugawg.py, default /work/shared/tools)
"""
import collections, os, sys
import numpy as np
sys.path.insert(0, os.environ.get('TOOLS', '/work/shared/tools'))
import ugawg  # noqa: E402

if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
    sys.exit(__doc__)
fn = sys.argv[1]
P, T, tr, _ = ugawg.read_mesh(fn)
M = ugawg.metric(P, 'linear')
E = ugawg.edges_of(T)
on = np.zeros(len(P), bool); on[tr.ravel()] = True
# points one edge from the surface
near = np.zeros(len(P), bool)
se = on[E[:, 0]] | on[E[:, 1]]
near[E[se].ravel()] = True
near &= ~on
E = E[~on[E[:, 0]] & ~on[E[:, 1]]]
L = ugawg.edge_lengths(P, E, M)
mid = 0.5 * (P[E[:, 0]] + P[E[:, 1]])
def face_dist(X):
    return np.minimum(X, 1 - X).min(axis=1)
d = np.minimum(np.minimum(face_dist(P[E[:, 0]]), face_dist(P[E[:, 1]])), face_dist(mid))
dz = np.abs(mid[:, 2] - 0.5)
v = P[E[:, 1]] - P[E[:, 0]]; vl = np.linalg.norm(v, axis=1)
c = np.abs(v[:, 2]) / vl
direction = np.where(c >= np.cos(np.pi/6), 'z-ward', np.where(c <= np.sin(np.pi/6), 'in-plane', 'oblique'))
layer = np.where(near[E].any(axis=1), 'next to surface', 'deeper')
short = L < 2**-0.5; long_ = L > 2**0.5; out = short | long_
print(f'# {fn}: {len(E)} edges with no end on the surface, {100*(~out).mean():.2f}% in range, '
      f'{short.sum()} short, {long_.sum()} long')
bins = [0.01, 0.03, 0.1, np.inf]; bname = ['0-0.01', '0.01-0.03', '0.03-0.1', '>0.1']
zb = [0.01, 0.05, 0.2, np.inf]; zname = ['0-0.01', '0.01-0.05', '0.05-0.2', '>0.2']
db = np.searchsorted(bins, d); zbb = np.searchsorted(zb, dz)
for title, b, names in (('distance to the cube\'s faces', db, bname), ('|z - 0.5| (the fine plane)', zbb, zname)):
    print(f'\n## by {title}\n')
    print('| band | edges | in range | short | long | share of all misses |')
    print('|---|---|---|---|---|---|')
    for i, n in enumerate(names):
        s = b == i
        print(f'| {n} | {s.sum()} | {100*(~out[s]).mean() if s.any() else 0:.1f}% | {short[s].sum()} | '
              f'{long_[s].sum()} | {100*out[s].sum()/max(out.sum(),1):.1f}% |')
print('\n## misses by class, the largest first\n')
print('| short/long | face distance | \\|z-0.5\\| | direction | layer | count | share of misses | median metric length | median Euclidean length |')
print('|---|---|---|---|---|---|---|---|---|')
cls = collections.Counter(); idx = collections.defaultdict(list)
for k in np.nonzero(out)[0]:
    key = ('short' if short[k] else 'long', bname[db[k]], zname[zbb[k]], direction[k], layer[k])
    cls[key] += 1; idx[key].append(k)
for key, n in cls.most_common(15):
    ii = np.array(idx[key])
    print(f'| {" | ".join(key)} | {n} | {100*n/out.sum():.1f}% | {np.median(L[ii]):.3g} | {np.median(vl[ii]):.3g} |')
