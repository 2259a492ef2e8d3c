#!/usr/bin/python3
"""Lake Superior (the paper's 2D example) meshed by anitet mesh2d, Gmsh 2D and CGAL's
Delaunay_mesher_2, one core each (taskset -c 0), runs alternated in rounds; times and quality
side by side, quality by tests/tools/check2d.py (written apart from all three).

usage: run_bench.py ANITET CGAL_MESH2D OUTDIR [ROUNDS] [INPUT.poly]
  ANITET: the `anitet` binary; CGAL_MESH2D: bench/mesh2d's cgal_mesh2d (-DANITET_BUILD_BENCH=ON);
  gmsh from PATH (Debian's). Writes OUTDIR/results.json and OUTDIR/results.md.

The settings, chosen so that all three aim at the same sizes:
  anitet: defaults (sizes from the segments' lengths, smoothed inside; every segment kept whole).
  Gmsh:   a .geo with the points' mesh sizes the mean length of their two segments, interpolated
          inside (Gmsh's default), each segment a transfinite curve of 2 nodes (kept whole, no
          point added), the default 2D algorithm (Frontal-Delaunay), one thread.
  CGAL:   refine_Delaunay_mesh_2 with the shape bound 0.125 (angles >= 20.7 deg) and a size bound
          (the longest edge) set to give about as many triangles as anitet; Ruppert's refinement
          adds points on the segments (conforming, not boundary constrained).
"""
import json, math, os, platform, re, statistics, subprocess, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "..", "..", "tests", "tools", "check2d.py")
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests", "tools"))
from check2d import read_poly, loops_of  # noqa: E402


def write_geo(poly, geo):
    """The .poly as a Gmsh .geo: points with sizes, lines, loops, one plane surface."""
    Q, S, H = read_poly(poly)
    length = [0.0] * len(Q)
    count = [0] * len(Q)
    for a, b in S:
        L = math.dist(Q[a], Q[b])
        for v in (a, b):
            length[v] += L
            count[v] += 1
    loops = loops_of(len(Q), S)
    area = [0.5 * sum(Q[l[k]][0] * Q[l[(k + 1) % len(l)]][1] - Q[l[(k + 1) % len(l)]][0] * Q[l[k]][1] for k in range(len(l))) for l in loops]
    outer = max(range(len(loops)), key=lambda i: abs(area[i]))
    with open(geo, "w") as f:
        f.write("// %s for Gmsh: every segment one transfinite curve of 2 nodes (kept whole)\n" % os.path.basename(poly))
        for v, (x, y) in enumerate(Q):
            f.write("Point(%d) = {%.17g, %.17g, 0, %.17g};\n" % (v + 1, x, y, length[v] / max(count[v], 1)))
        line = 0
        loop_ids = []
        for i, l in enumerate(loops):
            ids = []
            for k in range(len(l)):
                line += 1
                f.write("Line(%d) = {%d, %d};\n" % (line, l[k] + 1, l[(k + 1) % len(l)] + 1))
                ids.append(line)
            f.write("Curve Loop(%d) = {%s};\n" % (i + 1, ", ".join(map(str, ids))))
            loop_ids.append(i + 1)
        others = [i + 1 for i in range(len(loops)) if i != outer]
        f.write("Plane Surface(1) = {%s};\n" % ", ".join(map(str, [outer + 1] + others)))
        f.write("Transfinite Curve {1:%d} = 2;\n" % line)
        f.write("Mesh.Algorithm = 6;\nGeneral.NumThreads = 1;\n")


