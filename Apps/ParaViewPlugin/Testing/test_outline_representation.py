# ParaView's Outline (the first display) of the sparse volume (vtkSparseDictionaryVolume).
# LVDIFSparseVolumeRepresentation's Outline is vtkSparseVolumeOutlineRepresentation: one
# box of the whole volume from the Core volume's geometry, no partition decoded. ParaView's
# own outline (UniformGridRepresentation on the same data, shown in another view as the
# peer) runs vtkPVGeometryFilter over every partition: it decodes each chunk image and
# draws one box per partition.
# Oracles: the whole volume's bounds are those of the explicit dense image of the same
# volume (Sparse Volume To Image, ParaView's data information); the box's edges are
# vtkOutlineSource's for those bounds. ParaView's own outline, its Outline filter and the
# sparse volume's data information reach the same box (they gave the band's before session 22).
# Volumes: Mesh To SDF of an ellipsoid (16 voxels of padding, so the outer chunks are
# uniform and the partitions do not cover the volume) and the same volume as .lvdv
# (kept, with the dense image's bounds, for mpi_outline_representation.py).
#
# Usage: pvpython --force-offscreen-rendering test_outline_representation.py PLUGIN TMPDIR
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys
import time

import paraview.simple as pvs
from vtkmodules.vtkFiltersSources import vtkOutlineSource

plugin, tmpdir = sys.argv[1], sys.argv[2]
T.load_plugin(plugin, ["vtkMeshToSDF", "vtkDictionaryVolumeReader", "vtkSparseVolumeToImage"], remote=False)
check = T.check


def leaves(data):
    """The leaves of a representation's rendered data (a multiblock of polydata)."""
    out = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        out.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return out


def edges(poly):
    """The line cells as a set of unordered pairs of rounded point coordinates."""
    # rounded: vtkOutlineSource's points are float
    pts = [tuple(round(c, 5) for c in poly.GetPoint(i)) for i in range(poly.GetNumberOfPoints())]
    result = set()
    lines = poly.GetLines()
    ids = lines.GetData()
    k = 0
    while k < ids.GetNumberOfTuples():
        n = int(ids.GetValue(k))
        cell = [pts[int(ids.GetValue(k + 1 + j))] for j in range(n)]
        for a, b in zip(cell, cell[1:]):
            result.add(frozenset((a, b)))
        k += n + 1
    return result


def shown(source, kind, label):
    view = pvs.CreateRenderView()
    view.ViewSize = [200, 200]
    t0 = time.time()
    display = pvs.Show(source, view, kind) if kind else pvs.Show(source, view)
    pvs.Render(view)
    seconds = time.time() - t0
    rep = display.GetClientSideObject().GetActiveRepresentation()
    print("%s: %s, %s via %s: %.2f s" % (label, display.GetXMLName(), display.Representation, rep.GetClassName(), seconds))
    return display, rep, view


