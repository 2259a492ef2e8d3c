#!/usr/bin/env bash
# Installs, builds and runs the whole test suite: a Release build, then the same suite under
# AddressSanitizer + UndefinedBehaviorSanitizer. Set ANITET_SKIP_SANITIZERS=1 to skip the second.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
jobs=${JOBS:-$(nproc)}

echo "== Release build and tests"
BUILD_DIR=$root/build BUILD_TYPE=Release "$root/scripts/build.sh" -DANITET_WERROR=ON
ctest --test-dir "$root/build" -j "$jobs" --output-on-failure

if [[ ${ANITET_SKIP_SANITIZERS:-0} != 1 ]]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  BUILD_DIR=$root/build-asan BUILD_TYPE=RelWithDebInfo "$root/scripts/build.sh" \
    -DANITET_SANITIZE=ON -DANITET_WERROR=ON
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build-asan" -j "$jobs" --output-on-failure -LE slow
fi
