#!/usr/bin/env bash
# Quick start, command 1: installs what is missing (Debian packages), builds, installs the steadylattice module
# for /usr/bin/python3 and the workbench into ~/.local/share/FreeCAD/Mod, then runs the main job: a lattice
# trimmed into a part and exported as STEP (examples/main_job.py; output in ./out).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
scripts/setup.sh
scripts/build.sh
cmake --install build > build/install.log
echo "install: module  -> $(/usr/bin/python3 -c 'import steadylattice; print(steadylattice.__file__)')"
echo "install: workbench -> $HOME/.local/share/FreeCAD/Mod/LatticeWorkbench"
mkdir -p out
rm -f out/lattice_part.step
LATTICE_OUT="$root/out" freecad -c "$root/examples/main_job.py"
# freecad -c exits 0 even when a script fails to import: check the result itself
[ -s out/lattice_part.step ] || { echo "install: the main job did not write out/lattice_part.step"; exit 1; }
echo "install: main job done; results in $root/out:"
ls -l "$root/out"
