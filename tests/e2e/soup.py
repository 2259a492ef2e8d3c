#!/usr/bin/env python3
"""soup.py IN.off OUT.obj [SEED]: the surface as a polygon soup, as other tools write STL-like
files: every triangle with its own three corners (duplicated coincident vertices), about half the
triangles facing the other way at random, and the triangles shuffled."""
import random
import sys


def read_off(path):
    toks = [t for line in open(path) for t in line.split("#")[0].split()]
    assert toks[0].upper().endswith("OFF"), "not an OFF file"
    nv, nf = int(toks[1]), int(toks[2])
    at = 4
    pts = [toks[at + 3 * i:at + 3 * i + 3] for i in range(nv)]
    at += 3 * nv
    tris = []
    for _ in range(nf):
        n = int(toks[at])
        ids = list(map(int, toks[at + 1:at + 1 + n]))
        tris += [[ids[0], ids[k], ids[k + 1]] for k in range(1, n - 1)]
        at += 1 + n
    return pts, tris


def main():
    pts, tris = read_off(sys.argv[1])
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    rng.shuffle(tris)
    flipped = 0
    with open(sys.argv[2], "w") as f:
        for i, t in enumerate(tris):
            if rng.random() < 0.5:
                t = [t[0], t[2], t[1]]
                flipped += 1
            for v in t:
                f.write("v %s %s %s\n" % tuple(pts[v]))
            f.write("f %d %d %d\n" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
    print(f"{len(tris)} triangles, {3 * len(tris)} vertices, {flipped} flipped")


if __name__ == "__main__":
    main()
