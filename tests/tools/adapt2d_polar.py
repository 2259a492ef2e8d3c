#!/usr/bin/python3
"""The anisotropic case of docs/mesh2d.md through the command line: the UGAWG-style loop of
`anitet mesh2d` runs, each given the analytic polar metric at the previous mesh's vertices as a
Dimension 2 .sol on that mesh (--metric m.sol --background prev.mesh), then check2d.py's UGAWG
edge-length measure on the last mesh.

usage: adapt2d_polar.py ANITET INPUT.poly WORKDIR PASSES [MIN_PERCENT]
  (the metric: h_r = 0.001 + 2 (0.1 - 0.001) |r - 0.25| about (0.5, 0.5), 0.1 tangentially).
  Prints one JSON line per pass; exit status 1 when a run fails, or when the last pass has
  fewer than MIN_PERCENT of its edges in [1/sqrt2, sqrt2].
"""
import json, os, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check2d import read_medit2d, polar_metric  # noqa: E402

anitet, poly, work, passes = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
r0 = 0.25
least = float(sys.argv[5]) if len(sys.argv) > 5 else 0.0
os.makedirs(work, exist_ok=True)
prev = os.path.join(work, "pass0.mesh")
# Pass 0: the input's own sizes.
if subprocess.run([anitet, "mesh2d", poly, "-o", prev, "-q"]).returncode != 0:
    sys.exit(1)
for k in range(1, passes + 1):
    P, _, _ = read_medit2d(prev)
    M = polar_metric(P, r0)
    sol = os.path.join(work, "pass%d.sol" % (k - 1))
    with open(sol, "w") as f:
        f.write("MeshVersionFormatted 2\n\nDimension 2\n\nSolAtVertices\n%d\n1 3\n\n" % len(M))
        for m in M:
            f.write("%.17g %.17g %.17g\n" % (m[0, 0], m[0, 1], m[1, 1]))
        f.write("\nEnd\n")
    out = os.path.join(work, "pass%d.mesh" % k)
    r = subprocess.run([anitet, "mesh2d", poly, "-o", out, "--metric", sol, "--background", prev, "--json"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout + r.stderr)
        sys.exit(1)
    rep = json.loads(r.stdout)
    c = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "check2d.py"),
                        out, poly, "--metric", "polar:%g" % r0, "--json"], capture_output=True, text=True)
    fig = json.loads(c.stdout)
    print(json.dumps({"pass": k, "triangles": rep["triangles"], "seconds": round(rep["seconds"], 3),
                      "in_range_percent": fig["in_range_percent"], "length_min": fig["length_min"],
                      "length_max": fig["length_max"], "failures": fig["failures"]}), flush=True)
    prev = out
if fig["in_range_percent"] < least:
    print("FAIL: %.2f%% of the edges in range, %g%% needed" % (fig["in_range_percent"], least))
    sys.exit(1)
