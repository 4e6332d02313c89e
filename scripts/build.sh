#!/usr/bin/env bash
# Configures and builds everything (kernel, module, tests, benchmarks) into ./build. Used by install.sh and test.sh.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
# ccache, when the machine has it, makes rebuilds after a branch switch cheap; the build does not need it.
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" > "$root/build-configure.log" 2>&1 || {
  cat "$root/build-configure.log"; exit 1; }
cmake --build "$root/build" -j "$(nproc)"
