#!/usr/bin/python3
"""Pictures for docs/SIGN_QUALITY.md from the fields that bench_sign_quality --dump writes.

usage: xvfb-run -a /usr/bin/python3 scripts/sign_quality_images.py STEM OUTPREFIX [slices|surfaces|both] [Z|auto] [AXIS]
         [AZIMUTH] [ELEVATION]
  STEM       DIR/NAME_RES (the .txt header and the NAME_RES_MODE.f32 fields)
  OUTPREFIX  e.g. docs/images/sign_quality_lvdif-bunny  (-> OUTPREFIX_slices.png, OUTPREFIX_surfaces.png)
  Z          slice index (default: the slice with most wrong far voxels in the Normal field among those
             whose inside area is at least half the largest)
  AXIS       slice normal, z (default) or y or x
  AZIMUTH, ELEVATION  camera of the surface renders (degrees, default 30 15)
PNGs are quantized to 64 colours (PIL) to keep them small.

Slices: one per mode; inside = blue, outside = white, wrong sign (against the WindingNumber field) = red
where the mode says inside and orange where it says outside; voxels within 1 voxel of the surface are drawn
a shade darker. Surfaces: the zero isosurface of each field (VTK's own vtkFlyingEdges3D), like the paper's
Fig. 3 (the surface after each stage).
"""
import sys

import numpy as np
import vtk
from vtk.util import numpy_support

MODES = [("normal", "Normal (Alg. 1)"), ("svf1", "SVF1"), ("svf12", "+SVF2"), ("svf123", "+SVF3"),
         ("svf1234", "+SVF4"), ("pseudo", "PseudoNormal"), ("winding", "WindingNumber (reference)")]


def load(stem):
    with open(stem + ".txt") as f:
        dims = [int(v) for v in f.readline().split()]
        origin = [float(v) for v in f.readline().split()]
        spacing = [float(v) for v in f.readline().split()]
    fields = {}
    for key, _ in MODES:
        a = np.fromfile("%s_%s.f32" % (stem, key), dtype=np.float32)
        fields[key] = a.reshape(dims[2], dims[1], dims[0])  # z, y, x
    return dims, origin, spacing, fields


def take(a, axis, index):
    return {"z": lambda: a[index, :, :], "y": lambda: a[:, index, :], "x": lambda: a[:, :, index]}[axis]()


def slice_rgb(field, ref, axis, index):
    f, r = take(field, axis, index), take(ref, axis, index)
    inside, ref_in = f < 0, r < 0
    rgb = np.empty(f.shape + (3,), np.uint8)
    rgb[:] = (245, 245, 245)
    rgb[inside] = (70, 110, 200)
    rgb[inside & ~ref_in] = (220, 20, 20)
    rgb[~inside & ref_in] = (255, 160, 0)
    near = np.abs(r) <= 1.0
    rgb[near] = (rgb[near] * 0.7).astype(np.uint8)
    return rgb


def image_actor(rgb):
    h, w, _ = rgb.shape
    img = vtk.vtkImageData()
    img.SetDimensions(w, h, 1)
    arr = numpy_support.numpy_to_vtk(rgb.reshape(-1, 3).copy(), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR)
    img.GetPointData().SetScalars(arr)
    actor = vtk.vtkImageActor()
    actor.GetMapper().SetInputData(img)
    return actor, w, h


def label(text, size=14):
    t = vtk.vtkTextActor()
    t.SetInput(text)
    t.GetTextProperty().SetFontSize(size)
    t.GetTextProperty().SetColor(0, 0, 0)
    t.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    t.SetPosition(0.03, 0.9)
    return t


