#!/usr/bin/env bash
# Runs the GUI tests in a real FreeCAD window under Xvfb, with the workbench of this checkout.
# Debian's freecad crashes on -M in GUI mode, so the checkout's Mod folder is linked into a throw-away HOME
# (FreeCAD scans ~/.local/share/FreeCAD/Mod), which also keeps the user's own FreeCAD settings out of the test.
# Usage: tests/gui/run_gui.sh <build dir>
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
source_dir="$(cd "$here/../.." && pwd)"
build_dir="$(cd "${1:-$source_dir/build}" && pwd)"
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
mkdir -p "$home/.local/share/FreeCAD/Mod"
ln -s "$source_dir/Mod/LatticeWorkbench" "$home/.local/share/FreeCAD/Mod/LatticeWorkbench"
export HOME="$home"
export STEADY_BUILD_PYTHON="$build_dir/python"
export STEADY_MOD_DIR="$source_dir/Mod/LatticeWorkbench"
export STEADY_SOURCE_DIR="$source_dir"
export STEADY_SCREENSHOT_DIR="${STEADY_SCREENSHOT_DIR:-$build_dir/screenshots}"
export QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox
exec xvfb-run -a -s "-screen 0 1280x1024x24" freecad "$here/run_gui_tests.py"
