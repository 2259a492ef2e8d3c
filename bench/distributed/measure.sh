#!/usr/bin/env bash
# The per-rank costs of docs/distributed.md's design model, measured on one core (taskset -c 0,
# --threads 1), one run at a time:
#  - stages 1-2 (layers, recovery, coupling): `anitet mesh --no-refine --no-optimize` per surface;
#    seconds per stage, coupled tets and peak resident memory (GNU time), per surface triangle;
#  - stages 3b/3c: full `anitet mesh` runs (SURFACE:SIZE); tets, estimated tets (the sizing field's
#    prediction on the coupled mesh, estimate_refined_tets), refine/optimize seconds, peak memory,
#    bytes and microseconds per final tet.
# bench/distributed/model.py takes its constants from these tables (the measured figures are in
# bench/results/distributed/*-design-model.md).
#
#   bench/distributed/measure.sh [-o OUTDIR] [--stages12 SURFACE ...] [--full SURFACE:SIZE ...]
#
# OUTDIR (default out/bench-distributed) gets results.txt (overwritten by each call) and the runs'
# JSON, stderr and GNU time figures.
#
# SURFACE: a path, or a file name without its extension in DATA (kitten, armadillo, ...);
# 'NAME@4' is NAME split 1-to-4 (every triangle into four at its edge midpoints: the same shape,
# four times the triangles), written to OUTDIR. Needs GNU time, taskset, meshio and NumPy.
# Environment: ANITET (default build/app/anitet), DATA (default ../shared/data/surfaces from the
# checkout).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/out/bench-distributed
anitet=${ANITET:-$root/build/app/anitet}
data=${DATA:-$root/../shared/data/surfaces}
py=/usr/bin/python3
stages12=() full=() mode=""
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -o) out=$2; shift 2 ;;
    --stages12) mode=s; shift ;;
    --full) mode=f; shift ;;
    *) if [[ $mode == s ]]; then stages12+=("$1"); elif [[ $mode == f ]]; then full+=("$1");
       else echo "usage: $0 [-o OUTDIR] [--stages12 SURFACE ...] [--full SURFACE:SIZE ...]" >&2; exit 2; fi; shift ;;
  esac
