"""Runs `lvdif demo` (the embedded dice script) and checks its outputs against
oracles independent of the meshing code:
* the PLY is closed (VTK's vtkFeatureEdges finds no boundary/non-manifold edge);
* its bounding box is the dice's analytic box, n/2 +- 0.4 n;
* its enclosed volume (vtkMassProperties) matches the count of inside voxels of
  the saved .lvdv, read back through vtkDictionaryVolumeReader (a different
  path: file decoding and voxel counting, no surface);
* both the white body and the red interior exposed by the pips are coloured;
* `lvdif info` reads the file back and the PNG is a real picture."""
import subprocess
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

exe, out = sys.argv[1], sys.argv[2]
n = 96
run = subprocess.run([exe, "demo", "--out", out, "--size", str(n)], capture_output=True, text=True, timeout=240)
print(run.stdout)
print(run.stderr, file=sys.stderr)
assert run.returncode == 0, f"demo exited with {run.returncode}"

reader = vtk.vtkPLYReader()
reader.SetFileName(f"{out}/demo.ply")
reader.Update()
mesh = reader.GetOutput()
clean = vtk.vtkCleanPolyData()
clean.SetInputData(mesh)
clean.Update()
edges = vtk.vtkFeatureEdges()
edges.SetInputConnection(clean.GetOutputPort())
edges.BoundaryEdgesOn()
edges.NonManifoldEdgesOn()
edges.FeatureEdgesOff()
edges.ManifoldEdgesOff()
edges.Update()
assert edges.GetOutput().GetNumberOfCells() == 0, f"{edges.GetOutput().GetNumberOfCells()} open or non-manifold edges"

lo, hi = n / 2 - 0.4 * n, n / 2 + 0.4 * n
b = mesh.GetBounds()
for axis in range(3):
    assert abs(b[2 * axis] - lo) < 1.0 and abs(b[2 * axis + 1] - hi) < 1.0, (b, lo, hi)

mass = vtk.vtkMassProperties()
mass.SetInputConnection(clean.GetOutputPort())
mass.Update()

from lvdif import vtkDictionaryVolumeReader, vtkSparseVolumeToImage  # noqa: E402

vol = vtkDictionaryVolumeReader()
vol.SetFileName(f"{out}/demo.lvdv")
dense = vtkSparseVolumeToImage()  # the reader gives the sparse volume; the voxels are checked here
dense.SetInputConnection(vol.GetOutputPort())
dense.Update()
sdf = vtk_to_numpy(dense.GetOutput().GetPointData().GetArray("sdf"))
inside = float(np.count_nonzero(sdf < 0))
rel = abs(mass.GetVolume() - inside) / inside
print(f"enclosed volume {mass.GetVolume():.0f}, inside voxels {inside:.0f}, relative difference {rel:.4f}")
assert rel < 0.02, rel

rgba = vtk_to_numpy(mesh.GetPointData().GetArray("RGBA") or mesh.GetPointData().GetScalars())
red = np.count_nonzero((rgba[:, 0] > 180) & (rgba[:, 1] < 80))
white = np.count_nonzero((rgba[:, 0] > 200) & (rgba[:, 1] > 200) & (rgba[:, 2] > 200))
print(f"red vertices {red}, white vertices {white}")
assert red > 100 and white > 1000

info = subprocess.run([exe, "info", f"{out}/demo.lvdv"], capture_output=True, text=True, timeout=60)
assert info.returncode == 0 and f"{n} x {n} x {n}" in info.stdout, info.stdout + info.stderr

png = vtk.vtkPNGReader()
png.SetFileName(f"{out}/demo.png")
png.Update()
img = png.GetOutput()
assert img.GetDimensions()[:2] == (800, 600)
lo_px, hi_px = img.GetPointData().GetScalars().GetRange(0)
assert hi_px - lo_px > 100, "the picture is flat"
print("demo outputs OK")
