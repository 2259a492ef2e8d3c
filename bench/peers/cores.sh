#!/usr/bin/env bash
# Issue 12's speed-up from one core to two, and the ratio to HXT with 2 threads, in alternated
# rounds on one input: anitet on one core (`taskset -c 0`: TBB then runs one thread), anitet on
# every core, Gmsh's HXT with 2 threads (keeping the surface); each line gives the wall times, the
# speed-up, each anitet run's CPU time (user+sys: equal CPU times mean two threads do no extra
# work; CPU over twice the wall time is the share of two cores the run kept busy), the load before
# the round and the stage times (`-v`); at the end, whether both anitet meshes are the same bytes.
#
#   bench/peers/cores.sh [-r ROUNDS] ANITET [SURFACE]
#
# SURFACE: a file name in ../shared/data/surfaces (default armadillo.obj); ROUNDS default 3.
# Outputs under out/bench-cores. Needs gmsh and meshio (bench/peers/run.sh installs both). Not
# run by CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
rounds=3
if [[ ${1:-} == -r ]]; then rounds=$2; shift 2; fi
anitet=${1:?usage: bench/peers/cores.sh [-r ROUNDS] ANITET [SURFACE]}
surface=${2:-armadillo.obj}
in=$root/../shared/data/surfaces/$surface
dir=$root/out/bench-cores/${surface%.*}
mkdir -p "$dir"
[[ -f $dir/surface.mesh ]] || /usr/bin/python3 "$root/bench/peers/to_medit.py" "$in" "$dir/surface.mesh"
printf 'Merge "surface.mesh";\nSurface Loop(1) = Surface{:};\nVolume(1) = {1};\nMesh.Algorithm3D = 10;\nGeneral.NumThreads = 2;\n' \
  > "$dir/hxt2.geo"
# wall LOG COMMAND...: runs it with its output in LOG, prints its wall seconds.
wall() { local log=$1 t0 t1; shift; t0=$(date +%s.%N); "$@" > "$log" 2>&1 || return 1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
# cpu TIMEFILE: the user+sys seconds /usr/bin/time wrote there.
cpu() { tail -1 "$1" | awk '{ print $1 + $2 }'; }
for ((r = 1; r <= rounds; ++r)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  t1=$(wall "$dir/one-$r.log" taskset -c 0 /usr/bin/time -f '%U %S' -o "$dir/one.time" "$anitet" mesh "$in" -o "$dir/one.mesh" -v)
  t2=$(wall "$dir/all-$r.log" /usr/bin/time -f '%U %S' -o "$dir/all.time" "$anitet" mesh "$in" -o "$dir/all.mesh" -v)
  th=$(wall "$dir/hxt2-$r.log" gmsh "$dir/hxt2.geo" -3 -format msh4 -o "$dir/hxt2.msh")
  stages() { grep -E 'stage (layers|recovery|coupling|refine|optimize):' "$1" | awk '{printf "%s%.2f ", $2, $3}'; }
  awk -v r="$r" -v a="$t1" -v b="$t2" -v h="$th" -v ca="$(cpu "$dir/one.time")" -v cb="$(cpu "$dir/all.time")" -v l="$load" \
    'BEGIN { printf "round %d (load %s): one core %.2f s (CPU %.2f s), all cores %.2f s (CPU %.2f s; %.2fx), HXT 2 threads %.2f s\n", r, l, a, ca, b, cb, a / b, h }'
  echo "  one core:  $(stages "$dir/one-$r.log")"
  echo "  all cores: $(stages "$dir/all-$r.log")"
done
echo "tets: anitet $(grep -o -E '[0-9]+ tets in' "$dir/all-$rounds.log" | cut -d' ' -f1), HXT $(grep -o -E '[0-9]+ tetrahedra' "$dir/hxt2-$rounds.log" | tail -1 | cut -d' ' -f1)"
if cmp -s "$dir/one.mesh" "$dir/all.mesh"; then echo "one core and all cores: the same mesh"; else echo "one core and all cores: DIFFERENT meshes"; fi
