"""The sparse dictionary volume through VTK (vtkSparseDictionaryVolume).

Usage: test_sparse_volume.py LVDIF_CLI DICE_SCRIPT WORKDIR

1. Generic VTK filters on the data object: vtkContourFilter runs per partition
   and gives the surface vtkChunkedMarchingCubes gives (an independent oracle:
   VTK's own contouring): the same vertex set (each vertex of one within 1e-4
   of a vertex of the other, and as many), area within 0.5%, and the contour
   is closed (no boundary or non-manifold edge after merging the partitions'
   shared points, i.e. the partitions meet without seams). vtkCutter and
   vtkOutlineFilter run on it too.
2. The chain reader -> vtkChunkedMarchingCubes -> .ply under an
   LVDIF_MEMORY_LIMIT that a dense copy exceeds: the chain succeeds, never
   builds the partitions, and the explicit dense conversion is refused with
   one clear error naming the size and the limit.
3. ShallowCopy shares the Core volume; DeepCopy clones it; the executive
   (vtkTrivialProducer, vtkPassThrough) keeps the subclass.
4. .vtpd: vtkXMLPartitionedDataSetWriter writes the partitions of a volume
   fresh from its reader (a plain vtkPartitionedDataSet sharing its decoded
   partitions), and the file reads back
   (vtkXMLPartitionedDataSetReader) equal to the dense image of
   vtkSparseVolumeToImage, voxel for voxel where the band is; over the memory
   limit the partitions are refused with one clear error (none written as if
   it were the volume).
"""
import os
import subprocess
import sys

import lvdif
from lvdif_check import check, finish
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPartitionedDataSet, vtkPlane, vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
from vtkmodules.vtkFiltersCore import (vtkAppendPolyData, vtkCleanPolyData, vtkContourFilter, vtkCutter,
                                       vtkFeatureEdges, vtkMassProperties, vtkPassThrough, vtkTriangleFilter)

from vtkmodules.vtkFiltersModeling import vtkOutlineFilter
from vtkmodules.vtkCommonDataModel import vtkPointLocator
from vtkmodules.vtkIOPLY import vtkPLYWriter

cli, dice_script, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)


def make_dice(n):
    path = os.path.join(work, "dice%d.lvdv" % n)
    src = open(dice_script).read().replace("n = 128", "n = %d" % n, 1)
    script = os.path.join(work, "dice%d.lvs" % n)
    open(script, "w").write(src)
    subprocess.run([cli, "script", script, "--out", path], check=True, stdout=subprocess.DEVNULL)
    return path


def merged(polys):
    """All pieces in one polydata, exactly coincident points merged."""
    append = vtkAppendPolyData()
    for p in polys:
        append.AddInputData(p)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(append.GetOutputPort())
    clean.ToleranceIsAbsoluteOn()
    clean.SetAbsoluteTolerance(0.0)
    clean.PointMergingOn()
    tri = vtkTriangleFilter()
    tri.SetInputConnection(clean.GetOutputPort())
    tri.Update()
    return tri.GetOutput()


def blocks(composite):
    it = composite.NewIterator()
    out = []
    while not it.IsDoneWithTraversal():
        out.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return out


def open_edges(pd):
    fe = vtkFeatureEdges()
    fe.SetInputData(pd)
    fe.BoundaryEdgesOn()
    fe.NonManifoldEdgesOn()
    fe.FeatureEdgesOff()
    fe.ManifoldEdgesOff()
    fe.Update()
    return fe.GetOutput().GetNumberOfCells()


def area(pd):
    m = vtkMassProperties()
    m.SetInputData(pd)
    m.Update()
    return m.GetSurfaceArea()


def unmatched(a, b, tol=1e-4):
    """Points of a farther than tol from every point of b."""
    loc = vtkPointLocator()
    loc.SetDataSet(b)
    loc.BuildLocator()
    bad = 0
    for i in range(a.GetNumberOfPoints()):
        p = a.GetPoint(i)
        q = b.GetPoint(loc.FindClosestPoint(p))
        bad += sum((p[k] - q[k]) ** 2 for k in range(3)) > tol * tol
    return bad


