#!/usr/bin/env bash
# threads_check.sh ANITET SURFACE WORKDIR
# --threads N: the same mesh on 1 thread, on 2 and by default, and no more than N threads doing
# work. The process's threads are sampled every few milliseconds from /proc (their CPU time);
# a thread counts as working once it has used 30 ms of CPU (libraries' idle threads, such as the
# pool OpenVDB's logging library starts, never do). Also: no more than N threads at once in the
# TBB arena is what --threads promises; this checks what ps shows of it.
set -uo pipefail
anitet=$1 surface=$2 work=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
tick=$(getconf CLK_TCK)
# run N: meshes to $work/tN.mesh; prints the number of threads that worked.
run() {
  local n=$1
  "$anitet" mesh "$surface" -o "$work/t$n.mesh" --threads "$n" -q &
  local pid=$! max_working=0
  declare -A cpu
  while kill -0 "$pid" 2>/dev/null; do
    for stat in /proc/"$pid"/task/*/stat; do
      read -r -a f <"$stat" 2>/dev/null || continue
      cpu[${f[0]}]=$((f[13] + f[14]))
    done
    sleep 0.003
  done
  wait "$pid" || fail "anitet mesh --threads $n exited $?"
  local working=0
  for tid in "${!cpu[@]}"; do ((cpu[$tid] * 1000 / tick >= 30)) && working=$((working + 1)); done
  echo "$working"
}
w1=$(run 1) || exit 1
w2=$(run 2) || exit 1
w0=$(run 0) || exit 1
echo "threads that worked: --threads 1: $w1, --threads 2: $w2, default ($(nproc) cores): $w0"
((w1 == 1)) || fail "--threads 1: $w1 threads worked"
((w2 <= 2)) || fail "--threads 2: $w2 threads worked"
((w0 <= $(nproc))) || fail "default: $w0 threads worked on $(nproc) cores"
cmp -s "$work/t1.mesh" "$work/t2.mesh" || fail "the meshes of --threads 1 and 2 differ"
cmp -s "$work/t1.mesh" "$work/t0.mesh" || fail "the meshes of --threads 1 and the default differ"
echo "PASS: the same mesh on 1, 2 and all threads"
