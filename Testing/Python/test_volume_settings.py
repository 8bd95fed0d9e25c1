"""One rule for BandWidth and ChunkEdge in every class that has them
(docs/USER_GUIDE.md, "Band width, chunk edge, padding, compression level"):
- BandWidth: a number of voxels > 0; 0 means no band (every distance kept);
  negative or NaN is refused with one error naming BandWidth (before: the
  filters read a negative band as no band, the writers refused 0, the editing
  filter clamped to [1, 1e6]).
- Padding of vtkMeshToSDF's fitted grid: a finite number of voxels >= 0; a
  negative one (clamped to 0 before), NaN or infinity is refused by name; a
  Max Dimension too small for it names both properties (not Core's maxDim).
- CompressionLevel of the .lvdv writers: 1..19, refused outside (clamped before),
  for an image and a sparse input, nothing written, an older file kept.
- ChunkEdge of a volume: a power of two in [4, 256]; anything else is refused
  when used, and never clamped (before: the filters clamped 2 to 4 and 512 to
  256, the writers refused them). The marching cubes' ChunkEdge (cells) is
  16..256, refused outside (it clamped).
Oracles: the band and chunk edge the volume itself reports (written and read
back for the writers), the errors the class reports. Runs without ParaView,
on a non-cubic grid with anisotropic spacing.
Usage: test_volume_settings.py OUTDIR"""
import math
import glob
import os
import sys

import numpy as np
import vtk
from vtkmodules.util import numpy_support as ns

import lvdif
from lvdif_check import check, finish

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
RULE = "BandWidth must be a number of voxels >= 0 (0: no band), not "


