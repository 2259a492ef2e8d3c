#!/usr/bin/env bash
# anitet against Gmsh (HXT with 1 and 2 threads, and its default 3D Delaunay, all keeping the
# surface) and TetGen (-pq1.414Y), back to back on each input, every output checked by
# ../shared/tools/meshcheck.py; then bench/peers/table.py writes the tables.
#
#   bench/peers/run.sh [-o OUTDIR] [SURFACE ...]
#
# SURFACE: file names in ../shared/data/surfaces or paths (default: the nine below). OUTDIR
# (default out/bench-peers) gets one directory per surface with every mesher's output, log,
# time and meshcheck verdict, and results.md / results.html / results.json. Not run by CI.
# Environment: TIMEOUT (seconds per run, default 600), BUILD_DIR (anitet's build, default build/).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/out/bench-peers
if [[ ${1:-} == "-o" ]]; then out=$2; shift 2; fi
surfaces=("$@")
[[ ${#surfaces[@]} -gt 0 ]] || surfaces=(decimated-knight.off femur.off casting.off bimba_low.off kitten.off
                                         elephant.obj fandisk.off airplane.obj rocker-arm.obj)
shared=$root/../shared
timeout_s=${TIMEOUT:-600}

# What it needs: anitet's dependencies and build, the peers, meshcheck's Python modules.
"$root/scripts/setup.sh"
missing=()
for p in gmsh tetgen; do command -v "$p" >/dev/null || missing+=("$p"); done
if [[ ${#missing[@]} -gt 0 ]]; then
  sudo=""; [[ $(id -u) == 0 ]] || sudo=sudo
  $sudo apt-get install -y "${missing[@]}"
fi
build=${BUILD_DIR:-$root/build}
if [ -f "$build/CMakeCache.txt" ]; then "$root/scripts/build.sh"; else "$root/scripts/build.sh" -DANITET_BUILD_TESTS=OFF; fi
anitet=$build/app/anitet
py=python3; $py -c 'import numpy, meshio' 2>/dev/null || py=/usr/bin/python3

mkdir -p "$out"
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "anitet: $(cd "$root" && git describe --always --dirty 2>/dev/null || echo unknown)"
  echo "gmsh: $(gmsh --version 2>&1 | head -1)"
  echo "tetgen: $(dpkg-query -W -f='${Version}' tetgen 2>/dev/null || echo unknown)"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores"
  echo "memory: $(free -g | awk '/^Mem:/ {print $2}') GB"
  echo "os: $(. /etc/os-release && echo "$PRETTY_NAME")"
} > "$out/machine.txt"
cat "$out/machine.txt"

# run NAME DIR COMMAND...: times COMMAND (wall seconds and peak memory), keeps its log and status.
run() {
  local name=$1 dir=$2; shift 2
  local t0 t1 rc=0
  t0=$(date +%s.%N)
  /usr/bin/time -f '%M' -o "$dir/$name.rss" timeout "$timeout_s" "$@" > "$dir/$name.log" 2>&1 || rc=$?
  t1=$(date +%s.%N)
  echo "$rc" > "$dir/$name.rc"
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }' > "$dir/$name.seconds"
  printf '  %-14s exit %-3s %8s s\n' "$name" "$rc" "$(cat "$dir/$name.seconds")"
}

# check NAME DIR MESH SURFACE: meshcheck.py's verdict as NAME.json (absent: no mesh).
check() {
  local name=$1 dir=$2 mesh=$3 surface=$4
  rm -f "$dir/$name.json"
  [[ $(cat "$dir/$name.rc") == 0 && -s $mesh ]] || return 0
  $py "$shared/tools/meshcheck.py" "$mesh" --surface "$surface" > "$dir/$name.json" 2> "$dir/$name.check.log" ||
    rm -f "$dir/$name.json"
}

for s in "${surfaces[@]}"; do
  surface=$s; [[ -f $surface ]] || surface=$shared/data/surfaces/$s
  [[ -f $surface ]] || { echo "no surface '$s'" >&2; exit 2; }
  stem=$(basename "${surface%.*}")
  dir=$out/$stem
  rm -rf "$dir"; mkdir -p "$dir"
  echo "$stem:"
  # Gmsh and TetGen read the surface as a double-precision Medit file (binary STL is float32
  # already, so the copy is exact); anitet reads the original.
  "$anitet" check-surface "$surface" > /dev/null || { echo "  invalid surface, skipped"; continue; }
  $py "$root/bench/peers/to_medit.py" "$surface" "$dir/surface.mesh" || { echo "  cannot convert it for the peers, skipped"; continue; }
  run anitet "$dir" "$anitet" mesh "$surface" -o "$dir/anitet.mesh"
  check anitet "$dir" "$dir/anitet.mesh" "$surface"
  for variant in hxt1:10:1 hxt2:10:2 delaunay:1:1; do
    IFS=: read -r name algo threads <<<"$variant"
    printf 'Merge "surface.mesh";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\nMesh.Algorithm3D = %s;\nGeneral.NumThreads = %s;\n' \
      "$algo" "$threads" > "$dir/$name.geo"
    run "gmsh-$name" "$dir" gmsh "$dir/$name.geo" -3 -format msh4 -o "$dir/gmsh-$name.msh"
    check "gmsh-$name" "$dir" "$dir/gmsh-$name.msh" "$surface"
  done
  cp "$dir/surface.mesh" "$dir/tg.mesh"
  run tetgen "$dir" tetgen -pq1.414YQ "$dir/tg.mesh"
  check tetgen "$dir" "$dir/tg.1.ele" "$surface"
done

$py "$root/bench/peers/table.py" "$out" "${surfaces[@]}"
echo "tables: $out/results.md $out/results.html"
