"""pvpython: every failing LVDIF reader or filter reports ONE clear error.

ParaView runs RequestData even when RequestInformation failed (pvpython's
UpdatePipeline, the GUI's Apply): a missing .lvdv gave its error twice, a
reader without a file name first "no file name" then "cannot open ''", a bad
Band Width or Chunk Edge of Mesh To SDF twice. Counts every error message in the
output window (VTK's executive's "returned failure" dumps too); also: a reader that failed shows no stale
data from its last good file, and the band / chunk edge / padding / compression
level rule of docs/USER_GUIDE.md through the proxies (Band Width 0 = no band),
a fitted grid's error in the properties' names, and a failed reader feeding two
of our filters gives its one error (the filters below added one each).
Usage: test_errors.py PLUGIN TMPDIR"""
import lvdif_pvtest  # noqa: F401  (first: ParaView's Python on sys.path)

import math
import os
import sys

import paraview.simple as pvs
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from lvdif_check import check, finish

plugin, tmp = sys.argv[1], sys.argv[2]
pvs.LoadPlugin(plugin, remote=False)  # adds the proxies to paraview.simple
out = os.path.join(tmp, "errors")
os.makedirs(out, exist_ok=True)


# Every error reaches the output window, also those of the information pass that
# runs when a proxy is created (before an observer could be added to it).
window = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window)
# pvpython sends Python's own output to the output window too: keep it on the terminal
sys.stdout, sys.stderr = sys.__stdout__, sys.__stderr__


def errors_during(work):
    """Every error message while `work` runs, VTK's executive's too: its "Algorithm X
    returned failure for request: <the request dumped>" after a reader's or filter's
    own error (one for the information pass, one for the RequestData ParaView runs
    anyway: three messages for one missing file) is dropped now
    (LVDIFVolumeBridge::FailReported), so one failure is one message here."""
    start = len(window.GetOutput())
    result = work()
    text = window.GetOutput()[start:]
    return result, [" ".join(m.split()) for m in text.split("ERROR: In ")[1:]]


def one_error(label, make, needle):
    """Creates and updates the proxy `make()` gives: exactly one error containing `needle`."""
    proxy, got = errors_during(lambda: updated(make()))
    check(len(got) == 1 and needle in got[0], "%s: one error with '%s', got %d: %s" % (label, needle, len(got), got))
    return proxy


def updated(proxy):
    proxy.UpdatePipeline()
    return proxy


def points(proxy):
    proxy.UpdatePipeline()
    return proxy.GetDataInformation().GetNumberOfPoints()


sphere = pvs.Sphere(ThetaResolution=24, PhiResolution=12)
src_level = pvs.MeshToSDF(Input=sphere, MaxDimension=24)
good = os.path.join(out, "good.lvdv")
pvs.SaveData(good, proxy=pvs.MeshToSDF(Input=sphere, MaxDimension=24))
check(os.path.exists(good), "the reference .lvdv is written")

missing = os.path.join(out, "missing.lvdv")
one_error("lvdv reader, missing file", lambda: pvs.LVDIFDictionaryVolumeReader(FileName=missing),
          "cannot open '%s'" % missing)
one_error("lvdv reader, no file name", lambda: pvs.LVDIFDictionaryVolumeReader(), "no file name")
missingp = os.path.join(out, "missing.lvdvp")
one_error("lvdvp reader, missing file", lambda: pvs.LVDIFParallelDictionaryVolumeReader(FileName=missingp),
              "'%s'" % missingp)
one_error("lvdvp reader, no file name", lambda: pvs.LVDIFParallelDictionaryVolumeReader(), "no file name")

# a reader pointed from a good file to a missing one shows nothing of the good one
reader = pvs.LVDIFDictionaryVolumeReader(FileName=good)
n_good = points(reader)
check(n_good > 0, "the good file reads (%d points)" % n_good)


def point_at_missing():
    reader.FileName = missing
    return reader


one_error("lvdv reader, good then missing file", point_at_missing, "cannot open")
check(points(reader) == 0, "no stale data after the failure (%d points)" % points(reader))