def test(source, label):
    source.UpdatePipeline()
    dense = pvs.SparseVolumeToImage(Input=source)
    dense.UpdatePipeline()
    bounds = dense.GetDataInformation().GetBounds()  # the whole volume: every voxel
    partitions = source.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPartitions()
    # ParaView's own outline first: the peer, and the proof that the partitions do not cover the volume
    stock, stock_rep, stock_view = shown(source, "UniformGridRepresentation", label + " ParaView's outline")
    stock_boxes = leaves(stock_rep.GetRenderedDataObject(0))
    print("%s: %d partitions; ParaView's outline draws %d boxes" % (label, partitions, len(stock_boxes)))
    check(len(stock_boxes) == partitions > 1, "%s: ParaView's outline draws %d boxes for %d partitions"
          % (label, len(stock_boxes), partitions))
    union = [0.0] * 6
    for a in range(3):
        union[2 * a] = min(b.GetBounds()[2 * a] for b in stock_boxes)
        union[2 * a + 1] = max(b.GetBounds()[2 * a + 1] for b in stock_boxes)
    # the partitions' union is the volume's box (the grid's corner points are partitions when the
    # band's chunks do not reach them: it was the band's box, smaller than the volume)
    check(all(abs(union[i] - bounds[i]) <= 1e-6 * max(1.0, abs(bounds[i])) for i in range(6)),
          "%s: the partitions' union %s is the volume's box %s" % (label, union, bounds))
    # ParaView's Outline filter (vtkPOutlineFilter) on the volume: the volume's box
    box_filter = pvs.Outline(Input=source)
    box_filter.UpdatePipeline()
    got_filter = box_filter.GetDataInformation().GetBounds()
    check(all(abs(got_filter[i] - bounds[i]) <= 1e-5 * max(1.0, abs(bounds[i])) for i in range(6)),
          "%s: ParaView's Outline filter gives %s, the volume's box is %s" % (label, got_filter, bounds))
    info_bounds = source.GetDataInformation().GetBounds()
    check(all(abs(info_bounds[i] - bounds[i]) <= 1e-9 * max(1.0, abs(bounds[i])) for i in range(6)),
          "%s: the data information's bounds %s, the volume's %s" % (label, info_bounds, bounds))
    pvs.Delete(box_filter)

    display, rep, view = shown(source, None, label)
    check(display.GetXMLName() == "LVDIFSparseVolumeRepresentation",
          "%s: the sparse volume shows through %s" % (label, display.GetXMLName()))
    check(display.Representation == "Outline", "%s: first display %s (Outline expected)" % (label, display.Representation))
    check(rep.GetClassName() == "vtkSparseVolumeOutlineRepresentation", "%s: outline by %s" % (label, rep.GetClassName()))
    boxes = leaves(rep.GetRenderedDataObject(0))
    check(len(boxes) == 1, "%s: the outline has %d leaves (one box expected)" % (label, len(boxes)))
    box = boxes[0]
    got = box.GetBounds()
    check(box.GetNumberOfPoints() == 8 and box.GetNumberOfLines() == 12 and box.GetNumberOfPolys() == 0,
          "%s: the outline has %d points, %d lines, %d polygons (a box: 8, 12, 0)"
          % (label, box.GetNumberOfPoints(), box.GetNumberOfLines(), box.GetNumberOfPolys()))
    check(all(abs(got[i] - bounds[i]) <= 1e-9 * max(1.0, abs(bounds[i])) for i in range(6)),
          "%s: outline bounds %s, the dense image's %s" % (label, got, bounds))
    oracle = vtkOutlineSource()
    oracle.SetBounds(bounds)
    oracle.Update()
    check(edges(box) == edges(oracle.GetOutput()) and len(edges(box)) == 12,
          "%s: the outline's edges differ from vtkOutlineSource's for the volume's bounds" % label)
    # the other representations still work after the outline (Slice, then back)
    display.SetRepresentationType("Slice")
    pvs.Render(view)
    display.SetRepresentationType("Outline")
    pvs.Render(view)
    check(len(leaves(rep.GetRenderedDataObject(0))) == 1, "%s: outline again after Slice" % label)
    for v in (view, stock_view):
        pvs.Delete(v)
    return bounds


ellipsoid = pvs.Transform(Input=pvs.Sphere(ThetaResolution=48, PhiResolution=48))
ellipsoid.Transform.Scale = [1.0, 0.6, 0.4]
sdf = pvs.MeshToSDF(Input=ellipsoid, MaxDimension=96, Padding=16.0)
test(sdf, "MeshToSDF")
path = os.path.join(tmpdir, "outline_rep.lvdv")
pvs.SaveData(path, proxy=sdf)
bounds = test(pvs.OpenDataFile(path), "lvdv")
# the oracle of the pvbatch run (mpi_outline_representation.py), which opens the same file
with open(os.path.join(tmpdir, "outline_rep_bounds.txt"), "w") as f:
    f.write(" ".join(repr(b) for b in bounds) + "\n")
print("failures:", check.failures)
if check.failures:
    sys.exit(1)
