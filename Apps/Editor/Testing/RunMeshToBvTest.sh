#!/bin/bash
# --open-mesh with --save X.bv (a format of cubic volumes only): the grid fitted
# to the mesh is made cubic, as `lvdif mesh-to-sdf MESH X.bv --dims N` makes
# it, and the two files are the same byte for byte. The editor converted to a
# 22 x 32 x 22 grid and then failed to save it.
# usage: RunMeshToBvTest.sh EDITOR CHECK LVDIF DIR SIZE   (needs a display; SIZE: the window, WxH)
set -u
EDITOR=$1
CHECK=$2
LVDIF=$3
DIR=$4
SIZE=$5
source "$(dirname "${BASH_SOURCE[0]}")/TestPreamble.sh"
"$CHECK" --write-cone-obj "$DIR/cone.obj" || fail "could not write the mesh"
"$EDITOR" --open-mesh "$DIR/cone.obj" --mesh-resolution 32 --size "$SIZE" --no-recovery --autosave 0 \
  --save "$DIR/SDF_32_editor.bv" || fail "the editor failed"
"$LVDIF" mesh-to-sdf "$DIR/cone.obj" "$DIR/SDF_32_cli.bv" --dims 32 || fail "the CLI failed"
cmp "$DIR/SDF_32_editor.bv" "$DIR/SDF_32_cli.bv" || fail "the editor's .bv differs from the CLI's"
echo "the same .bv as the CLI's"
