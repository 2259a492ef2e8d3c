#!/usr/bin/env bash
# Installs, builds, and runs anitet's main job on the example surface shipped in examples/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" -DANITET_BUILD_TESTS=OFF
anitet=${BUILD_DIR:-$root/build}/app/anitet
# The main job: mesh the example (validate, layers, recovery, coupling) and print the quality report.
mkdir -p "$root/out"
"$anitet" mesh "$root/examples/fandisk.off" -o "$root/out/fandisk.mesh"
