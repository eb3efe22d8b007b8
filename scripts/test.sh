#!/usr/bin/env bash
# Builds everything and runs every test, on a fresh Debian bookworm machine:
#   installs the missing packages, fetches CGAL's data set, configures build/ (Release), builds, runs ctest.
# Usage: bash scripts/test.sh [extra cmake arguments, e.g. -DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
bash scripts/fetch_cgal_data.sh
jobs="${JOBS:-2}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON "$@"
cmake --build build -j "$jobs"
cd build
ctest --output-on-failure -j "$jobs"
