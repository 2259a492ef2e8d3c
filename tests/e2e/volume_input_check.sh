#!/usr/bin/env bash
# volume_input_check.sh ANITET MESHCHECK INPUT.mesh WORKDIR
# A volume mesh as input (INPUT.mesh: tets whose interior vertices are numbered among the surface
# ones, boundary triangles with patch labels) meshed by `anitet mesh` to every output format:
#   - meshcheck.py (the independent checker) on .mesh, .msh and .vtu: valid, no file triangle
#     that is not a face of the tets, boundary constrained against INPUT;
#   - boundary_elements_check.py: every file read by other readers than anitet's (meshio, h5py,
#     netCDF4, an OpenFOAM parser), each boundary element a face, the boundary covered once, each
#     patch exactly the input's triangles of its label;
#   - OpenFOAM's checkMesh "Mesh OK." on the polyMesh and cgnscheck -w3 on the CGNS file.
set -uo pipefail
anitet=$1 meshcheck=$2 input=$3 work=$4
python=/usr/bin/python3
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"

outputs=("$work/x.mesh" "$work/x.msh" "$work/x.vtu" "$work/x.su2" "$work/case/constant/polyMesh")
args=(mesh "$input" -o "${outputs[0]}")
for o in "${outputs[@]:1}" "$work/x.cgns" "$work/x.exo"; do args+=(--also-write "$o"); done
"$anitet" "${args[@]}" -q || fail "anitet mesh exited $?"

for f in x.mesh x.msh x.vtu; do
  "$python" "$meshcheck" "$work/$f" --surface "$input" >"$work/$f.json" || fail "meshcheck.py on $f exited $?"
  "$python" - "$work/$f.json" "$f" <<'EOF' || fail "meshcheck.py: $f"
import json, sys
r = json.load(open(sys.argv[1]))
bad = {k: r[k] for k in ("file_triangles_not_tet_faces", "unused_vertices", "coincident_vertices", "input_triangles_missing")
       if r.get(k, 0) != 0}
print(f"meshcheck.py {sys.argv[2]}: valid {r['valid']}, boundary constrained {r['boundary_constrained']}, "
      f"file triangles not tet faces {r['file_triangles_not_tet_faces']}")
sys.exit(0 if r["valid"] and r["boundary_constrained"] and not bad else 1)
EOF
done

"$python" "$here/boundary_elements_check.py" "$input" "$work" || fail "boundary_elements_check.py"

# The real consumers.
mkdir -p "$work/case/system"
header() { printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n    object %s;\n}\n' "$1"; }
{ header controlDict
  printf 'application checkMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT 1;\n'
  printf 'writeControl timeStep;\nwriteInterval 1;\n'; } >"$work/case/system/controlDict"
{ header fvSchemes
  printf 'ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n'
  printf 'divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n'
  printf 'interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n'; } >"$work/case/system/fvSchemes"
header fvSolution >"$work/case/system/fvSolution"
bashrc=""
for f in /usr/share/openfoam/etc/bashrc /usr/lib/openfoam/openfoam*/etc/bashrc /opt/openfoam*/etc/bashrc; do
  [[ -f $f ]] && { bashrc=$f; break; }
done
[[ -n $bashrc ]] || fail "no OpenFOAM etc/bashrc found (Debian: openfoam, installed by scripts/setup.sh)"
(set +u; source "$bashrc" >/dev/null 2>&1; checkMesh -case "$work/case") >"$work/checkMesh.log" 2>&1 ||
  { tail -20 "$work/checkMesh.log"; fail "checkMesh exited $?"; }
grep -qx "Mesh OK." "$work/checkMesh.log" || { tail -30 "$work/checkMesh.log"; fail "checkMesh did not print 'Mesh OK.'"; }
echo "checkMesh: Mesh OK."
cgnscheck -w3 "$work/x.cgns" >"$work/cgnscheck.log" 2>&1 || { cat "$work/cgnscheck.log"; fail "cgnscheck exited $?"; }
grep -qx "checking complete" "$work/cgnscheck.log" || fail "cgnscheck did not complete"
! grep -Eiq "error|warning" "$work/cgnscheck.log" || { cat "$work/cgnscheck.log"; fail "cgnscheck reported errors or warnings"; }
echo "cgnscheck -w3: checking complete, no error or warning"
echo "PASS"
