#!/usr/bin/env python3
"""The sphere case's misses (issue 46) by class, as markdown tables: every edge out of
[1/sqrt2, sqrt2] by the UGAWG measure (the analytic metric at its ends, as ugawg.py measures)
classified by short/long, its distance d to the ball (the smaller |r - 0.5| of its ends and
midpoint), its direction against the radial at its midpoint (radial or tangential within 30
degrees, else oblique) and its ends' kinds (on the ball's surface or inner; box-: on the box);
and the tets of mean ratio below 0.1 by their closest point's d and their points on the surface.

usage: sphere_classes.py MESH   (TOOLS: the directory of ugawg.py, default /work/shared/tools)
"""
import collections, os, sys
import numpy as np
sys.path.insert(0, os.environ.get('TOOLS', '/work/shared/tools'))
import ugawg  # noqa: E402

if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
    sys.exit(__doc__)
fn = sys.argv[1]
P, T, tr, _ = ugawg.read_mesh(fn)
M = ugawg.metric(P, 'sphere')
E = ugawg.edges_of(T)
L = ugawg.edge_lengths(P, E, M)
q = ugawg.mean_ratio(P, T, M)
on = np.zeros(len(P), bool); on[tr.ravel()] = True
r = np.linalg.norm(P, axis=1)
# an edge's distance to the ball: the smaller |r-0.5| of its ends (and of its midpoint)
mid = 0.5 * (P[E[:, 0]] + P[E[:, 1]])
d = np.minimum(np.abs(r[E]-0.5).min(axis=1), np.abs(np.linalg.norm(mid, axis=1) - 0.5))
v = P[E[:, 1]] - P[E[:, 0]]; vl = np.linalg.norm(v, axis=1)
nrad = mid / np.linalg.norm(mid, axis=1)[:, None]
c = np.abs(np.einsum('ij,ij->i', v, nrad)) / vl
direction = np.where(c >= np.cos(np.pi/6), 'radial', np.where(c <= np.sin(np.pi/6), 'tangential', 'oblique'))
kinds = on[E].sum(axis=1)
kind = np.array(['inner-inner', 'surf-inner', 'surf-surf'])[kinds]
# the ball's surface vs the box's
ball_pt = on & (r < 0.75)
kind = np.where((kinds > 0) & ~(ball_pt[E].any(axis=1)), np.char.add('box-', kind), kind)
edges_d = [0.002, 0.01, 0.05, 0.2, np.inf]
dname = ['0-0.002', '0.002-0.01', '0.01-0.05', '0.05-0.2', '>0.2']
db = np.searchsorted(edges_d, d, side='left')
short = L < 2**-0.5; long_ = L > 2**0.5
out = short | long_
print(f'# {fn}: {len(P)} points, {len(T)} tets, {len(E)} edges, {100*(~out).mean():.2f}% in range, '
      f'{short.sum()} short, {long_.sum()} long; mean ratio min {q.min():.3g} mean {q.mean():.3f}')
print('\n## out-of-range edges by distance to the ball (d = min |r-0.5| of ends and midpoint)\n')
print('| d | edges | in range | short | long | share of all misses |')
print('|---|---|---|---|---|---|')
for i, n in enumerate(dname):
    s = db == i
    print(f'| {n} | {s.sum()} | {100*(~out[s]).mean() if s.any() else 0:.1f}% | {short[s].sum()} | {long_[s].sum()} | {100*(out[s]).sum()/max(out.sum(),1):.1f}% |')
print('\n## misses by class (short/long, d, direction, ends), the largest first\n')
print('| short/long | d | direction | ends | count | share of misses | median metric length | median Euclidean length |')
print('|---|---|---|---|---|---|---|---|')
cls = collections.Counter()
idx = collections.defaultdict(list)
for k in np.nonzero(out)[0]:
    key = ('short' if short[k] else 'long', dname[db[k]], direction[k], kind[k])
    cls[key] += 1; idx[key].append(k)
for key, n in cls.most_common(25):
    ii = np.array(idx[key])
    print(f'| {" | ".join(key)} | {n} | {100*n/out.sum():.1f}% | {np.median(L[ii]):.3g} | {np.median(vl[ii]):.3g} |')
# tets of mean ratio < 0.1
bad = np.nonzero(q < 0.1)[0]
print(f'\n## tets of mean ratio < 0.1: {len(bad)} (< 0.01: {(q < 0.01).sum()})\n')
if len(bad):
    rt = np.abs(r[T[bad]] - 0.5).min(axis=1)
    tb = np.searchsorted(edges_d, rt, side='left')
    nsurf = on[T[bad]].sum(axis=1)
    c2 = collections.Counter((dname[tb[i]], int(nsurf[i])) for i in range(len(bad)))
    print('| d (closest vertex) | surface vertices | count |')
    print('|---|---|---|')
    for key, n in sorted(c2.items()):
        print(f'| {key[0]} | {key[1]} | {n} |')
