"""Runs `lvdif demo` and checks its outputs against independent oracles:
the mesh is closed (VTK's vtkFeatureEdges finds no boundary or non-manifold
edge) and encloses the volume of the analytic shape (sphere minus box,
integrated by Monte Carlo with a fixed seed), and the PNG is a real picture."""
import subprocess
import sys

import numpy as np
import vtk

exe, out = sys.argv[1], sys.argv[2]
size = 96
run = subprocess.run([exe, "demo", "--out", out, "--size", str(size)], capture_output=True, text=True, timeout=240)
print(run.stdout)
print(run.stderr, file=sys.stderr)
assert run.returncode == 0, f"demo exited with {run.returncode}"
assert "triangles" in run.stdout

reader = vtk.vtkPLYReader()
reader.SetFileName(f"{out}/demo.ply")
reader.Update()
mesh = reader.GetOutput()
assert mesh.GetNumberOfPolys() > 1000, mesh.GetNumberOfPolys()

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

mass = vtk.vtkMassProperties()
mass.SetInputConnection(clean.GetOutputPort())
mass.Update()

# The analytic shape of DemoScene.cxx in voxel units.
c, r = 0.5 * size, 0.3 * size
rng = np.random.default_rng(1)
p = rng.uniform(c - r, c + r, size=(2_000_000, 3))
in_sphere = np.linalg.norm(p - c, axis=1) < r
in_box = np.all(np.abs(p - (c + 0.5 * r)) < 0.45 * r, axis=1)
analytic = (2 * r) ** 3 * np.mean(in_sphere & ~in_box)
rel = abs(mass.GetVolume() - analytic) / analytic
print(f"enclosed volume {mass.GetVolume():.1f}, analytic {analytic:.1f}, relative error {rel:.4f}")
assert rel < 0.01, rel

png = vtk.vtkPNGReader()
png.SetFileName(f"{out}/demo.png")
png.Update()
img = png.GetOutput()
assert img.GetDimensions()[:2] == (800, 600)
lo, hi = img.GetPointData().GetScalars().GetRange(0)
assert hi - lo > 100, "the picture is flat"
print("demo outputs OK")
