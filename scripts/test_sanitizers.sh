#!/usr/bin/env bash
# Builds the tests, the program and the examples with AddressSanitizer and UndefinedBehaviorSanitizer
# (GCC, -O1 -g1: line tables for the stacks; the assertions of CGAL and Eigen on, so Eigen checks every
# index) in build-sanitizers/, and runs every ctest test there: a sanitizer report or a failed assertion
# fails the test. Used by CI. The Python module's tests run with the sanitizers' runtimes preloaded into the
# interpreter (CMakeLists.txt), leaks left out there.
# Usage: bash scripts/test_sanitizers.sh [extra ctest arguments, e.g. -R Io]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
bash scripts/fetch_cgal_data.sh
jobs="${JOBS:-2}"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-sanitizers -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DBUILD_TESTING=ON \
  -DTRIVIAL_CONNECTIONS_WITH_EDITOR=OFF
cmake --build build-sanitizers -j "$jobs"
# halt at the first report of either sanitizer, with a stack; leaks are reported at exit (LeakSanitizer)
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build-sanitizers
ctest --output-on-failure -j "$jobs" -E '^install_consumer$' "$@"
