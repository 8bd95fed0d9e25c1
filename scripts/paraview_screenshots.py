# pvpython: the pictures of docs/PARAVIEW.md, taken with SaveScreenshot.
# Run by scripts/paraview-screenshots.sh (Xvfb, route-B paths).
# Usage: pvpython --force-offscreen-rendering paraview_screenshots.py PLUGIN OUT_DIR [MESH_DIR]
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import paraview.simple as pvs

plugin, out = sys.argv[1], sys.argv[2]
mesh_dir = sys.argv[3] if len(sys.argv) > 3 else ""
pvs.LoadPlugin(plugin, remote=False)
pvs.LoadPalette("WhiteBackground")


def mesh(name, fallback_scale):
    path = os.path.join(mesh_dir, name)
    if mesh_dir and os.path.exists(path):
        return getattr(pvs, T.PROXY_NAMES["vtkLVDIFMeshReader"])(FileName=path), name
    # without the extracted meshes: an elongated ellipsoid
    e = pvs.Transform(Input=pvs.Sphere(ThetaResolution=96, PhiResolution=64))
    e.Transform.Scale = fallback_scale
    return e, "ellipsoid"


def view(size=(640, 480)):
    v = pvs.CreateRenderView()
    v.ViewSize = list(size)
    v.OrientationAxesVisibility = 0
    return v


def camera(v, position, up=(0, 1, 0)):
    v.CameraPosition = list(position)
    v.CameraFocalPoint = [0, 0, 0]
    v.CameraViewUp = list(up)
    v.ResetCamera()
    pvs.Render(v)


# 1. The three filters with default properties, chained; what ParaView shows first
#    for each: the sparse volume as its outline (one box: the whole volume), the
#    surface as a surface.
src, name = mesh("bunny00.off", [1.0, 0.7, 0.5])
sdf = pvs.MeshToSDF(Input=src)
svf = pvs.SignVoxelFilter(Input=sdf)
mc = pvs.ChunkedMarchingCubes(Input=svf)
v = view()
pvs.Show(sdf, v)
d = pvs.Show(mc, v)
d.ColorArrayName = [None, ""]
d.DiffuseColor = [0.9, 0.6, 0.3]
camera(v, (0.3, 0.4, 2.0))
pvs.SaveScreenshot(os.path.join(out, "paraview-defaults.png"), v, ImageResolution=[640, 480])
print("paraview-defaults.png:", name)

# 2. A slice through the signed distances (band 8: |sdf| saturates 8 voxels from the surface):
#    ParaView's Slice filter on the sparse volume's partitions (the Slice representation
#    takes images only); uniform chunks have no partition, so the slice covers the band.
svf.UpdatePipeline()
b = svf.GetDataInformation().GetBounds()
cut = pvs.Slice(Input=svf)
cut.SliceType = "Plane"
cut.SliceType.Origin = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
cut.SliceType.Normal = [0.0, 0.0, 1.0]
s = pvs.Show(cut, v)
pvs.ColorBy(s, ("POINTS", "sdf"))
lut = pvs.GetColorTransferFunction("sdf")
lut.ApplyPreset("Cool to Warm", True)
lut.RescaleTransferFunction(-8.0, 8.0)
s.SetScalarBarVisibility(v, True)
d.Opacity = 0.35
camera(v, (0.0, 0.0, 2.2))
pvs.SaveScreenshot(os.path.join(out, "paraview-sdf-slice.png"), v, ImageResolution=[640, 480])
pvs.Delete(v)
del v

# 3. The former default next to the fixed one, on the cow at Max Dimension 64: the
#    iso value used to be the middle of the sdf range (an offset surface cut open by the
#    grid's box); it is 0 now (the mesh's surface).
src, name = mesh("cow.off", [1.0, 0.6, 0.35])
sdf = pvs.MeshToSDF(Input=src, MaxDimension=64, BandWidth=0)  # no band: the range of the report
svf = pvs.SignVoxelFilter(Input=sdf)
svf.UpdatePipeline()
lo, hi = svf.PointData["sdf"].GetRange()
layout = pvs.CreateLayout("compare")
for i, (iso, label) in enumerate(((0.5 * (lo + hi), "former default: mid-range %.2f" % (0.5 * (lo + hi))),
                                  (0.0, "now: 0"))):
    v = view((480, 400))
    pvs.AssignViewToLayout(v, layout, 0 if i == 0 else 2)
    if i == 0:
        layout.SplitHorizontal(0, 0.5)
        pvs.AssignViewToLayout(v, layout, 1)
    m = pvs.ChunkedMarchingCubes(Input=svf, IsoValue=iso)
    dm = pvs.Show(m, v)
    dm.ColorArrayName = [None, ""]
    dm.DiffuseColor = [0.9, 0.6, 0.3]
    pvs.Show(sdf, v)
    t = pvs.Text(Text=label)
    dt = pvs.Show(t, v)
    dt.FontSize = 14
    dt.WindowLocation = "Upper Center"
    camera(v, (1.2, 0.5, 1.5))
pvs.SaveScreenshot(os.path.join(out, "paraview-isovalue.png"), layout, ImageResolution=[960, 400])
print("paraview-isovalue.png:", name, "range", lo, hi)
