#!/usr/bin/env bash
# solver_consumers.sh TOOL ANITET SURFACE WORKDIR PATCHES -- [anitet mesh options...]
# Meshes SURFACE with `anitet mesh` and has the real consumer read the result:
#   openfoam  CASE/constant/polyMesh, then OpenFOAM's checkMesh on CASE: "Mesh OK.", points and
#             cells as anitet printed, each patch with its name and face count
#   cgns      x.cgns, then cgnscheck -w3: "checking complete", no error and no warning line
#   meshio    x.su2, x.cgns, x.exo read by meshio (points, tets, triangles as anitet printed);
#             the names and per-patch counts read back from each file (SU2 MARKER_TAG lines,
#             CGNS nodes through h5py, Exodus side sets through netCDF4)
# PATCHES: NAME=FACES,... the patches expected (names as given to --patch-names, faces = the
# input's triangles of that label). Exits 77 (ctest SKIP_RETURN_CODE) when the consumer is not
# installed or anitet was built without the format's library; 0 when all checks pass.
set -uo pipefail
tool=$1 anitet=$2 surface=$3 work=$4 patches=$5
shift 5
[[ ${1:-} == "--" ]] && shift
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

python=/usr/bin/python3
case $tool in
  openfoam) command -v checkMesh >/dev/null || skip "OpenFOAM's checkMesh is not installed (Debian: openfoam)" ;;
  cgns) command -v cgnscheck >/dev/null || skip "cgnscheck is not installed (Debian: cgns-convert)" ;;
  meshio)
    "$python" -c 'import meshio, h5py, netCDF4' 2>/dev/null ||
      skip "$python lacks meshio, h5py or netCDF4 (Debian: python3-meshio python3-h5py python3-netcdf4)" ;;
  *) fail "unknown tool '$tool'" ;;
esac

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
# Runs anitet mesh to $1; sets nv and nt from its summary line. Exit 5 (not built with the
# format's library) is a skip.
mesh_to() {
  local dest=$1 out rc
  shift
  out=$("$anitet" mesh "$surface" -o "$dest" "$@" 2>&1); rc=$?
  printf '%s\n' "$out" | grep -E "^anitet mesh: .* -> " || true
  if ((rc == 5)); then printf '%s\n' "$out" | tail -3; skip "anitet was not built with this format's library"; fi
  ((rc == 0)) || { printf '%s\n' "$out" | tail -20; fail "anitet mesh exited $rc"; }
  read -r nv nt < <(printf '%s\n' "$out" | sed -nE 's/^anitet mesh: .* -> .*: ([0-9]+) vertices, ([0-9]+) tets in .*/\1 \2/p')
  [[ -n ${nt:-} ]] || fail "no 'N vertices, M tets' line in anitet's output"
}

