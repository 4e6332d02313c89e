#!/usr/bin/env bash
# The reliability pass (docs/reliability.md), run by scripts/test.sh --sanitizers[=short]:
#   full    every kernel and core GoogleTest under AddressSanitizer + UndefinedBehaviorSanitizer, then each fuzz
#           target's short run (STEADY_FUZZ_SECONDS, 25 s by default) from its corpus
#   short   the CI form: the same minus the slowest kernel tests (scripts/sanitizer_slow_tests.txt, each > 10 s
#           under ASan), so that it adds a few minutes to CI once build-asan is built
# Both build ./build-asan first (scripts/build.sh --sanitizers). Any sanitizer report fails its test.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
mode="${1:-full}"
scripts/build.sh --sanitizers
exclude=()
if [ "$mode" = short ]; then
  # The slowest kernel tests under ASan (scripts/sanitizer_slow_tests.txt, measured in the full pass), as one
  # ctest exclusion regex: dots literal, names anchored at the start.
  slow=$(grep -v '^#' scripts/sanitizer_slow_tests.txt | grep -v '^$' | sed 's/\./\\./g; s/^/^/' | paste -sd'|')
  exclude=(-E "$slow")
fi
start=$(date +%s)
ctest --test-dir build-asan --output-on-failure -j 2 --timeout 3000 -L 'kernel|fuzz' "${exclude[@]}"
echo "sanitizers ($mode): $(( $(date +%s) - start )) s of tests"
