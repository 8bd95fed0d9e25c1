# ParaView's Volume representation on the sparse volume (vtkSparseDictionaryVolume).
# ParaView offered *Volume* for it (its image representation) and drew nothing, without
# a message: vtkImageVolumeRepresentation renders only the partitions' images, which
# the sparse volume decodes on demand (and uniform chunks have none). The sparse
# producers' representation (LVDIFSparseVolumeRepresentation) now overrides its
# VolumeRepresentation with vtkSparseVolumeVolumeRepresentation, which renders the
# dense image of the volume decoded from the Core volume (refused above the memory limit).
# Oracle: ParaView's own Volume representation of the explicit dense image of the same
# volume (Sparse Volume To Image), in a view of the same size, camera and transfer
# functions: the pictures must be identical pixel for pixel, and draw the volume
# (thousands of pixels; the old code drew none). Volumes: Mesh To SDF of an ellipsoid
# on a fitted non-cubic grid, straight and written as .lvdv and opened again.
#
# Usage: pvpython --force-offscreen-rendering test_volume_representation.py PLUGIN TMPDIR
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import paraview.simple as pvs
from lvdif_check import finish
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, tmpdir = sys.argv[1], sys.argv[2]
T.load_plugin(plugin, ["vtkMeshToSDF", "vtkDictionaryVolumeReader", "vtkSparseVolumeToImage"], remote=False)
check = T.check
SIZE = [320, 240]


def picture(view, name):
    path = os.path.join(tmpdir, "volume_%s.png" % name)
    pvs.SaveScreenshot(path, view, ImageResolution=SIZE)
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    return vtk_to_numpy(img.GetPointData().GetScalars()).reshape(-1, img.GetNumberOfScalarComponents())[:, :3]


def render(source, name, camera=None):
    view = pvs.CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    d = pvs.Show(source, view)
    d.SetRepresentationType("Volume")
    pvs.ColorBy(d, ("POINTS", "sdf"))
    if camera is None:
        pvs.ResetCamera(view)
        view.CameraPosition = [4.0, -6.0, 5.0]
        view.CameraFocalPoint = [0.0, 0.0, 0.0]
        view.CameraViewUp = [0.0, 0.0, 1.0]
        pvs.ResetCamera(view)
    else:
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp, view.CameraParallelScale = camera
    pvs.Render(view)
    cam = (list(view.CameraPosition), list(view.CameraFocalPoint), list(view.CameraViewUp), view.CameraParallelScale)
    return d, view, picture(view, name), cam


ellipsoid = pvs.Transform(Input=pvs.Sphere(Radius=1.0, ThetaResolution=48, PhiResolution=48))
ellipsoid.Transform.Scale = [3.0, 1.0, 0.6]
sdf = pvs.MeshToSDF(Input=ellipsoid, MaxDimension=64, Padding=8.0)
lvdv = os.path.join(tmpdir, "volume_representation.%s" % T.LVD_EXTENSION)
pvs.SaveData(lvdv, proxy=sdf)
reader = pvs.LVDIFDictionaryVolumeReader(FileName=lvdv)

for label, source in (("mesh_to_sdf", sdf), ("lvdv", reader)):
    dense = pvs.SparseVolumeToImage(Input=source)
    dense.UpdatePipeline()
    ext = dense.GetDataInformation().GetExtent()
    check(ext[1] != ext[3] and ext[3] != ext[5], "%s: the grid is not cubic (%s)" % (label, ext))
    # the same transfer functions for both (ColorBy shares them by array name); the range of the data
    lut = pvs.GetColorTransferFunction("sdf")
    lut.RescaleTransferFunction(-8.0, 8.0)
    pvs.GetOpacityTransferFunction("sdf").RescaleTransferFunction(-8.0, 8.0)
    d_oracle, v_oracle, oracle, cam = render(dense, label + "_dense")
    d_sparse, v_sparse, got, _ = render(source, label + "_sparse", cam)
    check(d_sparse.Representation == "Volume", "%s: the sparse volume shows as Volume" % label)
    background = oracle[0]
    drawn = int((abs(oracle.astype(int) - background.astype(int)).max(axis=1) > 0).sum())
    drawn_sparse = int((abs(got.astype(int) - background.astype(int)).max(axis=1) > 0).sum())
    check(drawn > 10000, "%s: the dense image's volume draws %d pixels" % (label, drawn))
    check(drawn_sparse > 10000, "%s: the sparse volume's draws %d pixels (ParaView's drew none)" % (label, drawn_sparse))
    diff = int((abs(got.astype(int) - oracle.astype(int)).max(axis=1) > 0).sum())
    check(diff == 0, "%s: the sparse volume's picture equals the dense image's (%d of %d pixels differ)"
          % (label, diff, got.shape[0]))
    for v in (v_oracle, v_sparse):
        pvs.Delete(v)

finish()
