#!/usr/bin/env bash
# Configures and builds everything (kernel, module, tests, benchmarks) into ./build. Used by install.sh and test.sh.
#   --sanitizers   instead, the reliability build into ./build-asan (docs/reliability.md): clang, AddressSanitizer +
#                  UndefinedBehaviorSanitizer over the kernel and its GoogleTest suites, and the libFuzzer targets
#                  of tests/fuzz; no Python module (Python cannot load an ASan library) and no benchmarks.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
sanitizers=0
for a in "$@"; do
  case "$a" in
    --sanitizers) sanitizers=1 ;;
    *) echo "build.sh: unknown option $a (use --sanitizers)"; exit 2 ;;
  esac
done
# ccache, when the machine has it, makes rebuilds after a branch switch cheap; the build does not need it.
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
if [ "$sanitizers" = 1 ]; then
  dir="$root/build-asan"
  # -O1: the usual level for sanitizer builds (reports stay exact, the tests run at a few times native speed);
  # line tables only: symbolized stacks without the compile time of full debug information.
  cmake -S "$root" -B "$dir" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
        -DSTEADY_SANITIZE=ON -DSTEADY_BUILD_FUZZ=ON -DSTEADY_BUILD_PYTHON=OFF -DSTEADY_BUILD_BENCHMARKS=OFF \
        "${launcher[@]}" > "$root/build-asan-configure.log" 2>&1 || { cat "$root/build-asan-configure.log"; exit 1; }
  cmake --build "$dir" -j "$(nproc)"
  exit 0
fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" > "$root/build-configure.log" 2>&1 || {
  cat "$root/build-configure.log"; exit 1; }
cmake --build "$root/build" -j "$(nproc)"
