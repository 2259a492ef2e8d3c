#!/usr/bin/env bash
# Issue 46's acceptance runs: UGAWG loops of `anitet adapt` and Mmg, one core each (taskset -c 0
# inside ugawg.py), one after the other in this script, measured by the shared ugawg.py.
#   ANITET=build/app/anitet MMG=/path/to/mmg3d_O3 [ROUNDS=3] bench/adapt/ugawg_vs_mmg.sh [OUTDIR] [--sphere]
# Runs: linear 5 passes (anitet, then Mmg; ROUNDS times alternating, default 1), linear 5 passes
# --keep-surface (anitet: the share of edges with no end on the surface; SKIP_KEEP=1 skips it),
# and with --sphere the curved case (make_sphere_case.py, its start mesh by `anitet mesh`, 5
# passes of anitet then Mmg, sphere_surface.py's surface figures of anitet's meshes and
# sphere_classes.py's classes of the misses of its last, in OUTDIR/sphere-anitet-classes.md). Prints the
# JSON lines of ugawg.py; writes them to OUTDIR/*.jsonl.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
anitet=${ANITET:-$here/../../build/app/anitet}
mmg=${MMG:?set MMG to an mmg3d_O3 binary}
tools=${TOOLS:-/work/shared/tools}
data=${UGAWG:-/work/shared/data/ugawg}
out=${1:-/tmp/ugawg-bench}; sphere=${2:-}
python=/usr/bin/python3
mkdir -p "$out"
echo "# $(date -u +%FT%TZ) $(uname -n), load: $(cut -d' ' -f1-3 /proc/loadavg), anitet $(git -C "$here" rev-parse --short HEAD)"
run() {  # NAME ugawg-args...
  local name=$1; shift
  "$python" "$tools/ugawg.py" "$@" | tee "$out/$name.jsonl"
}
for r in $(seq "${ROUNDS:-1}"); do
  run linear-anitet-$r "anitet:$anitet" "$data/cube-linear-00.mesh" linear 5
  run linear-mmg-$r "mmg:$mmg" "$data/cube-linear-00.mesh" linear 5
done
[[ ${SKIP_KEEP:-} ]] || run linear-keep-surface-anitet "anitet:$anitet" "$data/cube-linear-00.mesh" linear 5 --keep-surface
if [[ $sphere == --sphere ]]; then
  "$python" "$here/make_sphere_case.py" "$out/sphere-surface.mesh"
  "$anitet" mesh "$out/sphere-surface.mesh" -o "$out/sphere-start.mesh" -q
  "$python" "$here/sphere_surface.py" "$out/sphere-start.mesh" | tee "$out/sphere-start-surface.jsonl"
  before=$(ls -d /tmp/ugawg-* 2>/dev/null | sort)
  run sphere-anitet "anitet:$anitet" "$out/sphere-start.mesh" sphere 5
  work=$(comm -13 <(echo "$before") <(ls -d /tmp/ugawg-* | sort) | head -1)  # ugawg.py's work directory
  "$python" "$here/sphere_surface.py" "$work"/p[1-5].mesh | tee "$out/sphere-anitet-surface.jsonl"
  TOOLS=$tools "$python" "$here/sphere_classes.py" "$work/p5.mesh" > "$out/sphere-anitet-classes.md"  # the misses by class
  run sphere-mmg "mmg:$mmg" "$out/sphere-start.mesh" sphere 5
fi
