#!/usr/bin/env bash
# Creates a private prefix in which Debian's python3-paraview "is installed",
# without installing it system-wide (route B of docs/PARAVIEW.md).
#
# Why: python3-paraview conflicts with python3-vtk9 (needed by libvtk9-dev, our
# main VTK 9.1 build), and ParaView's CMake config refuses to configure without
# the files python3-paraview ships (vtkmodules/*.so, pvpython, wrapping
# hierarchy). The prefix mirrors /usr with symlinks, adds the unpacked
# python3-paraview, and holds a REAL copy of cmake/paraview-5.11 (CMake resolves
# symlinks, so a linked config would compute its import prefix as /usr again).
#
# Usage: scripts/paraview-shim.sh [PREFIX]      (default /opt/lvdif-pvshim)
# Idempotent: re-running on a complete prefix does nothing. Network is needed
# only for `apt-get download python3-paraview` (and for installing the -dev
# packages below if they are missing).
# Prints nothing but errors and, at the end, the ParaView_DIR to use.
set -euo pipefail

D="${1:-/opt/lvdif-pvshim}"
S="$D/usr"
ARCH_LIB=/usr/lib/x86_64-linux-gnu
PV_CMAKE="$ARCH_LIB/cmake/paraview-5.11"
STAMP="$D/.complete-v1"

# --- system packages (never python3-paraview itself: it would remove libvtk9-dev)
need=()
for p in paraview-dev libqt5svg5-dev xvfb openmpi-bin; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "paraview-shim: installing ${need[*]} (without recommends: paraview recommends python3-paraview)" >&2
  SUDO=""; [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq >&2
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" >&2
fi
[ -d "$PV_CMAKE" ] || { echo "paraview-shim: $PV_CMAKE missing after installing paraview-dev" >&2; exit 1; }

# Links every entry of $1 into $2 that $2 lacks (except the names given after).
mirror() {
  local src=$1 dst=$2 f n; shift 2
  for f in "$src"/*; do
    n=${f##*/}
    case " $* " in *" $n "*) continue ;; esac
    [ -e "$dst/$n" ] || [ -L "$dst/$n" ] || ln -s "$f" "$dst/$n"
  done
}

if [ -f "$STAMP" ]; then
  # Packages installed since the prefix was made must show through it too.
  mirror "$ARCH_LIB" "$S/lib/x86_64-linux-gnu" cmake vtk
  mirror "$ARCH_LIB/cmake" "$S/lib/x86_64-linux-gnu/cmake" paraview-5.11
  mirror /usr/bin "$S/bin" pvpython pvpython3.11
  echo "$S/lib/x86_64-linux-gnu/cmake/paraview-5.11"
  exit 0
fi

mkdir -p "$D/deb"
# --- python3-paraview, unpacked (not installed); the version must match paraview-dev
pvver=$(dpkg-query -W -f='${Version}' paraview-dev)
deb=$(ls "$D"/deb/python3-paraview_*.deb 2>/dev/null | head -n1 || true)
if [ -z "$deb" ]; then
  (cd "$D/deb" && { apt-get download "python3-paraview=$pvver" >&2 2>/dev/null \
    || { apt-get update -qq >&2 && apt-get download "python3-paraview=$pvver" >&2; }; })
  deb=$(ls "$D"/deb/python3-paraview_*.deb | head -n1)
fi
rm -rf "$D/pvpy" "$S"
dpkg-deb -x "$deb" "$D/pvpy"

# --- the mirror of /usr
mkdir -p "$S/lib/x86_64-linux-gnu/cmake" "$S/lib/x86_64-linux-gnu/vtk/hierarchy" "$S/bin" "$S/lib/python3"
mirror "$ARCH_LIB" "$S/lib/x86_64-linux-gnu" cmake vtk
mirror "$ARCH_LIB/cmake" "$S/lib/x86_64-linux-gnu/cmake" paraview-5.11
cp -r "$PV_CMAKE" "$S/lib/x86_64-linux-gnu/cmake/"   # a real copy (see the header)
if [ -d "$ARCH_LIB/vtk/hierarchy" ]; then
  for f in "$ARCH_LIB"/vtk/hierarchy/*; do ln -s "$f" "$S/lib/x86_64-linux-gnu/vtk/hierarchy/"; done
fi
ln -s "$D/pvpy/usr/lib/x86_64-linux-gnu/vtk/hierarchy/ParaView" "$S/lib/x86_64-linux-gnu/vtk/hierarchy/"
mirror /usr/bin "$S/bin" pvpython pvpython3.11
ln -sf "$D/pvpy/usr/bin/pvpython3.11" "$S/bin/pvpython3.11"
ln -sf pvpython3.11 "$S/bin/pvpython"
ln -s "$D/pvpy/usr/lib/python3/dist-packages" "$S/lib/python3/dist-packages"
ln -s /usr/include "$S/include"
ln -s /usr/share "$S/share"

# pvbatch lives in the paraview package (/usr/bin/pvbatch), pvpython in the deb.
[ -x "$D/pvpy/usr/bin/pvpython3.11" ] || { echo "paraview-shim: pvpython3.11 not in $deb" >&2; exit 1; }
touch "$STAMP"
echo "$S/lib/x86_64-linux-gnu/cmake/paraview-5.11"
