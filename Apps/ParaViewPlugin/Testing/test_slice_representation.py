# ParaView's Slice representation on the sparse volume (vtkSparseDictionaryVolume).
# The sparse producers show through LVDIFSparseVolumeRepresentation, ParaView's
# image representation whose Slice takes the sparse volume (before, the Slice
# representation failed: "Can not execute simple algorithm vtkImageSliceRepresentation
# without output ports", and drew nothing).
# Oracle: ParaView's own Slice representation of the explicit dense image of the
# same volume (Sparse Volume To Image, UniformGridRepresentation), rendered in the
# same view with the same camera and colour map: the pictures must be identical,
# pixel for pixel, for the three slice directions and several slice indices (slice 1
# lies in the padding, where the sdf is +8 everywhere: checked on the dense image).
# Volumes: Mesh To SDF of an ellipsoid
# (band 8, 16 voxels of padding) straight, and the same volume written as .lvdv
# and opened again.
# Under pvbatch with several ranks each rank slices only its own chunks (the
# reader's pieces) and the composited picture must equal the serial run's dense one
# (ParaView's Slice of the distributed dense image itself differs from it).
#
# Usage: pvpython|pvbatch --force-offscreen-rendering test_slice_representation.py PLUGIN TMPDIR
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import numpy as np

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, tmpdir = sys.argv[1], sys.argv[2]
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
T.load_plugin(plugin, ["vtkMeshToSDF", "vtkDictionaryVolumeReader", "vtkSparseVolumeToImage"], remote=True)
check = T.check
tag = "np%d" % ranks
print("ranks:", ranks)


def picture(view, name):
    path = os.path.join(tmpdir, "slice_%s_%s.png" % (tag, name))
    pvs.SaveScreenshot(path, view, ImageResolution=[320, 320])
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    a = vtk_to_numpy(img.GetPointData().GetScalars()).reshape(-1, img.GetNumberOfScalarComponents())
    return a[:, :3], path


def differences(a, b):
    return int((abs(a.astype(int) - b.astype(int)).max(axis=1) > 0).sum())


def shifted_differences(a, b, radius, levels):
    """Pixels of a whose colour differs by more than `levels` from every pixel of b within `radius`."""
    a3, b3 = a.reshape(320, 320, 3).astype(int), b.reshape(320, 320, 3).astype(int)
    best = None
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            d = abs(a3 - np.roll(np.roll(b3, dy, 0), dx, 1)).max(axis=2)
            best = d if best is None else np.minimum(best, d)
    return int((best > levels).sum())


def serial_picture(path):
    """The picture the serial run (np1) took of the same slice."""
    r = vtkPNGReader()
    r.SetFileName(path.replace("slice_%s_" % tag, "slice_np1_"))
    r.Update()
    img = r.GetOutput()
    return vtk_to_numpy(img.GetPointData().GetScalars()).reshape(-1, img.GetNumberOfScalarComponents())[:, :3]


