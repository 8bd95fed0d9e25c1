"""pvpython: the original LVDIF's .bv files open in ParaView (LVDIFLegacyBvReader).
They could not (no reader registered the extension: "No reader found for 'SDF_6_x.bv'"),
though the CLI converts them and vtkLegacyBvReader was in the plugin.
Oracle: a hand-made 6^3 file whose record at their (X, Y, Z) holds the inside-positive
value 0.001 (100 X + 10 Y + Z + 1) on the even key 2 (100 X + 10 Y + Z + 1) (their table,
original-code-spec.md 3.2): with the default SwapXZ our point (x, y, z) = their (z, y, x)
holds minus that value; the grid is 6^3 points of spacing 1 from the origin. A file whose
size is not 4 N^3 gives one error naming the rule, and the Open dialog lists *.bv.
Usage: test_legacy_bv.py PLUGIN TMPDIR"""
import lvdif_pvtest  # noqa: F401  (first: ParaView's Python on sys.path)
import os
import struct
import sys

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from lvdif_check import check, finish

plugin, tmp = sys.argv[1], sys.argv[2]
pvs.LoadPlugin(plugin, remote=False)
out = os.path.join(tmp, "legacy_bv")
os.makedirs(out, exist_ok=True)
window = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window)
sys.stdout, sys.stderr = sys.__stdout__, sys.__stderr__

N = 6


def theirs(X, Y, Z):
    return 100 * X + 10 * Y + Z + 1


path = os.path.join(out, "SDF_%d_ramp.bv" % N)
with open(path, "wb") as f:
    for Z in range(N):
        for Y in range(N):
            for X in range(N):
                f.write(struct.pack("<HH", 2 * theirs(X, Y, Z), 0))

rf = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
session = servermanager.ActiveConnection.Session
check("*.bv" in rf.GetSupportedFileTypes(session), "the Open dialog lists *.bv")
ok = rf.CanReadFile(path, session)
check(bool(ok) and rf.GetReaderName() == "LVDIFLegacyBvReader",
      "the reader factory picks %s for the .bv" % (rf.GetReaderName() if ok else None))

reader = pvs.OpenDataFile(path)
check(reader is not None and reader.GetXMLName() == "LVDIFLegacyBvReader", "OpenDataFile opens the .bv")
dense = pvs.SparseVolumeToImage(Input=reader)
img = servermanager.Fetch(dense)
check(img.GetDimensions() == (N, N, N) and img.GetOrigin() == (0.0, 0.0, 0.0) and img.GetSpacing() == (1.0, 1.0, 1.0),
      "grid %s, origin %s, spacing %s" % (img.GetDimensions(), img.GetOrigin(), img.GetSpacing()))
sdf = img.GetPointData().GetArray("sdf")
worst = 0.0
for z in range(N):
    for y in range(N):
        for x in range(N):
            want = -0.001 * theirs(z, y, x)  # SwapXZ: our (x, y, z) is their (z, y, x); negated
            worst = max(worst, abs(sdf.GetValue(x + N * (y + N * z)) - want))
check(worst < 1e-6, "every sdf value is their value, negated and X/Z exchanged (worst %g)" % worst)
view = pvs.CreateRenderView()
display = pvs.Show(reader, view)
check(display.GetXMLName() == "LVDIFSparseVolumeRepresentation" and display.Representation == "Outline",
      "first display %s as %s" % (display.GetXMLName(), display.Representation))
check(reader.GetDataInformation().GetBounds() == (0.0, N - 1.0, 0.0, N - 1.0, 0.0, N - 1.0),
      "bounds %s: the grid's" % (reader.GetDataInformation().GetBounds(),))

# a size that is not 4 N^3, opened by its reader: one error naming the rule
bad = os.path.join(out, "odd.bv")
with open(bad, "wb") as f:
    f.write(b"\0" * (4 * 27 + 1))
start = len(window.GetOutput())
proxy = pvs.LVDIFLegacyBVReader(FileName=bad)
proxy.UpdatePipeline()
got = [" ".join(m.split()) for m in window.GetOutput()[start:].split("ERROR: In ")[1:]]
check(len(got) == 1 and "109 bytes is not 4*N^3" in got[0], "a bad size: one error, got %d: %s" % (len(got), got))
finish()
