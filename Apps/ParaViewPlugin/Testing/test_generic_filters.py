"""pvbatch test: ParaView's own filters that keep the partitions' pointers run
on the sparse volume and give the dense image's results.

Calculator (vtkArrayCalculator fills each output leaf after setting it), Plot
Over Line (vtkProbeLineFilter) and Ghost Cells Generator (vtkDIYGhostUtilities
collects every partition first) ended pvbatch with a segmentation fault until
session 26, when the sparse volume released each decoded partition at its
iterator's next step (docs/PARAVIEW.md, "Filters that keep the partitions").
Oracle: the same filter on Sparse Volume To Image's dense image of the same
volume; values compared at the same global grid points.

Usage: pvbatch test_generic_filters.py PLUGIN
"""
import lvdif_pvtest as T  # first: fixes sys.path for route B

import sys

import paraview.simple as pvs
from vtkmodules.numpy_interface import dataset_adapter  # noqa: F401  (ParaView's numpy bridge loads)

check = T.check
T.load_plugin(sys.argv[1], ["vtkMeshToSDF", "vtkSparseVolumeToImage"], remote=False)


def output(proxy):
    """The proxy's output data object (one process: the server's own object, as a
    representation gets it; servermanager.Fetch cannot move a partitioned dataset)."""
    proxy.UpdatePipeline()
    return proxy.GetClientSideObject().GetOutputDataObject(0)


def leaves(data):
    """The non-empty leaves of a composite dataset (or the dataset itself)."""
    if not data.IsA("vtkCompositeDataSet"):
        return [data]
    out = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        leaf = it.GetCurrentDataObject()
        if leaf is not None and leaf.GetNumberOfPoints() > 0:
            out.append(leaf)
        it.GoToNextItem()
    return out


def dense_lookup(image, name):
    """f(i, j, k) -> the dense image's array `name` at grid point (i, j, k)."""
    ext = image.GetExtent()
    nx, ny = ext[1] - ext[0] + 1, ext[3] - ext[2] + 1
    array = image.GetPointData().GetArray(name)
    return lambda i, j, k: array.GetValue((i - ext[0]) + nx * ((j - ext[2]) + ny * (k - ext[4])))


HIDDEN_POINT = 2  # vtkDataSetAttributes::HIDDENPOINT: a ghost point that no neighbour had


def mismatched_points(leaf, name, at, tol=0.0):
    """Points of an image leaf whose `name` differs from at(i, j, k) by more than tol (hidden
    ghost points are not points of the data: VTK's ghost generator fills them with 0)."""
    ext = leaf.GetExtent()
    array = leaf.GetPointData().GetArray(name)
    ghosts = leaf.GetPointData().GetArray("vtkGhostType")
    if array is None:
        return -1
    bad = n = 0
    for k in range(ext[4], ext[5] + 1):
        for j in range(ext[2], ext[3] + 1):
            for i in range(ext[0], ext[1] + 1):
                if not (ghosts and ghosts.GetValue(n) & HIDDEN_POINT):
                    bad += abs(array.GetValue(n) - at(i, j, k)) > tol
                n += 1
    return bad


ellipsoid = pvs.Transform(Input=pvs.Sphere(ThetaResolution=40, PhiResolution=40))
ellipsoid.Transform.Scale = [1.0, 0.7, 0.45]
sdf = pvs.MeshToSDF(Input=ellipsoid, MaxDimension=72, Padding=12.0)
dense = pvs.SparseVolumeToImage(Input=sdf)
dense_image = output(dense)
check(dense_image.IsA("vtkImageData") and dense_image.GetPointData().GetArray("sdf") is not None,
      "the oracle: a dense image with sdf")
sparse = output(sdf)
check(sparse.IsA("vtkSparseDictionaryVolume") and sparse.GetNumberOfPartitions() > 8,
      "Mesh To SDF gives the sparse volume (%d partitions)" % sparse.GetNumberOfPartitions())

# ---- Calculator ---------------------------------------------------------------------------
calc = pvs.Calculator(Input=sdf, Function="sdf*2", ResultArrayName="twice")
calc_dense = pvs.Calculator(Input=dense, Function="sdf*2", ResultArrayName="twice")
got = leaves(output(calc))
at = dense_lookup(output(calc_dense), "twice")
bad = sum(mismatched_points(leaf, "twice", at) for leaf in got)
check(len(got) == sparse.GetNumberOfPartitions() and bad == 0,
      "Calculator: %d leaves, %d points differ from the dense image's result" % (len(got), bad))

# ---- Plot Over Line -----------------------------------------------------------------------
b = dense_image.GetBounds()
p1 = [b[0] + 0.02 * (b[1] - b[0]), b[2] + 0.3 * (b[3] - b[2]), b[4] + 0.45 * (b[5] - b[4])]
p2 = [b[0] + 0.98 * (b[1] - b[0]), b[2] + 0.6 * (b[3] - b[2]), b[4] + 0.55 * (b[5] - b[4])]
lines = []
for source in (sdf, dense):
    plot = pvs.PlotOverLine(Input=source)
    plot.Point1, plot.Point2 = p1, p2
    plot.Resolution = 400
    lines.append(output(plot))
