# pvbatch test of distributed execution: mesh -> SDF -> marching cubes
# -> write (parallel .pvtp) -> read, every rank computing its own piece of the
# volume, compared with the single-process result.
#
# Usage (ParaView runs the script on rank 0 and the pipeline on every rank):
#   pvbatch --force-offscreen-rendering mpi_pipeline.py PLUGIN TMPDIR --reference [classes]
#   mpirun -np 2 pvbatch --force-offscreen-rendering mpi_pipeline.py PLUGIN TMPDIR --compare [classes]
# Options: --n N (grid points per axis, default the tests' 48), --time (print stage times).
#
# Ownership rule checked here (docs/PARAVIEW.md): VTK splits the point extent
# into pieces that share one point plane per cut. A CELL lies in exactly one
# piece, so every triangle is made by exactly one rank (no duplicates). A POINT
# on a shared plane belongs to the piece where it is NOT on the upper face,
# i.e. index i on axis a is owned when lo_a <= i < hi_a, or i == hi_a == the
# whole extent's maximum. Point reductions (inside-voxel counts, chunk output of
# the writer) must use this rule; surface vertices on shared planes exist once
# per rank and are merged only when one file is wanted (clean / merge points).
import lvdif_pvtest as T  # first: fixes sys.path for route B

import builtins  # pvbatch scripts see numpy_interface.algorithms.sum as `sum`
import json
import os
import sys
import time

import paraview.simple as pvs
from paraview import servermanager

args = sys.argv[1:]
plugin, tmpdir, mode = args[0], args[1], args[2]
rest = args[3:]
timing = "--time" in rest
if "--n" in rest:
    T.N = int(rest[rest.index("--n") + 1])
    rest = [a for i, a in enumerate(rest) if a != "--n" and (i == 0 or rest[i - 1] != "--n")]
classes = [a for a in rest if a.startswith("vtk")]
check = T.check

nranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks:", nranks)
present = T.load_plugin(plugin, classes, remote=True)