def image(dims=(37, 90, 12), spacing=(1.0, 0.5, 2.0)):
    """A ball's signed distance (voxel units of x) on an image with a colour array."""
    img = vtk.vtkImageData()
    img.SetDimensions(*dims)
    img.SetSpacing(*spacing)
    z, y, x = np.meshgrid(*[np.arange(d) * s for d, s in zip(dims[::-1], spacing[::-1])], indexing="ij")
    c = [(d - 1) * s / 2 for d, s in zip(dims, spacing)]
    sdf = (np.sqrt((x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2) - 5.0).astype(np.float32).ravel()
    a = ns.numpy_to_vtk(sdf, deep=1)
    a.SetName("sdf")
    img.GetPointData().AddArray(a)
    img.GetPointData().SetActiveScalars("sdf")
    return img


class Errors:
    """The error events of one algorithm (its own vtkErrorMacro)."""

    def __init__(self, obj):
        self.messages = []

        @vtk.calldata_type(vtk.VTK_STRING)
        def on_error(_o, _e, text):
            # the message without VTK's "ERROR: In FILE, line N CLASS (0x..): " (the
            # passing checks print it, and ctest fails a test whose output has "ERROR:")
            self.messages.append(" ".join(text.split()).split("): ", 1)[-1])

        self.callback = on_error
        obj.AddObserver("ErrorEvent", on_error)


def run(cls, band=None, edge=None, inp=None, path=None, **props):
    """Runs one class with the settings given (props: other properties by name):
    (succeeded, errors, object)."""
    obj = getattr(lvdif, cls)()
    errors = Errors(obj)
    for name, value in props.items():
        getattr(obj, "Set" + name)(value)
    if inp is not None:
        obj.SetInputData(inp)
    if band is not None:
        obj.SetBandWidth(band)
    if edge is not None:
        obj.SetChunkEdge(edge)
    if path is not None:
        obj.SetFileName(path)
    if hasattr(obj, "Write"):
        ok = obj.Write() == 1
    else:
        obj.Update()
        ok = not errors.messages
    return ok, errors.messages, obj


def sphere():
    s = vtk.vtkSphereSource()
    s.SetRadius(3.0)
    s.SetThetaResolution(24)
    s.SetPhiResolution(12)
    s.Update()
    return s.GetOutput()


def mesh_to_sdf(**kw):
    ok, errs, f = run("vtkMeshToSDF", inp=sphere(), **kw)
    return ok, errs, f.GetOutput() if ok else None


def volume_of(cls, inp, **kw):
    ok, errs, f = run(cls, inp=inp, **kw)
    return ok, errs, f.GetOutput() if ok else None


def written(cls, ext, inp, **kw):
    path = os.path.join(out, "settings_%s.%s" % (cls, ext))
    # a fresh write: the index and, for a .lvdvp, its pieces (pieces without their index are refused
    # as possibly another volume's files)
    for name in [path] + glob.glob(os.path.join(out, "settings_%s_*.lvdv" % cls)):
        if os.path.exists(name):
            os.remove(name)
    ok, errs, _ = run(cls, inp=inp, path=path, **kw)
    if not ok:
        return ok, errs, None
    reader = lvdif.vtkPDictionaryVolumeReader() if ext == "lvdvp" else lvdif.vtkDictionaryVolumeReader()
    reader.SetFileName(path)
    reader.Update()
    return ok, errs, reader.GetOutput()


img = image()
IMG_MIN = img.GetPointData().GetArray("sdf").GetRange()[0]


def band_of(vol):
    """The band a volume reports, or for an image (vtkVolumeEditFilter's output on
    an image) the one its distances show: the input's deepest distance cut at -band."""
    if hasattr(vol, "GetBandWidth"):
        return vol.GetBandWidth()
    lo = vol.GetPointData().GetArray("sdf").GetRange()[0]
    return math.inf if lo < IMG_MIN + 0.01 else -lo


cubic = image((32, 32, 32), (1.0, 1.0, 1.0))
bv = os.path.join(out, "settings_ball.bv")
ok, errs, _ = run("vtkLegacyBvWriter", inp=cubic, path=bv)
assert ok, errs


def bv_read(**kw):
    ok, errs, r = run("vtkLegacyBvReader", path=bv, **kw)
    return ok, errs, r.GetOutput() if ok else None


# every class with a BandWidth, and how it makes a volume that reports its band
BANDED = {
    "vtkMeshToSDF": lambda **kw: mesh_to_sdf(**kw),
    "vtkImageToSparseVolume": lambda **kw: volume_of("vtkImageToSparseVolume", img, **kw),
    "vtkVolumeEditFilter": lambda **kw: volume_of("vtkVolumeEditFilter", img, **kw),
    "vtkDictionaryVolumeWriter": lambda **kw: written("vtkDictionaryVolumeWriter", "lvdv", img, **kw),
    "vtkPDictionaryVolumeWriter": lambda **kw: written("vtkPDictionaryVolumeWriter", "lvdvp", img, **kw),
    "vtkLegacyBvWriter": lambda **kw: written_bv(**kw),
    "vtkLegacyBvReader": lambda **kw: bv_read(**kw),
}


def written_bv(**kw):
    path = os.path.join(out, "settings_out.bv")
    ok, errs, _ = run("vtkLegacyBvWriter", inp=cubic, path=path, **kw)
    if not ok:
        return ok, errs, None
    r = lvdif.vtkLegacyBvReader()
    r.SetFileName(path)
    r.SetBandWidth(0)  # the file's own distances, not clipped again on import
    r.Update()
    return ok, errs, r.GetOutput()


for cls, make in BANDED.items():
    for band, want in ((8, 8.0), (2.5, 2.5), (0, math.inf), (1e300, math.inf)):
        ok, errs, vol = make(band=band)
        check(ok and not errs, "%s BandWidth %g: failed %s" % (cls, band, errs))
        # .bv stores no band; an image shows no band deeper than its ball (5)
        if ok and cls != "vtkLegacyBvWriter" and (band != 8 or hasattr(vol, "GetBandWidth")):
            got = band_of(vol)
            check(abs(got - want) < 0.01 if want < math.inf else got == want,
                  "%s BandWidth %g: the volume's band is %g, not %g" % (cls, band, got, want))
    if cls == "vtkLegacyBvWriter":
        # the file keeps the band's clipping: |sdf| <= 2.5 with band 2.5, the ball's full range with 0
        # (the ball's centre lies 0.87 voxel from the nearest point: its deepest distance is -4.13)
        for band, lo, hi in ((2.5, -2.51, -2.49), (0, -4.2, -4.0)):
            ok, errs, vol = make(band=band)
            if not ok:
                continue  # reported above
            conv = lvdif.vtkSparseVolumeToImage()
            conv.SetInputData(vol)
            conv.Update()
            arr = conv.GetOutput().GetPointData().GetArray("sdf")
            rng = arr.GetRange() if arr else None
            check(rng is not None and lo <= rng[0] <= hi, "vtkLegacyBvWriter BandWidth %g: sdf range %s" % (band, rng))
    for band in (-1, -1e-9, float("nan")):
        ok, errs, _ = make(band=band)
        check(not ok and len(errs) == 1 and (RULE + ("%g" % band if band == band else "nan")) in errs[0],
              "%s BandWidth %g: %s %s" % (cls, band, "succeeded" if ok else "failed", errs))

# the storage chunk edge: the same enumeration everywhere, no clamp
CHUNKED = {k: BANDED[k] for k in ("vtkMeshToSDF", "vtkImageToSparseVolume", "vtkVolumeEditFilter",
                                  "vtkDictionaryVolumeWriter", "vtkPDictionaryVolumeWriter")}
for cls, make in CHUNKED.items():
    for edge in (4, 256):
        ok, errs, vol = make(edge=edge)
        # (an image output has no chunks to show)
        got = vol.GetChunkEdge() if ok and hasattr(vol, "GetChunkEdge") else edge if ok else None
        check(got == edge, "%s ChunkEdge %d: %s %s" % (cls, edge, errs, got))
    for edge in (2, 3, 48, 512, 0, -32):
        obj = getattr(lvdif, cls)()
        obj.SetChunkEdge(edge)
        check(obj.GetChunkEdge() == edge, "%s ChunkEdge %d reads back %d (clamped)" % (cls, edge, obj.GetChunkEdge()))
        ok, errs, _ = make(edge=edge)
        check(not ok and len(errs) == 1 and ("chunk edge %d must be a power of two in [4, 256]" % edge) in errs[0],
              "%s ChunkEdge %d: %s %s" % (cls, edge, "succeeded" if ok else "failed", errs))

# the marching cubes' chunk edge (cells): 16..256, refused outside, no clamp
sparse = volume_of("vtkImageToSparseVolume", img)[2]
for edge in (16, 256):
    ok, errs, mc = run("vtkChunkedMarchingCubes", inp=sparse, edge=edge)
    check(ok and mc.GetOutput().GetNumberOfCells() > 0, "vtkChunkedMarchingCubes ChunkEdge %d: %s" % (edge, errs))
for edge in (15, 257, 0):
    ok, errs, mc = run("vtkChunkedMarchingCubes", inp=sparse, edge=edge)
    check(mc.GetChunkEdge() == edge and not ok and len(errs) == 1 and "16" in errs[0] and "256" in errs[0],
          "vtkChunkedMarchingCubes ChunkEdge %d: read back %d, %s" % (edge, mc.GetChunkEdge(), errs))

# a sparse input keeps its own band and chunk edge: the editing filter's settings
# (even out of range) do not apply to it, as the writers' do not
sparse_in = volume_of("vtkImageToSparseVolume", img, band=2.5, edge=16)[2]
for band, edge in ((-1, 48), (0, 4)):
    ok, errs, f = run("vtkVolumeEditFilter", inp=sparse_in, band=band, edge=edge)
    vol = f.GetOutput() if ok else None
    check(ok and vol.GetBandWidth() == 2.5 and vol.GetChunkEdge() == 16,
          "vtkVolumeEditFilter on a sparse volume, BandWidth %g ChunkEdge %d: %s %s" % (
              band, edge, errs, (vol.GetBandWidth(), vol.GetChunkEdge()) if vol else None))

# a writer checks its folder before the work: with an image input and a bad chunk edge
# the folder's error comes alone (the conversion used to run first and report the chunk edge)
for cls, ext in (("vtkDictionaryVolumeWriter", "lvdv"), ("vtkPDictionaryVolumeWriter", "lvdvp")):
    ok, errs, _ = run(cls, inp=img, edge=48, path="/nonexistent-lvdif/x." + ext)
    check(not ok and len(errs) == 1 and "the folder '/nonexistent-lvdif' does not exist" in errs[0]
          and "x." + ext in errs[0], "%s into a missing folder: %s" % (cls, errs))

# vtkMeshToSDF's Padding: no clamp, one error naming it, on both fitted grids; the
# oracle for the accepted ones: the fitted grid's points on the longest axis stay
# MaxDimension, and the sphere (diameter 6) spans MaxDimension - 1 - 2 x Padding cells
PADDING_RULE = "Padding must be a finite number of voxels >= 0, not "
for padding in (0.0, 2.5):
    ok, errs, vol = mesh_to_sdf(MaxDimension=40, Padding=padding)
    grid = None
    if ok:
        conv = lvdif.vtkSparseVolumeToImage()
        conv.SetInputData(vol)
        conv.Update()
        grid = (conv.GetOutput().GetDimensions(), conv.GetOutput().GetSpacing())
    h = 6.0 / (40 - 1 - 2 * padding)  # the sphere source's polygon spans a little less than 6 on x
    check(ok and grid[0][0] == 40 and abs(grid[1][0] - h) < 0.01 * h,
          "vtkMeshToSDF Padding %g: %s %s (spacing %g wanted)" % (padding, errs, grid, h))
for padding, text in ((-1.0, "-1"), (-1e-9, "-1e-09"), (float("nan"), "nan"), (float("inf"), "inf")):
    for spacing in (0.0, 0.25):
        ok, errs, f = run("vtkMeshToSDF", inp=sphere(), Padding=padding, SampleSpacing=spacing)
        back = f.GetPadding()
        check((back == padding or (back != back and padding != padding)) and not ok and len(errs) == 1
              and PADDING_RULE + text in errs[0],
              "vtkMeshToSDF Padding %g (Sample Spacing %g): read back %g, %s" % (padding, spacing, back, errs))
# Max Dimension and Sample Spacing likewise: refused by name with the value given
for props, text in (({"MaxDimension": 1}, "Max Dimension must be in [2, 1048576] (points on the longest axis), not 1"),
                    ({"MaxDimension": 0}, "Max Dimension must be in [2, 1048576] (points on the longest axis), not 0"),
                    ({"SampleSpacing": -1.0}, "Sample Spacing must be a finite length >= 0 (0: use Max Dimension), not -1"),
                    ({"SampleSpacing": float("nan")}, "Sample Spacing must be a finite length >= 0 (0: use Max Dimension), not nan")):
    ok, errs, f = run("vtkMeshToSDF", inp=sphere(), **props)
    back = [getattr(f, "Get" + k)() for k in props]
    check(not ok and len(errs) == 1 and text in errs[0] and str(back) == str(list(props.values())),
          "vtkMeshToSDF %s: read back %s, %s" % (props, back, errs))
# an explicit grid does not use Padding: not checked there
ok, errs, f = run("vtkMeshToSDF", inp=sphere(), Padding=-1.0, UseExplicitGrid=True, Dimensions=(16, 12, 10))
check(ok and not errs, "vtkMeshToSDF Padding -1 with an explicit grid: %s" % errs)
# an explicit grid: 1 point on an axis is a 2-D slice of the field, kept (VTK's
# Contour gives the sphere's cross-section on it: lines); 0 points or a spacing
# <= 0 are refused by the property's name with the values given
ok, errs, f = run("vtkMeshToSDF", inp=sphere(), UseExplicitGrid=True, Dimensions=(16, 12, 1),
                  Origin=(-4.0, -4.0, 0.0), Spacing=(0.5, 0.5, 0.5))
lines = -1
if ok:
    conv = lvdif.vtkSparseVolumeToImage()
    conv.SetInputData(f.GetOutput())
    conv.Update()
    contour = vtk.vtkContourFilter()
    contour.SetInputData(conv.GetOutput())
    contour.SetValue(0, 0.0)
    contour.Update()
    lines = contour.GetOutput().GetNumberOfLines()
check(ok and not errs and lines > 0, "vtkMeshToSDF explicit grid 16 x 12 x 1: %s, %d contour lines" % (errs, lines))
for props, text in (({"Dimensions": (16, 12, 0)}, "Dimensions must be at least 1 point on each axis, not 16 x 12 x 0"),
                    ({"Spacing": (0.5, 0.0, 0.5)}, "Spacing must be > 0 on each axis, not 0.5, 0, 0.5")):
    ok, errs, f = run("vtkMeshToSDF", inp=sphere(), UseExplicitGrid=True, **props)
    check(not ok and len(errs) == 1 and text in errs[0] and not f.GetOutput().HasVolume(),
          "vtkMeshToSDF explicit grid %s: %s" % (props, errs))
for dim, good in ((5, False), (6, True)):
    ok, errs, f = run("vtkMeshToSDF", inp=sphere(), MaxDimension=dim, Padding=2.0)
    check(ok == good and (good or (len(errs) == 1 and "Max Dimension 5 leaves no voxel for the mesh inside 2 voxels"
                                   " of Padding" in errs[0] and "maxDim" not in errs[0])),
          "vtkMeshToSDF Max Dimension %d, Padding 2: %s" % (dim, errs))

# the writers' CompressionLevel: no clamp, one error, nothing written, an older file kept
LEVEL_RULE = "CompressionLevel must be a zstd level in [1, 19], not "
sparse_src = volume_of("vtkImageToSparseVolume", img)[2]
for cls, ext in (("vtkDictionaryVolumeWriter", "lvdv"), ("vtkPDictionaryVolumeWriter", "lvdvp")):
    for inp, kind in ((img, "image"), (sparse_src, "sparse volume")):
        for level in (1, 19):
            ok, errs, vol = written(cls, ext, inp, CompressionLevel=level)
            check(ok and not errs and vol is not None and vol.HasVolume() and vol.GetNumberOfChunks() > 0,
                  "%s CompressionLevel %d, %s: %s" % (cls, level, kind, errs))
        path = os.path.join(out, "settings_%s.%s" % (cls, ext))
        before = open(path, "rb").read()
        for level in (0, 20, -3):
            ok, errs, w = run(cls, inp=inp, path=path, CompressionLevel=level)
            check(w.GetCompressionLevel() == level and not ok and len(errs) == 1 and LEVEL_RULE + str(level) in errs[0]
                  and open(path, "rb").read() == before,
                  "%s CompressionLevel %d, %s: read back %d, %s" % (cls, level, kind, w.GetCompressionLevel(), errs))

# vtkSignVoxelFilter: Threshold, Axis, MaxIterations and the Filters mask by Core's
# one rule (lvdif::checkSignVoxelFilterParams), refused at update with one error
# naming the parameter and the value given, nothing computed, never clamped (before:
# Threshold -1 ran as 0, Axis 3 as z, MaxIterations -1 as automatic, Filters 16 as 15)
SVF_BAD = (({"Threshold": -1.0}, "the threshold must be finite and >= 0, not -1"),
           ({"Threshold": float("nan")}, "the threshold must be finite and >= 0, not nan"),
           ({"Threshold": 1e39}, "the threshold must be finite and >= 0, not inf"),  # beyond float
           ({"Axis": 3}, "the axis must be 0 (x), 1 (y) or 2 (z), not 3"),
           ({"Axis": -1}, "the axis must be 0 (x), 1 (y) or 2 (z), not -1"),
           ({"MaxIterations": -1}, "maxIterations must be >= 0 (0 = automatic), not -1"),
           ({"Filters": 16}, "the filter mask may only contain Svf1..Svf4 bits (0..15), not 16"),
           ({"Filters": -1}, "the filter mask may only contain Svf1..Svf4 bits (0..15), not -1"))
SVF_GOOD = ({"Threshold": 0.0}, {"Threshold": 0.3}, {"Threshold": 1e30}, {"Axis": 2}, {"Axis": 1},
            {"MaxIterations": 7}, {"MaxIterations": 0}, {"Filters": 0}, {"Filters": 5})
for inp, kind in ((img, "image"), (sparse_src, "sparse volume")):
    for props, text in SVF_BAD:
        ok, errs, f = run("vtkSignVoxelFilter", inp=inp, **props)
        back = [getattr(f, "Get" + k)() for k in props]
        o = f.GetOutput()
        empty = not o.HasVolume() if kind == "sparse volume" else o.GetNumberOfPoints() == 0
        check(not ok and len(errs) == 1 and text in errs[0] and str(back) == str(list(props.values())) and empty,
              "vtkSignVoxelFilter %s, %s: read back %s, empty output %s, %s" % (props, kind, back, empty, errs))
    for props in SVF_GOOD:
        ok, errs, f = run("vtkSignVoxelFilter", inp=inp, **props)
        back = [getattr(f, "Get" + k)() for k in props]
        check(ok and not errs and back == list(props.values()),
              "vtkSignVoxelFilter %s, %s: read back %s, %s" % (props, kind, back, errs))

# Enumerations (Boundary, Device, SignMode, Accelerator, OutputMode) and the
# sign filter mask of vtkMeshToSDF: refused at update with one error naming the
# property, its values and the value given; the getter returns what was set; no
# output (before: vtkSetClampMacro, so Device 7 ran on CUDA, Boundary 5 as free,
# OutputMode 2 as merged, SignMode -1 as normal, SignVoxelFilters 16 as all four)
DEVICE = "Device must be 0 (auto), 1 (CPU) or 2 (CUDA), not "


def output_empty(f):
    o = f.GetOutputDataObject(0)
    return not o.HasVolume() if hasattr(o, "HasVolume") else o.GetNumberOfPoints() == 0


ENUM_BAD = (
    ("vtkSignVoxelFilter", lambda: sparse_src, {"Boundary": 2}, "Boundary must be 0 (outside) or 1 (free), not 2"),
    ("vtkSignVoxelFilter", lambda: img, {"Boundary": -1}, "Boundary must be 0 (outside) or 1 (free), not -1"),
    ("vtkSignVoxelFilter", lambda: sparse_src, {"Device": 3}, DEVICE + "3"),
    ("vtkSignVoxelFilter", lambda: img, {"Device": -1}, DEVICE + "-1"),
    ("vtkMeshToSDF", sphere, {"SignMode": 4},
     "SignMode must be 0 (normal), 1 (pseudo-normal), 2 (winding number) or 3 (unsigned), not 4"),
    ("vtkMeshToSDF", sphere, {"SignMode": -1}, "not -1"),
    ("vtkMeshToSDF", sphere, {"Accelerator": 3}, "Accelerator must be 0 (BVH), 1 (faithful) or 2 (brute force), not 3"),
    ("vtkMeshToSDF", sphere, {"SignVoxelFilters": 16}, "the filter mask may only contain Svf1..Svf4 bits (0..15), not 16"),
    ("vtkMeshToSDF", sphere, {"SignVoxelFilters": -1}, "the filter mask may only contain Svf1..Svf4 bits (0..15), not -1"),
    ("vtkMeshToSDF", sphere, {"Device": 7}, DEVICE + "7"),
    ("vtkChunkedMarchingCubes", lambda: sparse_src, {"OutputMode": 2}, "OutputMode must be 0 (partitioned) or 1 (merged), not 2"),
    ("vtkChunkedMarchingCubes", lambda: img, {"OutputMode": -1}, "OutputMode must be 0 (partitioned) or 1 (merged), not -1"),
    ("vtkChunkedMarchingCubes", lambda: sparse_src, {"Device": 3}, DEVICE + "3"))
for cls, inp, props, text in ENUM_BAD:
    ok, errs, f = run(cls, inp=inp(), MaxDimension=24, **props) if cls == "vtkMeshToSDF" else run(cls, inp=inp(), **props)
    back = [getattr(f, "Get" + k)() for k in props]
    check(not ok and len(errs) == 1 and text in errs[0] and back == list(props.values()) and output_empty(f),
          "%s %s: read back %s, empty output %s, %s" % (cls, props, back, output_empty(f), errs))
ENUM_GOOD = (("vtkSignVoxelFilter", lambda: sparse_src, {"Boundary": 1, "Device": 1}),
             ("vtkMeshToSDF", sphere, {"SignMode": 3, "Accelerator": 2, "SignVoxelFilters": 15, "Device": 1}),
             ("vtkMeshToSDF", sphere, {"SignMode": 0, "Accelerator": 1}),
             ("vtkChunkedMarchingCubes", lambda: sparse_src, {"OutputMode": 1, "Device": 1}),
             ("vtkChunkedMarchingCubes", lambda: img, {"OutputMode": 0}))
for cls, inp, props in ENUM_GOOD:
    ok, errs, f = run(cls, inp=inp(), MaxDimension=24, **props) if cls == "vtkMeshToSDF" else run(cls, inp=inp(), **props)
    back = [getattr(f, "Get" + k)() for k in props]
    check(ok and not errs and back == list(props.values()) and not output_empty(f),
          "%s %s: read back %s, %s" % (cls, props, back, errs))

# the mesh reader's Format (an enumeration), the mesh report's WeldTolerance (with Weld
# on) and the .lvdvp writer's Piece / NumberOfPieces: refused by name, never clamped
# (before: Format 5 read the file as PLY, -1 as auto; WeldTolerance -1 welded with 0;
# Piece -1 wrote piece 0, NumberOfPieces 0 wrote one piece)
tet = os.path.join(out, "settings_tet.off")
with open(tet, "w") as f:
    f.write("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
for fmt in (0, 2):
    ok, errs, r = run("vtkLVDIFMeshReader", path=tet, Format=fmt)
    check(ok and r.GetOutput().GetNumberOfPoints() == 4 and r.GetFormat() == fmt,
          "vtkLVDIFMeshReader Format %d: %s" % (fmt, errs))
for fmt in (5, -1):
    ok, errs, r = run("vtkLVDIFMeshReader", path=tet, Format=fmt)
    check(not ok and r.GetFormat() == fmt and len(errs) == 1 and r.GetOutput().GetNumberOfPoints() == 0
          and "Format must be 0 (auto), 1 (OBJ), 2 (OFF), 3 (STL) or 4 (PLY), not %d" % fmt in errs[0],
          "vtkLVDIFMeshReader Format %d: read back %d, %s" % (fmt, r.GetFormat(), errs))
for weld, tol, good in ((True, 0.0, True), (True, 1e-3, True), (False, -1.0, True), (True, -1.0, False),
                        (True, float("nan"), False), (True, float("inf"), False)):
    ok, errs, rep = run("vtkLVDIFMeshReport", inp=sphere(), Weld=weld, WeldTolerance=tol)
    back = rep.GetWeldTolerance()
    check((back == tol or (back != back and tol != tol)) and ok == good and
          (good or (len(errs) == 1 and "WeldTolerance must be a finite length >= 0 (world units), not %g" % tol in errs[0])),
          "vtkLVDIFMeshReport Weld %s WeldTolerance %g: read back %g, %s" % (weld, tol, back, errs))
pieces = os.path.join(out, "settings_pieces.lvdvp")
ok, errs, _ = run("vtkPDictionaryVolumeWriter", inp=img, path=pieces)
assert ok, errs
before = open(pieces, "rb").read()
for piece, count in ((-1, 1), (0, 0), (0, -2), (2, 2)):
    ok, errs, w = run("vtkPDictionaryVolumeWriter", inp=img, path=pieces, Piece=piece, NumberOfPieces=count)
    check((w.GetPiece(), w.GetNumberOfPieces()) == (piece, count) and not ok and len(errs) == 1
          and "piece %d of %d does not exist" % (piece, count) in errs[0] and open(pieces, "rb").read() == before,
          "vtkPDictionaryVolumeWriter piece %d of %d: read back %d of %d, %s" % (
              piece, count, w.GetPiece(), w.GetNumberOfPieces(), errs))

# OpenVDB: the writer's HalfWidth (0: the volume's band, or 1..10000 voxels) and the
# reader's Padding (0..65536): refused by name with the value given, never clamped
# (before: HalfWidth -1 ran as 0, 20000 as 10000, 0.5 was taken; Padding -1 as 0); a refused save keeps the older file. Oracles: the band
# of the file read back (background / voxel size = the half width) and the padded box.
if hasattr(lvdif, "vtkOpenVDBLevelSetWriter"):
    HALF_RULE = "HalfWidth must be 0 (the volume's band) or a number of voxels in [1, 10000], not "
    vdb = os.path.join(out, "settings.vdb")
    # (0: an image's volume gets OpenVDB's default band, 3)
    for hw, want in ((0.0, 3.0), (1.0, 1.0), (2.5, 2.5), (10000.0, 10000.0)):
        ok, errs, w = run("vtkOpenVDBLevelSetWriter", inp=cubic, path=vdb, HalfWidth=hw)
        r = lvdif.vtkOpenVDBLevelSetReader()
        r.SetFileName(vdb)
        r.Update()
        band = r.GetOutput().GetBandWidth() if ok else None
        check(ok and not errs and band == want, "vtkOpenVDBLevelSetWriter HalfWidth %g: band read back %s, %s" % (hw, band, errs))
    before = open(vdb, "rb").read()
    for hw, text in ((0.5, "0.5"), (1e-9, "1e-09"), (10000.5, "10000.5"), (-1.0, "-1"), (float("nan"), "nan"), (float("inf"), "inf")):
        for inp, kind in ((cubic, "image"), (volume_of("vtkImageToSparseVolume", cubic)[2], "sparse volume")):
            ok, errs, w = run("vtkOpenVDBLevelSetWriter", inp=inp, path=vdb, HalfWidth=hw)
            back = w.GetHalfWidth()
            check((back == hw or (back != back and hw != hw)) and not ok and len(errs) == 1 and HALF_RULE + text in errs[0]
                  and open(vdb, "rb").read() == before,
                  "vtkOpenVDBLevelSetWriter HalfWidth %g, %s: read back %g, %s" % (hw, kind, back, errs))
    dims = {}
    for padding in (0, 3):
        ok, errs, r = run("vtkOpenVDBLevelSetReader", path=vdb, Padding=padding)
        d = [0, 0, 0]
        if ok:
            r.GetOutput().GetDimensions(d)
        dims[padding] = d if ok else None
        check(ok and not errs, "vtkOpenVDBLevelSetReader Padding %d: %s" % (padding, errs))
    check(None not in dims.values() and [b - a for a, b in zip(dims[0], dims[3])] == [6, 6, 6],
          "vtkOpenVDBLevelSetReader Padding 3 grows the box by 3 voxels a side: %s" % dims)
    for padding, text in ((-1, "Padding must be a finite number of voxels >= 0, not -1"),
                          (65537, "Padding must be a number of voxels in [0, 65536], not 65537")):
        ok, errs, r = run("vtkOpenVDBLevelSetReader", path=vdb, Padding=padding)
        check(r.GetPadding() == padding and not ok and len(errs) == 1 and text in errs[0] and output_empty(r),
              "vtkOpenVDBLevelSetReader Padding %d: read back %d, %s" % (padding, r.GetPadding(), errs))

# the editor object (the Qt editor's volumes): the same rule for new volumes
ed = lvdif.vtkLVDIFEditor()
for band, good in ((0, True), (8, True), (-1, False), (float("nan"), False)):
    errors = Errors(ed)
    ed.SetBandWidth(band)
    r = ed.NewVolume(24, 40, 16, False)
    check(bool(r) == good and (good or (len(errors.messages) == 1 and RULE in errors.messages[0])),
          "vtkLVDIFEditor BandWidth %g: NewVolume %d %s" % (band, r, errors.messages))

# the editor's Device: refused at the call (it has no update), with the filters' words
errors = Errors(ed)
ed.SetDevice(1)
ed.SetDevice(3)
check(ed.GetDevice() == 1 and len(errors.messages) == 1 and DEVICE + "3" in errors.messages[0],
      "vtkLVDIFEditor Device 3: read back %d, %s" % (ed.GetDevice(), errors.messages))

finish()
