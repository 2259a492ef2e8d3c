#!/usr/bin/python3
"""check2d.py's own test: it passes a hand-made valid mesh and fails each broken copy of it.

The domain is the square [0, 3]^2 minus the hole [1, 2]^2 (8 segments, a hole point), meshed by
8 triangles written here by hand (no mesher involved). Each mutation must make check2d.py exit
non-zero with the named failure; the valid mesh (and a point on a segment with --split) must pass.
"""
import os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, 'check2d.py')

POLY = """8 2 0 0
1 0 0
2 3 0
3 3 3
4 0 3
5 1 1
6 2 1
7 2 2
8 1 2
8 0
1 1 2
2 2 3
3 3 4
4 4 1
5 5 6
6 6 7
7 7 8
8 8 5
1
1 1.5 1.5
"""
POINTS = [(0, 0), (3, 0), (3, 3), (0, 3), (1, 1), (2, 1), (2, 2), (1, 2)]
TRIANGLES = [(1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 4, 8), (3, 8, 7), (4, 1, 5), (4, 5, 8)]


def medit(points, triangles):
    out = ['MeshVersionFormatted 2', 'Dimension 2', 'Vertices', str(len(points))]
    out += ['%.17g %.17g 0' % p for p in points]
    out += ['Triangles', str(len(triangles))] + ['%d %d %d 0' % t for t in triangles] + ['End', '']
    return '\n'.join(out)


def run(tmp, name, points, triangles, extra, expect):
    """expect: None for a pass, else a substring of the failure check2d.py must print."""
    mesh = os.path.join(tmp, name + '.mesh')
    with open(mesh, 'w') as f:
        f.write(medit(points, triangles))
    r = subprocess.run([sys.executable, CHECK, mesh, os.path.join(tmp, 'ring.poly')] + extra,
                       capture_output=True, text=True)
    fails = [l for l in r.stdout.splitlines() if l.startswith('FAIL')]
    if expect is None:
        ok = r.returncode == 0 and not fails
    else:
        ok = r.returncode != 0 and any(expect in l for l in fails)
    print('%s %s: exit %d %s' % ('PASS' if ok else 'FAIL', name, r.returncode, fails or ''))
    if not ok:
        print(r.stdout + r.stderr)
    return ok


def main():
    on_segment = POINTS + [(1.5, 0)]           # point 9 on segment 1 (0,0)-(3,0)
    split = [(1, 9, 5), (9, 2, 6), (9, 6, 5)] + TRIANGLES[2:]
    off_segment = POINTS + [(1.5, 1e-3)]       # the same point just inside: segment 1 not kept
    cases = [
        ('valid', POINTS, TRIANGLES, [], None),
        ('valid-quality', POINTS, TRIANGLES, ['--min-angle-all', '18', '--mean-rr', '0.4'], None),
        ('quality-bar', POINTS, TRIANGLES, ['--min-angle-all', '50'], 'quality: min angle'),
        ('inverted', POINTS, [(2, 1, 6)] + TRIANGLES[1:], [], 'not counter-clockwise'),
        ('duplicate', POINTS, TRIANGLES + [TRIANGLES[0]], [], '3 or more triangles'),
        ('gap', POINTS, TRIANGLES[1:], [], 'boundary: 2 mesh border edges'),
        ('hole-filled', POINTS, TRIANGLES + [(5, 6, 7), (5, 7, 8)], [], 'domain:'),
        ('point-on-segment', on_segment, split, [], 'no_added: 1 mesh points'),
        ('point-on-segment-split', on_segment, split, ['--split'], None),
        ('segment-lost', off_segment, split, [], 'segments: 1 input segments are not'),
    ]
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, 'ring.poly'), 'w') as f:
            f.write(POLY)
        results = [run(tmp, *c) for c in cases]
    print('check2d self-test: %d of %d cases as expected' % (sum(results), len(results)))
    return 0 if all(results) else 1


if __name__ == '__main__':
    sys.exit(main())