def compare(source, dense, label):
    view = pvs.CreateRenderView()
    view.ViewSize = [320, 320]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    ds = pvs.Show(source, view)
    check(ds.GetXMLName() == "LVDIFSparseVolumeRepresentation",
          "%s: the sparse volume shows through %s" % (label, ds.GetXMLName()))
    check(ds.Representation == "Outline", "%s: first display %s (Outline expected)" % (label, ds.Representation))
    dd = pvs.Show(dense, view)
    check(dd.GetXMLName() == "UniformGridRepresentation", "%s: the dense image shows through %s" % (label, dd.GetXMLName()))
    lut = pvs.GetColorTransferFunction("sdf")
    for d in (ds, dd):
        d.SetRepresentationType("Slice")
        pvs.ColorBy(d, ("POINTS", "sdf"))
    lut.AutomaticRescaleRangeMode = "Never"  # the same colours in every run, whatever the data ranges say
    lut.RescaleTransferFunction(-8.0, 8.0)
    info = dense.GetDataInformation().DataInformation
    ext = info.GetExtent()
    dims = [ext[1] - ext[0] + 1, ext[3] - ext[2] + 1, ext[5] - ext[4] + 1]
    values = None
    if ranks == 1:
        img = servermanager.Fetch(dense)
        values = vtk_to_numpy(img.GetPointData().GetArray("sdf")).reshape(dims[2], dims[1], dims[0])
    for mode, axis, look in (("XY Plane", 2, "Z"), ("YZ Plane", 0, "X"), ("XZ Plane", 1, "Y")):
        getattr(view, "ResetActiveCameraToPositive" + look)()  # look along the slice's normal
        n = dims[axis]
        for s in (n // 2, n // 3, 1, n - 1):  # 1 and n-1: near the faces, in the padding
            for d in (ds, dd):
                d.SliceMode = mode
                d.Slice = s
            pvs.Hide(dense, view)
            pvs.Show(source, view)
            view.ResetCamera()
            a, pa = picture(view, "%s_%s_%d_sparse" % (label, mode[:2], s))
            pvs.Hide(source, view)
            pvs.Show(dense, view)
            b, pb = picture(view, "%s_%s_%d_dense" % (label, mode[:2], s))
            drawn = int((a != 255).any(axis=1).sum())
            colours = len({tuple(p) for p in a[::7]})
            if ranks == 1:
                differ = differences(a, b)
                check(differ == 0 and drawn > 0.2 * len(a),
                      "%s %s slice %d: sparse and dense Slice pictures differ in %d of %d pixels "
                      "(%d drawn, %d colours)" % (label, mode, s, differ, len(a), drawn, colours))
                if s == n // 2:
                    # calibration of the distributed runs' tolerance: the next plane must fail it
                    dd.Slice = s + 1
                    c, _ = picture(view, "%s_%s_%d_dense" % (label, mode[:2], s + 1))
                    far = shifted_differences(c, b, 3, 2)
                    check(far > 0.0005 * drawn, "%s %s: slice %d against slice %d: %d pixels off beyond a "
                          "3-pixel shift (the tolerance of the distributed runs is %d)"
                          % (label, mode, s + 1, s, far, int(0.0005 * drawn)))
            else:
                # Each rank draws its own part of the plane as a textured quad, and the texels of
                # a part sit a fraction of a texel away from those of the whole plane: pictures of
                # pieces are the serial one only up to that shift (ParaView's own Slice of the
                # distributed dense image, split differently, shows the same). The oracle is the
                # serial dense picture: the same drawn area, and every pixel's colour within
                # 2 levels of a pixel at most 3 pixels away (a wrong plane or a missing piece is
                # far more).
                serial = serial_picture(pb)
                far = shifted_differences(a, serial, 3, 2)
                check(drawn == int((serial != 255).any(axis=1).sum()) and far <= 0.0005 * drawn,
                      "%s %s slice %d: sparse Slice from %d ranks against the serial dense picture: %d drawn "
                      "(serial %d), %d pixels off beyond a 3-pixel shift; unshifted %d (ParaView's distributed "
                      "dense Slice: %d, %d)" % (label, mode, s, ranks, drawn, int((serial != 255).any(axis=1).sum()),
                                                far, differences(a, serial), shifted_differences(b, serial, 3, 2),
                                                differences(b, serial)))
            if s == 1 and values is not None:
                plane = values.take(1, axis=2 - axis)  # numpy order z, y, x
                check(len(set(plane.ravel().tolist())) == 1,
                      "%s %s slice 1 lies where the volume is uniform: sdf values %s"
                      % (label, mode, sorted(set(plane.ravel().tolist()))[:4]))
            if s == n // 2:
                check(colours > 20, "%s %s slice %d: %d colours (a slice of a distance field)" % (label, mode, s, colours))
    pvs.Delete(view)


ellipsoid = pvs.Transform(Input=pvs.Sphere(ThetaResolution=48, PhiResolution=48))
ellipsoid.Transform.Scale = [1.0, 0.6, 0.4]
# 16 voxels of padding: the outer chunk layers are uniform (+band), no partition there
sdf = pvs.MeshToSDF(Input=ellipsoid, MaxDimension=64, Padding=16.0)
if ranks == 1:
    compare(sdf, pvs.SparseVolumeToImage(Input=sdf), "MeshToSDF")
# the serial run writes the file; under MPI (where the serial writer is not offered) it is read
path = os.path.join(tmpdir, "slice_rep_np1.lvdv")
if ranks == 1:
    pvs.SaveData(path, proxy=sdf)
reader = pvs.OpenDataFile(path)
compare(reader, pvs.SparseVolumeToImage(Input=reader), "lvdv")
print("failures:", check.failures)
if check.failures:
    sys.exit(1)