def timed(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(["taskset", "-c", "0"] + cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError("%s failed: %s" % (cmd[0], (r.stdout + r.stderr)[-500:]))
    return dt, r.stdout + r.stderr


def check(mesh, poly, split):
    r = subprocess.run([sys.executable, CHECK, mesh, poly, "--json"] + (["--split"] if split else []),
                       capture_output=True, text=True)
    return json.loads(r.stdout)


def main():
    anitet, cgal, out = sys.argv[1], sys.argv[2], sys.argv[3]
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 7
    poly = sys.argv[5] if len(sys.argv) > 5 else os.path.join(HERE, "..", "..", "..", "shared", "data", "surfaces", "superior.poly")
    os.makedirs(out, exist_ok=True)
    geo = os.path.join(out, "superior.geo")
    write_geo(poly, geo)
    m = {k: os.path.join(out, k + ".mesh") for k in ("anitet", "gmsh", "cgal")}
    # CGAL's size bound: the one giving about anitet's triangle count (a short search).
    subprocess.run([anitet, "mesh2d", poly, "-o", m["anitet"], "-q"], check=True)
    target = check(m["anitet"], poly, False)["triangles"]
    lo, hi = 1e-4, 0.1
    for _ in range(20):
        mid = math.sqrt(lo * hi)
        subprocess.run([cgal, poly, m["cgal"], str(mid)], check=True, capture_output=True)
        n = check(m["cgal"], poly, True)["triangles"]
        lo, hi = (mid, hi) if n > target else (lo, mid)
    size_bound = math.sqrt(lo * hi)
    runs = {"anitet": [], "gmsh": [], "cgal": []}
    inner = {"anitet": [], "gmsh": [], "cgal": []}
    for _ in range(rounds):
        dt, text = timed([anitet, "mesh2d", poly, "-o", m["anitet"], "--json"])
        runs["anitet"].append(dt)
        inner["anitet"].append(json.loads(text)["seconds"])
        dt, text = timed(["gmsh", "-2", geo, "-o", m["gmsh"], "-format", "mesh", "-nt", "1"])
        runs["gmsh"].append(dt)
        g = re.search(r"Done meshing 2D \(Wall ([0-9.e-]+)s", text)
        inner["gmsh"].append(float(g.group(1)) if g else float("nan"))
        dt, text = timed([cgal, poly, m["cgal"], repr(size_bound)])
        runs["cgal"].append(dt)
        inner["cgal"].append(float(text.split()[-1]))
    quality = {"anitet": check(m["anitet"], poly, False), "gmsh": check(m["gmsh"], poly, False),
               "cgal": check(m["cgal"], poly, True)}
    res = {"input": os.path.basename(poly), "rounds": rounds, "cgal_size_bound": size_bound,
           "machine": {"cpu": platform.processor() or open("/proc/cpuinfo").read().split("model name")[1].split("\n")[0].strip(": "),
                       "cores": os.cpu_count(), "loadavg_after": os.getloadavg()},
           "versions": {"gmsh": subprocess.run(["gmsh", "--version"], capture_output=True, text=True).stderr.strip() or
                                subprocess.run(["gmsh", "--version"], capture_output=True, text=True).stdout.strip()},
           "tools": {}}
    for k in runs:
        q = quality[k]
        res["tools"][k] = {"process_seconds_median": statistics.median(runs[k]), "process_seconds": runs[k],
                           "mesher_seconds_median": statistics.median(inner[k]), "mesher_seconds": inner[k],
                           "triangles": q["triangles"], "vertices": q["vertices"],
                           "min_angle": q["min_angle"], "min_angle_no_input_point": q["min_angle_no_input_point"],
                           "mean_radius_ratio": q["mean_radius_ratio"], "min_radius_ratio": q["min_radius_ratio"],
                           "points_added_on_segments": q["points_on_segments_added"], "check_failures": q["failures"]}
    json.dump(res, open(os.path.join(out, "results.json"), "w"), indent=1)
    with open(os.path.join(out, "results.md"), "w") as f:
        f.write("| tool | triangles | process s (median) | mesher s (median) | min angle | min angle off input points | mean radius ratio | min radius ratio | points on segments | checks |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|\n")
        for k, t in res["tools"].items():
            f.write("| %s | %d | %.3f | %.3f | %.2f | %.2f | %.4f | %.4f | %d | %s |\n" % (
                k, t["triangles"], t["process_seconds_median"], t["mesher_seconds_median"], t["min_angle"],
                t["min_angle_no_input_point"], t["mean_radius_ratio"], t["min_radius_ratio"],
                t["points_added_on_segments"], "pass" if not t["check_failures"] else "; ".join(t["check_failures"])))
    print(open(os.path.join(out, "results.md")).read())
    print(json.dumps(res["machine"]))


if __name__ == "__main__":
    main()
