#!/usr/bin/env bash
# Installs the Debian (bookworm) packages the project needs, only those that are missing.
# Usage: bash scripts/install_dependencies.sh [--cholmod]
#   --cholmod   also install libsuitesparse-dev (for -DTRIVIAL_CONNECTIONS_WITH_CHOLMOD=ON)
set -euo pipefail
pkgs=(build-essential cmake libcgal-dev libeigen3-dev libboost-graph-dev
      libgtest-dev googletest libbenchmark-dev python3 python3-numpy)
for arg in "$@"; do
  case "$arg" in
    --cholmod) pkgs+=(libsuitesparse-dev) ;;
    -h|--help) sed -n '2,4p' "$0"; exit 0 ;;
    *) echo "install_dependencies.sh: unknown argument '$arg'" >&2; exit 2 ;;
  esac
done

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
