# Run by ParaView's GUI (paraview --script=...): the default chain on a mesh,
# each filter updated before the next is made (as Apply does in the GUI, so the
# Scalars lists are filled), Sign Voxel Filter selected so that the Properties
# panel shows its checkboxes.
# scripts/paraview-screenshots.sh grabs the screen afterwards.
import os

from paraview.simple import *  # noqa: F403 (the GUI's own Python)

mesh = LVDIFMeshReader(FileName=os.environ["LVDIF_GUI_MESH"])  # noqa: F405
sdf = MeshToSDF(Input=mesh)  # noqa: F405
sdf.UpdatePipeline()
svf = SignVoxelFilter(Input=sdf)  # noqa: F405
svf.UpdatePipeline()
mc = ChunkedMarchingCubes(Input=svf)  # noqa: F405
v = GetActiveViewOrCreate("RenderView")  # noqa: F405
Show(sdf, v)  # noqa: F405
d = Show(mc, v)  # noqa: F405
d.ColorArrayName = [None, ""]
d.DiffuseColor = [0.9, 0.6, 0.3]
v.OrientationAxesVisibility = 0
v.CameraPosition = [0.3, 0.4, 2.0]
v.CameraFocalPoint = [0, 0, 0]
v.CameraViewUp = [0, 1, 0]
v.ResetCamera()
Render(v)  # noqa: F405
SetActiveSource(svf)  # noqa: F405
