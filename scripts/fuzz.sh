#!/usr/bin/env bash
# A short fuzz run (issue 11): builds the libFuzzer targets of fuzz/ with clang in BUILD_DIR
# (default build-fuzz/), then runs each target for SECONDS (default 16: about 3 minutes for the 12
# targets) over its committed seed corpus fuzz/corpus/<target>. New interesting inputs go to
# BUILD_DIR/corpus/<target> (not committed), crashing inputs to BUILD_DIR/crashes/<target>/.
# Exits non-zero when a target crashed, broke a reader's contract, leaked, timed out or ran out
# of memory. A crasher, once fixed, is kept in fuzz/regressions/<target>/ (replayed by ctest).
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build-fuzz}
jobs=${JOBS:-$(nproc)}
seconds=${1:-16}
shift || true
"$root/scripts/setup.sh"

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DANITET_BUILD_FUZZERS=ON -DANITET_BUILD_TESTS=OFF -DANITET_WERROR=ON >/dev/null
cmake --build "$build" -j "$jobs" --target fuzzers

targets=("$@")
if ((${#targets[@]} == 0)); then
  for dir in "$root"/fuzz/corpus/*/; do targets+=("$(basename "$dir")"); done
fi

failed=()
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/crashes/$t" "$build/logs"
  log=$build/logs/$t.log
  # -max_len: the seeds are at most a few KB; -timeout: seconds for one input (a hang is a bug,
  # but the machine may be shared, so generous).
  # libFuzzer also writes slow-unit-* files (an input over 10 s, which a loaded machine can make
  # of a normal one): only crashes, leaks, timeouts and out-of-memory inputs count.
  found() { find "$build/crashes/$t" -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' | wc -l; }
  crashes_before=$(found)
  status=0
  "$build/fuzz/fuzz_$t" "$build/corpus/$t" "$root/fuzz/corpus/$t" \
    -max_total_time="$seconds" -max_len=4096 -rss_limit_mb=2048 -timeout=25 \
    -artifact_prefix="$build/crashes/$t/" -print_final_stats=1 >"$log" 2>&1 || status=$?
  summary=$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)
  echo "fuzz $t: ${summary:-no progress line} (exit $status)"
  if ((status != 0)) || (($(found) > crashes_before)); then
    failed+=("$t")
    grep -E -A 20 '^==[0-9]+==|contract broken|^SUMMARY' "$log" | head -n 40 || tail -n 40 "$log"
  fi
done

if ((${#failed[@]} > 0)); then
  echo "fuzz: FAILED: ${failed[*]}; inputs in $build/crashes/<target>/ (logs in $build/logs/)."
  echo "Reproduce with $build/fuzz/fuzz_<target> FILE; after the fix, keep FILE in fuzz/regressions/<target>/."
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each: no crash"
