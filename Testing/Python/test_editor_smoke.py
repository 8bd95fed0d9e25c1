"""Smoke test: the editing API is usable from Python (from lvdif import vtkLVDIFEditor)."""
import math
import sys

from lvdif import vtkLVDIFEditor, vtkVolumeEditFilter


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


ed = vtkLVDIFEditor()
if not ed.NewVolume(32, 32, 32, False):
    fail(ed.GetLastError())
events = []
ed.AddObserver(vtkLVDIFEditor.ChunksModifiedEvent, lambda obj, ev: events.append(ev))
ed.SetOperationToAdd()
ed.SetRadius(6.0)
ed.SetColor(255, 0, 0, 255)
if not ed.Dab(16, 16, 16):
    fail(ed.GetLastError())
if not events:
    fail("no ChunksModifiedEvent")
src = ed.GetImageSource()
src.Update()
img = src.GetOutput()
sdf = img.GetPointData().GetArray("sdf")
centre = img.ComputePointId([16, 16, 16])
# oracle: the analytic sphere distance at its centre is -radius, saturated to the band (8)
if abs(sdf.GetValue(centre) - (-6.0)) > 1e-3:
    fail("centre distance %g" % sdf.GetValue(centre))
if not ed.CanUndo() or not ed.Undo():
    fail("undo")
src.Update()
if src.GetOutput().GetPointData().GetArray("sdf").GetValue(centre) <= 0:
    fail("undo did not restore the empty volume")
# a script's edits are undoable through the same session
if not ed.RunScript("op add\nsphere 16 16 16 3"):
    fail(ed.GetLastError())
if ed.GetUndoCount() != 1 or not ed.Undo():
    fail("script edit not undoable (undo count %d)" % ed.GetUndoCount())
# the session: where it runs (GPU when usable, else the CPU with a notice) and the mesh chunks of the events
if ed.GetDevice() != 0 or (ed.IsOnDevice() and ed.GetNotice()):
    fail("device %d, on the GPU %s, notice %s" % (ed.GetDevice(), ed.IsOnDevice(), ed.GetNotice()))
if ed.GetMeshChunkEdge() < 16:
    fail("mesh chunk edge %d" % ed.GetMeshChunkEdge())
ed.GlobalWarningDisplayOff()  # the next error is expected
if ed.RunScript("sphere 1 2 3 4\n  bogus 1\n"):
    fail("a bad script succeeded")
if (ed.GetLastErrorLine(), ed.GetLastErrorColumn()) != (2, 3):
    fail("error at %d:%d: %s" % (ed.GetLastErrorLine(), ed.GetLastErrorColumn(), ed.GetLastError()))

f = vtkVolumeEditFilter()
f.SetInputConnection(src.GetOutputPort())
f.SetScriptText("sphere 10, 10, 10, 3")
f.Update()
v = f.GetOutput().GetPointData().GetArray("sdf").GetValue(f.GetOutput().ComputePointId([10, 10, 10]))
if not math.isclose(v, -3.0, abs_tol=1e-3):
    fail("filter output %g" % v)
print("ok")
