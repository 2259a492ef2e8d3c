#!/usr/bin/env bash
# mesh_interior_gate.sh ANITET IN OUT TOUCH_MIN TOUCH_MAX_BAD [mesh options...]
# The issue-8 acceptance for inputs with poor triangles (angles down to 0.45 degrees, which no tet
# on them can hide): after mesh_and_check.sh's checks (valid, boundary constrained, volume kept),
# the tets not touching S must meet the thresholds of mesh_quality_gate.sh (radius ratio mean
# >= 0.75, min >= 0.15, good (> 0.4) >= 99%, bad (< 0.1) none, smallest dihedral >= 10 degrees),
# and the tets touching S must have a minimum radius ratio of at least TOUCH_MIN and at most
# TOUCH_MAX_BAD of them below 0.1: Gmsh HXT's figures on the same input (bench/peers/run.sh).
set -u
here=$(dirname "$0")
anitet=$1; in=$2; out=$3; touch_min=$4; touch_max_bad=$5; shift 5
"$here/mesh_and_check.sh" "$anitet" "$in" "$out" "$@" || exit 1
python3 - "$out.json" "$touch_min" "$touch_max_bad" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
touch_min, touch_max_bad = float(sys.argv[2]), int(sys.argv[3])
i, t = d["quality_interior"], d["quality_touching_surface"]
ri, rt = i["radius_ratio"], t["radius_ratio"]
bad_touching = round(t["bad_fraction_rr_lt_0.1"] * t["tets"])
print("interior: %d tets, radius ratio mean %.4f min %.4f, good %.4f, bad %g, min dihedral %.2f" % (
    i["tets"], ri["mean"], ri["min"], i["good_fraction_rr_gt_0.4"], i["bad_fraction_rr_lt_0.1"], i["min_dihedral_deg"]))
print("touching S: %d tets, radius ratio min %.6f (bar %g), %d below 0.1 (bar %d)" % (
    t["tets"], rt["min"], touch_min, bad_touching, touch_max_bad))
ok = (ri["mean"] >= 0.75 and ri["min"] >= 0.15 and i["good_fraction_rr_gt_0.4"] >= 0.99 and
      i["bad_fraction_rr_lt_0.1"] == 0 and i["min_dihedral_deg"] >= 10 and
      rt["min"] >= touch_min and bad_touching <= touch_max_bad)
print("PASS: thresholds met" if ok else "FAIL: below the acceptance thresholds")
sys.exit(0 if ok else 1)
PY
