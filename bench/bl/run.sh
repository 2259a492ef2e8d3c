#!/bin/bash
# bench/bl/run.sh ANITET OUTDIR [CASE...]: issue 48's boundary-layer cases side by side with the
# closed-wall airplane (examples/cfd, 5 and 15 layers), each run on one core (taskset -c 0), one
# after the other. Per case: tets, seconds, tets/s, the stages' seconds, full columns, the
# transition ratio at the layers' top (first interior tets' height over the BL tets', median) and,
# with OpenFOAM installed, checkMesh's verdict on the polyMesh with --bl-cells prisms. Writes
# OUTDIR/CASE.json (anitet's --json), OUTDIR/CASE.checkMesh.log, OUTDIR/CASE.columns.csv and the
# table OUTDIR/table.md. Cases: airplane5 airplane15 pipe hemisphere wing (default: all).
# Not run by CI (about 15 minutes on an idle core; Gmsh for the hemisphere and the wing).
# CORE=N: the core to run on (default 0).
# TABLE_ONLY=1: no run, the table from the files OUTDIR has.
set -u
anitet=$(realpath "${1:?usage: run.sh ANITET OUTDIR [CASE...]}")
out=$(mkdir -p "${2:?usage: run.sh ANITET OUTDIR [CASE...]}" && cd "$2" && pwd)
shift 2
cases=${*:-airplane5 airplane15 pipe hemisphere wing}
root=$(cd "$(dirname "$0")/../.." && pwd)
py=/usr/bin/python3
foam=/usr/share/openfoam/etc/bashrc

surface() {  # the case's domain surface in OUT
  case $1 in
    airplane*) [ -f "$out/airplane_in_box.mesh" ] ||
      $py "$root/examples/cfd/body_in_box.py" "$root/../shared/data/surfaces/airplane.obj" "$out/airplane_in_box.mesh" >/dev/null
      echo "$out/airplane_in_box.mesh" ;;
    pipe) $py "$root/examples/cfd/cases.py" pipe "$out/pipe.mesh" >/dev/null; echo "$out/pipe.mesh" ;;
    hemisphere) $py "$root/examples/cfd/cases.py" hemisphere "$out/hemi.msh" --size 0.025 >/dev/null; echo "$out/hemi.msh" ;;
    wing) $py "$root/examples/cfd/cases.py" wing "$out/wing.msh" --floor-size 0.1 >/dev/null; echo "$out/wing.msh" ;;
  esac
}
options() {  # the case's anitet mesh options (docs/boundary-layers.md)
  case $1 in
    airplane5) echo "--front-layers 2 --patch-names 1=wall,2=farfield --bl-patches 1 --bl-yplus 100 --bl-reynolds 5e6 --bl-ref-length 14.6868 --bl-layers 5 --bl-growth 1.2 --hgrad 1.3" ;;
    airplane15) echo "--front-layers 2 --patch-names 1=wall,2=farfield --bl-patches 1 --bl-first-height 0.0146868 --bl-layers 15 --bl-growth 1.2 --hgrad 1.3" ;;
    pipe) echo "--bl-patches 1 --bl-slide-patches 2,3 --bl-first-height 1e-3 --bl-growth 1.15 --bl-layers 20" ;;
    hemisphere) echo "--bl-patches 1 --bl-slide-patches 2 --bl-yplus 1 --bl-reynolds 1e6 --bl-ref-length 1 --bl-growth 1.15 --bl-layers 30" ;;
    wing) echo "--bl-patches 1,2 --bl-slide-patches 3,4,5 --bl-first-height 1e-4 --bl-growth 1.2 --bl-layers 20" ;;
  esac
}
checkmesh() {  # checkmesh CASE_DIR LOG: checkMesh on CASE_DIR/constant/polyMesh
  local c=$1
  mkdir -p "$c/system"
  printf 'FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\napplication checkMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\n' >"$c/system/controlDict"
  printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\nddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\ndivSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\ninterpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n' >"$c/system/fvSchemes"
  printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n' >"$c/system/fvSolution"
  (set +u; source "$foam" >/dev/null 2>&1; checkMesh -case "$c") >"$2" 2>&1
}

[ -n "${TABLE_ONLY:-}" ] ||
{ echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); anitet: $(cd "$root" && git rev-parse --short HEAD)"
  echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start; each run taskset -c ${CORE:-0}"; } >"$out/table.md"
for c in $cases; do
  [ -n "${TABLE_ONLY:-}" ] && break
  s=$(surface "$c")
  # shellcheck disable=SC2046
  taskset -c "${CORE:-0}" "$anitet" mesh "$s" -o "$out/$c/constant/polyMesh" --bl-cells prisms --bl-columns "$out/$c.columns.csv" \
    $(options "$c") --json >"$out/$c.json" 2>"$out/$c.err" || { echo "$c: anitet mesh exited $?"; continue; }
  verdict="(no OpenFOAM)"
  if [ -f "$foam" ]; then
    checkmesh "$out/$c" "$out/$c.checkMesh.log"
    verdict=$(grep -E "^Mesh OK\.|^Failed [0-9]+ mesh check" "$out/$c.checkMesh.log" | head -1)
    # The flagged checks (checkMesh marks them ***), shortened.
    verdict="$verdict$(grep -E '^ *\*\*\*' "$out/$c.checkMesh.log" | sed -E 's/^ *\*\*\*/; /; s/ (which may|detected).*//' | tr -d '\n')"
  fi
  echo "$c|$verdict" >>"$out/verdicts.txt"
  echo "$c done: $verdict (load $(cut -d' ' -f1 /proc/loadavg))"
done
[ -n "${TABLE_ONLY:-}" ] && sed -i '/^| /d; /^$/d' "$out/table.md"
$py - "$out" $cases <<'PY' >>"$out/table.md"
import json, sys, os
out = sys.argv[1]
verdicts = dict(l.rstrip("\n").split("|", 1) for l in open(os.path.join(out, "verdicts.txt")))
print("\n| case | valid | tets (prisms, pyramids written) | seconds | tets/s | layers / sizing / refine / optimize s | full columns | transition median (within 1.5) | checkMesh (prisms) |")
print("|---|---|---|---|---|---|---|---|---|")
for c in sys.argv[2:]:
    p = os.path.join(out, c + ".json")
    if not os.path.exists(p) or os.path.getsize(p) == 0:
        print(f"| {c} | failed | | | | | | | |")
        continue
    d = json.load(open(p))
    b = d["boundary_layer"]
    st = {s["stage"]: s["seconds"] for s in d["stages"]}
    tets = d["quality"]["tets"]
    stages = " / ".join(f"{st.get(k, 0):.1f}" for k in ("layers", "sizing", "refine", "optimize"))
    within = b["transition_within_1_5"] / max(b["transition_faces"], 1)
    valid = "yes" if d["quality"]["valid"] and d["quality"]["input_triangles_missing"] == 0 else "NO"
    print(f"| {c} | {valid} | {tets} ({b.get('prisms', 0)}, {b.get('pyramids', 0)}) | {d['seconds']:.1f} | {d['tets_per_second']:.0f} | {stages} | "
          f"{b['full_columns']} / {b['wall_vertices']} | {b['transition_ratio_median']:.1f} ({100 * within:.0f}%) | {verdicts.get(c, '')} |")
PY
cat "$out/table.md"
