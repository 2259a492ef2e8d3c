#!/usr/bin/env bash
# mesh_quality_gate.sh ANITET IN OUT [--interior TOUCH_MIN TOUCH_MAX_BAD] [mesh options...]
# The issue-8 acceptance thresholds: after mesh_and_check.sh's checks (valid, boundary
# constrained, volume kept), `anitet quality --json` must report radius ratio mean >= 0.75 and
# min >= 0.15, good (> 0.4) >= 99%, bad (< 0.1) = 0 and the smallest dihedral angle >= 10 degrees:
#   - for all tets, on inputs whose triangles are of good shape;
#   - with --interior, for the tets not touching S, on inputs with poor triangles (angles down to
#     0.45 degrees, which no tet on them can hide); the tets touching S must then have a minimum
#     radius ratio of at least TOUCH_MIN and at most TOUCH_MAX_BAD of them below 0.1: Gmsh HXT's
#     figures on the same input (bench/peers/run.sh).
set -u
here=$(dirname "$0")
anitet=$1; in=$2; out=$3; shift 3
part=all; touch_min=0; touch_max_bad=0
if [[ ${1:-} == --interior ]]; then part=interior; touch_min=$2; touch_max_bad=$3; shift 3; fi
"$here/mesh_and_check.sh" "$anitet" "$in" "$out" "$@" || exit 1
python3 - "$out.json" "$part" "$touch_min" "$touch_max_bad" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
part, touch_min, touch_max_bad = sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
q = d["quality"] if part == "all" else d["quality_interior"]
rr = q["radius_ratio"]
print("%s: radius ratio mean %.4f min %.4f, good %.4f, bad %g, min dihedral %.2f" % (
    "all tets" if part == "all" else "tets off S", rr["mean"], rr["min"], q["good_fraction_rr_gt_0.4"],
    q["bad_fraction_rr_lt_0.1"], q["min_dihedral_deg"]))
ok = (rr["mean"] >= 0.75 and rr["min"] >= 0.15 and q["good_fraction_rr_gt_0.4"] >= 0.99 and
      q["bad_fraction_rr_lt_0.1"] == 0 and q["min_dihedral_deg"] >= 10)
if part == "interior":
    t = d["quality_touching_surface"]
    bad_touching = round(t["bad_fraction_rr_lt_0.1"] * t["tets"])
    print("tets touching S: %d, radius ratio min %.7f (bar %g), %d below 0.1 (bar %d)" % (
        t["tets"], t["radius_ratio"]["min"], touch_min, bad_touching, touch_max_bad))
    ok = ok and t["radius_ratio"]["min"] >= touch_min and bad_touching <= touch_max_bad
print("PASS: quality thresholds met" if ok else "FAIL: below the acceptance thresholds")
sys.exit(0 if ok else 1)
PY