# ---- 1. generic filters against vtkChunkedMarchingCubes -------------------------------------
small = make_dice(96)
reader = lvdif.vtkDictionaryVolumeReader()
reader.SetFileName(small)
reader.Update()
volume = reader.GetOutput()
check(volume.IsA("vtkSparseDictionaryVolume") and volume.IsA("vtkPartitionedDataSet"), "the reader gives the sparse data object")
check(volume.HasVolume() and not volume.GetPartitionsBuilt(), "partitions are not built before a generic filter asks")
mc = lvdif.vtkChunkedMarchingCubes()
mc.SetInputConnection(reader.GetOutputPort())
mc.SetOutputModeToMerged()
mc.Update()
check(not volume.GetPartitionsBuilt(), "vtkChunkedMarchingCubes meshes the Core volume, no partitions")
ours = merged([mc.GetOutput()])
contour = vtkContourFilter()
contour.SetInputConnection(reader.GetOutputPort())
contour.SetValue(0, 0.0)
contour.Update()
parts = [b for b in blocks(contour.GetOutputDataObject(0)) if b.GetNumberOfPoints() > 0]
check(volume.GetPartitionsBuilt() and volume.GetNumberOfPartitions() > 1,
      "the contour ran on %d image partitions" % volume.GetNumberOfPartitions())
# held by default: every partition the contour visited stays decoded (a consumer may keep
# its pointers: vtkArrayCalculator, ParaView's Calculator, Plot Over Line, Ghost Cells)
held_kib = volume.GetHeldPartitionBytes() / 1024
check(not volume.GetReleasePartitionsAfterUse() and
      volume.GetPartitionBytes() / 1024 <= held_kib < 1.1 * volume.GetPartitionBytes() / 1024 + 64 * 27,
      "after the contour the partitions are held: %d KiB (all decoded at once: %d KiB)" % (
          held_kib, volume.GetPartitionBytes() / 1024))
check(volume.GetActualMemorySize() >= held_kib + volume.GetVolumeMemoryBytes() / 1024 - 1,
      "GetActualMemorySize counts the held partitions")
# released after use: no partition stays decoded after a filter iterated them, one at a time
streamed = lvdif.vtkDictionaryVolumeReader()
streamed.SetFileName(small)
streamed.Update()
streamed.GetOutput().ReleasePartitionsAfterUseOn()
streamed_contour = vtkContourFilter()
streamed_contour.SetInputConnection(streamed.GetOutputPort())
streamed_contour.SetValue(0, 0.0)
streamed_contour.Update()
check(streamed.GetOutput().GetHeldPartitionBytes() == 0 and
      streamed_contour.GetOutputDataObject(0).GetNumberOfCells() ==
      contour.GetOutputDataObject(0).GetNumberOfCells(),
      "released after use: the same contour, no partition held after it")
it = volume.NewIterator()
it.InitTraversal()
leaf = it.GetCurrentDataObject()
check(leaf.GetPointData().GetArray("sdf") is not None and leaf.GetPointData().GetArray("rgba") is not None,
      "the iterator hands out a decoded partition (sdf, rgba)")
first = volume.GetPartition(0)
check(first.GetPointData().GetArray("sdf") is not None and
      first.GetPointData().GetArray("sdf").GetRange() == leaf.GetPointData().GetArray("sdf").GetRange(),
      "GetPartition(0) is decoded too, with the iterator's values")
check(volume.GetNumberOfPoints() == sum(volume.GetPartition(i).GetNumberOfPoints()
                                        for i in range(volume.GetNumberOfPartitions())),
      "GetNumberOfPoints from the extents = the decoded partitions' points")
out = contour.GetOutputDataObject(0)
check(not (out.IsA("vtkSparseDictionaryVolume") and out.HasVolume()),
      "the contour's composite output does not claim the Core volume")
vtks = merged(parts)
print("   chunked MC: %d points %d triangles area %.3f; VTK contour: %d points %d triangles area %.3f" % (
    ours.GetNumberOfPoints(), ours.GetNumberOfCells(), area(ours), vtks.GetNumberOfPoints(), vtks.GetNumberOfCells(),
    area(vtks)))