# the band and chunk edge rule, through the proxies
for label, props, needle in (
        ("Mesh To SDF, Band Width -1", {"BandWidth": -1}, "BandWidth must be a number of voxels >= 0 (0: no band), not -1"),
        ("Mesh To SDF, Band Width NaN", {"BandWidth": float("nan")}, "not nan"),
        ("Mesh To SDF, Chunk Edge 48", {"ChunkEdge": 48}, "chunk edge 48 must be a power of two in [4, 256]"),
        ("Mesh To SDF, Chunk Edge 512", {"ChunkEdge": 512}, "chunk edge 512 must be a power of two in [4, 256]")):
    one_error(label, lambda: pvs.MeshToSDF(Input=sphere, MaxDimension=24, **props), needle)
image = pvs.SparseVolumeToImage(Input=pvs.MeshToSDF(Input=sphere, MaxDimension=24))
one_error("Image To Sparse Volume, Band Width -2", lambda: pvs.ImageToSparseVolume(Input=image, BandWidth=-2),
          "BandWidth must be a number of voxels >= 0 (0: no band), not -2")
for cls, kw in (("MeshToSDF", {"Input": sphere, "MaxDimension": 24}), ("ImageToSparseVolume", {"Input": image}),
                ("VolumeEditFilter", {"Input": image})):
    for edge in (4, 256):
        f, errs = errors_during(lambda: updated(getattr(pvs, cls)(ChunkEdge=edge, BandWidth=0, **kw)))
        check(not errs and f.GetDataInformation().GetNumberOfPoints() > 0,
              "%s: Chunk Edge %d and Band Width 0 run: %s" % (cls, edge, errs))
# Band Width 0 = no band: the distances are not cut (the sphere's centre lies about 9 voxels deep)
deep = pvs.SparseVolumeToImage(Input=pvs.MeshToSDF(Input=sphere, MaxDimension=24, BandWidth=0))
deep.UpdatePipeline()
lo, hi = deep.PointData["sdf"].GetRange()
cut = pvs.SparseVolumeToImage(Input=pvs.MeshToSDF(Input=sphere, MaxDimension=24, BandWidth=1))
cut.UpdatePipeline()
clo, chi = cut.PointData["sdf"].GetRange()
check(lo < -5 and abs(clo + 1) < 0.01 and abs(chi - 1) < 0.01,
      "Band Width 0 keeps every distance (%g..%g), Band Width 1 cuts at 1 (%g..%g)" % (lo, hi, clo, chi))

# Padding and the writers' Compression Level have the same rule (refused by name, never clamped)
for label, props, needle in (
        ("Mesh To SDF, Padding -1", {"Padding": -1}, "Padding must be a finite number of voxels >= 0, not -1"),
        ("Mesh To SDF, Padding NaN", {"Padding": float("nan")}, "Padding must be a finite number of voxels >= 0, not nan"),
        # the fitted grid's error names the properties the user sees (it named Core's maxDim and padding)
        ("Mesh To SDF, Max Dimension 1", {"MaxDimension": 1}, "Max Dimension must be in [2, 1048576]"),
        ("Mesh To SDF, Sample Spacing -1", {"SampleSpacing": -1}, "Sample Spacing must be a finite length >= 0"),
        ("Mesh To SDF, Max Dimension 5, Padding 2", {"MaxDimension": 5, "Padding": 2},
         "Max Dimension 5 leaves no voxel for the mesh inside 2 voxels of Padding")):
    proxy = one_error(label, lambda: pvs.MeshToSDF(Input=sphere, **props), needle)
    _, errs = errors_during(lambda: updated(proxy))
    check(not any("maxDim" in e for e in errs), "%s: no internal name (%s)" % (label, errs))
for ext in ("lvdv", "lvdvp"):
    target = os.path.join(out, "level." + ext)
    with open(target, "wb") as f:
        f.write(b"an older file")  # kept: the refusal comes before any file is written
    for level in (0, 20):
        _, errs = errors_during(lambda: updated(pvs.CreateWriter(target, src_level, CompressionLevel=level)))
        check(len(errs) == 1 and "CompressionLevel must be a zstd level in [1, 19], not %d" % level in errs[0]
              and open(target, "rb").read() == b"an older file", "%s writer, Compression Level %d: %s" % (ext, level, errs))

