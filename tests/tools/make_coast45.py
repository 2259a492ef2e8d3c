#!/usr/bin/python3
"""Writes the geographic test input of docs/mesh2d.md: a bay around 45 N, 63 W (about 230 km by
160 km) with three islands, as a GeoJSON FeatureCollection in lon/lat, its vertices about SIZE
metres apart along each ring (WGS84 geodesics, python3-geographiclib), and a LineString labelling
the mouth of the bay 3 (an open boundary for ADCIRC).

usage: make_coast45.py OUT.geojson [SIZE]   (SIZE: 5000 by default)
"""
import json, math, sys
from geographiclib.geodesic import Geodesic

G = Geodesic.WGS84
LAT0, LON0 = 45.0, -63.0


def offset(east_km, north_km):
    """The point east_km, north_km (km) from the centre, on the ellipsoid."""
    d = math.hypot(east_km, north_km) * 1000.0
    az = math.degrees(math.atan2(east_km, north_km))
    g = G.Direct(LAT0, LON0, az, d)
    return g['lon2'], g['lat2']


def ring(shape, n=2000):
    """A closed ring from a polar shape r(theta) in km, resampled to SIZE geodesic metres."""
    dense = [offset(shape(t) * math.cos(t), shape(t) * math.sin(t)) for t in (2 * math.pi * i / n for i in range(n))]
    lengths = [G.Inverse(a[1], a[0], b[1], b[0])['s12'] for a, b in zip(dense, dense[1:] + dense[:1])]
    total = sum(lengths)
    count = max(3, round(total / SIZE))
    step = total / count
    out, walked, k = [], 0.0, 0
    for i in range(count):
        target = i * step
        while walked + lengths[k] < target:
            walked += lengths[k]; k += 1
        a, b = dense[k], dense[(k + 1) % n]
        f = (target - walked) / lengths[k]
        out.append([round(a[0] + f * (b[0] - a[0]), 9), round(a[1] + f * (b[1] - a[1]), 9)])
    return out


SIZE = float(sys.argv[2]) if len(sys.argv) > 2 else 5000.0
coast = ring(lambda t: 90 + 18 * math.sin(3 * t) + 8 * math.cos(7 * t) - 25 * math.exp(-((t - 4.7) / 0.25) ** 2))
islands = []
for (ce, cn, r) in [(-30, 20, 9), (35, -10, 12), (5, -45, 7)]:
    isl = ring(lambda t, r=r: r * (1 + 0.2 * math.sin(2 * t)))
    # Shift the island's ring to its centre (the ring is around the bay's centre).
    cx, cy = offset(ce, cn)
    isl = [[round(p[0] - LON0 + cx, 9), round(p[1] - LAT0 + cy, 9)] for p in isl]
    islands.append(isl[::-1])  # holes run clockwise
coast_closed = coast + [coast[0]]
features = [{"type": "Feature", "properties": {"name": "bay", "label": 1},
             "geometry": {"type": "Polygon", "coordinates": [coast_closed] + [i + [i[0]] for i in islands]}}]
# Label the island rings 2 and the bay's mouth (the coast's southernmost stretch) 3.
for isl in islands:
    features.append({"type": "Feature", "properties": {"label": 2},
                     "geometry": {"type": "LineString", "coordinates": isl + [isl[0]]}})
south = sorted(range(len(coast)), key=lambda i: coast[i][1])[0]
mouth = [coast[(south + k) % len(coast)] for k in range(-3, 4)]
features.append({"type": "Feature", "properties": {"label": 3, "name": "mouth"},
                 "geometry": {"type": "LineString", "coordinates": mouth}})
json.dump({"type": "FeatureCollection", "features": features}, open(sys.argv[1], 'w'), indent=1)
print("%s: coast %d points, islands %s, size %g m" % (sys.argv[1], len(coast), [len(i) for i in islands], SIZE))
