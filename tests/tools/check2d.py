#!/usr/bin/python3
"""Independent checker of 2D triangle meshes against their input (written apart from the mesher).

usage: check2d.py MESH.mesh INPUT [options]
  MESH   a Medit 2D .mesh (Vertices, Edges, Triangles)
  INPUT  the mesher's input: Triangle .poly, Medit 2D .mesh (Edges) or GeoJSON (lon/lat polygons)

Checks (each failure is listed; exit status 1 when any check fails or a threshold is missed):
  valid        every triangle counter-clockwise (exact orientation for the near-flat ones), every
               edge in at most two triangles with opposite orientations
  boundary     every edge of one triangle lies on an input segment (the mesh has no other border)
  segments     every input segment is a mesh edge (default) or, with --split, a chain of mesh
               edges through points on it
  no_added     no mesh point lies on an input segment but the input's own (not with --split)
  domain       every triangle's centroid inside the domain (not in a hole, not outside), the hole
               points in no triangle, and the triangles' total area equal to the domain's
Figures: min angle over all triangles and over those with no input point, mean and min radius
ratio 2r/R (1 for equilateral), and with --metric or --geodesic the share of edges of length in
[1/sqrt2, sqrt2] (UGAWG's edge length rule: the logarithmic mean of the lengths in the metrics at
the two ends, as /work/shared/tools/ugawg.py's edge_lengths).
Options:
  --split              points on segments are allowed (the mesher's --split-segments)
  --min-angle A        require the min angle over triangles with no input point >= A degrees
  --min-angle-all A    require the min angle over all triangles >= A degrees
  --mean-rr R          require the mean radius ratio >= R
  --metric polar:R0    the anisotropic test metric about (0.5, 0.5): h_r = 0.001 + 2 (0.1 - 0.001)
                       |r - R0| radially, 0.1 tangentially
  --metric const:A,B,C the constant metric [[A, B], [B, C]]
  --geodesic H         the mesh is in lon/lat: edge lengths as WGS84 geodesics over H metres
  --in-range P         require that share (percent) >= P
  --json               print the figures as one JSON line
"""
import json, math, sys
from fractions import Fraction
import numpy as np


def tokens_of(path):
    with open(path) as f:
        return ' '.join(line.split('#')[0] for line in f).split()


def read_medit2d(path):
    t = tokens_of(path)
    out = {'Vertices': np.zeros((0, 2)), 'Edges': np.zeros((0, 3), int), 'Triangles': np.zeros((0, 4), int)}
    i, dim = 0, 2
    while i < len(t):
        k = t[i]
        if k in ('MeshVersionFormatted',):
            i += 2
        elif k == 'Dimension':
            dim = int(t[i + 1]); i += 2
        elif k == 'Vertices':
            n = int(t[i + 1]); w = dim + 1
            a = np.array(t[i + 2:i + 2 + n * w], dtype=float).reshape(n, w)
            out['Vertices'] = a[:, :2]; i += 2 + n * w
        elif k in ('Edges', 'Triangles'):
            w = 3 if k == 'Edges' else 4
            n = int(t[i + 1])
            out[k] = np.array(t[i + 2:i + 2 + n * w], dtype=np.int64).reshape(n, w); i += 2 + n * w
        elif k == 'End':
            break
        else:
            raise ValueError('unknown keyword ' + k)
    return out['Vertices'], out['Edges'][:, :2] - 1, out['Triangles'][:, :3] - 1


def read_poly(path):
    t = tokens_of(path)
    n, dim, na, nm = (int(x) for x in t[0:4]); i = 4
    if n == 0:
        nt = tokens_of(path[:-5] + '.node'); n, dim, na, nm = (int(x) for x in nt[0:4])
        pts, base = [], None; j = 4
        for _ in range(n):
            base = int(nt[j]) if base is None else base
            pts.append((float(nt[j + 1]), float(nt[j + 2]))); j += 3 + na + nm
    else:
        pts, base = [], None
        for _ in range(n):
            base = int(t[i]) if base is None else base
            pts.append((float(t[i + 1]), float(t[i + 2]))); i += 3 + na + nm
    ns, sm = int(t[i]), int(t[i + 1]); i += 2
    segs = []
    for _ in range(ns):
        segs.append((int(t[i + 1]) - base, int(t[i + 2]) - base)); i += 3 + sm
    nh = int(t[i]); i += 1
    holes = []
    for _ in range(nh):
        holes.append((float(t[i + 1]), float(t[i + 2]))); i += 3
    return np.array(pts), np.array(segs, dtype=np.int64), np.array(holes).reshape(-1, 2)