# an enumeration set outside its menu (the server-manager property takes any integer):
# one error naming the property and its values, nothing clamped (Device 5 ran on CUDA)
def enum_out_of_range(make, name, value):
    def build():
        p = make()
        p.SMProxy.GetProperty(name).SetElement(0, value)
        p.SMProxy.UpdateVTKObjects()
        return p
    return build


for label, make, name, value, needle in (
        ("Sign Voxel Filter, Device 5", lambda: pvs.SignVoxelFilter(Input=src_level), "Device", 5,
         "Device must be 0 (auto), 1 (CPU) or 2 (CUDA), not 5"),
        ("Sign Voxel Filter, Boundary 2", lambda: pvs.SignVoxelFilter(Input=src_level), "Boundary", 2,
         "Boundary must be 0 (outside) or 1 (free), not 2"),
        ("Mesh To SDF, Sign Mode 9", lambda: pvs.MeshToSDF(Input=sphere, MaxDimension=24), "SignMode", 9,
         "SignMode must be 0 (normal), 1 (pseudo-normal), 2 (winding number) or 3 (unsigned), not 9")):
    proxy = one_error(label, enum_out_of_range(make, name, value), needle)
    check(proxy.GetDataInformation().GetNumberOfPoints() == 0, "%s: no output" % label)

# A reader that failed (a missing or malformed file) feeding two of our filters: its one
# error, nothing from the filters below. ParaView runs every proxy below a failed reader
# on its empty output, and each of our filters added an error of its own ("the input
# sparse volume holds no dictionary volume", "the input mesh has no points", ...); VTK's
# own filters give an empty output for an empty input without an error, and so do ours now.
malformed = os.path.join(out, "malformed.lvdv")
with open(malformed, "wb") as f:
    f.write(open(good, "rb").read()[:300])  # a truncated file: its header, no table
for label, make_reader, filters, needle in (
        ("missing .lvdv", lambda: pvs.LVDIFDictionaryVolumeReader(FileName=missing),
         ("SignVoxelFilter", "ChunkedMarchingCubes"), "cannot open '%s'" % missing),
        ("malformed .lvdv", lambda: pvs.LVDIFDictionaryVolumeReader(FileName=malformed),
         ("SignVoxelFilter", "SparseVolumeToImage"), "'%s'" % malformed),
        ("missing .lvdvp", lambda: pvs.LVDIFParallelDictionaryVolumeReader(FileName=missingp),
         ("VolumeEditFilter", "ChunkedMarchingCubes"), "'%s'" % missingp),
        ("missing mesh", lambda: pvs.LVDIFMeshReader(FileName=os.path.join(out, "missing.obj")),
         ("MeshToSDF", "SignVoxelFilter"), "missing.obj")):
    def build_and_apply():
        proxies = [make_reader()]
        for name in filters:
            proxies.append(getattr(pvs, name)(Input=proxies[-1]))
        for p in proxies:  # as the GUI's Apply: every proxy of the pipeline updated
            p.UpdatePipeline()
        return proxies
    proxies, got = errors_during(build_and_apply)
    check(len(got) == 1 and needle in got[0], "%s -> %s: one error with %s, got %d: %s" % (
        label, " -> ".join(filters), needle, len(got), got))
    check(all(p.GetDataInformation().GetNumberOfPoints() == 0 for p in proxies[1:]),
          "%s: the filters below give empty outputs" % label)
    # shown in a view (the representations update the last filter again): still nothing more
    view = pvs.CreateRenderView()
    _, got = errors_during(lambda: (pvs.Show(proxies[-1], view), pvs.Render(view)))
    check(not got, "%s: showing the last filter adds no error: %s" % (label, got))
    pvs.Delete(view)  # a live view at exit gives an X GLXBadContext error
    del view

# a writer into a folder that does not exist: one error naming it, nothing written
src = pvs.MeshToSDF(Input=sphere, MaxDimension=24)
for ext in ("lvdv", "lvdvp"):
    target = "/nonexistent-lvdif/dir/x." + ext
    _, errs = errors_during(lambda: updated(pvs.CreateWriter(target, src)))
    check(len(errs) == 1 and "cannot write '%s': the folder '/nonexistent-lvdif/dir' does not exist" % target in errs[0],
          "%s writer into a missing folder: %s" % (ext, errs))

finish()
