# pvpython test of the LVDIF plugin: load it, run mesh -> SDF -> SVF -> contour
# -> .lvdv write -> read, check numbers against independent oracles, compare a
# rendering with a baseline, and check the reader/writer dialog hints.
# Usage: pvpython --force-offscreen-rendering test_plugin.py PLUGIN BASELINE.png TMPDIR [vtkClass ...]
#   (the classes are those whose XML the plugin registered; see CMakeLists.txt)
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, baseline, tmpdir = sys.argv[1:4]
expected = sys.argv[4:]
present = T.load_plugin(plugin, expected, remote=False)
check = T.check

# --- mesh -> SDF: the sparse volume travels through every stage below; voxels are
# read and corrupted through its explicit dense conversion (T.as_image)
sdf, how = T.sdf_stage(present, sparse=True)
print("SDF stage:", how)
sdf.UpdatePipeline()
img = T.as_image(sdf)
img.UpdatePipeline()
info = img.GetDataInformation()
check(info.GetNumberOfPoints() == T.N ** 3, "SDF grid has %d^3 points (%d)" % (T.N, info.GetNumberOfPoints()))
rng = sdf.PointData["sdf"].GetRange()
h = T.spacing()
# Oracle: the analytic SDF of the sphere in voxel units has min -R/h (centre)
# and max at the corners (sqrt(3)*HALF - R)/h; band-limited filters clamp it.
check(rng[0] < 0 < rng[1], "sdf changes sign (range %s)" % (rng,))

# --- sign voxel filter
field = sdf
if present["vtkSignVoxelFilter"]:
    # Oracle: isolated far voxels get a wrong sign; the filter must give back
    # exactly the inside set of the clean field.
    clean_inside = T.inside_count(sdf)
    bad = T.corrupt_signs(T.as_image(sdf))
    bad_inside = T.inside_count(bad)
    check(bad_inside != clean_inside, "corruption moved the inside count by %d" % (bad_inside - clean_inside))
    if T.is_sparse(sdf):
        bad = pvs.ImageToSparseVolume(Input=bad)  # the sign filter takes the sparse volume
    field = T.sign_voxel_stage(bad)
    check(T.is_sparse(field) == T.is_sparse(sdf), "Sign Voxel Filter's output is %s"
          % ("the sparse volume" if T.is_sparse(field) else "an image"))
    fixed_inside = T.inside_count(field)
    check(fixed_inside == clean_inside, "Sign Voxel Filter restores the inside set: %d voxels vs %d clean (%d corrupted)"
          % (fixed_inside, clean_inside, bad_inside))
else:
    print("SVF stage: skipped (vtkSignVoxelFilter not in the plugin)")

# --- the editing filter (script -> analytic volume)
if present["vtkVolumeEditFilter"]:
    T.edit_stage(field, check)
else:
    print("edit stage: skipped (vtkVolumeEditFilter not in the plugin)")

# --- the validating mesh reader
if present["vtkLVDIFMeshReader"]:
    T.mesh_reader_stage(tmpdir, check)
else:
    print("mesh reader stage: skipped (vtkLVDIFMeshReader not in the plugin)")

# --- contour: ParaView's Contour is the oracle of the LVDIF marching cubes
c, mc = T.contour(field, present)
a_pv = T.area(c)
a_ref = T.sphere_area()
check(abs(a_pv - a_ref) / a_ref < 0.015, "Contour area %.5f vs analytic 4 pi R^2 = %.5f" % (a_pv, a_ref))
surface = c
if mc is not None:
    a_mc = T.area(mc)
    check(abs(a_mc - a_pv) / a_pv < 0.002, "ChunkedMarchingCubes area %.5f vs ParaView Contour %.5f" % (a_mc, a_pv))
    surface = mc
else:
    print("MC stage: ParaView Contour only (vtkChunkedMarchingCubes not in the plugin)")