case $tool in
  openfoam)
    case_dir=$work/case
    mesh_to "$case_dir/constant/polyMesh" "$@"
    mkdir -p "$case_dir/system"
    header() { printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n    object %s;\n}\n' "$1"; }
    { header controlDict
      printf 'application checkMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT 1;\n'
      printf 'writeControl timeStep;\nwriteInterval 1;\n'; } >"$case_dir/system/controlDict"
    { header fvSchemes
      printf 'ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n'
      printf 'divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n'
      printf 'interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n'; } >"$case_dir/system/fvSchemes"
    header fvSolution >"$case_dir/system/fvSolution"
    # Debian's openfoam puts checkMesh on PATH; its etc/bashrc sets WM_PROJECT_DIR (where
    # checkMesh finds etc/controlDict). Other installs: the first openfoam*/etc/bashrc found.
    bashrc=""
    for f in /usr/share/openfoam/etc/bashrc /usr/lib/openfoam/openfoam*/etc/bashrc /opt/openfoam*/etc/bashrc; do
      [[ -f $f ]] && { bashrc=$f; break; }
    done
    [[ -n $bashrc ]] || skip "no OpenFOAM etc/bashrc found"
    log=$work/checkMesh.log
    # The bashrc reads unset variables: not under set -u.
    (set +u; source "$bashrc" >/dev/null 2>&1; checkMesh -case "$case_dir") >"$log" 2>&1
    rc=$?
    sed -n '/^Mesh stats/,$p' "$log"
    ((rc == 0)) || { tail -30 "$log"; fail "checkMesh exited $rc"; }
    grep -qx "Mesh OK." "$log" || fail "checkMesh did not print 'Mesh OK.'"
    grep -Eq "^ +points: +$nv\$" "$log" || fail "checkMesh does not count $nv points"
    grep -Eq "^ +cells: +$nt\$" "$log" || fail "checkMesh does not count $nt cells"
    grep -Eq "^ +tetrahedra: +$nt\$" "$log" || fail "checkMesh does not count $nt tetrahedra"
    IFS=, read -ra list <<<"$patches"
    grep -Eq "^ +boundary patches: +${#list[@]}\$" "$log" || fail "checkMesh does not count ${#list[@]} patches"
    for p in "${list[@]}"; do
      name=${p%%=*} faces=${p#*=}
      grep -Eq "^ +$name +$faces +[0-9]+ +ok" "$log" || fail "checkMesh does not list patch $name with $faces faces, ok"
    done
    echo "PASS: checkMesh: Mesh OK., $nv points, $nt cells, patches $patches"
    ;;
  cgns)
    mesh_to "$work/x.cgns" "$@"
    log=$work/cgnscheck.log
    cgnscheck -w3 "$work/x.cgns" >"$log" 2>&1
    rc=$?
    cat "$log"
    ((rc == 0)) || fail "cgnscheck exited $rc"
    grep -qx "checking complete" "$log" || fail "cgnscheck did not complete"
    ! grep -Eiq "error|warning" "$log" || fail "cgnscheck reported errors or warnings"
    IFS=, read -ra list <<<"$patches"
    for p in "${list[@]}"; do
      grep -q "checking BC \"${p%%=*}\"" "$log" || fail "cgnscheck did not check the BC ${p%%=*}"
    done
    echo "PASS: cgnscheck -w3: checking complete, no error or warning; BCs ${patches}"
    ;;
  meshio)
    mesh_to "$work/x.su2" "$@"
    nv_su2=$nv nt_su2=$nt
    mesh_to "$work/x.cgns" "$@"
    mesh_to "$work/x.exo" "$@"
    [[ $nv == "$nv_su2" && $nt == "$nt_su2" ]] || fail "the three runs gave different meshes ($nv_su2/$nt_su2, $nv/$nt)"
    "$python" - "$work" "$nv" "$nt" "$patches" <<'EOF' || fail "a check on the files failed"
import sys, warnings
import numpy as np
import meshio, h5py, netCDF4
warnings.simplefilter("ignore")
work, nv, nt = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
patches = [(p.split("=")[0], int(p.split("=")[1])) for p in sys.argv[4].split(",")]
nb = sum(n for _, n in patches)

def count(m, kind):
    return sum(len(c.data) for c in m.cells if c.type == kind)

for ext, tris in (("su2", nb), ("cgns", 0), ("exo", 0)):
    m = meshio.read(f"{work}/x.{ext}")
    got = (len(m.points), count(m, "tetra"), count(m, "triangle"))
    print(f"meshio {ext}: {got[0]} points, {got[1]} tetra, {got[2]} triangles")
    # meshio reads the CGNS GridElements section and the Exodus blocks only (no boundary sections)
    assert got == (nv, nt, tris), (ext, got, (nv, nt, tris))

# SU2: the markers in order, with their counts
markers, lines = [], open(f"{work}/x.su2").read().split("\n")
for i, line in enumerate(lines):
    if line.startswith("MARKER_TAG= "):
        markers.append((line[12:], int(lines[i + 1].split("=")[1])))
print("su2 markers:", markers)
assert markers == patches, markers

# CGNS (HDF5): one TRI_3 section and one BC per patch, the BC's range the section's
f = h5py.File(f"{work}/x.cgns", "r")
zone = f["Base"]["Zone1"]
found = []
for name, n in patches:
    rng = zone[name]["ElementRange"][" data"][:]
    found.append((name, int(rng[1] - rng[0] + 1)))
    bc = zone["ZoneBC"][name]
    assert (bc["PointRange"][" data"][:].ravel() == rng).all(), (name, rng)
print("cgns sections and BCs:", found)
assert found == patches, found

# Exodus (netCDF): side-set names and sizes, the element blocks' total
nc = netCDF4.Dataset(f"{work}/x.exo")
def names(var):
    v = nc.variables[var]
    v.set_auto_mask(False)
    return [b"".join(c).decode().rstrip("\x00") for c in v[:]]
ss = [(n, len(nc.dimensions[f"num_side_ss{i + 1}"])) for i, n in enumerate(names("ss_names"))]
print("exodus side sets:", ss, "blocks:", names("eb_names"))
assert ss == patches, ss
assert sum(len(nc.dimensions[f"num_el_in_blk{i + 1}"]) for i in range(len(nc.dimensions["num_el_blk"]))) == nt
print(f"PASS: meshio read .su2/.cgns/.exo ({nv} points, {nt} tets); names and counts {patches}")
EOF
    ;;
esac
