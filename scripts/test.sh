#!/usr/bin/env bash
# Installs, builds and runs the whole test suite: a Release build, then the same suite under
# AddressSanitizer + UndefinedBehaviorSanitizer, then a short fuzz run (scripts/fuzz.sh: every
# fuzz target for a few seconds over its seed corpus). Set ANITET_SKIP_SANITIZERS=1 to skip the
# second, ANITET_SKIP_FUZZ=1 the third.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
jobs=${JOBS:-$(nproc)}

echo "== Release build and tests"
# Tests ON explicitly: demo.sh and examples/cfd/run.sh configure build/ without them.
BUILD_DIR=$root/build BUILD_TYPE=Release "$root/scripts/build.sh" -DANITET_WERROR=ON -DANITET_BUILD_TESTS=ON
ctest --test-dir "$root/build" -j "$jobs" --output-on-failure --no-tests=error

if [[ ${ANITET_SKIP_SANITIZERS:-0} != 1 ]]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  BUILD_DIR=$root/build-asan BUILD_TYPE=RelWithDebInfo "$root/scripts/build.sh" \
    -DANITET_SANITIZE=ON -DANITET_WERROR=ON -DANITET_BUILD_TESTS=ON
  # Under the sanitizers the code runs 10-50x slower. The multi-layer variants, the quality gates,
  # the largest layer runs (41 tests, 860 s of the 1230 s the ASan half took on 2 cores) and the
  # recovery/layer-count retries run in the Release half only; their 1-layer and plain-mesh
  # siblings run here too.
  asan_skip='_[23]_layers$|^e2e\.layers[23]\.|^e2e\.mesh-quality\.|^e2e\.mesh-interior\.|tray_bottom|^e2e\.layers-bl\.fandisk'
  asan_skip+='|^BoundaryLayer\.AirplaneInAFarfieldBox$|^e2e\.recover\.casting|^e2e\.mesh-retry\.|^e2e\.mesh-default\.'
  asan_skip+='|^Layers\.(WorstTetsStandOnPoorInputTriangles|IsotropicQualityOnGoodSurfaces|IsotropicQualityWithTwoLayers|PaperSchemeIsValidToo|ReportsHalvingsAndProvenance)$'
  # The pieces path on 3 and 4 ranks (its 2-rank sibling runs here), and the anisotropic cube in
  # parts (three anisotropic runs; the distributed unit test's anisotropic case runs here).
  asan_skip+='|^e2e\.mesh-mpi-pieces\.fandisk\.(3-ranks|4-ranks-balanced)$|^e2e\.mesh-mpi-aniso\.'
  asan_skip+='|^e2e\.invariance\.|^e2e\.recover-translated\.|^RecoverySplit\.(Hammer|Skull)$|^Stage2\.|^Pipeline\.AirplaneInAFarfieldBoxWith15BoundaryLayers$'
  # intercept_tls_get_addr=0: up to GCC 13 / LLVM 16 the runtime's __tls_get_addr interceptor
  # takes a dynamic TLS block whose address is 16 past a page boundary for glibc 2.19's layout and
  # reads a bogus range from before it; LeakSanitizer's tracer then crashes at exit after a test
  # passed (google/sanitizers#1322). It happened here whenever allocations moved such a block
  # there (Pipeline.AttemptsStopWhenTheirBudgetRunsOut with the split recovery's maps reserved:
  # 6 crashes in 6 runs, none with this option).
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build-asan" -j "$jobs" --output-on-failure --no-tests=error -LE slow -E "$asan_skip"
fi

if [[ ${ANITET_SKIP_FUZZ:-0} != 1 ]]; then
  echo "== Short fuzz run (clang libFuzzer + ASan + UBSan)"
  # About 4.5 minutes on 2 cores: 3 to build with clang, 1.5 to run the 11 targets (FUZZ_SECONDS
  # each; scripts/fuzz.sh alone defaults to 16).
  "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-8}"
fi
