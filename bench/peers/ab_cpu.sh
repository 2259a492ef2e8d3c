#!/usr/bin/env bash
# Before/after of one change on one core: two anitet binaries pinned to core 0 (`taskset -c 0`),
# alternated on each input, CPU time (user+sys, /usr/bin/time) and wall time with the load
# average before each run; at the end, per input, the median CPU times, their ratio and whether
# both binaries wrote the same mesh bytes.
#
#   bench/peers/ab_cpu.sh [-r ROUNDS] OLD NEW INPUT[@SIZE] ...
#
# INPUT: `sphere` (out/bench-one-core/sphere/sphere.off, made by one_core.sh) or a file name in
# ../shared/data/surfaces; @SIZE adds `--size SIZE`. ROUNDS default 3. ARGS (environment): more
# options for both runs, e.g. ARGS='--threads 2' (two threads on the one core: the CPU time is
# then all the work of a two-thread run). Outputs under out/bench-ab. Not run by CI.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
rounds=3
if [[ ${1:-} == -r ]]; then rounds=$2; shift 2; fi
old=$(realpath "${1:?usage: bench/peers/ab_cpu.sh [-r ROUNDS] OLD NEW INPUT[@SIZE] ...}")
new=$(realpath "${2:?usage: bench/peers/ab_cpu.sh [-r ROUNDS] OLD NEW INPUT[@SIZE] ...}")
shift 2
out=$root/out/bench-ab
mkdir -p "$out"
tsv=$out/runs.tsv
: > "$tsv"
for ((r = 1; r <= rounds; ++r)); do
  for arg in "$@"; do
    s=${arg%@*} size=
    [[ $arg == *@* ]] && size=${arg#*@}
    in=$root/../shared/data/surfaces/$s
    [[ $s == sphere ]] && in=$root/out/bench-one-core/sphere/sphere.off
    for which in old new; do
      bin=$old
      [[ $which == new ]] && bin=$new
      load=$(cut -d' ' -f1 /proc/loadavg)
      taskset -c 0 /usr/bin/time -f '%e %U %S %M' -o "$out/time" "$bin" mesh "$in" -o "$out/$which-${s%.*}.mesh" \
        ${size:+--size "$size"} ${ARGS:-} > "$out/$which.log" 2>&1 || { echo "$which failed on $arg: $(tail -1 "$out/$which.log")"; exit 1; }
      read -r wall user sys rss < <(tail -1 "$out/time")
      printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$arg" "$which" "$wall" "$(echo "$user + $sys" | bc)" "$rss" "$load" >> "$tsv"
      printf 'round %d %-22s %s: wall %6.2f s, CPU %6.2f s, %s kB, load %s\n' "$r" "$arg" "$which" "$wall" \
        "$(echo "$user + $sys" | bc)" "$rss" "$load"
    done
  done
done
echo
/usr/bin/python3 - "$tsv" "$out" "$@" <<'PY'
import filecmp, statistics, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])]
print("| input | old CPU s | new CPU s | new / old | old wall s | new wall s | load | same mesh |")
print("|---|---|---|---|---|---|---|---|")
for arg in sys.argv[3:]:
    med = lambda w, i: statistics.median(float(r[i]) for r in rows if r[0] == arg and r[1] == w)
    loads = [float(r[5]) for r in rows if r[0] == arg]
    s = arg.split("@")[0].rsplit(".", 1)[0]
    same = filecmp.cmp(f"{sys.argv[2]}/old-{s}.mesh", f"{sys.argv[2]}/new-{s}.mesh", shallow=False)
    print(f"| {arg} | {med('old', 3):.2f} | {med('new', 3):.2f} | {med('new', 3) / med('old', 3):.2f} | "
          f"{med('old', 2):.2f} | {med('new', 2):.2f} | {min(loads):.1f}-{max(loads):.1f} | {'yes' if same else 'NO'} |")
PY
