#!/usr/bin/python3
"""columns.py COLUMNS.csv --layers N --h0 H --growth R [--feature NAME=EXPR ...] [--json]: the
boundary-layer columns that `anitet mesh --bl-columns COLUMNS.csv` wrote, measured by feature.

A feature is a set of wall vertices given by a Python expression over numpy arrays x, y, z and
`on(label)` (the vertices on that patch), e.g. --feature "te=on(1) & (x > 0.9999)". Prints, per
feature and for all wall vertices: vertices, full columns, mean and least layers reached, first
height (min/mean/max), the full columns' total height (min/mean) against h0 (r^n - 1)/(r - 1), and
the normal share (min/mean: the layers' thickness across the wall over their height along the
column; below 1 at edges and corners, where one column serves several wall directions)."""
import argparse
import json
import sys

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--layers", type=int, required=True)
    ap.add_argument("--h0", type=float, required=True)
    ap.add_argument("--growth", type=float, required=True)
    ap.add_argument("--feature", action="append", default=[])
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    lines = [line.rstrip("\n").split(",") for line in open(a.csv)]
    col = {name: k for k, name in enumerate(lines[0])}
    rows = lines[1:]
    get = lambda name, kind=float: np.array([kind(r[col[name]]) for r in rows]) if name in col else np.full(len(rows), np.nan)
    x, y, z = get("x"), get("y"), get("z")
    layers, first, total, share = get("layers", int), get("first_height"), get("total_height"), get("normal_share")
    patches = [set(map(int, r[col["patches"]].split())) for r in rows]
    on = lambda label: np.array([label in p for p in patches], bool)
    nominal = a.h0 * (a.growth ** a.layers - 1) / (a.growth - 1)
    groups = [("all walls", np.ones(len(rows), bool))]
    for f in a.feature:
        name, expr = f.split("=", 1)
        groups.append((name, np.asarray(eval(expr, {"np": np}, {"x": x, "y": y, "z": z, "on": on}), bool)))
    out = []
    for name, mask in groups:
        r, reached, full = layers[mask], layers[mask] > 0, layers[mask] == a.layers
        row = {"feature": name, "vertices": int(mask.sum()), "full": int(full.sum())}
        if row["vertices"]:
            row.update(layers_mean=float(r.mean()), layers_min=int(r.min()),
                       first_min=float(first[mask][reached].min()) if reached.any() else 0.0,
                       first_mean=float(first[mask][reached].mean()) if reached.any() else 0.0,
                       first_max=float(first[mask].max()),
                       total_min_full=float(total[mask][full].min()) if full.any() else 0.0,
                       total_mean_full=float(total[mask][full].mean()) if full.any() else 0.0,
                       total_nominal=nominal,
                       normal_share_min=float(share[mask][reached].min()) if reached.any() else 0.0,
                       normal_share_mean=float(share[mask][reached].mean()) if reached.any() else 0.0)
        out.append(row)
    if a.json:
        json.dump(out, sys.stdout, indent=1)
        print()
        return
    for r in out:
        if not r["vertices"]:
            print(f"{r['feature']}: no vertex")
            continue
        print(f"{r['feature']}: {r['vertices']} wall vertices, {r['full']} full columns "
              f"({100 * r['full'] / r['vertices']:.1f}%), layers mean {r['layers_mean']:.2f} min {r['layers_min']}; "
              f"first height {r['first_min']:.3g} / {r['first_mean']:.3g} / {r['first_max']:.3g}; full columns' "
              f"total height min {r['total_min_full']:.4g} mean {r['total_mean_full']:.4g} (nominal {nominal:.4g}); "
              f"normal share min {r['normal_share_min']:.3f} mean {r['normal_share_mean']:.3f}")


if __name__ == "__main__":
    main()