values = [line.GetPointData().GetArray("sdf") for line in lines]
masks = [line.GetPointData().GetArray("vtkValidPointMask") for line in lines]
check(None not in values and values[0].GetNumberOfTuples() == values[1].GetNumberOfTuples() > 100,
      "Plot Over Line samples both (%d points)" % (values[1].GetNumberOfTuples() if values[1] else 0))
if None not in values and None not in masks:
    # inside the band the sparse partitions cover the line; uniform chunks have no partition
    # (their value is +-band, no surface), so the sparse line is compared where it is valid
    n = values[1].GetNumberOfTuples()
    valid = [i for i in range(n) if masks[0].GetValue(i) and masks[1].GetValue(i)]
    differ = sum(abs(values[0].GetValue(i) - values[1].GetValue(i)) > 1e-4 for i in valid)
    inside = sum(values[1].GetValue(i) < 0 for i in valid)
    check(len(valid) > 50 and 0 < inside < len(valid) and differ == 0,
          "Plot Over Line: %d valid samples (%d inside, through the surface), %d differ from the dense image's" % (
              len(valid), inside, differ))

# ---- Ghost Cells Generator ----------------------------------------------------------------
ghosts = pvs.GhostCellsGenerator(Input=sdf)
ghosted = leaves(output(ghosts))
at = dense_lookup(dense_image, "sdf")
bad = sum(mismatched_points(leaf, "sdf", at) for leaf in ghosted)
grown = sum(leaf.GetNumberOfPoints() for leaf in ghosted) - sum(leaf.GetNumberOfPoints() for leaf in leaves(sparse))
hidden = sum(sum(leaf.GetPointData().GetArray("vtkGhostType").GetValue(n) & HIDDEN_POINT != 0
                 for n in range(leaf.GetNumberOfPoints())) for leaf in ghosted)
# a ghost layer that reaches a uniform chunk (no partition: no surface there) is hidden
check(len(ghosted) == sparse.GetNumberOfPartitions() and bad == 0 and grown > hidden,
      "Ghost Cells Generator: %d leaves, %d more points with the ghost layers (%d hidden: uniform chunks), "
      "%d differ from the dense image" % (len(ghosted), grown, hidden, bad))

# Save Data as .vtpd (XMLPPartitionedDataSetWriter through ParaView's file series writer): every
# partition is written as its own .vti, equal to the dense image at the same grid points. Until
# session 27 the writer's copy of the volume read the partitioned dataset's own leaves, which were
# empty. VTK's writer names the index's type after the input's class, vtkSparseDictionaryVolume,
# which ParaView's .vtpd reader refuses; Open takes the plugin's LVDIFSparseVolumeVTPDReader for it.
import os
import shutil
import tempfile
import xml.etree.ElementTree as ET
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
folder = tempfile.mkdtemp(prefix="lvdif-vtpd-")
vtpd = os.path.join(folder, "sdf.vtpd")
pvs.SaveData(vtpd, proxy=sdf)
files = []
if os.path.exists(vtpd):
    files = [e.get("file") for e in ET.parse(vtpd).getroot().iter("DataSet") if e.get("file")]
parts = []
for name in files:
    piece = vtkXMLImageDataReader()
    piece.SetFileName(os.path.join(folder, name))
    piece.Update()
    parts.append(piece.GetOutput())
bad = sum(mismatched_points(leaf, "sdf", at) for leaf in parts)
points = sum(leaf.GetNumberOfPoints() for leaf in parts)
check(os.path.exists(vtpd) and len(parts) == sparse.GetNumberOfPartitions() and points == sparse.GetNumberOfPoints()
      and bad == 0,
      "Save Data .vtpd: %d partition files of %d, %d points of %d, %d differ from the dense image"
      % (len(parts), sparse.GetNumberOfPartitions(), points, sparse.GetNumberOfPoints(), bad))
reopened = pvs.OpenDataFile(vtpd) if os.path.exists(vtpd) else None
kind = reopened.GetXMLName() if reopened is not None else None
back = leaves(output(reopened)) if reopened is not None else []
bad = sum(mismatched_points(leaf, "sdf", at) for leaf in back)
check(kind == "LVDIFSparseVolumeVTPDReader" and len(back) == sparse.GetNumberOfPartitions() and bad == 0
      and sum(leaf.GetNumberOfPoints() for leaf in back) == sparse.GetNumberOfPoints(),
      "Open of the saved .vtpd: reader %s, %d partitions of %d, %d points differ from the dense image"
      % (kind, len(back), sparse.GetNumberOfPartitions(), bad))
shutil.rmtree(folder, ignore_errors=True)

print("failures:", check.failures)
if check.failures:
    sys.exit(1)
