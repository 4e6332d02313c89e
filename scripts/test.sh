#!/usr/bin/env bash
# Quick start, command 2: runs all the tests (kernel GoogleTest, module pytest, FreeCAD App tests headless and
# GUI tests under Xvfb, and the example macros). Installs and builds what it needs first, so it works alone on a
# fresh machine. Options:
#   --long               also the long suites (fuzzing, large sizes) and the benchmarks (tests/bench/run.sh --long)
#   --bench              also the default benchmarks (tests/bench/run.sh)
#   --sanitizers         also the reliability pass (docs/reliability.md): builds build-asan (clang, AddressSanitizer +
#                        UndefinedBehaviorSanitizer, libFuzzer) and runs every kernel and core GoogleTest there, then
#                        each fuzz target for its short run (tests/fuzz)
#   --sanitizers=short   the same pass in the short form CI runs (.ci/run): the fast kernel suites and shorter fuzz
#                        runs, a few minutes once build-asan is built
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
long=0
bench=0
sanitizers=""
for a in "$@"; do
  case "$a" in
    --long) long=1 ;;
    --bench) bench=1 ;;
    --sanitizers) sanitizers=full ;;
    --sanitizers=short) sanitizers=short ;;
    *) echo "test.sh: unknown option $a (use --long, --bench, --sanitizers or --sanitizers=short)"; exit 2 ;;
  esac
done
scripts/setup.sh
scripts/build.sh
if [ "$long" = 1 ]; then export STEADY_LONG_TESTS=1; fi
ctest --test-dir build --output-on-failure -j 2 --timeout 1500
if [ -n "$sanitizers" ]; then
  scripts/sanitizers.sh "$sanitizers"
fi
if [ "$long" = 1 ]; then
  tests/bench/run.sh --long
elif [ "$bench" = 1 ]; then
  tests/bench/run.sh
fi
