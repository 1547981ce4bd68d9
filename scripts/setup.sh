#!/usr/bin/env bash
# Installs the Debian 12 packages seedcal needs (only those missing) and builds build/seedcal.
# Usage: scripts/setup.sh [--preset release|ci]   (run as root on a fresh machine, or with sudo)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/packages.sh
preset=release
if [ "${1:-}" = "--preset" ]; then preset="$2"; fi

# Every package the build, the tests and the reports use. Extra ones for optional stages are
# installed by scripts/test.sh when it runs them.
packages=(build-essential cmake ninja-build pkg-config
          libeigen3-dev libnlopt-cxx-dev libgsl-dev libhdf5-dev libtoml11-dev libcli11-dev
          nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox
          libopenmpi-dev openmpi-bin python3 python3-h5py python3-pandas)
ensure_packages "${packages[@]}"

cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