t0 = time.perf_counter()
sdf, how = T.sdf_stage(present)
print("SDF stage:", how)
# The sign voxel filter scans whole rows and planes; it asks for the whole
# input and outputs the rank's piece (docs/PARAVIEW.md), so every piece equals
# the serial result. The corruption includes a box of wrong signs that crosses
# the cuts of 2 and 4 pieces (z = 24, y = 24 at N = 48), and the filter axis is
# Z, so its rows are cut too: a piece filtered alone would not repair it.
SLAB = ((T.N * 3 // 8, T.N * 3 // 8, T.N * 5 // 24), (T.N * 5 // 8, T.N * 5 // 8, T.N * 19 // 24))
field = sdf
if present["vtkSignVoxelFilter"]:
    field = T.sign_voxel_stage(T.corrupt_signs(sdf, slab=SLAB))
    field.Axis = "Z"
    print("SVF stage: Sign Voxel Filter (axis Z) on corrupted signs, box %s..%s" % SLAB)
c, mc = T.contour(field, present)
surface = mc if mc is not None else c
surface.UpdatePipeline()
t1 = time.perf_counter()


OWNED_SCRIPT = """
import numpy as np
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk
img = self.GetInputDataObject(0, 0)
whole = self.GetInputInformation(0, 0).Get(sddp.WHOLE_EXTENT())
e = img.GetExtent()
d = vtk_to_numpy(img.GetPointData().GetArray('sdf'))
nx, ny, nz = e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1
d = d.reshape(nz, ny, nx)
# keep index i when lo <= i < hi, or i == hi == whole max
hx = nx if e[1] == whole[1] else nx - 1
hy = ny if e[3] == whole[3] else ny - 1
hz = nz if e[5] == whole[5] else nz - 1
k, j, i = np.nonzero(d[:hz, :hy, :hx] < 0)
o, s = img.GetOrigin(), img.GetSpacing()
xyz = np.stack([(i + e[0]) * s[0] + o[0], (j + e[2]) * s[1] + o[1], (k + e[4]) * s[2] + o[2]], axis=1)
pts = vtkPoints(); pts.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=1))
out = self.GetPolyDataOutput(); out.SetPoints(pts)
"""


def owned_inside(image):
    owned = pvs.ProgrammableFilter(Input=image, OutputDataSetType="vtkPolyData")
    owned.Script = OWNED_SCRIPT
    owned_pd = servermanager.Fetch(owned)
    n = owned_pd.GetNumberOfPoints()
    return n, len({tuple(round(x, 6) for x in owned_pd.GetPoint(i)) for i in range(n)})


def parallel_volume_stage():
    """Every rank writes its piece (.lvdv) and rank 0 the .lvdvp index; then the
    index is read back distributed and contoured. Returns the contour's triangles."""
    path = os.path.join(tmpdir, "mpi_volume_np%d.%s" % (nranks, T.PLVD_EXTENSION))
    pieces = [os.path.join(tmpdir, "mpi_volume_np%d_%d.lvdv" % (nranks, r)) for r in range(nranks)]
    for old in [path] + pieces:
        if os.path.exists(old):
            os.remove(old)
    T.check_parallel_io_hints(field, check)
    wf = servermanager.vtkSMProxyManager.GetProxyManager().GetWriterFactory()
    types = wf.GetSupportedFileTypes(field.SMProxy, 0)
    if nranks > 1:
        check("*.%s)" % T.LVD_EXTENSION not in types and "*.%s " % T.LVD_EXTENSION not in types,
              "distributed session: the serial .%s writer is not offered, the .%s one is" % (T.LVD_EXTENSION, T.PLVD_EXTENSION))
    t = time.perf_counter()
    pvs.SaveData(path, proxy=field)
    t_write = time.perf_counter() - t
    with open(path) as f:
        listed = [line.split()[-1] for line in f if line.startswith("piece ")]
    check(os.path.exists(path) and listed == [os.path.basename(p) for p in pieces] and builtins.all(os.path.exists(p) for p in pieces),
          "%d ranks wrote the index and %d piece files %s" % (nranks, len(listed), listed))
    rd = getattr(pvs, T.PROXY_NAMES["vtkPDictionaryVolumeReader"])(FileName=path)
    check(T.is_sparse(rd), "the .lvdvp reader gives the sparse volume")
    # Contour over each rank's partitions (its own chunk block), merged to one polydata a rank
    rc = pvs.ExtractSurface(Input=pvs.MergeBlocks(Input=pvs.Contour(
        Input=rd, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0,
        ComputeScalars=0, ComputeGradients=0)))
    rpid = servermanager.Fetch(pvs.ProcessIdScalars(Input=rc))
    prange = rpid.GetPointData().GetArray("ProcessId").GetRange()
    check(prange == (0.0, nranks - 1.0), "every rank read its part of the .lvdvp and contoured it (%s)" % (prange,))
    if timing:
        print("TIME ranks=%d N=%d lvdvp_write=%.3f s" % (nranks, T.N, t_write))
    return T.triangle_key_list(servermanager.Fetch(rc))


def verify():
    # Owned inside points per rank, by the ownership rule.
    inside, inside_unique = owned_inside(field)
    if field is not sdf and mode == "--reference":
        clean, _ = owned_inside(sdf)
        check(inside == clean, "Sign Voxel Filter restores the inside set: %d voxels vs %d clean" % (inside, clean))

    # Which rank made which triangles.
    pid = pvs.ProcessIdScalars(Input=surface)
    pid_pd = servermanager.Fetch(pid)
    pid_range = pid_pd.GetPointData().GetArray("ProcessId").GetRange() if pid_pd.GetNumberOfPoints() else (-1, -1)

    # write (one piece per rank + a .pvtp index) -> read back
    t2 = time.perf_counter()
    path = os.path.join(tmpdir, "mpi_surface_np%d.pvtp" % nranks)
    pvs.SaveData(path, proxy=surface)
    t3 = time.perf_counter()
    back = pvs.OpenDataFile(path)
    merged = servermanager.Fetch(back)
    tris = T.triangle_key_list(merged)  # ghost (DUPLICATECELL) triangles dropped
    ghost = merged.GetCellData().GetArray("vtkGhostType")
    print("read back %d cells, %d of them ghost copies" % (merged.GetNumberOfCells(),
          builtins.sum(1 for i in range(merged.GetNumberOfCells()) if ghost and int(ghost.GetValue(i)) & 1)))

    if timing:
        print("TIME ranks=%d N=%d pipeline=%.3f s write=%.3f s triangles=%d" % (nranks, T.N, t1 - t0, t3 - t2, len(tris)))

    # Distributed reading: the serial run writes the volume (.lvdv, serial
    # writer); every run reads it back piecewise (each rank decodes only the
    # chunks of its extent) and contours it.
    lvd = os.path.join(tmpdir, "mpi_volume_N%d.%s" % (T.N, T.LVD_EXTENSION))
    read_tris = None
    if present["vtkDictionaryVolumeReader"] and present["vtkDictionaryVolumeWriter"]:
        if mode == "--reference":
            pvs.SaveData(lvd, proxy=field)
        reader = T.PROXY_NAMES["vtkDictionaryVolumeReader"]
        rd = getattr(pvs, reader)(FileName=lvd)
        # the reader gives the sparse volume; a rank reads the block of storage
        # chunks it owns and Contour runs on their partitions (the composite
        # result is merged to one polydata per rank for the comparison)
        rc = pvs.ExtractSurface(Input=pvs.MergeBlocks(Input=pvs.Contour(
            Input=rd, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0, ComputeScalars=0,
            ComputeGradients=0)))
        rpid = servermanager.Fetch(pvs.ProcessIdScalars(Input=rc))
        read_pid_range = rpid.GetPointData().GetArray("ProcessId").GetRange()
        read_tris = T.triangle_key_list(servermanager.Fetch(rc))
        print("read %s on %d ranks: %d triangles, ProcessId range %s" % (
            os.path.basename(lvd), nranks, len(read_tris), read_pid_range))
    else:
        print("distributed read: skipped (reader/writer not in the plugin)")

    pread_tris = None
    if present["vtkPDictionaryVolumeWriter"] and present["vtkPDictionaryVolumeReader"]:
        pread_tris = parallel_volume_stage()
    else:
        print("distributed write: skipped (parallel reader/writer not in the plugin)")

    ref_path = os.path.join(tmpdir, "mpi_reference_N%d.json" % T.N)
    if mode == "--reference":
        check(nranks == 1, "reference run is single-process")
        check(len(tris) > 0 and len(set(tris)) == len(tris), "serial surface has %d distinct triangles" % len(tris))
        check(inside == inside_unique, "serial owned points are distinct (%d)" % inside)
        if read_tris is not None:
            check(len(read_tris) > 0, "serial contour of the read volume: %d triangles" % len(read_tris))
        with open(ref_path, "w") as f:
            json.dump({"triangles": tris, "inside": inside, "sdf": how, "read_triangles": read_tris,
                       "pread_triangles": pread_tris}, f)
    else:
        with open(ref_path) as f:
            ref = json.load(f)
        ref_tris = [tuple(tuple(v) for v in t) for t in ref["triangles"]]
        check(nranks > 1, "%d ranks" % nranks)
        check(pid_range == (0.0, nranks - 1.0), "triangles come from ranks %s (want 0..%d)" % (pid_range, nranks - 1))
        check(len(tris) == len(ref_tris), "%d triangles from %d ranks vs %d serial" % (len(tris), nranks, len(ref_tris)))
        check(len(set(tris)) == len(tris), "no duplicated triangle across ranks")
        check(tris == ref_tris, "the triangles (rounded vertices) equal the serial ones")
        check(inside == ref["inside"] and inside_unique == inside,
              "owned inside points: %d over ranks (%d distinct) vs %d serial" % (inside, inside_unique, ref["inside"]))
        if read_tris is not None:
            ref_read = [tuple(tuple(v) for v in t) for t in (ref.get("read_triangles") or [])]
            check(read_pid_range == (0.0, nranks - 1.0), "every rank read and contoured its part (%s)" % (read_pid_range,))
            check(read_tris == ref_read, "contour of the distributed read: %d triangles, equal to the serial %d" % (
                len(read_tris), len(ref_read)))
        if pread_tris is not None:
            ref_pread = [tuple(tuple(v) for v in t) for t in (ref.get("pread_triangles") or [])]
            check(len(pread_tris) > 0 and pread_tris == ref_pread,
                  "contour of the %d-rank .lvdvp read on %d ranks: %d triangles, equal to the serial %d" % (
                      nranks, nranks, len(pread_tris), len(ref_pread)))



def bench():
    """Timing only (scripts/bench-paraview-mpi.sh): the first, uncached update
    of the whole pipeline (t0..t1 above), then the parallel write."""
    path = os.path.join(tmpdir, "bench_surface_np%d.pvtp" % nranks)
    t2 = time.perf_counter()
    pvs.SaveData(path, proxy=surface)
    t3 = time.perf_counter()
    ntri = surface.GetDataInformation().GetNumberOfCells()
    print("BENCH ranks=%d N=%d sdf=%s surface=%s pipeline_s=%.3f write_s=%.3f triangles=%d" % (
        nranks, T.N, how.split(":")[0], "vtkChunkedMarchingCubes" if mc is not None else "Contour",
        t1 - t0, t3 - t2, ntri))


if mode == "--bench":
    bench()
else:
    verify()
print("failures:", check.failures)
# Never sys.exit(0) under pvbatch: it leaves without MPI_Finalize and mpirun
# reports an abnormal termination. A failure may (the exit code is what counts).
if check.failures:
    sys.exit(1)
