#!/usr/bin/env python3
"""table.py OUTDIR SURFACE...: the tables of bench/peers/run.sh's results in OUTDIR.

Writes OUTDIR/results.json (every figure), results.md (markdown) and results.html (the same, one
self-contained page): per surface and mesher the tets, wall seconds, tets per second, time
relative to anitet, peak memory, meshcheck.py's verdict (valid, boundary kept) and quality (radius
ratio mean and min, min dihedral, share below 0.1), or the failure with the last line of its log;
then the paper's Tables 2-4 for its four examples (fandisk, airplane, femur, bimba) beside the
paper's own figures."""
import html
import json
import os
import sys

MESHERS = [
    ("anitet", "anitet"),
    ("gmsh-hxt1", "Gmsh HXT, 1 thread"),
    ("gmsh-hxt2", "Gmsh HXT, 2 threads"),
    ("gmsh-delaunay", "Gmsh Delaunay"),
    ("tetgen", "TetGen -pq1.414Y"),
]

# The paper's Tables 2-4 (its own surfaces, finer than the shared ones).
PAPER = {
    "fandisk": dict(bv=16853, bt=33702, v=91614, t=476463, avg=0.72, min=0.23, good=0.99, bad=0.0,
                    n_b=110805, avg_b=0.71, min_b=0.23, good_b=0.99, bad_b=0.0),
    "airplane": dict(bv=71477, bt=142958, v=209700, t=974270, avg=0.71, min=0.12, good=0.99, bad=0.0,
                     n_b=427979, avg_b=0.72, min_b=0.12, good_b=0.99, bad_b=0.0),
    "femur": dict(bv=28213, bt=56422, v=148197, t=780343, avg=0.73, min=0.43, good=0.99, bad=0.0,
                  n_b=167728, avg_b=0.74, min_b=0.43, good_b=0.99, bad_b=0.0),
    "bimba_low": dict(bv=74764, bt=149524, v=497273, t=2680102, avg=0.75, min=0.04, good=0.99, bad=7.46e-7,
                      n_b=423940, avg_b=0.76, min_b=0.04, good_b=0.99, bad_b=4.72e-6),
}


def read(path, default=None):
    try:
        with open(path) as f:
            return f.read().strip()
    except OSError:
        return default


def load(outdir, stem, key):
    d = os.path.join(outdir, stem)
    r = {"mesher": key, "rc": read(os.path.join(d, key + ".rc")), "seconds": None}
    if r["rc"] is None:
        return None
    r["seconds"] = float(read(os.path.join(d, key + ".seconds"), "nan"))
    rss = read(os.path.join(d, key + ".rss"), "")
    r["peak_mb"] = int(rss.splitlines()[-1]) / 1024 if rss and rss.splitlines()[-1].isdigit() else None
    check = read(os.path.join(d, key + ".json"))
    if check:
        c = json.loads(check)
        q = c["quality"]
        r.update(tets=c["tets"], vertices=c["vertices"], valid=c["valid"],
                 boundary=c.get("boundary_constrained"), missing=c.get("input_triangles_missing"),
                 steiner=c.get("steiner_points_on_boundary"), rr_mean=q["radius_ratio"]["mean"],
                 rr_min=q["radius_ratio"]["min"], dihedral_min=q["min_dihedral_deg"],
                 good=q["good_fraction_rr_gt_0.4"], bad=q["bad_fraction_rr_lt_0.1"],
                 input_triangles=c.get("input_triangles"))
        t = c.get("quality_touching_surface")
        if t:
            r.update(n_b=t["tets"], avg_b=t["radius_ratio"]["mean"], min_b=t["radius_ratio"]["min"],
                     good_b=t["good_fraction_rr_gt_0.4"], bad_b=t["bad_fraction_rr_lt_0.1"])
    else:
        log = read(os.path.join(d, key + ".log"), "") or ""
        lines = [l for l in log.splitlines() if l.strip()]
        reason = "timed out" if r["rc"] == "124" else (lines[-1] if lines else "no output")
        if r["rc"] == "0":
            reason = "no mesh, or meshcheck.py could not read it"
        r["failure"] = reason[:300]
    return r


def fmt(x, spec):
    return "" if x is None else format(x, spec)


def rows_for(outdir, stems):
    rows = []
    for stem in stems:
        runs = {k: load(outdir, stem, k) for k, _ in MESHERS}
        base = runs.get("anitet")
        for key, label in MESHERS:
            r = runs[key]
            if r is None:
                continue
            r["surface"] = stem
            r["label"] = label
            if r.get("tets") and r["seconds"]:
                r["tets_per_s"] = r["tets"] / r["seconds"]
            if base and base.get("tets_per_s") and r.get("tets_per_s"):
                r["time_vs_anitet"] = r["seconds"] / base["seconds"]
                r["rate_vs_anitet"] = r["tets_per_s"] / base["tets_per_s"]
            rows.append(r)
    return rows


HEAD = ["surface", "mesher", "tets", "seconds", "tets/s", "tets/s vs anitet", "peak MB", "valid",
        "boundary kept", "rr mean", "rr min", "min dihedral", "rr < 0.1", "failure"]


