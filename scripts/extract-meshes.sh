#!/usr/bin/env bash
# Extracts real meshes from Debian's libcgal-demo package into Data/extracted/
# (ignored by git): the Stanford bunny (closed), the armadillo (closed) and a
# Chinese dragon with holes. Nothing is installed: the .deb is downloaded and
# unpacked into a temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=Data/extracted
mkdir -p "$dest"
if [ -f "$dest/bunny00.off" ] && [ -f "$dest/armadillo.off" ] && [ -f "$dest/ChineseDragon-10kv.off" ]; then
  echo "meshes already in $dest"; exit 0
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
chmod 777 "$tmp"
(cd "$tmp" && apt-get download libcgal-demo >/dev/null 2>&1)
dpkg-deb -x "$tmp"/libcgal-demo_*.deb "$tmp/x"
# the meshes sit inside a tarball of CGAL's data folder
tar -xzf "$tmp/x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$tmp" \
  data/meshes/bunny00.off data/meshes/armadillo.off data/meshes/ChineseDragon-10kv.off
cp "$tmp"/data/meshes/*.off "$dest/"
ls -la "$dest"
