#!/usr/bin/env bash
# Installs the Debian (bookworm) packages the project needs, only those that are missing.
# Usage: bash scripts/install_dependencies.sh [--no-cholmod] [--doc] [--fuzz]
#   --no-cholmod   skip libsuitesparse-dev, libopenblas0-pthread and libmetis-dev (CHOLMOD on OpenBLAS, which
#                  the program uses on large meshes, and METIS; the library itself is header-only and
#                  defaults to Eigen's SimplicialLDLT)
#   --doc          also what the documentation needs (cmake --build build --target doc): doxygen; MathJax
#                  (libjs-mathjax), copied into the manual so that its formulas render offline; chromium,
#                  headless, for the check that they do render (doc/check_mathjax.py)
#   --fuzz         also clang and libFuzzer's runtime, for the fuzz harness (scripts/run_fuzzer.sh)
set -euo pipefail
pkgs=(build-essential cmake libcgal-dev libeigen3-dev libboost-graph-dev
      libgtest-dev googletest libbenchmark-dev python3 python3-numpy python3-matplotlib
      python3-dev pybind11-dev python3-pybind11 python3-pytest
      mypy python3-venv python3-pip python3-setuptools python3-wheel python3-distributed)
# mypy: ctest python_typing (the module's type stubs); python3-venv, -pip, -setuptools, -wheel: pip install . of
# the module (pyproject.toml) and ctest python_pip_install; python3-distributed (Dask): trivial_connections-batch and
# ctest python_batch
cholmod=1
doc=0
fuzz=0
for arg in "$@"; do
  case "$arg" in
    --cholmod) ;; # installed by default now; kept for old command lines
    --no-cholmod) cholmod=0 ;;
    --doc) doc=1 ;;
    --fuzz) fuzz=1 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "install_dependencies.sh: unknown argument '$arg'" >&2; exit 2 ;;
  esac
done

# with CHOLMOD: OpenBLAS (its supernodal factorization runs on BLAS; Debian's reference BLAS is 1.3 to 2 times
# slower there) and METIS (nested dissection for the simplicial backend on large meshes)
if [ "$cholmod" = 1 ]; then pkgs+=(libsuitesparse-dev libopenblas0-pthread libmetis-dev); fi
if [ "$doc" = 1 ]; then pkgs+=(doxygen libjs-mathjax chromium); fi
# the field editor: node and npm (whichever installed them: a nodejs from elsewhere brings its own npm, which
# Debian's npm package would conflict with), and Chromium for its browser test
command -v node >/dev/null 2>&1 || pkgs+=(nodejs)
command -v npm >/dev/null 2>&1 || pkgs+=(npm)
command -v chromium >/dev/null 2>&1 || pkgs+=(chromium)
if [ "$fuzz" = 1 ]; then pkgs+=(clang libclang-rt-14-dev); fi

missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -qx installed; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "All dependencies are installed."
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "error: missing packages (${missing[*]}) and not root; install them or run as root" >&2; exit 1
  fi
fi
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update </dev/null
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" </dev/null
