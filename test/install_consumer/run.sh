#!/usr/bin/env bash
# Installs the package from a configured build tree into a fresh prefix, then configures, builds and runs the
# consumer project against it (nothing from the source tree on its include path). Used by ctest.
# Usage: run.sh BUILD_DIR WORK_DIR CONSUMER_SOURCE_DIR
set -euo pipefail
build="$1" work="$2" consumer="$3"
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/include/CGAL/Trivial_connections/Trivial_connection_solver.h"
test -f "$work/prefix/lib/cmake/CGAL_Trivial_connections/CGAL_Trivial_connectionsConfig.cmake"
test -x "$work/prefix/share/CGAL_Trivial_connections/render_field.py"
cmake -S "$consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/consumer"
# the Python module, when the build has it (TC_PYTHON_SITE: its folder under the prefix)
if [ -n "${TC_PYTHON_SITE:-}" ]; then
  ls "$work/prefix/$TC_PYTHON_SITE"/trivial_connections*.so "$work/prefix/$TC_PYTHON_SITE"/trivial_connections.pyi > /dev/null
  (cd "$work" && PYTHONPATH="$work/prefix/$TC_PYTHON_SITE" "$TC_PYTHON" -c \
    "import trivial_connections as tc; assert tc.__file__.startswith('$work/prefix/'), tc.__file__; assert tc.__version__")
fi
