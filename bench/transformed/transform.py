#!/usr/bin/env python3
"""transform.py IN OUT.mesh VARIANT: the surface IN moved by VARIANT and written as a Medit .mesh
with every coordinate in full double precision. VARIANT is given (unmoved), rotate (a random rotation,
seeded by the file name so reruns match), scale1e-4, scale1e4, scale1e-6, scale1e6, translate1e6, or
scale2p-20 and scale2p20 (by 2^-20 and 2^20: exact, so the same surface up to scale), or ulp1, ulp2, ...
(every coordinate moved by -1, 0 or +1 ulp at random, seeded by the file name and the number: the
rounding any inexact transform adds, without the transform). Exactly equal input points are merged
first (STL repeats them per triangle). back1e6 moves a Medit mesh by -1e6 exactly (to
check a translated result where digits are not lost to cancellation)."""
import hashlib
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "peers"))
import to_medit  # noqa: E402  (its surface reader and Medit writer)


def read(path):
    points, tris = to_medit.read_surface(path)
    points = np.asarray(points, dtype=float)
    tris = np.asarray(tris, dtype=np.int64)
    unique, inverse = np.unique(points, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1)[tris]


def random_rotation(seed):
    rng = np.random.default_rng(seed)
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def shift_back(src, dst):
    """A Medit mesh (ours or anitet's) moved by -1e6, exactly: every coordinate x is near 1e6,
    so x - 1e6 is exact (Sterbenz), written with all its digits, cells and labels kept."""
    import meshio
    m = meshio.read(src)
    m.points = m.points - 1e6
    meshio.write(dst, m, file_format="medit", float_fmt=".17e")


def main():
    src, dst, variant = sys.argv[1:4]
    if variant == "back1e6":
        return shift_back(src, dst)
    points, tris = read(src)
    if variant == "given":
        pass
    elif variant == "rotate":
        seed = int(hashlib.sha256(os.path.basename(src).encode()).hexdigest()[:8], 16)
        points = points @ random_rotation(seed).T
    elif variant == "scale1e-4":
        points = points * 1e-4
    elif variant == "scale1e4":
        points = points * 1e4
    elif variant == "scale1e-6":
        points = points * 1e-6
    elif variant == "scale1e6":
        points = points * 1e6
    elif variant == "scale2p-20":
        points = points * 2.0**-20
    elif variant == "scale2p20":
        points = points * 2.0**20
    elif variant == "translate1e6":
        points = points + 1e6
    elif variant.startswith("ulp") and variant[3:].isdigit():
        key = os.path.basename(src) + ":" + variant
        rng = np.random.default_rng(int(hashlib.sha256(key.encode()).hexdigest()[:8], 16))
        step = rng.integers(-1, 2, size=points.shape)
        points = np.where(step > 0, np.nextafter(points, np.inf), np.where(step < 0, np.nextafter(points, -np.inf), points))
    else:
        sys.exit("transform.py: unknown variant " + variant)
    to_medit.write_medit(dst, points, tris)


if __name__ == "__main__":
    main()
