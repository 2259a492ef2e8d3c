#!/usr/bin/env bash
# Issue 11's scale run: one surface, the unit sphere (Gmsh -2 with size 0.04: about 19,000
# triangles), meshed by anitet at three global sizes that give about 1e5, 1e6 and 1e7 tets
# (`--size` 2.0, 0.9 and 0.42 by default). Per run: tets, the pipeline's seconds (anitet's own
# figure, without reading, writing and the report) and the wall seconds, the peak resident memory
# (GNU time), bytes per tet at that peak, and the pipeline's seconds per n log2 n relative to the
# first run (1.0: time grows as n log n; below: slower growth). Each mesh is checked by anitet's
# own quality report (validity and boundary preservation against the sphere) and then deleted.
#
#   bench/scale/run.sh [-o OUTDIR] [SIZE ...]
#
# OUTDIR defaults to out/bench-scale; results.txt there. Not run by CI (the 1e7 run takes
# minutes and about 2 GB). Environment: BUILD_DIR (anitet's build, default build/).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/out/bench-scale
if [[ ${1:-} == "-o" ]]; then out=$2; shift 2; fi
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(2.0 0.9 0.42)
"$root/scripts/setup.sh" gmsh time
build=${BUILD_DIR:-$root/build}
if [ -f "$build/CMakeCache.txt" ]; then "$root/scripts/build.sh"; else "$root/scripts/build.sh" -DANITET_BUILD_TESTS=OFF; fi
anitet=$build/app/anitet
"$root/bench/peers/unit_sphere.sh" "$out" 0.04
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "anitet: $(cd "$root" && git describe --always --dirty 2>/dev/null || echo unknown)"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores; memory: $(free -g | awk '/^Mem:/ {print $2}') GB"
  printf '%-6s %10s %10s %10s %10s %10s %12s %s\n' size tets pipeline_s wall_s peak_MB bytes/tet s/nlogn_rel verdict
} | tee "$out/results.txt"
first=""
for s in "${sizes[@]}"; do
  log=$out/size-$s.log
  t0=$(date +%s.%N)
  rc=0
  /usr/bin/time -f '%M' -o "$out/size-$s.rss" "$anitet" mesh "$out/sphere.off" -o "$out/size-$s.mesh" --size "$s" > "$log" 2>&1 || rc=$?
  t1=$(date +%s.%N)
  rm -f "$out/size-$s.mesh"
  if [[ $rc != 0 ]]; then
    printf '%-6s failed (exit %s), see %s\n' "$s" "$rc" "$log" | tee -a "$out/results.txt"
    continue
  fi
  # "anitet mesh: IN -> OUT: V vertices, T tets in TIME (...)", TIME as "12.3 s", "2 min 24 s" or
  # "1 h 02 min" (the summary's format_seconds).
  read -r tets secs < <(sed -n 's/^anitet mesh: .*: [0-9]* vertices, \([0-9]*\) tets in \(.*\) (.*/\1 \2/p' "$log" |
    awk '{ s = 0; for (i = 3; i <= NF; ++i) s += $(i - 1) * ($i == "h" ? 3600 : $i == "min" ? 60 : $i == "s" ? 1 : 0); print $1, s }')
  verdict=$(grep -q "^  surface kept exactly: YES" "$log" && grep -q "^  valid: YES" "$log" && echo "valid, boundary constrained" || echo "NOT VALID or surface lost")
  kb=$(cat "$out/size-$s.rss")
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
  per=$(awk -v n="$tets" -v t="$secs" 'BEGIN { printf "%.6e", t / (n * log(n) / log(2)) }')
  [[ -n $first ]] || first=$per
  awk -v s="$s" -v n="$tets" -v t="$secs" -v w="$wall" -v kb="$kb" -v per="$per" -v first="$first" -v v="$verdict" \
    'BEGIN { printf "%-6s %10d %10.1f %10s %10.0f %10.0f %12.2f %s\n", s, n, t, w, kb / 1024, kb * 1024 / n, per / first, v }' |
    tee -a "$out/results.txt"
done