def read_geojson(path):
    """Points, segments and polygons (lists of rings of point indices) of a GeoJSON's polygons."""
    doc = json.load(open(path))
    feats = doc['features'] if doc.get('type') == 'FeatureCollection' else [doc]
    index, pts, segs, polys = {}, [], set(), []
    def pid(p):
        key = (float(p[0]), float(p[1]))
        if key not in index:
            index[key] = len(pts); pts.append(key)
        return index[key]
    def geoms(g):
        if g is None: return
        if g['type'] == 'Polygon': yield g['coordinates']
        elif g['type'] == 'MultiPolygon': yield from g['coordinates']
        elif g['type'] == 'GeometryCollection':
            for h in g['geometries']: yield from geoms(h)
    for f in feats:
        g = f.get('geometry', f) if f.get('type') == 'Feature' else f
        for poly in geoms(g):
            rings = []
            for ring in poly:
                r = [pid(p) for p in ring]
                r = [v for k, v in enumerate(r) if k == 0 or v != r[k - 1]]
                if r[0] == r[-1]: r.pop()
                rings.append(r)
                for k in range(len(r)):
                    a, b = r[k], r[(k + 1) % len(r)]
                    segs.add((min(a, b), max(a, b)))
            polys.append(rings)
    return np.array(pts), np.array(sorted(segs), dtype=np.int64), polys


def loops_of(n, segs):
    """Closed loops of the segment graph (every point of even degree), as point lists."""
    adj = {}
    for k, (a, b) in enumerate(segs):
        adj.setdefault(int(a), []).append((int(b), k)); adj.setdefault(int(b), []).append((int(a), k))
    used, loops = set(), []
    for k, (a, b) in enumerate(segs):
        if k in used: continue
        loop, cur, prev_seg = [int(a)], int(b), k
        used.add(k)
        while cur != loop[0]:
            loop.append(cur)
            nxt = [(w, s) for (w, s) in adj[cur] if s not in used]
            if not nxt: raise ValueError('open loop at point %d' % cur)
            w, s = nxt[0]; used.add(s); cur = w
        loops.append(loop)
    return loops


def inside_rings(P, rings, q):
    """Even-odd: number of rings (point lists over P) around each query point, per ring (bool array)."""
    res = []
    x, y = q[:, 0], q[:, 1]
    for r in rings:
        a = P[r]; b = P[np.roll(np.array(r), -1)]
        ins = np.zeros(len(q), bool)
        for (ax, ay), (bx, by) in zip(a, b):
            cond = (ay > y) != (by > y)
            with np.errstate(divide='ignore', invalid='ignore'):
                xc = ax + (y - ay) * (bx - ax) / (by - ay)
            ins ^= cond & (x < xc)
        res.append(ins)
    return np.array(res).reshape(len(rings), len(q))


def orient_exact(a, b, c):
    ax, ay, bx, by, cx, cy = (Fraction(float(v)) for v in (a[0], a[1], b[0], b[1], c[0], c[1]))
    d = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return (d > 0) - (d < 0)


def polar_metric(P, r0):
    d = P - 0.5; r = np.hypot(d[:, 0], d[:, 1]); n = d / np.maximum(r, 1e-300)[:, None]
    hr = 0.001 + 2 * (0.1 - 0.001) * np.abs(r - r0)
    nn = np.einsum('ij,ik->ijk', n, n)
    return nn * (hr ** -2)[:, None, None] + (np.eye(2)[None] - nn) * 0.1 ** -2


def ugawg_lengths(P, E, M):
    v = P[E[:, 1]] - P[E[:, 0]]
    la = np.sqrt(np.einsum('ij,ijk,ik->i', v, M[E[:, 0]], v)); lb = np.sqrt(np.einsum('ij,ijk,ik->i', v, M[E[:, 1]], v))
    out = (la + lb) / 2
    far = np.abs(la - lb) > 1e-3
    out[far] = (la[far] - lb[far]) / np.log(la[far] / lb[far])
    return out


