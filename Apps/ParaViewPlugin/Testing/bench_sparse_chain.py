# pvbatch benchmark of the sparse chain: a mesh file -> Mesh To SDF (longest
# axis N points, otherwise default properties) -> Sign Voxel Filter (defaults)
# -> Chunked Marching Cubes (defaults) -> the filtered volume saved as .lvdv.
# Prints the time, the resident memory, the peak so far (VmHWM) and glibc's bytes in use
# and held free (mallinfo2) after each stage, then one line
#   BENCH n=.. dims=AxBxC sdf_s=.. svf_s=.. mc_s=.. write_s=.. triangles=.. sdf_output_mib=.. svf_output_mib=.. surface_mib=.. file_mib=..
# (*_output_mib: the data object's GetActualMemorySize: the Core volume plus any partitions built for ParaView)
# Peak RSS comes from the caller (/usr/bin/time -v; scripts/bench-sparse-chain-pvbatch.sh).
# Usage: pvbatch --force-offscreen-rendering bench_sparse_chain.py PLUGIN MESH N OUT.lvdv [--apply]
#   default: the chain and the writer are created first, then updated stage by stage (a script);
#   --apply: each filter is updated before the next is created, as the GUI's Apply does.
import lvdif_pvtest as T  # first: fixes sys.path for route B

import ctypes
import os
import sys
import time

import paraview.simple as pvs

plugin, mesh, n, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
apply_flow = "--apply" in sys.argv[5:]
pvs.LoadPlugin(plugin, remote=False)


def rss_mib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2.0 ** 20


def peak_mib():
    """The process's peak RSS so far (VmHWM): with it each stage's own peak shows."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


class _MallInfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks", "keepcost")]


def heap_mib():
    """glibc's view: (allocated and in use, free but kept by the allocator) in MiB;
    with RSS this tells live data from memory the allocator holds on to."""
    try:
        f = ctypes.CDLL(None).mallinfo2
    except (AttributeError, OSError):
        return float("nan"), float("nan")
    f.restype = _MallInfo2
    m = f()
    return (m.uordblks + m.hblkhd) / 2.0 ** 20, m.fordblks / 2.0 ** 20


def report(name, dt):
    used, free = heap_mib()
    print("%-22s %8.2f s   RSS %7.0f MiB (peak so far %7.0f)   malloc: in use %7.0f MiB, free held %6.0f MiB" % (
        name, dt, rss_mib(), peak_mib(), used, free), flush=True)


def stage(name, proxy):
    t = time.perf_counter()
    proxy.UpdatePipeline()
    dt = time.perf_counter() - t
    report(name, dt)
    return dt


report("start", 0.0)
reader = getattr(pvs, T.PROXY_NAMES["vtkLVDIFMeshReader"])(FileName=mesh)
if apply_flow:
    # as the GUI's Apply does: each filter updated before the next is created
    # (ParaView then gathers the data information of each output, for the
    # next filter's domains)
    stage("read mesh", reader)
    sdf = pvs.MeshToSDF(Input=reader, MaxDimension=n)
    t_sdf = stage("Mesh To SDF", sdf)
    svf = pvs.SignVoxelFilter(Input=sdf)
    t_svf = stage("Sign Voxel Filter", svf)
    mc = pvs.ChunkedMarchingCubes(Input=svf)
    t_mc = stage("Chunked Marching Cubes", mc)
    t = time.perf_counter()
    pvs.SaveData(out, proxy=svf)
    t_write = time.perf_counter() - t
else:
    # as a script does (docs/PARAVIEW.md): the chain and the writer first, then the updates
    sdf = pvs.MeshToSDF(Input=reader, MaxDimension=n)
    svf = pvs.SignVoxelFilter(Input=sdf)
    mc = pvs.ChunkedMarchingCubes(Input=svf)
    # the writer proxy itself: the writer factory (CreateWriter, SaveData) asks
    # for the input's data information, which would run the chain
    from paraview import servermanager
    writer = getattr(servermanager.writers, T.PROXY_NAMES["vtkDictionaryVolumeWriter"])(Input=svf, FileName=out)
    stage("read mesh", reader)
    t_sdf = stage("Mesh To SDF", sdf)
    t_svf = stage("Sign Voxel Filter", svf)
    t_mc = stage("Chunked Marching Cubes", mc)
    t = time.perf_counter()
    writer.UpdatePipeline()
    t_write = time.perf_counter() - t
report("write .lvdv", t_write)

# the VTK objects of this (builtin) session; pvbatch does not load lvdif's
# Python classes, so they show as vtkPartitionedDataSet: only virtual methods
vol = svf.GetClientSideObject().GetOutputDataObject(0)
src = sdf.GetClientSideObject().GetOutputDataObject(0)
surface = mc.GetClientSideObject().GetOutputDataObject(0)
triangles = surface.GetNumberOfCells()
e = sdf.GetDataInformation().GetExtent()
print("BENCH n=%d dims=%dx%dx%d sdf_s=%.2f svf_s=%.2f mc_s=%.2f write_s=%.2f triangles=%d "
      "sdf_output_mib=%.0f svf_output_mib=%.0f surface_mib=%.0f file_mib=%.1f" % (
          n, e[1] + 1, e[3] + 1, e[5] + 1, t_sdf, t_svf, t_mc, t_write, triangles,
          src.GetActualMemorySize() / 1024.0, vol.GetActualMemorySize() / 1024.0,
          surface.GetActualMemorySize() / 1024.0, os.path.getsize(out) / 2.0 ** 20))
for v in pvs.GetViews():
    pvs.Delete(v)
