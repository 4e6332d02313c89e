#!/usr/bin/env bash
# Runs every benchmark and prints its table. Usage: tests/bench/run.sh [--long] [name-filter]
#   --long   also the large sizes (minutes to tens of minutes); the default run stays short.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${STEADY_BUILD_DIR:-$here/../../build}"
long=""
filter=""
for a in "$@"; do
  case "$a" in
    --long) long="--long" ;;
    *) filter="$a" ;;
  esac
done
status=0
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  name="$(basename "$b")"
  [ -n "$filter" ] && [[ "$name" != *"$filter"* ]] && continue
  echo "=== $name $long"
  "$b" $long || status=1
done
for p in "$here"/bench_*.py; do
  [ -f "$p" ] || continue
  name="$(basename "$p" .py)"
  [ -n "$filter" ] && [[ "$name" != *"$filter"* ]] && continue
  echo "=== $name $long"
  PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 "$p" $long || status=1
done
exit $status