check(ours.GetNumberOfCells() > 1000, "a real surface")
check(vtks.GetNumberOfPoints() == ours.GetNumberOfPoints(), "the same number of vertices")
check(unmatched(vtks, ours) == 0 and unmatched(ours, vtks) == 0, "the same vertex set (within 1e-4)")
check(abs(area(vtks) - area(ours)) < 0.005 * area(ours), "the same area (within 0.5%)")
check(open_edges(vtks) == 0, "the contour of the partitions is closed: no seams")
check(open_edges(ours) == 0, "the chunked MC surface is closed")
mc.SetChunkEdge(16)  # 216 chunks: the merge runs over several batches
mc.Update()
small_chunks = merged([mc.GetOutput()])
check(mc.GetOutput().GetNumberOfPoints() == ours.GetNumberOfPoints() and open_edges(mc.GetOutput()) == 0 and
      unmatched(small_chunks, vtks) == 0, "chunk edge 16 (merged batch by batch): the same closed surface")

plane = vtkPlane()
plane.SetOrigin(47.3, 47.3, 47.3)
plane.SetNormal(0, 0, 1)
cutter = vtkCutter()
cutter.SetCutFunction(plane)
cutter.SetInputConnection(reader.GetOutputPort())
cutter.Update()
cut = sum(b.GetNumberOfCells() for b in blocks(cutter.GetOutputDataObject(0)))
check(cut > 0, "vtkCutter slices the partitions (%d cells)" % cut)

# ParaView copies every output (its post filter): CopyStructure, then a shallow copy of each leaf
# the iterator decoded. The original's decoded partitions are held, shared with the copy, and
# they are its own leaves (session 27: held beside empty leaves before, which the paths that read
# the tree itself, e.g. vtkPartitionedDataSet.GetPartition, saw empty);
# the copy keeps the shallow copies it was given (they share the held arrays); a decoded leaf's
# arrays are its own, so ranges cached in them (ParaView's data information) go with it.
fresh = lvdif.vtkDictionaryVolumeReader()
fresh.SetFileName(small)
fresh.Update()
original = fresh.GetOutput()
copy = lvdif.vtkSparseDictionaryVolume()
copy.CopyStructure(original)
it = original.NewIterator()
it.InitTraversal()
chunk_ids = []
while not it.IsDoneWithTraversal():
    leaf = it.GetCurrentDataObject()
    chunk_ids.append(leaf.GetFieldData().GetArray("chunk_id").GetValue(0))
    leaf_copy = leaf.NewInstance()
    leaf_copy.ShallowCopy(leaf)
    copy.SetDataSet(it, leaf_copy)
    it.GoToNextItem()
n = original.GetNumberOfPartitions()
check(len(chunk_ids) == n and len(set(chunk_ids)) == n and chunk_ids == sorted(chunk_ids),
      "the iterator visits the %d empty leaves, each decoded with its own chunk" % n)
check(copy.HasVolume() and copy.GetNumberOfPartitions() == n and
      all(vtkPartitionedDataSet.GetPartition(original, i) is not None and
          vtkPartitionedDataSet.GetPartition(original, i) == original.GetPartition(i) for i in range(n)) and
      original.GetHeldPartitionBytes() > 0 and copy.GetHeldPartitionBytes() == original.GetHeldPartitionBytes(),
      "the original's leaves are its held partitions; the copy shares them")
skip = original.NewIterator()
skip.SkipEmptyNodesOn()  # as vtk::Range and ParaView's geometry filter ask
skip.InitTraversal()
visited = 0
while not skip.IsDoneWithTraversal():
    visited += skip.GetCurrentDataObject().GetPointData().GetArray("sdf") is not None
    skip.GoToNextItem()
check(visited == n, "asked to skip empty nodes, the iterator still decodes every partition (%d)" % visited)
copied = [b.GetPointData().GetArray("sdf").GetRange() for b in blocks(copy)]
check(copied == [b.GetPointData().GetArray("sdf").GetRange() for b in blocks(original)],
      "the copy decodes the same partitions")