def cells(r):
    kept = r.get("boundary")
    if kept is not None and not kept:
        kept_text = f"no ({r.get('missing')} missing, {r.get('steiner')} Steiner)"
    else:
        kept_text = "" if kept is None else "yes"
    return [r["surface"], r["label"], fmt(r.get("tets"), "d"), fmt(r["seconds"], ".2f"),
            fmt(r.get("tets_per_s"), ".0f"), fmt(r.get("rate_vs_anitet"), ".2f"), fmt(r.get("peak_mb"), ".0f"),
            "" if "valid" not in r else ("yes" if r["valid"] else "NO"), kept_text, fmt(r.get("rr_mean"), ".3f"),
            fmt(r.get("rr_min"), ".4f"), fmt(r.get("dihedral_min"), ".2f"),
            "" if r.get("bad") is None else f"{100 * r['bad']:.2f}%", r.get("failure", "")]


PAPER_ROWS = [("Boundary vertices", "bv", "d"), ("Boundary triangles", "bt", "d"), ("Total vertices", "v", "d"),
              ("Total tetrahedra", "t", "d"), ("Average quality", "avg", ".2f"), ("Minimal quality", "min", ".3f"),
              ("Good elements (> 0.4)", "good", ".4f"), ("Bad elements (< 0.1)", "bad", ".2e"),
              ("Near-boundary elements", "n_b", "d"), ("  average quality", "avg_b", ".2f"),
              ("  minimal quality", "min_b", ".3f"), ("  good elements", "good_b", ".4f"),
              ("  bad elements", "bad_b", ".2e")]


def paper_tables(outdir, rows, stems):
    tables = []
    for stem in stems:
        if stem not in PAPER:
            continue
        mine = {r["mesher"]: r for r in rows if r["surface"] == stem}
        cols = [("paper", PAPER[stem])]
        for key, label in MESHERS:
            r = mine.get(key)
            if r and r.get("tets"):
                r = dict(r, v=r["vertices"], t=r["tets"], bt=r.get("input_triangles"), avg=r["rr_mean"],
                         min=r["rr_min"], bv=surface_vertices(outdir, stem))
                cols.append((label, r))
        table = [["", *[c for c, _ in cols]]]
        for name, k, spec in PAPER_ROWS:
            table.append([name, *[fmt(d.get(k), spec) for _, d in cols]])
        tables.append((stem, table))
    return tables


def surface_vertices(outdir, stem):
    text = read(os.path.join(outdir, stem, "surface.mesh"), "")
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.strip() == "Vertices":
            return int(lines[i + 1])
    return None


def markdown(table):
    out = ["| " + " | ".join(table[0]) + " |", "|" + "---|" * len(table[0])]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in table[1:]]
    return "\n".join(out)


def html_table(table):
    head = "".join(f"<th>{html.escape(c)}</th>" for c in table[0])
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in table[1:])
    return f"<table><tr>{head}</tr>{body}</table>"


def main():
    outdir, stems = sys.argv[1], [os.path.splitext(os.path.basename(s))[0] for s in sys.argv[2:]]
    rows = rows_for(outdir, stems)
    machine = read(os.path.join(outdir, "machine.txt"), "")
    main_table = [HEAD] + [cells(r) for r in rows]
    papers = paper_tables(outdir, rows, stems)
    note = ("Wall seconds of each run, back to back on the same machine; tets/s relative to anitet's "
            "on the same input (above 1: faster than anitet). Quality by meshcheck.py: radius ratio "
            "3 r / R (the paper's quality), min dihedral in degrees. Each mesher sizes the mesh its own "
            "way from the surface (anitet refines to its sizing field), so counts differ.")
    with open(os.path.join(outdir, "results.json"), "w") as f:
        json.dump({"machine": machine, "runs": rows}, f, indent=1)
    with open(os.path.join(outdir, "results.md"), "w") as f:
        f.write("# anitet against Gmsh and TetGen\n\n```\n" + machine + "\n```\n\n" + note + "\n\n")
        f.write(markdown(main_table) + "\n")
        for stem, t in papers:
            f.write(f"\n## The paper's Tables 2-4: {stem}\n\n" + markdown(t) + "\n")
    with open(os.path.join(outdir, "results.html"), "w") as f:
        f.write("<!doctype html><html><head><meta charset=\"utf-8\"><title>anitet against Gmsh and TetGen</title>"
                "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin:1em 0}"
                "td,th{border:1px solid #bbb;padding:3px 7px;font-size:13px}th{background:#eef}</style></head><body>")
        f.write("<h1>anitet against Gmsh and TetGen</h1><pre>" + html.escape(machine) + "</pre><p>" +
                html.escape(note) + "</p>" + html_table(main_table))
        for stem, t in papers:
            f.write(f"<h2>The paper's Tables 2-4: {html.escape(stem)}</h2>" + html_table(t))
        f.write("</body></html>\n")
    print(markdown(main_table))


if __name__ == "__main__":
    main()