# --- write .lvdv -> read
lvd = os.path.join(tmpdir, "test_plugin." + T.LVD_EXTENSION)
if present["vtkDictionaryVolumeWriter"] and present["vtkDictionaryVolumeReader"]:
    reader = T.write_read_stage(field, lvd, check)
    # the surface of the read volume is the same sphere
    check(T.is_sparse(reader), "the .lvdv reader gives the sparse volume")
    a_rd = T.area(pvs.Contour(Input=reader, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0,
                              ComputeScalars=0))
    check(abs(a_rd - a_pv) / a_pv < 0.002, "Contour area after write/read %.5f vs before %.5f" % (a_rd, a_pv))
else:
    print("write/read stage: skipped (reader/writer not in the plugin)")

# --- distributed volume (.lvdvp) written by one process: index + one piece; equals the .lvdv read
plvd = os.path.join(tmpdir, "test_plugin." + T.PLVD_EXTENSION)
if present["vtkPDictionaryVolumeWriter"] and present["vtkPDictionaryVolumeReader"] and os.path.exists(lvd):
    for old in (plvd, os.path.join(tmpdir, "test_plugin_0.lvdv")):
        if os.path.exists(old):
            os.remove(old)
    pvs.SaveData(plvd, proxy=field)
    check(os.path.exists(plvd) and os.path.exists(os.path.join(tmpdir, "test_plugin_0.lvdv")),
          "SaveData wrote the index %s and its piece" % os.path.basename(plvd))
    preader = pvs.OpenDataFile(plvd)
    check(preader is not None and preader.GetXMLName() == T.PROXY_NAMES["vtkPDictionaryVolumeReader"],
          "OpenDataFile chose %s" % (preader.GetXMLName() if preader is not None else None))
    check(T.is_sparse(preader), "the .lvdvp reader gives the sparse volume")
    same, why = T.same_volume(servermanager.Fetch(T.dense(preader)), servermanager.Fetch(T.dense(pvs.OpenDataFile(lvd))))
    check(same, ".lvdvp read equals the .lvdv read: " + why)
    T.check_parallel_io_hints(field, check, plvd)
else:
    print("distributed volume stage: skipped (parallel reader/writer not in the plugin)")

# --- reader/writer in ParaView's open/save dialogs
if present["vtkDictionaryVolumeReader"]:
    T.check_reader_hints(check, lvd if os.path.exists(lvd) else None)
if present["vtkDictionaryVolumeWriter"]:
    T.check_writer_hints(field, check)

# --- rendering vs baseline
view = pvs.CreateRenderView()
view.ViewSize = [400, 400]
view.OrientationAxesVisibility = 0
view.Background = [0.32, 0.34, 0.43]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
d = pvs.Show(surface, view)
d.DiffuseColor = [0.9, 0.6, 0.3]
view.CameraPosition = [3.0, 2.0, 4.0]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 0
view.ResetCamera()
pvs.Render(view)
from paraview.vtk.test import Testing as VTKTesting  # noqa: E402
if not os.path.exists(baseline):
    out = os.path.join(tmpdir, os.path.basename(baseline))
    pvs.SaveScreenshot(out, view, ImageResolution=[400, 400])
    check(False, "baseline %s missing; wrote %s (inspect it and copy it there)" % (baseline, out))
else:
    try:
        VTKTesting.compareImage(view.GetRenderWindow(), baseline, threshold=0.15)
        check(True, "image matches %s" % baseline)
    except Exception as e:  # compareImage raises on mismatch
        pvs.SaveScreenshot(os.path.join(tmpdir, "test_plugin_failed.png"), view, ImageResolution=[400, 400])
        check(False, "image differs from %s: %s" % (baseline, e))

print("failures:", check.failures)
pvs.Delete(d)
pvs.Delete(view)  # a live view at exit gives an X_GLXMakeCurrent error
del view
sys.exit(1 if check.failures else 0)