outline = vtkOutlineFilter()
outline.SetInputConnection(reader.GetOutputPort())
outline.Update()
b = outline.GetOutput().GetBounds()
check(outline.GetOutput().GetNumberOfCells() > 0 and b[0] >= 0 and b[1] <= 95, "vtkOutlineFilter works")

# ---- pieces: a piece is a block of storage chunks (the reader's ownership rule) --------------
whole_tris = vtks.GetNumberOfCells()
for n in (2, 4):
    polys, volume_bytes = [], []
    for p in range(n):
        rp = lvdif.vtkDictionaryVolumeReader()
        rp.SetFileName(small)
        cp = vtkContourFilter()
        cp.SetInputConnection(rp.GetOutputPort())
        cp.SetValue(0, 0.0)
        cp.UpdatePiece(p, n, 0)
        polys += [b for b in blocks(cp.GetOutputDataObject(0)) if b.GetNumberOfPoints() > 0]
        volume_bytes.append(rp.GetOutput().GetVolumeMemoryBytes())
    union = merged(polys)
    check(union.GetNumberOfCells() == whole_tris and unmatched(union, vtks) == 0 and open_edges(union) == 0,
          "%d pieces: the contours of the pieces make the whole closed surface once (%d triangles)" % (
              n, union.GetNumberOfCells()))
    check(max(volume_bytes) < volume.GetVolumeMemoryBytes(),
          "%d pieces: a piece holds only its chunks (largest %d of %d bytes)" % (
              n, max(volume_bytes), volume.GetVolumeMemoryBytes()))

# ---- 3. copies and the executive keep the Core volume --------------------------------------
shallow = lvdif.vtkSparseDictionaryVolume()
shallow.ShallowCopy(volume)
check(shallow.HasVolume() and shallow.GetVolumeMemoryBytes() == volume.GetVolumeMemoryBytes(), "ShallowCopy shares the volume")
deep = lvdif.vtkSparseDictionaryVolume()
deep.DeepCopy(volume)
check(deep.HasVolume() and deep.GetNumberOfExpandedChunks() == volume.GetNumberOfExpandedChunks(), "DeepCopy clones the volume")
tp = vtkTrivialProducer()
tp.SetOutput(deep)
pt = vtkPassThrough()
pt.SetInputConnection(tp.GetOutputPort())
mc2 = lvdif.vtkChunkedMarchingCubes()
mc2.SetInputConnection(pt.GetOutputPort())
mc2.SetOutputModeToMerged()
mc2.Update()
check(pt.GetOutputDataObject(0).IsA("vtkSparseDictionaryVolume"), "vtkPassThrough keeps the subclass")
check(mc2.GetOutput().GetNumberOfCells() == mc.GetOutput().GetNumberOfCells(), "the copy meshes like the original")