def main(argv):
    args = [a for a in argv[1:]]
    opts = {'split': False, 'json': False}
    pos = []
    i = 0
    while i < len(args):
        a = args[i]
        if a in ('--split', '--json'): opts[a[2:]] = True; i += 1
        elif a in ('--min-angle', '--min-angle-all', '--mean-rr', '--in-range', '--geodesic'): opts[a[2:]] = float(args[i + 1]); i += 2
        elif a == '--metric': opts['metric'] = args[i + 1]; i += 2
        else: pos.append(a); i += 1
    if len(pos) != 2:
        print(__doc__); return 2
    P, E, T = read_medit2d(pos[0])
    inp = pos[1]
    polys, holes = None, np.zeros((0, 2))
    if inp.endswith('.poly'):
        Q, S, holes = read_poly(inp)
    elif inp.endswith('.geojson') or inp.endswith('.json'):
        Q, S, polys = read_geojson(inp)
    else:
        Q, Sl, _ = read_medit2d(inp); S = Sl
    fails, fig = [], {}
    # --- validity
    a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    scale = np.maximum(np.abs(b - a).max(1), np.abs(c - a).max(1)) ** 2
    unsure = np.nonzero(np.abs(det) <= 1e-12 * scale)[0]
    bad = int((det[np.abs(det) > 1e-12 * scale] < 0).sum())
    bad += sum(1 for t in unsure if orient_exact(P[T[t, 0]], P[T[t, 1]], P[T[t, 2]]) <= 0)
    if bad: fails.append('valid: %d triangles not counter-clockwise' % bad)
    half = np.vstack([T[:, [0, 1]], T[:, [1, 2]], T[:, [2, 0]]])
    key = np.minimum(half[:, 0], half[:, 1]) * (len(P) + 1) + np.maximum(half[:, 0], half[:, 1])
    uniq, inv, cnt = np.unique(key, return_inverse=True, return_counts=True)
    if (cnt > 2).any(): fails.append('valid: %d edges in 3 or more triangles' % int((cnt > 2).sum()))
    fwd = half[:, 0] < half[:, 1]
    both = np.zeros(len(uniq), int); np.add.at(both, inv, np.where(fwd, 1, 2))
    if ((cnt == 2) & (both != 3)).any(): fails.append('valid: %d edges with two triangles of the same orientation' % int(((cnt == 2) & (both != 3)).sum()))
    # --- input points in the mesh (exact coordinates)
    where = {(float(x), float(y)): k for k, (x, y) in enumerate(P)}
    qid = np.array([where.get((float(x), float(y)), -1) for x, y in Q])
    fig['input_points_found_exactly'] = '%d of %d' % (int((qid >= 0).sum()), len(Q))
    if (qid[np.unique(S.ravel())] < 0).any():
        fails.append('segments: %d input points (on segments) are not mesh points' % int((qid[np.unique(S.ravel())] < 0).sum()))
    edges = set(map(tuple, np.sort(half, axis=1).tolist()))
    on_input = np.zeros(len(P), bool); on_input[qid[qid >= 0]] = True
    # --- segments kept; points on them
    seg_lo = np.minimum(Q[S[:, 0]], Q[S[:, 1]]); seg_hi = np.maximum(Q[S[:, 0]], Q[S[:, 1]])
    span = max(float(np.ptp(Q[:, 0])), float(np.ptp(Q[:, 1])), 1e-300)
    tol = 1e-10 * span
    seg_lo -= tol; seg_hi += tol
    cell = max(float(np.median(np.linalg.norm(Q[S[:, 1]] - Q[S[:, 0]], axis=1))), 1e-300)
    # (coarser cells while the segments' boxes would fill more than 4 million: thin inputs)
    while np.sum((seg_hi[:, 0] // cell - seg_lo[:, 0] // cell + 1) * (seg_hi[:, 1] // cell - seg_lo[:, 1] // cell + 1)) > 4e6:
        cell *= 2
    grid = {}
    for s in range(len(S)):
        for gx in range(int(seg_lo[s, 0] // cell), int(seg_hi[s, 0] // cell) + 1):
            for gy in range(int(seg_lo[s, 1] // cell), int(seg_hi[s, 1] // cell) + 1):
                grid.setdefault((gx, gy), []).append(s)
    def dist_to(s, p):
        A, B = Q[S[s, 0]], Q[S[s, 1]]; d = B - A; L2 = d @ d
        t = min(max(((p - A) @ d) / L2, 0.0), 1.0)
        return float(np.linalg.norm(A + t * d - p)), t
    on_seg = {}
    for v in range(len(P)):
        if on_input[v]: continue
        p = P[v]
        for s in grid.get((int(p[0] // cell), int(p[1] // cell)), []):
            dd, t = dist_to(s, p)
            # (without --split only a point exactly on the segment counts: the mesher adds
            # none, and on a thin input a point inside may lie within tol of a segment)
            if dd <= tol and 0 < t < 1 and (opts['split'] or orient_exact(Q[S[s, 0]], Q[S[s, 1]], p) == 0):
                on_seg.setdefault(s, []).append((t, v))
    added = sum(len(x) for x in on_seg.values())
    fig['points_on_segments_added'] = added
    if added and not opts['split']: fails.append('no_added: %d mesh points lie on input segments' % added)
    missing = 0
    for s, (qa, qb) in enumerate(S):
        chain = [qid[qa]] + [v for _, v in sorted(on_seg.get(s, []))] + [qid[qb]]
        for u, w in zip(chain[:-1], chain[1:]):
            if (min(u, w), max(u, w)) not in edges: missing += 1; break
    if missing: fails.append('segments: %d input segments are not (chains of) mesh edges' % missing)
    # --- boundary edges on segments
    bnd = uniq[cnt == 1]
    seg_edges = set()
    for s, (qa, qb) in enumerate(S):
        chain = [qid[qa]] + [v for _, v in sorted(on_seg.get(s, []))] + [qid[qb]]
        for u, w in zip(chain[:-1], chain[1:]): seg_edges.add((min(u, w), max(u, w)))
    stray = sum(1 for k in bnd if (int(k // (len(P) + 1)), int(k % (len(P) + 1))) not in seg_edges)
    if stray: fails.append('boundary: %d mesh border edges are on no input segment' % stray)
    # --- domain: centroids inside, holes empty, area
    cen = (a + b + c) / 3
    directed = set(map(tuple, half.tolist()))
    if polys is not None:
        ins = np.zeros(len(cen), bool)
        for rings in polys:
            ins |= (inside_rings(Q, rings, cen).sum(0) % 2 == 1)
        dom_area = sum(sum((1 if k == 0 else -1) * abs(ring_area(Q, r)) for k, r in enumerate(rings)) for rings in polys)
    else:
        # Faces of the segments: the loops around a point; hole faces are those of hole points.
        loops = loops_of(len(Q), S)
        member = inside_rings(Q, loops, cen)
        ins = member.any(0)
        if len(holes):
            hole_member = inside_rings(Q, loops, holes)
            for h in range(hole_member.shape[1]):
                ins &= ~(member == hole_member[:, h:h + 1]).all(0)
        # The domain's area: each loop's area, added when the mesh lies inside it along it,
        # subtracted when outside (a hole's or an island's border), not counted when on both
        # sides (an interface between regions).
        dom_area = 0.0
        seg_index = {(int(min(x, y)), int(max(x, y))): k for k, (x, y) in enumerate(S)}
        for l in loops:
            # The loop's first mesh edge: from its first point to the next point on its first
            # segment (that segment's far end, or the nearest point added on it).
            k = seg_index[(min(l[0], l[1]), max(l[0], l[1]))]
            inner = sorted(on_seg.get(k, []))
            if inner and S[k][0] != l[0]: inner = [(1 - t, v) for t, v in inner][::-1]
            u, w = qid[l[0]], (inner[0][1] if inner else qid[l[1]])
            left, right = (u, w) in directed, (w, u) in directed
            ar = ring_area(Q, l)
            if left != right: dom_area += abs(ar) * (1 if left == (ar > 0) else -1)
    if (~ins).any(): fails.append('domain: %d triangles outside the domain or in a hole' % int((~ins).sum()))
    for h in holes:
        la = ((b[:, 0] - a[:, 0]) * (h[1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (h[0] - a[:, 0])) >= 0
        lb = ((c[:, 0] - b[:, 0]) * (h[1] - b[:, 1]) - (c[:, 1] - b[:, 1]) * (h[0] - b[:, 0])) >= 0
        lc = ((a[:, 0] - c[:, 0]) * (h[1] - c[:, 1]) - (a[:, 1] - c[:, 1]) * (h[0] - c[:, 0])) >= 0
        if (la & lb & lc).any(): fails.append('domain: hole point (%g, %g) is inside a triangle' % (h[0], h[1]))
    mesh_area = float(det.sum() / 2)
    fig['mesh_area'] = mesh_area
    fig['domain_area'] = float(dom_area)
    if abs(mesh_area - dom_area) > 1e-9 * max(abs(dom_area), 1e-300):
        fails.append('domain: triangles cover %.17g, the domain is %.17g (overlap or gap)' % (mesh_area, dom_area))
    # --- quality
    la_ = np.linalg.norm(b - c, axis=1); lb_ = np.linalg.norm(c - a, axis=1); lc_ = np.linalg.norm(a - b, axis=1)
    area = np.abs(det) / 2
    ang = np.degrees(np.vstack([np.arccos(np.clip((lb_**2 + lc_**2 - la_**2) / (2 * lb_ * lc_), -1, 1)),
                                np.arccos(np.clip((la_**2 + lc_**2 - lb_**2) / (2 * la_ * lc_), -1, 1)),
                                np.arccos(np.clip((la_**2 + lb_**2 - lc_**2) / (2 * la_ * lb_), -1, 1))]).min(0))
    s = (la_ + lb_ + lc_) / 2
    rr = 8 * area**2 / (s * la_ * lb_ * lc_)
    interior = ~on_input[T].any(1)
    fig.update(vertices=int(len(P)), triangles=int(len(T)), min_angle=round(float(ang.min()), 3),
               min_angle_no_input_point=round(float(ang[interior].min()) if interior.any() else 180.0, 3),
               triangles_no_input_point=int(interior.sum()),
               mean_radius_ratio=round(float(rr.mean()), 4), min_radius_ratio=round(float(rr.min()), 4))
    if 'min-angle' in opts and fig['min_angle_no_input_point'] < opts['min-angle']:
        fails.append('quality: min angle %.3f < %g over the triangles with no input point' % (fig['min_angle_no_input_point'], opts['min-angle']))
    if 'min-angle-all' in opts and fig['min_angle'] < opts['min-angle-all']:
        fails.append('quality: min angle %.3f < %g' % (fig['min_angle'], opts['min-angle-all']))
    if 'mean-rr' in opts and fig['mean_radius_ratio'] < opts['mean-rr']:
        fails.append('quality: mean radius ratio %.4f < %g' % (fig['mean_radius_ratio'], opts['mean-rr']))
    # --- edge lengths
    ME = np.array(sorted(edges), dtype=np.int64)
    if 'metric' in opts:
        kind, arg = opts['metric'].split(':')
        if kind == 'polar':
            M = polar_metric(P, float(arg))
        elif kind == 'const':
            a, b, c = (float(v) for v in arg.split(','))
            M = np.broadcast_to(np.array([[a, b], [b, c]]), (len(P), 2, 2))
        else:
            sys.exit('check2d.py: unknown --metric kind %r' % kind)
        L = ugawg_lengths(P, ME, M)
        fig['edges'] = int(len(ME)); fig['in_range_percent'] = round(float(np.mean((L >= 2**-0.5) & (L <= 2**0.5)) * 100), 2)
        fig['length_min'] = round(float(L.min()), 3); fig['length_max'] = round(float(L.max()), 3)
    if 'geodesic' in opts:
        from geographiclib.geodesic import Geodesic
        g = Geodesic.WGS84
        L = np.array([g.Inverse(P[u, 1], P[u, 0], P[w, 1], P[w, 0])['s12'] for u, w in ME]) / opts['geodesic']
        fig['edges'] = int(len(ME)); fig['in_range_percent'] = round(float(np.mean((L >= 2**-0.5) & (L <= 2**0.5)) * 100), 2)
        fig['length_min'] = round(float(L.min()), 3); fig['length_max'] = round(float(L.max()), 3)
    if 'in-range' in opts and fig.get('in_range_percent', -1) < opts['in-range']:
        fails.append('lengths: %.2f%% of edges in [1/sqrt2, sqrt2] < %g%%' % (fig.get('in_range_percent', -1), opts['in-range']))
    fig['failures'] = fails
    if opts['json']:
        print(json.dumps(fig))
    else:
        for k, v in fig.items():
            if k != 'failures': print('%s: %s' % (k, v))
        for f in fails: print('FAIL ' + f)
        if not fails: print('all checks passed')
    return 1 if fails else 0


def ring_area(Q, ring):
    x, y = Q[ring, 0], Q[ring, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


if __name__ == '__main__':
    sys.exit(main(sys.argv))
