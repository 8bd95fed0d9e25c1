"""A failed read is ONE error in the output window (what pvpython and the
ParaView GUI show): the reader's own, naming the file. VTK's executive followed
it with "Algorithm X returned failure for request: <the request dumped>", once
for the information pass and again for each later update (ParaView updates a
proxy when it is created and again at UpdatePipeline / Apply), so a missing
file gave its error and two or more such dumps (LVDIFVolumeBridge::FailReported
now drops them). Counts every error message reaching the output window, with
no observer on the algorithms; the reader updated twice, then a filter below it.
Usage: test_reader_errors.py OUTDIR"""
import os
import sys

import vtk

import lvdif
from lvdif_check import check, finish

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
window = vtk.vtkStringOutputWindow()
vtk.vtkOutputWindow.SetInstance(window)


def errors_during(work):
    start = len(window.GetOutput())
    work()
    return [" ".join(m.split()) for m in window.GetOutput()[start:].split("ERROR: In ")[1:]]


def reader(cls, path):
    r = getattr(lvdif, cls)()
    if path is not None:
        r.SetFileName(path)
    return r


# a good .lvdv, then one cut after its header (the table missing)
mesh = vtk.vtkSphereSource()
sdf = lvdif.vtkMeshToSDF()
sdf.SetInputConnection(mesh.GetOutputPort())
sdf.SetMaxDimension(16)
good = os.path.join(out, "good.lvdv")
w = lvdif.vtkDictionaryVolumeWriter()
w.SetInputConnection(sdf.GetOutputPort())
w.SetFileName(good)
assert w.Write() == 1
malformed = os.path.join(out, "malformed.lvdv")
with open(malformed, "wb") as f:
    f.write(open(good, "rb").read()[:300])
junk = os.path.join(out, "junk.vdb")
with open(junk, "w") as f:
    f.write("this is not an OpenVDB file")

CASES = [("vtkDictionaryVolumeReader", os.path.join(out, "missing.lvdv"), "cannot open"),
         ("vtkDictionaryVolumeReader", None, "no file name"),
         ("vtkDictionaryVolumeReader", malformed, "malformed.lvdv"),
         ("vtkPDictionaryVolumeReader", os.path.join(out, "missing.lvdvp"), "missing.lvdvp"),
         ("vtkLegacyBvReader", os.path.join(out, "missing.bv"), "cannot open"),
         ("vtkLVDIFMeshReader", os.path.join(out, "missing.obj"), "cannot open"),
         ("vtkLVDIFMeshReader", None, "no file name")]
if hasattr(lvdif, "vtkOpenVDBLevelSetReader"):
    CASES += [("vtkOpenVDBLevelSetReader", os.path.join(out, "missing.vdb"), "cannot open"),
              ("vtkOpenVDBLevelSetReader", junk, "OpenVDB cannot open")]
for cls, path, needle in CASES:
    r = reader(cls, path)
    below = lvdif.vtkMeshToSDF() if cls == "vtkLVDIFMeshReader" else lvdif.vtkSignVoxelFilter()
    below.SetInputConnection(r.GetOutputPort())
    got = errors_during(lambda: (r.Update(), r.Update(), below.Update()))
    check(len(got) == 1 and needle in got[0] and (path is None or os.path.basename(path) in got[0]),
          "%s %s: one error with '%s', got %d: %s" % (cls, path, needle, len(got), [g[:300] for g in got]))
    # the reader pointed at a good file afterwards: no error, data (nothing stays quiet)
    if cls == "vtkDictionaryVolumeReader":
        r.SetFileName(good)
        got = errors_during(lambda: (r.Update(), below.Update()))
        check(not got and r.GetOutput().HasVolume(), "%s then %s: %s" % (cls, good, got))

# an error the reader did not report itself still reaches the window (the executive's
# own: a filter without its input), so nothing but the dumps of reported failures is dropped
lonely = lvdif.vtkSignVoxelFilter()
got = errors_during(lonely.Update)
check(len(got) >= 1, "a filter without input: the executive's error still shows (%d)" % len(got))
finish()