# ---- 2. a large chain under a memory limit a dense copy exceeds ----------------------------
n = 384
large = make_dice(n)
dense_bytes = n ** 3 * 8
os.environ["LVDIF_MEMORY_LIMIT"] = str(dense_bytes // 2)  # read by Core at every check
r2 = lvdif.vtkDictionaryVolumeReader()
r2.SetFileName(large)
mc3 = lvdif.vtkChunkedMarchingCubes()
mc3.SetInputConnection(r2.GetOutputPort())
mc3.SetOutputModeToMerged()
mc3.ComputeCornerColorsOff()
ply = vtkPLYWriter()
ply.SetInputConnection(mc3.GetOutputPort())
ply.SetFileName(os.path.join(work, "dice%d.ply" % n))
ply.SetFileTypeToBinary()
check(ply.Write() == 1 and mc3.GetOutput().GetNumberOfCells() > 100000,
      "%d^3 chain under LVDIF_MEMORY_LIMIT=%d (dense: %d bytes): %d triangles" % (
          n, dense_bytes // 2, dense_bytes, mc3.GetOutput().GetNumberOfCells()))
v2 = r2.GetOutput()
check(not v2.GetPartitionsBuilt(), "no partitions built on the way")
check(v2.GetVolumeMemoryBytes() < dense_bytes // 2, "the sparse volume fits: %d bytes" % v2.GetVolumeMemoryBytes())
errors = []


def on_error(obj, event, message):
    errors.append(message)


on_error.CallDataType = "string0"  # VTK passes the error text
to_dense = lvdif.vtkSparseVolumeToImage()
to_dense.SetInputConnection(r2.GetOutputPort())
to_dense.AddObserver(vtkCommand.ErrorEvent, on_error)  # observed: checked here, not printed
to_dense.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_error)
to_dense.Update()
check(to_dense.GetOutput().GetNumberOfPoints() == 0, "the dense conversion is refused")
message = errors[0] if errors else ""
print("   its error: " + message.strip().splitlines()[-1] if message else "   no error")
check("needs" in message and "limit" in message and "%d x %d x %d" % (n, n, n) in message,
      "one clear error naming the size and the limit")
check(to_dense.GetRequiredBytes() == dense_bytes, "it states the memory it needs (%d bytes)" % to_dense.GetRequiredBytes())
del os.environ["LVDIF_MEMORY_LIMIT"]

# ---- 4. .vtpd: VTK's partitioned dataset writer and reader ------------------------------------
from vtkmodules.vtkIOParallelXML import vtkXMLPartitionedDataSetWriter
from vtkmodules.vtkIOXML import vtkXMLPartitionedDataSetReader
fresh = lvdif.vtkDictionaryVolumeReader()
fresh.SetFileName(small)
fresh.Update()
vtpd = os.path.join(work, "dice96.vtpd")
if os.path.exists(vtpd):
    os.remove(vtpd)
# VTK's writer names the file's type after the input's class (vtkSparseDictionaryVolume), which VTK's
# reader refuses ("Cannot find vtkPartitionedDataSet element"): write a plain partitioned dataset
# sharing the partitions (docs/PYTHON.md). A plain ShallowCopy reads the tree itself: until
# session 27 its leaves were empty and the file held no partition.
fresh.GetOutput().GetNumberOfPartitions()  # builds (and, held, decodes) the partitions
check(fresh.GetOutput().DecodePartitions() and
      fresh.GetOutput().GetHeldPartitionBytes() >= fresh.GetOutput().GetPartitionBytes(),
      "DecodePartitions: every partition held (%d bytes; point arrays: %d)" % (
          fresh.GetOutput().GetHeldPartitionBytes(), fresh.GetOutput().GetPartitionBytes()))
plain = vtkPartitionedDataSet()
plain.ShallowCopy(fresh.GetOutput())
writer = vtkXMLPartitionedDataSetWriter()
writer.SetInputData(plain)
writer.SetFileName(vtpd)
check(writer.Write() == 1 and os.path.exists(vtpd), "vtkXMLPartitionedDataSetWriter wrote %s" % vtpd)
back = vtkXMLPartitionedDataSetReader()
back.SetFileName(vtpd)
back.Update()
read = back.GetOutput()
saved = fresh.GetOutput()
to_image = lvdif.vtkSparseVolumeToImage()
to_image.SetInputConnection(fresh.GetOutputPort())
to_image.Update()
image = to_image.GetOutput()
ie = image.GetExtent()
image_sdf = image.GetPointData().GetArray("sdf")


def against_image(read):
    """A partitioned dataset read back against the dense image: (partitions, points, points or
    partitions that differ, the image indices covered)."""
    n = read.GetNumberOfPartitions() if read is not None else 0
    bad = points = 0
    covered = set()
    for i in range(n):
        part = read.GetPartition(i)
        if part is None or part.GetPointData().GetArray("sdf") is None:
            bad += 1
            continue
        e = part.GetExtent()
        values = part.GetPointData().GetArray("sdf")
        k = 0
        for z in range(e[4], e[5] + 1):
            for y in range(e[2], e[3] + 1):
                row = ((z - ie[4]) * (ie[3] - ie[2] + 1) + (y - ie[2])) * (ie[1] - ie[0] + 1) - ie[0]
                for x in range(e[0], e[1] + 1):
                    bad += values.GetValue(k) != image_sdf.GetValue(row + x)
                    covered.add(row + x)
                    k += 1
        points += k
    return n, points, bad, covered


n_read, points, bad, covered = against_image(read)
check(n_read == saved.GetNumberOfPartitions() > 1,
      "the file holds %d partitions, the volume %d" % (n_read, saved.GetNumberOfPartitions()))
print("   .vtpd: %d partitions, %d points, %d differ from the dense image" % (n_read, points, bad))
check(bad == 0 and points == saved.GetNumberOfPoints(),
      "the .vtpd reads back equal to the dense image where the band is (%d points, %d differ)" % (points, bad))
# the volume written as it is (ParaView's Save Data does this): its index names the element after
# the sparse volume's class; VTK's reader refuses it, lvdif.vtkXMLSparseVolumeReader reads it, and
# only it (each reader's CanReadFile answers for its own files)
direct = os.path.join(work, "dice96-direct.vtpd")
if os.path.exists(direct):
    os.remove(direct)
writer_d = vtkXMLPartitionedDataSetWriter()
writer_d.SetInputData(saved)
writer_d.SetFileName(direct)
check(writer_d.Write() == 1 and os.path.exists(direct), "the sparse volume itself written as %s" % direct)
sparse_reader = lvdif.vtkXMLSparseVolumeReader()
check(sparse_reader.CanReadFile(direct) == 1 and vtkXMLPartitionedDataSetReader().CanReadFile(direct) == 0,
      "the direct .vtpd is the sparse-volume reader's, not VTK's")
check(sparse_reader.CanReadFile(vtpd) == 0 and vtkXMLPartitionedDataSetReader().CanReadFile(vtpd) == 1,
      "a plain partitioned dataset's .vtpd stays VTK's reader's")
sparse_reader.SetFileName(direct)
sparse_reader.Update()
n_direct, points_d, bad_d, _ = against_image(sparse_reader.GetOutput())
check(n_direct == saved.GetNumberOfPartitions() and bad_d == 0 and points_d == saved.GetNumberOfPoints(),
      "the direct .vtpd reads back equal to the dense image (%d partitions, %d points, %d differ)" %
      (n_direct, points_d, bad_d))
# every voxel of the dense image whose cells can differ is in the file: the band's voxels
band = 0
bw = saved.GetBandWidth()
for j in range(image_sdf.GetNumberOfTuples()):
    if abs(image_sdf.GetValue(j)) < bw and j not in covered:
        band += 1
check(band == 0, "every voxel inside the band is written (%d missing)" % band)
# over the memory limit: one clear error, no partition written as if it were the volume
refused = lvdif.vtkDictionaryVolumeReader()
refused.SetFileName(small)
refused.Update()
os.environ["LVDIF_MEMORY_LIMIT"] = str(int(0.4 * refused.GetOutput().GetPartitionBytes()))
vtpd2 = os.path.join(work, "dice96-refused.vtpd")
errors2 = []


def on_error2(obj, event, message):
    errors2.append(message)


on_error2.CallDataType = "string0"
refused.GetOutput().AddObserver(vtkCommand.ErrorEvent, on_error2)
refused.GetOutput().GetNumberOfPartitions()
check(not refused.GetOutput().DecodePartitions(), "over the memory limit DecodePartitions says False")
plain2 = vtkPartitionedDataSet()
plain2.ShallowCopy(refused.GetOutput())
writer2 = vtkXMLPartitionedDataSetWriter()
writer2.SetInputData(plain2)
writer2.SetFileName(vtpd2)
writer2.Write()
del os.environ["LVDIF_MEMORY_LIMIT"]
written = 0
if os.path.exists(vtpd2):
    back2 = vtkXMLPartitionedDataSetReader()
    back2.SetFileName(vtpd2)
    back2.Update()
    written = sum(1 for i in range(back2.GetOutput().GetNumberOfPartitions())
                  if back2.GetOutput().GetPartition(i) is not None)
print("   over the limit: %d error(s): %s" % (len(errors2), errors2[0].strip().splitlines()[-1] if errors2 else ""))
check(len(errors2) == 1 and "more than the limit" in errors2[0] and written == 0,
      "over the memory limit: one clear error, no partition written (%d errors, %d written)" % (len(errors2), written))

finish()
