#!/usr/bin/env bash
# Installs every dependency of LatticeWorkbench from Debian 12's packages, skipping what is present.
# Run as root (or with sudo available). Safe to run again.
set -euo pipefail

PACKAGES=(
  # build
  build-essential cmake pkg-config git
  # CAD host
  freecad freecad-python3
  # B-rep, STEP (OpenCASCADE 7.6)
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libocct-ocaf-dev libocct-visualization-dev
  # mesh algorithms (CGAL 5.5, header-only, needs GMP/MPFR)
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  # bindings and Python side
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-pil
  # maths, parallelism, formats
  libglm-dev libtbb-dev lib3mf-dev libzip-dev zlib1g-dev nlohmann-json3-dev
  # tests and benchmarks
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  # the voxel baseline of the benchmarks (OpenVDB)
  libopenvdb-dev
  # independent readers in the tests: XML schema validation of 3MF beam lattices; gmsh, which meshes our STEP
  # parts into tetrahedra for analysis (docs/fea.md)
  libxml2-utils gmsh python3-gmsh
  # a real FreeCAD window without a display; peak-memory measurement
  xvfb xauth time
  # the reliability build (scripts/test.sh --sanitizers, docs/reliability.md): clang with its AddressSanitizer,
  # UndefinedBehaviorSanitizer and libFuzzer runtimes, and llvm-symbolizer for readable reports
  clang-14 libclang-rt-14-dev llvm-14
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
# Refresh the index only when it is missing or older than a day.
if [ -z "$(find /var/lib/apt/lists -maxdepth 1 -name '*Packages*' -mtime -1 2>/dev/null | head -n 1)" ]; then
  $SUDO apt-get update -q
fi
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