def render(panels, path, cols, panel_w, panel_h, legend="", view=(30, 15)):
    rows = (len(panels) + cols - 1) // cols
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(cols * panel_w, rows * panel_h)
    for i, (props, text, parallel) in enumerate(panels):
        r, c = divmod(i, cols)
        ren = vtk.vtkRenderer()
        ren.SetViewport(c / cols, 1 - (r + 1) / rows, (c + 1) / cols, 1 - r / rows)
        ren.SetBackground(1, 1, 1)
        for p in props:
            ren.AddActor(p)
        ren.AddActor2D(label(text))
        ren.ResetCamera()
        if parallel:
            ren.GetActiveCamera().ParallelProjectionOn()
            ren.ResetCamera()
            ren.GetActiveCamera().Zoom(1.15)
        else:
            ren.GetActiveCamera().Azimuth(view[0])
            ren.GetActiveCamera().Elevation(view[1])
            ren.GetActiveCamera().OrthogonalizeViewUp()
            ren.ResetCamera()
            ren.GetActiveCamera().Zoom(1.3)
        win.AddRenderer(ren)
    for i in range(len(panels), rows * cols):  # empty panels: white, with the legend in the first
        r, c = divmod(i, cols)
        ren = vtk.vtkRenderer()
        ren.SetViewport(c / cols, 1 - (r + 1) / rows, (c + 1) / cols, 1 - r / rows)
        ren.SetBackground(1, 1, 1)
        if legend:
            t = label(legend, 12)
            t.SetPosition(0.03, 0.1)
            ren.AddActor2D(t)
            legend = ""
        win.AddRenderer(ren)
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    from PIL import Image
    Image.open(path).convert("RGB").quantize(64).save(path, optimize=True)
    print("wrote", path)


def surface_actor(field, origin, spacing):
    d = field.shape
    img = vtk.vtkImageData()
    img.SetDimensions(d[2], d[1], d[0])
    img.SetOrigin(origin)
    img.SetSpacing(spacing)
    img.GetPointData().SetScalars(numpy_support.numpy_to_vtk(field.ravel(), deep=True))
    fe = vtk.vtkFlyingEdges3D()
    fe.SetInputData(img)
    fe.SetValue(0, 0.0)
    fe.ComputeNormalsOn()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(fe.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.85, 0.75, 0.55)
    return actor


def main():
    stem, prefix = sys.argv[1], sys.argv[2]
    what = sys.argv[3] if len(sys.argv) > 3 else "both"
    axis = sys.argv[5] if len(sys.argv) > 5 else "z"
    view = (float(sys.argv[6]), float(sys.argv[7])) if len(sys.argv) > 7 else (30.0, 15.0)
    dims, origin, spacing, fields = load(stem)
    ref = fields["winding"]
    if len(sys.argv) > 4 and sys.argv[4] != "auto":
        index = int(sys.argv[4])
    else:
        # the slice with most wrong far voxels of the Normal field among those that cut the object
        wrong = ((fields["normal"] < 0) != (ref < 0)) & (np.abs(ref) > 1)
        dims_sum = {"z": (1, 2), "y": (0, 2), "x": (0, 1)}[axis]
        inside = (ref < 0).sum(axis=dims_sum)
        sums = np.where(inside > 0.5 * inside.max(), wrong.sum(axis=dims_sum), -1)
        index = int(np.argmax(sums))
    if what in ("slices", "both"):
        panels = []
        for key, name in MODES:
            rgb = slice_rgb(fields[key], ref, axis, index)
            wrong = int((((take(fields[key], axis, index) < 0) != (take(ref, axis, index) < 0))).sum())
            actor, w, h = image_actor(rgb)
            panels.append(([actor], "%s: %d wrong" % (name, wrong), True))
        scale = 260.0 / max(w, h)
        legend = ("%s-slice %d of %s\nblue: inside, white: outside\nred: wrong inside, orange: wrong outside\n"
                  "darker: within 1 voxel of the surface\nwrong = sign differs from WindingNumber" % (axis, index, stem.split("/")[-1]))
        render(panels, "%s_slices.png" % prefix, 4, int(w * scale) + 10, int(h * scale) + 10, legend)
        print("slice", axis, "=", index)
    if what in ("surfaces", "both"):
        panels = [([surface_actor(fields[key], origin, spacing)], name, False) for key, name in MODES]
        legend = "zero isosurface of each field\n(vtkFlyingEdges3D), %s" % stem.split("/")[-1]
        render(panels, "%s_surfaces.png" % prefix, 4, 280, 280, legend, view)


if __name__ == "__main__":
    main()
