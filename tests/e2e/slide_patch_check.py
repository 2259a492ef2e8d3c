#!/usr/bin/python3
"""slide_patch_check.py IN OUT LABEL[,LABEL...] [--kept KEPT.off] [--tolerance 1e-12]

Checks that the slide patches of a boundary-layer mesh (`anitet mesh --bl-slide-patches`) cover
exactly what they covered in the input surface: per slide patch LABEL,
  - the area of the output's boundary triangles with that label equals the input's (relative
    difference <= tolerance), and the sum of their vector areas has the same length (no fold, no
    overlap: the patches are planar where they are re-triangulated);
  - the boundary loops are the same: every input boundary vertex of the patch is an output
    boundary vertex, every output boundary vertex lies on an input boundary edge (distance <=
    tolerance x the patch's size), and the loops' total lengths agree (relative <= tolerance).
IN: the input surface (.mesh or .msh, read by meshio with its labels); OUT: the output volume
mesh (.mesh, its Triangles with their refs). --kept writes the input without the slide patches
(OFF) for meshcheck.py's input_triangles_missing. Prints one line per patch and exits 1 on a
failed check."""
import argparse
import sys

import meshio
import numpy as np


def labelled_triangles(path):
    m = meshio.read(path)
    tris, labels = [], []
    for i, block in enumerate(m.cells):
        if block.type != "triangle":
            continue
        tris.append(block.data)
        for key in ("medit:ref", "gmsh:physical"):
            if key in m.cell_data:
                labels.append(np.asarray(m.cell_data[key][i]))
                break
        else:
            sys.exit(f"{path}: no triangle labels")
    return np.asarray(m.points[:, :3], dtype=np.float64), np.vstack(tris).astype(np.int64), np.concatenate(labels)


def patch_measures(xyz, tris):
    p, q, r = xyz[tris[:, 0]], xyz[tris[:, 1]], xyz[tris[:, 2]]
    cross = np.cross(q - p, r - p) / 2
    norms = np.linalg.norm(cross, axis=1)
    area = norms.sum()
    # Per plane (triangles grouped by their normal): the area and the length of the summed vector
    # areas, equal when no triangle is folded over.
    planes = {}
    for n, c, a in zip(np.round(cross / norms[:, None], 6), cross, norms):
        key = tuple(n + 0.0)
        s = planes.setdefault(key, [np.zeros(3), 0.0])
        s[0] += c
        s[1] += a
    vector_area = sum(np.linalg.norm(v) for v, _ in planes.values())
    # Boundary edges: used once (as an unordered pair).
    edges = np.sort(np.vstack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    uniq, counts = np.unique(edges, axis=0, return_counts=True)
    boundary = uniq[counts == 1]
    length = np.linalg.norm(xyz[boundary[:, 0]] - xyz[boundary[:, 1]], axis=1).sum()
    return area, vector_area, boundary, length


def point_segment_distance(points, a, b):
    ab = b - a
    t = np.clip(((points[:, None, :] - a[None]) * ab[None]).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0, 1)
    closest = a[None] + t[..., None] * ab[None]
    return np.linalg.norm(points[:, None, :] - closest, axis=-1).min(axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("labels")
    ap.add_argument("--kept", default="")
    ap.add_argument("--tolerance", type=float, default=1e-12)
    args = ap.parse_args()
    labels = [int(x) for x in args.labels.split(",")]
    xi, ti, li = labelled_triangles(args.input)
    xo, to, lo = labelled_triangles(args.output)
    ok = True
    for label in labels:
        a_in, v_in, b_in, len_in = patch_measures(xi, ti[li == label])
        a_out, v_out, b_out, len_out = patch_measures(xo, to[lo == label])
        size = np.ptp(xi[np.unique(ti[li == label])], axis=0).max()
        vin = np.unique(b_in)
        vout = np.unique(b_out)
        # Input boundary vertices found among the output's (exact coordinates).
        out_set = {tuple(p) for p in xo[vout]}
        missing = sum(tuple(p) not in out_set for p in xi[vin])
        off_loop = point_segment_distance(xo[vout], xi[b_in[:, 0]], xi[b_in[:, 1]]).max() if len(vout) else 0.0
        area_err = abs(a_out - a_in) / a_in
        fold_err = abs(v_out - a_out) / a_out
        len_err = abs(len_out - len_in) / len_in
        good = (area_err <= args.tolerance and fold_err <= args.tolerance and len_err <= args.tolerance and
                missing == 0 and off_loop <= args.tolerance * size)
        ok = ok and good
        print(f"slide patch {label}: {len(ti[li == label])} -> {len(to[lo == label])} triangles "
              f"(+{len(to[lo == label]) - len(ti[li == label])}); area {a_in:.15g} -> {a_out:.15g} "
              f"(rel. {area_err:.2e}); folds/overlaps (|sum of vector areas| vs area) {fold_err:.2e}; "
              f"boundary loop length {len_in:.15g} -> {len_out:.15g} (rel. {len_err:.2e}), "
              f"{len(vin)} -> {len(vout)} vertices, input loop vertices missing {missing}, "
              f"farthest output loop vertex from the input loop {off_loop:.2e}: {'OK' if good else 'FAIL'}")
    if args.kept:
        keep = ~np.isin(li, labels)
        with open(args.kept, "w") as f:
            f.write(f"OFF\n{len(xi)} {int(keep.sum())} 0\n")
            for p in xi:
                f.write(f"{p[0]!r} {p[1]!r} {p[2]!r}\n")
            for t in ti[keep]:
                f.write(f"3 {t[0]} {t[1]} {t[2]}\n")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
