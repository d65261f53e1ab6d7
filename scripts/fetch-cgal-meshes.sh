#!/usr/bin/env bash
# Downloads the public robustness corpus: the ~100 meshes Debian ships in CGAL's demo data
# (package libcgal-demo: CAD parts, scans, thin shells, knots, meshes with holes) into a cache
# outside the repository. The meshes are never committed.
#
#   scripts/fetch-cgal-meshes.sh            # prints the mesh directory on its last line
#
# Cache: ${ADASCULPT_DATA:-$HOME/.cache/adasculpt}/cgal/  (data/meshes/ inside it holds the meshes)
# Idempotent: a second run finds the meshes and does nothing. Needs apt-get (Debian/Ubuntu) and
# network access for the first run; fails with one clear message otherwise.
set -euo pipefail

DATA=${ADASCULPT_DATA:-$HOME/.cache/adasculpt}
CACHE=$DATA/cgal
MESHES=$CACHE/data/meshes
say() { echo "fetch-cgal-meshes: $*" >&2; }
die() { echo "fetch-cgal-meshes: error: $*" >&2; exit 1; }

if [ -d "$MESHES" ] && [ -n "$(find "$MESHES" -maxdepth 1 -type f -print -quit)" ]; then
  say "already present: $(find "$MESHES" -maxdepth 1 -type f | wc -l) files in $MESHES"
  echo "$MESHES"
  exit 0
fi

command -v apt-get >/dev/null || die "apt-get not found: the corpus comes from Debian's libcgal-demo package"
command -v dpkg-deb >/dev/null || die "dpkg-deb not found"
mkdir -p "$CACHE/deb"
work=$(mktemp -d "$CACHE/tmp.XXXXXX")
trap 'rm -rf "$work"' EXIT

deb=$(find "$CACHE/deb" -maxdepth 1 -name 'libcgal-demo_*.deb' -print -quit)
if [ -z "$deb" ]; then
  say "downloading libcgal-demo with apt-get download into $CACHE/deb"
  # apt-get download writes into the current directory. It needs the package lists; when
  # they are missing, one apt-get update (root only) fetches them.
  if ! (cd "$CACHE/deb" && timeout 300 apt-get download libcgal-demo >"$work/apt.log" 2>&1); then
    if [ "$(id -u)" = 0 ] && grep -q "Unable to locate package" "$work/apt.log"; then
      say "package lists missing: running apt-get update"
      timeout 300 apt-get update >"$work/update.log" 2>&1 || die "apt-get update failed (offline?): $(tail -1 "$work/update.log")"
      (cd "$CACHE/deb" && timeout 300 apt-get download libcgal-demo >"$work/apt.log" 2>&1) ||
        die "apt-get download libcgal-demo failed (offline?): $(tail -1 "$work/apt.log")"
    else
      die "apt-get download libcgal-demo failed (offline?): $(tail -1 "$work/apt.log")"
    fi
  fi
  deb=$(find "$CACHE/deb" -maxdepth 1 -name 'libcgal-demo_*.deb' -print -quit)
  [ -n "$deb" ] || die "apt-get download reported success but no libcgal-demo_*.deb appeared in $CACHE/deb"
else
  say "using cached $(basename "$deb")"
fi

say "unpacking $(basename "$deb")"
dpkg-deb -x "$deb" "$work/pkg"
tarball=$work/pkg/usr/share/doc/libcgal-dev/data.tar.gz
[ -f "$tarball" ] || die "$(basename "$deb") has no usr/share/doc/libcgal-dev/data.tar.gz"
mkdir -p "$work/data"
tar -xzf "$tarball" -C "$work/data"
# The archive holds data/meshes/... (and other demo data); keep only the meshes.
src=$(find "$work/data" -type d -path '*/data/meshes' -print -quit)
[ -n "$src" ] || die "data.tar.gz has no data/meshes directory"
mkdir -p "$CACHE/data"
rm -rf "$MESHES"
mv "$src" "$MESHES"
say "unpacked $(find "$MESHES" -type f | wc -l) files into $MESHES"
echo "$MESHES"
