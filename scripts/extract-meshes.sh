#!/usr/bin/env bash
# Extracts real meshes from Debian's libcgal-demo package into Data/extracted/
# (ignored by git): the Stanford bunny (closed), the armadillo (closed), a
# Chinese dragon with holes, and the cow and the elephant (closed, elongated:
# fitted grids on them are far from cubic). Nothing is installed: the .deb is downloaded and
# unpacked into a temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=Data/extracted
mkdir -p "$dest"
meshes="bunny00.off armadillo.off ChineseDragon-10kv.off cow.off elephant.off"
missing=0
for m in $meshes; do [ -f "$dest/$m" ] || missing=1; done
if [ "$missing" = 0 ]; then
  echo "meshes already in $dest"; exit 0
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
chmod 777 "$tmp"
(cd "$tmp" && apt-get download libcgal-demo >/dev/null 2>&1)
dpkg-deb -x "$tmp"/libcgal-demo_*.deb "$tmp/x"
# the meshes sit inside a tarball of CGAL's data folder
tar -xzf "$tmp/x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$tmp" \
  $(for m in $meshes; do printf 'data/meshes/%s ' "$m"; done)
cp "$tmp"/data/meshes/*.off "$dest/"
ls -la "$dest"