done
if [[ ${#stages12[@]} -eq 0 && ${#full[@]} -eq 0 ]]; then
  echo "usage: $0 [-o OUTDIR] [--stages12 SURFACE ...] [--full SURFACE:SIZE ...] (--help)" >&2
  exit 2
fi
mkdir -p "$out"

# The path of SURFACE, splitting NAME@4 when asked.
surface_path() {
  local s=$1 name=${1%@4}
  local src=$name
  [[ -f $src ]] || src=$(ls "$data/$name".* 2>/dev/null | head -1)
  [[ -f $src ]] || { echo "no surface $name" >&2; exit 1; }
  if [[ $s == *@4 ]]; then
    local dst=$out/$(basename "${src%.*}")-split4.off
    [[ -f $dst ]] || "$py" - "$src" "$dst" <<'PY'
import sys
import meshio
import numpy as np
m = meshio.read(sys.argv[1])
p = m.points.astype(float)
t = m.cells_dict["triangle"].astype(np.int64)
# One midpoint per edge, shared by its two triangles.
e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
uniq, inv = np.unique(e, axis=0, return_inverse=True)
inv = inv.reshape(-1)
mid = len(p) + inv.reshape(3, -1).T  # per triangle: midpoints of edges 01, 12, 20
pts = np.vstack([p, 0.5 * (p[uniq[:, 0]] + p[uniq[:, 1]])])
a, b, c = t[:, 0], t[:, 1], t[:, 2]
ab, bc, ca = mid[:, 0], mid[:, 1], mid[:, 2]
tris = np.vstack([np.c_[a, ab, ca], np.c_[ab, b, bc], np.c_[ca, bc, c], np.c_[ab, bc, ca]])
with open(sys.argv[2], "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(pts), len(tris)))
    np.savetxt(f, pts, fmt="%.17g")
    np.savetxt(f, np.c_[np.full(len(tris), 3), tris], fmt="%d")
PY
    echo "$dst"
  else
    echo "$src"
  fi
}

# One run on core 0 with one thread: JSON to $1.json; peak KB, wall, user and system seconds to
# $1.rss. The machine is shared: cpu% (user + system over wall) says how much of core 0 the run
# got, and the stage seconds (wall) are scaled by it in model.py's constants.
run() {
  local stem=$1; shift
  /usr/bin/time -f '%M %e %U %S' -o "$stem.rss" taskset -c 0 "$anitet" mesh "$@" --threads 1 -v --json > "$stem.json" 2> "$stem.err"
}

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "anitet: $("$anitet" --version 2>/dev/null | head -1) ($anitet)"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores; memory: $(free -g | awk '/^Mem:/ {print $2}') GB; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$out/results.txt"

if [[ ${#stages12[@]} -gt 0 ]]; then
  echo "stages 1-2 (--no-refine --no-optimize), one core:" | tee -a "$out/results.txt"
  printf '%-22s %9s %8s %8s %8s %8s %9s %8s %9s %9s %s\n' surface triangles layers_s recov_s coupl_s s12_s coupled_t peak_MB us/tri KB/tri cpu% |
    tee -a "$out/results.txt"
  for s in "${stages12[@]}"; do
    path=$(surface_path "$s")
    stem=$out/s12-$(basename "${path%.*}")
    run "$stem" "$path" -o "$stem.mesh" --no-refine --no-optimize || { echo "$s failed: $stem.err" | tee -a "$out/results.txt"; continue; }
    rm -f "$stem.mesh"
    "$py" - "$stem.json" "$(tail -1 "$stem.rss")" "$(basename "$path")" <<'PY' | tee -a "$out/results.txt"
import json, sys
d = json.load(open(sys.argv[1]))
kb, wall, user, system = (float(x) for x in sys.argv[2].split())
cpu = 100 * (user + system) / wall
tri = d["quality"]["input_triangles"]
sec = {}
for st in d["stages"]:
    key = st["stage"].split(" ")[0]
    sec[key] = sec.get(key, 0.0) + st["seconds"]
coupled = [st["tets"] for st in d["stages"] if st["stage"].startswith("coupling")][-1]
s12 = sec.get("layers", 0) + sec.get("recovery", 0) + sec.get("coupling", 0)
print("%-22s %9d %8.2f %8.2f %8.2f %8.2f %9d %8.0f %9.1f %9.2f %3.0f" % (
    sys.argv[3], tri, sec.get("layers", 0), sec.get("recovery", 0), sec.get("coupling", 0), s12, coupled,
    kb / 1024, 1e6 * s12 / tri, kb / tri, cpu))
PY
  done
fi

if [[ ${#full[@]} -gt 0 ]]; then
  echo "full runs (stages 1-3c), one core:" | tee -a "$out/results.txt"
  printf '%-22s %5s %9s %10s %10s %9s %8s %8s %8s %8s %9s %s\n' surface size coupled_t estimated tets sizing_s refine_s optim_s peak_MB B/tet us/tet cpu% |
    tee -a "$out/results.txt"
  for sz in "${full[@]}"; do
    s=${sz%%:*} size=${sz##*:}
    path=$(surface_path "$s")
    stem=$out/full-$(basename "${path%.*}")-$size
    run "$stem" "$path" -o "$stem.mesh" --size "$size" || { echo "$sz failed: $stem.err" | tee -a "$out/results.txt"; continue; }
    rm -f "$stem.mesh"
    "$py" - "$stem.json" "$(tail -1 "$stem.rss")" "$(basename "$path")" "$size" <<'PY' | tee -a "$out/results.txt"
import json, sys
d = json.load(open(sys.argv[1]))
kb, wall, user, system = (float(x) for x in sys.argv[2].split())
cpu = 100 * (user + system) / wall
sec = {}
for st in d["stages"]:
    key = st["stage"].split(" ")[0]
    sec[key] = sec.get(key, 0.0) + st["seconds"]
coupled = [st["tets"] for st in d["stages"] if st["stage"].startswith("coupling")][-1]
tets = d["quality"]["tets"]
r, o = sec.get("refine", 0), sec.get("optimize", 0)
print("%-22s %5s %9d %10.0f %10d %9.2f %8.2f %8.2f %8.0f %8.0f %9.2f %3.0f" % (
    sys.argv[3], sys.argv[4], coupled, d["estimated_tets"], tets, sec.get("sizing", 0), r, o, kb / 1024,
    kb * 1024 / tets, 1e6 * (r + o) / tets, cpu))
PY
  done
fi
