#!/usr/bin/env bash
# Builds the documentation on a fresh Debian bookworm machine: installs doxygen, MathJax (libjs-mathjax) and
# chromium (and what is missing), fetches CGAL's meshes for the figures, configures build/ and builds the
# CMake target `doc`: the figures (scripts/make_figures.sh), the HTML manual with doxygen's warnings treated
# as errors, the reference completeness check (doc/check_reference.py), a copy of MathJax inside the HTML
# and the check, in headless chromium without network, that every formula renders (doc/check_mathjax.py).
# Result: build/doc/html/index.html, self-contained (it opens offline, formulas included).
# Usage: bash scripts/build_doc.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh --doc
bash scripts/fetch_cgal_data.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "${JOBS:-2}" --target doc
echo "Manual: $(pwd)/build/doc/html/index.html"
