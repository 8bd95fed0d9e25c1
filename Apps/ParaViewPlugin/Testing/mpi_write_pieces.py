# pvbatch: the distributed .lvdvp writer on a sparse volume whose chunk blocks
# are split unlike its points. Mesh To SDF of an ellipsoid on a 37 x 90 x 12
# grid with anisotropic spacing, chunk edge 8: under 2 ranks the points split
# at y = 44 but the chunks at y = 48 (12 chunks, 6 a rank). The writer cropped
# each rank's piece by the points' split, so rank 1's file held rows 44..47 its
# Mesh To SDF had never computed (a seam of wrong distances: 10,716 triangles
# instead of 10,348). Now a sparse piece is the producer's chunk block.
#
#   mpirun -np 1|2|4 pvbatch mpi_write_pieces.py PLUGIN TMPDIR
#
# Also a volume of one chunk: the ranks without a chunk write nothing (they
# failed, and no index was written).
# Oracle: Chunked Marching Cubes of the same Mesh To SDF (distributed: it asks
# each rank's extent, and gives the serial triangles), against the .lvdvp read
# back, straight and through Sign Voxel Filter; also the dense route (Sparse
# Volume To Image, split by points) written and read back. Same triangle count
# and area (1e-9).
import lvdif_pvtest as T  # first: fixes sys.path for route B

import glob
import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, tmpdir = sys.argv[1], sys.argv[2]
check = T.check
nranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
T.load_plugin(plugin, ["vtkMeshToSDF", "vtkPDictionaryVolumeWriter", "vtkPDictionaryVolumeReader"], remote=True)

ellipsoid = pvs.Transform(Input=pvs.Sphere(ThetaResolution=48, PhiResolution=24, Radius=0.5))
ellipsoid.Transform.Scale = [1.0, 1.8, 0.9]


def mesh_to_sdf():
    return pvs.MeshToSDF(Input=ellipsoid, UseExplicitGrid=1, Dimensions=[37, 90, 12], Origin=[-0.6, -1.0, -0.55],
                         Spacing=[1.2 / 36, 2.0 / 89, 1.1 / 11], ChunkEdge=8)


def surface(source):
    mc = pvs.ChunkedMarchingCubes(Input=source)
    mc.UpdatePipeline()
    area = pvs.IntegrateVariables(Input=mc)
    area.UpdatePipeline()
    a = servermanager.Fetch(area).GetCellData().GetArray("Area").GetValue(0)
    return mc.GetDataInformation().GetNumberOfCells(), a


want = surface(mesh_to_sdf())
want_svf = surface(pvs.SignVoxelFilter(Input=mesh_to_sdf()))
print("ranks %d, direct: %d triangles, area %.9f; through the sign filters: %d" % (nranks, want[0], want[1], want_svf[0]))
check(want[0] > 10000, "the direct surface has its triangles")
for name, make, ref in (
        ("sparse", lambda: mesh_to_sdf(), want),
        ("sparse through the sign filters", lambda: pvs.SignVoxelFilter(Input=mesh_to_sdf()), want_svf),
        ("dense", lambda: pvs.SparseVolumeToImage(Input=mesh_to_sdf()), want)):
    path = os.path.join(tmpdir, "mpi_write_pieces_np%d_%s.lvdvp" % (nranks, name.split()[0] + str(len(name))))
    pvs.SaveData(path, proxy=make())
    got = surface(pvs.LVDIFParallelDictionaryVolumeReader(FileName=path))
    check(got[0] == ref[0] and abs(got[1] - ref[1]) <= 1e-9 * ref[1],
          "%d ranks, %s volume written and read back: %d triangles, area %.9f (direct %d, %.9f)"
          % (nranks, name, got[0], got[1], ref[0], ref[1]))
# a volume of one chunk (32 points, chunk edge 32): the ranks but the first have no
# chunk, and wrote nothing but an error ("no input image or sparse volume"), and no index
small = pvs.MeshToSDF(Input=ellipsoid, MaxDimension=32)
want_small = surface(small)
path = os.path.join(tmpdir, "mpi_write_pieces_np%d_one_chunk.lvdvp" % nranks)
if os.path.exists(path):
    os.remove(path)
# one process (a serial write) refuses pieces left without their index, as possibly another volume's
# files: an earlier run's are removed (with several ranks, a rank's removal could meet another's new piece)
if nranks == 1:
    for old in glob.glob(path[:-len(".lvdvp")] + "_*.lvdv"):
        os.remove(old)
pvs.SaveData(path, proxy=small)
check(os.path.exists(path), "%d ranks wrote the index of a one-chunk volume" % nranks)
if os.path.exists(path):
    got = surface(pvs.LVDIFParallelDictionaryVolumeReader(FileName=path))
    check(got[0] == want_small[0] and abs(got[1] - want_small[1]) <= 1e-9 * want_small[1],
          "%d ranks, one-chunk volume written and read back: %d triangles (direct %d)" % (nranks, got[0], want_small[0]))

# shown (first display: Outline): every rank takes the sparse outline's path, also a
# rank without chunks (it ran ParaView's geometry filter, whose communication the
# others never entered: pvbatch aborted with MPI_ERR_TRUNCATE on 2 ranks)
view = pvs.CreateRenderView()
rep = pvs.Show(small, view)
pvs.Render(view)
n = rep.GetRepresentedDataInformation().GetNumberOfPoints()
check(n == 8, "%d ranks show the one-chunk volume's outline: one box (%d points)" % (nranks, n))

print("FAILURES: %d" % check.failures if check.failures else "ALL PASSED")
if check.failures:
    sys.exit(1)
