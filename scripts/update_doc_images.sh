#!/usr/bin/env bash
# Refreshes the pictures of README.md and docs/ from the real GUI: runs the GUI tests (which save screenshots named
# guide_*.png) and copies those into docs/images. Usage: scripts/update_doc_images.sh (after scripts/build.sh)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
shots="$root/build/screenshots"
rm -rf "$shots"
STEADY_SCREENSHOT_DIR="$shots" "$root/tests/gui/run_gui.sh" "$root/build"
mkdir -p "$root/docs/images"
for f in "$shots"/guide_*.png; do
  cp "$f" "$root/docs/images/$(basename "$f" | sed 's/^guide_//')"
done
ls -l "$root/docs/images"
