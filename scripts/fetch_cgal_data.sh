#!/usr/bin/env bash
# Fetches CGAL's own data set (the meshes of Debian's libcgal-demo package) into .cgal-data/, so that
# the meshes are in .cgal-data/data/meshes/*.off. Idempotent: does nothing when that folder exists.
# Only the .deb is downloaded and unpacked (apt-get download + dpkg -x): none of the package's GUI
# dependencies gets installed. Usage: bash scripts/fetch_cgal_data.sh [DEST]   (DEST default .cgal-data)
set -euo pipefail
cd "$(dirname "$0")/.."
dest="${1:-.cgal-data}"
if [ -d "$dest/data/meshes" ] && [ -n "$(ls -A "$dest/data/meshes" 2>/dev/null)" ]; then
  echo "CGAL data set already present: $dest/data/meshes"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# apt-get download as root drops privileges to _apt unless the folder is owned by root; a mktemp
# folder is owned by us, so this works (the "unsandboxed" notice apt may print is harmless).
download() { (cd "$work" && apt-get download libcgal-demo </dev/null); }
if ! download; then
  echo "apt-get download failed; running apt-get update and retrying" >&2
  $SUDO apt-get update </dev/null
  download
fi
deb="$(ls "$work"/libcgal-demo_*.deb | head -n 1)"
dpkg -x "$deb" "$work/x"
tarball="$work/x/usr/share/doc/libcgal-dev/data.tar.gz"
if [ ! -f "$tarball" ]; then
  echo "error: $deb has no usr/share/doc/libcgal-dev/data.tar.gz" >&2
  exit 1
fi
mkdir -p "$dest.tmp"
tar -xzf "$tarball" -C "$dest.tmp"
if [ ! -d "$dest.tmp/data/meshes" ]; then
  echo "error: data.tar.gz has no data/meshes folder" >&2
  rm -rf "$dest.tmp"
  exit 1
fi
rm -rf "$dest"
mv "$dest.tmp" "$dest"
echo "CGAL data set: $(ls "$dest/data/meshes" | wc -l) files in $dest/data/meshes"
