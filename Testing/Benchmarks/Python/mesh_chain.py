#!/usr/bin/python3
"""The mesh chain in Python (the VTK filters alone, no ParaView):
MESH -> vtkLVDIFMeshReader -> vtkMeshToSDF (longest axis N points, the plugin's
defaults) -> vtkSignVoxelFilter -> vtkChunkedMarchingCubes (merged, the
surface kept in memory) and the filtered volume -> vtkDictionaryVolumeWriter (.lvdv).

Usage: mesh_chain.py MESH N OUT.lvdv
Prints the time and resident memory after each stage and one BENCH line. Run
it under /usr/bin/time -v for the peak RSS (docs/BENCHMARKS.md).
"""
import os
import sys
import time

import lvdif

mesh, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]


def rss_mib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2.0 ** 20


def stage(name, alg):
    t = time.time()
    alg.Update()
    dt = time.time() - t
    print("%-22s %8.2f s   RSS %7.0f MiB" % (name, dt, rss_mib()), flush=True)
    return dt


print("%-22s %8s     RSS %7.0f MiB" % ("start", "", rss_mib()))
reader = lvdif.vtkLVDIFMeshReader()
reader.SetFileName(mesh)
stage("read mesh", reader)
sdf = lvdif.vtkMeshToSDF()
sdf.SetInputConnection(reader.GetOutputPort())
sdf.SetMaxDimension(n)
t_sdf = stage("Mesh To SDF", sdf)
svf = lvdif.vtkSignVoxelFilter()
svf.SetInputConnection(sdf.GetOutputPort())
t_svf = stage("Sign Voxel Filter", svf)
mc = lvdif.vtkChunkedMarchingCubes()
mc.SetInputConnection(svf.GetOutputPort())
mc.SetOutputModeToMerged()
t_mc = stage("Chunked Marching Cubes", mc)
writer = lvdif.vtkDictionaryVolumeWriter()
writer.SetInputConnection(svf.GetOutputPort())
writer.SetFileName(out)
t = time.time()
if not writer.Write():
    sys.exit("writing %s failed" % out)
t_write = time.time() - t
print("%-22s %8.2f s   RSS %7.0f MiB" % ("write .lvdv", t_write, rss_mib()), flush=True)
v = svf.GetOutputDataObject(0)
dims = [0, 0, 0]
v.GetDimensions(dims)
print("BENCH n=%d dims=%dx%dx%d sdf_s=%.2f svf_s=%.2f mc_s=%.2f write_s=%.2f triangles=%d volume_mib=%.0f "
      "expanded=%d partitions_built=%d file_mib=%.1f" % (
          n, dims[0], dims[1], dims[2], t_sdf, t_svf, t_mc, t_write, mc.GetOutput().GetNumberOfCells(),
          sdf.GetOutputDataObject(0).GetVolumeMemoryBytes() / 2.0 ** 20, v.GetNumberOfExpandedChunks(),
          int(v.GetPartitionsBuilt() or sdf.GetOutputDataObject(0).GetPartitionsBuilt()),
          os.path.getsize(out) / 2.0 ** 20))
