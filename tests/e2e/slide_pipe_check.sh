#!/usr/bin/env bash
# slide_pipe_check.sh ANITET CASES_PY MESHCHECK WORKDIR: a small pipe (r 1, length 4, 24 segments)
# meshed with 8 boundary layers on its wall sliding along the inlet and outlet; checks: every
# wall column full (JSON), the slide patches cover exactly the input's (slide_patch_check.py),
# meshcheck.py valid with no input triangle missing outside the slide patches; the transition
# figures on the 720 top faces; --bl-columns's CSV; and without --bl-slide-patches the run is
# refused with a message naming the option.
set -uo pipefail
anitet=$1 cases=$2 meshcheck=$3 work=$4
python=/usr/bin/python3
here=$(dirname "$0")
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
"$python" "$cases" pipe "$work/pipe.mesh" --segments 24 --length 4 || fail "cases.py failed"
out=$("$anitet" mesh "$work/pipe.mesh" -o "$work/none.mesh" --bl-patches 1 --bl-first-height 1e-3 2>&1); rc=$?
((rc == 2)) && grep -q -- "--bl-slide-patches 2" <<<"$out" || { echo "$out"; fail "without slide patches: exit $rc"; }
"$anitet" mesh "$work/pipe.mesh" -o "$work/out.mesh" --json --bl-patches 1 --bl-slide-patches 2,3 \
  --bl-first-height 1e-3 --bl-growth 1.15 --bl-layers 8 --bl-columns "$work/columns.csv" >"$work/run.json" ||
  fail "anitet mesh exited $?"
"$python" - "$work/run.json" "$work/columns.csv" <<'PY' || fail "report"
import json, sys
d = json.load(open(sys.argv[1]))
# --bl-columns: a line per wall vertex, 24 of them on each cap (the junction columns), all full.
rows = [line.strip().split(",") for line in open(sys.argv[2])]
assert rows[0] == ["x", "y", "z", "layers", "first_height", "total_height", "normal_share", "patches"], rows[0]
rows = rows[1:]
caps = sorted(r[7] for r in rows if r[7] != "1")
assert len(rows) == 384 and caps == ["1 2"] * 24 + ["1 3"] * 24, (len(rows), caps[:3])
assert all(r[3] == "8" and abs(float(r[5]) / (1e-3 * (1.15 ** 8 - 1) / 0.15) - 1) < 0.1 for r in rows)
# The columns stand on the wall (normal share near 1; 0.94 on the row next to the caps, leaning
# towards them).
assert min(float(r[6]) for r in rows) > 0.9, min(float(r[6]) for r in rows)
b, s = d["boundary_layer"], d["slide_patches"]
print(f"full columns {b['full_columns']}/{b['wall_vertices']}, nominal {b['nominal_columns']}, "
      f"non-orthogonality max {b['non_orthogonality_max']:.1f}, skewness max {b['skewness_max']:.2f}, "
      f"transition median {b['transition_ratio_median']:.1f} on {b['transition_faces']} faces, "
      f"slide patches {[(p['label'], p['triangles_before'], p['triangles_after']) for p in s['patches']]}")
ok = (b["full_columns"] == b["wall_vertices"] == 384 and b["nominal_columns"] == 384 and
      len(b["layer_height_mean"]) == 8 and abs(b["layer_height_mean"][7] / (1e-3 * 1.15 ** 7) - 1) < 0.1 and
      0 < b["non_orthogonality_max"] < 90 and b["dual_faces"] > 0 and
      # Every column full: the 720 wall triangles' top faces, under isotropic tets of about the
      # wall's size (0.26) over a top layer of 1e-3 1.15^7 = 2.7e-3.
      b["transition_faces"] == 720 and 20 < b["transition_ratio_median"] < 200 and
      b["transition_ratio_median"] <= b["transition_ratio_p90"] and b["transition_within_1_5"] == 0 and
      [p["label"] for p in s["patches"]] == [2, 3] and all(p["triangles_after"] > p["triangles_before"] for p in s["patches"]))
sys.exit(0 if ok else 1)
PY
"$python" "$here/slide_patch_check.py" "$work/pipe.mesh" "$work/out.mesh" 2,3 --kept "$work/kept.off" || fail "slide patches"
"$python" "$meshcheck" "$work/out.mesh" --surface "$work/kept.off" >"$work/meshcheck.json" || fail "meshcheck.py"
"$python" -c "
import json, sys; d = json.load(open('$work/meshcheck.json'))
sys.exit(0 if d['valid'] and d['input_triangles_missing'] == 0 else 1)" || fail "meshcheck: not valid or input triangles missing"
echo PASS
