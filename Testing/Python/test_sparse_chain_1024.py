"""The 1024^3 chain under a memory limit that a dense copy exceeds.

vtkMeshToSDF (a sphere of radius 0.1 of the grid's edge, explicit 1024^3 grid, band 8)
-> vtkSignVoxelFilter (all four filters) -> vtkChunkedMarchingCubes -> .ply,
and the filtered volume -> vtkDictionaryVolumeWriter (.lvdv), with
LVDIF_MEMORY_LIMIT = 1 GiB: a dense float image of the grid needs 4 GiB (the
sign filters' former dense grid alone), sdf + rgba 8 GiB. Checks:
- every stage succeeds, no partitions are built;
- the sign filters' input keeps its expanded chunks, and the filters add
  less than a quarter of the volume to the resident memory (their output
  shares the chunks they did not change: copy-on-write);
- the surface against an independent oracle: its area within 1% of the
  analytic sphere's, its enclosed volume within 1% of the ball's;
- the explicit dense conversion is refused with one error naming the size.
(Exactness of the filters on sparse volumes: the Core and C++ tests.)
Usage: test_sparse_chain_1024.py WORKDIR [N]
"""
import math
import os
import sys
import time

work = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1024
os.makedirs(work, exist_ok=True)
LIMIT = 1 << 30
os.environ["LVDIF_MEMORY_LIMIT"] = str(LIMIT)  # read by Core at every check

import lvdif  # noqa: E402
from lvdif_check import check, finish  # noqa: E402
from vtkmodules.vtkCommonCore import vtkCommand  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkIOPLY import vtkPLYWriter  # noqa: E402



def rss_mib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2.0 ** 20


t0 = time.time()
radius = 0.1 * (n - 1)  # voxel units; spacing 1, origin 0 (small: the test's time is the mesh's)
centre = 0.5 * (n - 1)
sphere = vtkSphereSource()
sphere.SetCenter(centre, centre, centre)
sphere.SetRadius(radius)
sphere.SetThetaResolution(256)
sphere.SetPhiResolution(128)
sdf = lvdif.vtkMeshToSDF()
sdf.SetInputConnection(sphere.GetOutputPort())
sdf.UseExplicitGridOn()
sdf.SetDimensions(n, n, n)
sdf.SetOrigin(0, 0, 0)
sdf.SetSpacing(1, 1, 1)
sdf.SetDevice(lvdif.vtkMeshToSDF.DEVICE_CPU)
sdf.Update()
src = sdf.GetOutputDataObject(0)
check(src.HasVolume(), "Mesh To SDF at %d^3 under LVDIF_MEMORY_LIMIT=%d: %d MiB volume (%.1f s, RSS %.0f MiB)" % (
    n, LIMIT, src.GetVolumeMemoryBytes() / 2 ** 20, time.time() - t0, rss_mib()))
expanded = src.GetNumberOfExpandedChunks()

rss0 = rss_mib()
t1 = time.time()
svf = lvdif.vtkSignVoxelFilter()
svf.SetInputConnection(sdf.GetOutputPort())
svf.SetDevice(lvdif.vtkSignVoxelFilter.DEVICE_CPU)
svf.Update()
out = svf.GetOutputDataObject(0)
check(out.HasVolume(), "Sign Voxel Filter (%.1f s, RSS %.0f MiB)" % (time.time() - t1, rss_mib()))
check(src.GetNumberOfExpandedChunks() == expanded, "its input still holds its %d expanded chunks" % expanded)
volume_mib = src.GetVolumeMemoryBytes() / 2 ** 20
check(rss_mib() - rss0 < 0.25 * volume_mib, "the filters added %.0f MiB to the resident memory (volume: %.0f MiB)" % (
    rss_mib() - rss0, volume_mib))

t2 = time.time()
mc = lvdif.vtkChunkedMarchingCubes()
mc.SetInputConnection(svf.GetOutputPort())
mc.SetOutputModeToMerged()
mc.ComputeNormalsOff()
ply = vtkPLYWriter()
ply.SetInputConnection(mc.GetOutputPort())
ply.SetFileName(os.path.join(work, "sphere%d.ply" % n))
ply.SetFileTypeToBinary()
check(ply.Write() == 1, "Chunked Marching Cubes -> .ply: %d triangles (%.1f s, RSS %.0f MiB)" % (
    mc.GetOutput().GetNumberOfCells(), time.time() - t2, rss_mib()))
writer = lvdif.vtkDictionaryVolumeWriter()
writer.SetInputConnection(svf.GetOutputPort())
writer.SetFileName(os.path.join(work, "sphere%d.lvdv" % n))
check(writer.Write() == 1 and os.path.getsize(writer.GetFileName()) > 0,
      ".lvdv written: %.1f MiB" % (os.path.getsize(writer.GetFileName()) / 2 ** 20))
check(not src.GetPartitionsBuilt() and not out.GetPartitionsBuilt(), "no partitions built on the way")

surface = mc.GetOutput()
mp = vtkMassProperties()
mp.SetInputData(surface)
mp.Update()
want = 4 * math.pi * radius * radius
check(abs(mp.GetSurfaceArea() - want) / want < 0.01, "area %.0f vs the sphere's %.0f (1%%)" % (mp.GetSurfaceArea(), want))
ball = 4.0 / 3.0 * math.pi * radius ** 3
check(abs(mp.GetVolume() - ball) / ball < 0.01, "enclosed volume %.0f vs the ball's %.0f (1%%)" % (mp.GetVolume(), ball))

errors = []


def on_error(obj, event, message):
    errors.append(message)


on_error.CallDataType = "string0"
to_dense = lvdif.vtkSparseVolumeToImage()
to_dense.SetInputConnection(svf.GetOutputPort())
to_dense.AddObserver(vtkCommand.ErrorEvent, on_error)
to_dense.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_error)
to_dense.Update()
check(to_dense.GetOutput().GetNumberOfPoints() == 0 and errors and "%d x %d x %d" % (n, n, n) in errors[0],
      "the dense conversion is refused: %s" % (errors[0].strip().splitlines()[-1] if errors else "no error"))
print("total %.1f s" % (time.time() - t0))
finish()
