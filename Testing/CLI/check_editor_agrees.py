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

# 2. a recording played without --in starts from its own canvas, as the editor's --script without --new
#    does: a cubic canvas (the sphere), a non-cubic one in version 4 (the rounded box) and in version 1
#    (the older sphere), and --fill empty as the editor's --fill empty
cubic = os.path.join(out, "cubic.lvr")
with open(cubic, "w") as f:
    f.write("LVDIF-RECORDING 2\ncanvas 40 40 40\nedit time=0 op=subtract shape=sphere kind=single spacing=1.6 "
            "blend=0 coloroffset=1.5 rounding=0 color=230,90,60,255 dabs=1\nd 20 20 33 6\n"
            "edit time=1 op=paint shape=sphere kind=single spacing=1.6 blend=0 coloroffset=1.5 rounding=0 "
            "color=20,200,90,255 dabs=1\nd 20 33 20 5\nend records=2\n")
cases = [(cubic, []), (os.path.join(editor_testing, "long-canvas-v2-said-box.lvr"), []),
         (os.path.join(editor_testing, "long-canvas-v1.lvr"), []), (cubic, ["--fill", "empty"]),
         (cubic, ["--fill", "full"])]
for i, (rec, fill) in enumerate(cases):
    cli, ed = os.path.join(out, f"play{i}-cli.vti"), os.path.join(out, f"play{i}-editor.vti")
    r = run([exe, "play", rec, "--out", cli, *fill])
    assert "records replayed on its own " in r.stdout, r.stdout
    run([editor, "--script", rec, "--save", ed, *fill, *EDITOR_BATCH])
    dims, sdf, rgba = same(cli, ed, (rec, fill))
    # not a trivial agreement: the starter (or the fill) holds material, and the recording changed it
    if fill != ["--fill", "empty"]:
        assert (sdf < 0).any() and (sdf > 0).any() or fill == ["--fill", "full"], (rec, fill)
# a version 2 recording of a non-cubic canvas cannot say which starter it was made on: refused as the
# editor refuses it, naming the CLI's way to give the volume, and nothing written
v2 = os.path.join(editor_testing, "long-canvas-v2.lvr")
target = os.path.join(out, "v2.vti")
r = run([exe, "play", v2, "--out", target], expect=1)
assert "does not say which starter shape it was made on" in r.stderr and "(--in VOLUME)" in r.stderr, r.stderr
assert not os.path.exists(target)
# --fill is the own canvas's: with --in it is refused before anything is read (status 2)
r = run([exe, "play", cubic, "--in", "missing.lvdv", "--fill", "empty"], expect=2)
assert r.stderr.strip() == ("lvdif play: --fill fills the recording's own canvas (without --in): not with --in "
                            "(the replay starts from that volume)"), r.stderr
r = run([exe, "play", cubic, "--fill", "sphre"], expect=2)
assert r.stderr.strip() == "lvdif play: --fill must be empty, full or sphere, not 'sphre'", r.stderr
# a recording that does not say its canvas needs --in
nocanvas = os.path.join(out, "nocanvas.lvr")
with open(cubic) as f, open(nocanvas, "w") as g:
    g.write(f.read().replace("canvas 40 40 40\n", ""))
r = run([exe, "play", nocanvas, "--out", os.path.join(out, "nocanvas.vti")], expect=1)
assert "does not say the canvas it was made on" in r.stderr and "--in VOLUME" in r.stderr, r.stderr

# 3. the voxels along a mesh's longest axis have one range in both: lvdif mesh-to-sdf --dims and the editor's
#    --mesh-resolution (8 to 4096 there, 2 to 1048576 here), refused in the same words, and below the
#    padding's least (2 x 2 + 2) each says why
sheet = os.path.join(editor_testing, "open-sheet.obj")
for n in ("1", "1048577"):
    cli = run([exe, "mesh-to-sdf", sheet, os.path.join(out, "range.lvdv"), "--dims", n], expect=2).stderr.strip()
    ed = run([editor, "--open-mesh", sheet, "--mesh-resolution", n, "--quit", *EDITOR_BATCH], expect=2).stderr.strip()
    assert cli == f"lvdif mesh-to-sdf: option --dims expects an integer in [2, 1048576], got '{n}'", cli
    assert ed == f"lvdif-editor: --mesh-resolution expects an integer in [2, 1048576], got '{n}'", ed
cli = run([exe, "mesh-to-sdf", sheet, os.path.join(out, "range.lvdv"), "--dims", "4"], expect=2).stderr.strip()
ed = run([editor, "--open-mesh", sheet, "--mesh-resolution", "4", "--quit", *EDITOR_BATCH], expect=2).stderr.strip()
assert "--dims 4 leaves no voxel for the mesh inside --padding 2" in cli, cli
assert ed == ("lvdif-editor: --mesh-resolution 4 leaves no voxel for the mesh inside the 2 voxels of padding on every "
              "side: use at least 6 (2 x padding + 2)"), ed
# above the old 4096 the option is taken (the next refusal is another rule's: no --open-mesh here)
ed = run([editor, "--mesh-resolution", "5000", "--quit", *EDITOR_BATCH], expect=2).stderr.strip()
assert ed == ("lvdif-editor: --mesh-resolution, --mesh-sign and --mesh-reorient are options of --open-mesh, which is "
              "not given"), ed
print("ok")
