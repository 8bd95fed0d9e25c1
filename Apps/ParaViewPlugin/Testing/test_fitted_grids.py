# pvpython test: Mesh To SDF -> Sign Voxel Filter -> Chunked Marching Cubes with
# DEFAULT properties (only Max Dimension set, for time; Band Width 0 in two cases,
# as in the report) on grids fitted to elongated meshes (non-cubic), built both
# as the GUI does (each filter updated, as Apply does, before the next is made:
# then ParaView fills domain defaults from the data) and as a script does
# (chained without any update). Oracle: ParaView's own Contour (iso value 0) of
# the same filtered image. Checks for every mesh and flow: the fitted grid is not
# cubic, the iso value is 0, the surface is closed and manifold (0 boundary and
# 0 non-manifold edges), it has the Contour's triangles, area and bounds, it lies
# on the input mesh (bounds within a voxel), and the sdf ranges ParaView reports
# are those of the values. Also: the defaults agree with `lvdif mesh-to-sdf`, the
# first display is an outline (image) or a surface (mesh), never a volume, and
# Mesh To SDF and the .lvdv reader warn before a large dense image.
#
# Usage: pvpython --force-offscreen-rendering test_fitted_grids.py PLUGIN [MESH_DIR]
#   MESH_DIR: optional folder with cow.off, elephant.off, bunny00.off
#   (scripts/extract-meshes.sh puts them in Data/extracted; they are never
#   committed); the generated meshes are always tested.
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys
import tempfile

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkFeatureEdges

plugin = sys.argv[1]
mesh_dir = sys.argv[2] if len(sys.argv) > 2 else None
T.load_plugin(plugin, ["vtkMeshToSDF", "vtkSignVoxelFilter", "vtkChunkedMarchingCubes", "vtkLVDIFMeshReader"],
              remote=False)
check = T.check

# `lvdif mesh-to-sdf` defaults (Apps/CLI/CommandMeshToSdf.cxx): --dims 128
# --padding 2 --band 8 --sign winding, no SVF.
CLI_DEFAULTS = {"MaxDimension": 128, "Padding": 2.0, "BandWidth": 8.0, "SignMode": "Winding Number"}


def open_edges(polydata):
    """(boundary edges, non-manifold edges) of a triangle surface, points as they are (no merging)."""
    counts = []
    for boundary in (1, 0):
        fe = vtkFeatureEdges()
        fe.SetInputData(polydata)
        fe.SetBoundaryEdges(boundary)
        fe.SetNonManifoldEdges(1 - boundary)
        fe.SetFeatureEdges(0)
        fe.SetManifoldEdges(0)
        fe.Update()
        counts.append(fe.GetOutput().GetNumberOfLines())
    return tuple(counts)


def generated_meshes():
    """Elongated closed meshes made by ParaView's own sources (name, proxy, MaxDimension, Band Width or None)."""
    ell = pvs.Transform(Input=pvs.Sphere(Radius=1.0, ThetaResolution=96, PhiResolution=64))
    ell.Transform.Scale = [3.0, 1.0, 0.6]
    box = pvs.Box(XLength=4.0, YLength=1.3, ZLength=0.7, Center=[0.3, -0.2, 0.1])
    torus = pvs.Superquadric(Toroidal=1, Thickness=0.35, ThetaResolution=96, PhiResolution=48,
                             ThetaRoundness=1.0, PhiRoundness=1.0)
    torus_t = pvs.Transform(Input=torus)
    torus_t.Transform.Scale = [2.0, 1.0, 1.0]
    torus_t.Transform.Rotate = [0.0, 0.0, 20.0]
    # Band Width 0 (exact distances far out, as in the report of the open surface): a lopsided range
    return [("ellipsoid 3:1:0.6", ell, 96, None), ("box 4:1.3:0.7", box, 80, None),
            ("torus 2:1, rotated", torus_t, 96, None), ("ellipsoid 3:1:0.6, band 0", ell, 96, 0.0)]


def file_meshes():
    out = []
    if not mesh_dir:
        return out
    for name, dims, band in (("cow.off", 64, None), ("cow.off", 64, 0.0), ("elephant.off", 96, None),
                             ("bunny00.off", 128, None)):
        path = os.path.join(mesh_dir, name)
        if os.path.exists(path):
            reader = getattr(pvs, T.PROXY_NAMES["vtkLVDIFMeshReader"])(FileName=path)
            out.append((name if band is None else "%s, band %g" % (name, band), reader, dims, band))
        else:
            print("skip %s (not in %s; scripts/extract-meshes.sh)" % (name, mesh_dir))
    return out


first = True
# Two ways to build the chain: as the GUI does (each filter updated by Apply before the next
# is made, so ParaView fills domain defaults from its data), and as a script does (no update
# in between; the domains then have no data). The open surface came from the first.
for mesh_name, mesh, dims, band in generated_meshes() + file_meshes():
    for flow in ("Apply", "chained"):
        name = "%s, %s" % (mesh_name, flow)
        sdf = pvs.MeshToSDF(Input=mesh)
        if first:
            for prop, value in CLI_DEFAULTS.items():
                got = getattr(sdf, prop)
                check(got == value, "Mesh To SDF default %s = %r (lvdif mesh-to-sdf: %r)" % (prop, got, value))
        if dims is not None:
            sdf.MaxDimension = dims
        if band is not None:
            sdf.BandWidth = band
        if flow == "Apply":
            sdf.UpdatePipeline()
        svf = pvs.SignVoxelFilter(Input=sdf)
        if flow == "Apply":
            svf.UpdatePipeline()
        mc = pvs.ChunkedMarchingCubes(Input=svf)
        check(mc.IsoValue == 0.0, "%s: Chunked Marching Cubes' default iso value is 0 (the SDF's zero set), is %r"
              % (name, mc.IsoValue))
        surface = servermanager.Fetch(mc)
        img_info = sdf.GetDataInformation()
        ext = img_info.GetExtent()
        pts = [ext[2 * a + 1] - ext[2 * a] + 1 for a in range(3)]
        check(len(set(pts)) > 1, "%s: fitted grid %s is not cubic" % (name, "x".join(map(str, pts))))
        # the filters pass the sparse volume; the oracle contours its explicit dense image
        spacing = servermanager.Fetch(pvs.SparseVolumeToImage(Input=sdf)).GetSpacing()
        dense = pvs.SparseVolumeToImage(Input=svf)
        oracle = pvs.Contour(Input=dense, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0,
                             ComputeScalars=0, ComputeGradients=0)
        ref = servermanager.Fetch(oracle)
        b_mc, n_mc = open_edges(surface)
        b_ref, n_ref = open_edges(ref)
        check(b_ref == 0 and n_ref == 0, "%s: oracle Contour is closed and manifold (%d boundary, %d non-manifold edges)"
              % (name, b_ref, n_ref))
        check(b_mc == 0 and n_mc == 0, "%s: Chunked Marching Cubes is closed and manifold (%d boundary, %d non-manifold edges)"
              % (name, b_mc, n_mc))
        check(surface.GetNumberOfCells() == ref.GetNumberOfCells(), "%s: %d triangles, Contour %d"
              % (name, surface.GetNumberOfCells(), ref.GetNumberOfCells()))
        a_mc, a_ref = T.area(mc), T.area(oracle)
        check(abs(a_mc - a_ref) <= 1e-5 * a_ref, "%s: area %.6f, Contour %.6f" % (name, a_mc, a_ref))
        bm, br = surface.GetBounds(), ref.GetBounds()
        diag = sum((br[2 * a + 1] - br[2 * a]) ** 2 for a in range(3)) ** 0.5
        check(max(abs(x - y) for x, y in zip(bm, br)) <= 1e-5 * diag, "%s: bounds %s, Contour %s"
              % (name, ["%.4f" % v for v in bm], ["%.4f" % v for v in br]))
        # the sdf ranges ParaView shows (the filters store them) are those of the values
        for p, what in ((sdf, "Mesh To SDF"), (svf, "Sign Voxel Filter")):
            shown = p.PointData["sdf"].GetRange()
            vals = vtk_to_numpy(servermanager.Fetch(pvs.SparseVolumeToImage(Input=p)).GetPointData().GetArray("sdf"))
            check(shown == (float(vals.min()), float(vals.max())), "%s: %s's sdf range %s, values %s"
                  % (name, what, shown, (float(vals.min()), float(vals.max()))))
        # the surface lies on the mesh: bounds within one voxel of the input's
        mb = servermanager.Fetch(mesh).GetBounds()
        off = max(abs(bm[i] - mb[i]) / spacing[i // 2] for i in range(6))
        check(off <= 1.0, "%s: surface bounds within %.2f voxels of the mesh's" % (name, off))

        if first:
            # first display: the image as an outline, the surface as a surface
            view = pvs.CreateRenderView()
            d_img = pvs.Show(sdf, view)
            d_mc = pvs.Show(mc, view)
            check(d_img.Representation == "Outline", "Mesh To SDF shows as %s (Outline expected)" % d_img.Representation)
            check(d_mc.Representation == "Surface", "Chunked Marching Cubes shows as %s (Surface expected)"
                  % d_mc.Representation)
            pvs.Delete(d_img)
            pvs.Delete(d_mc)
            pvs.Delete(view)
            del view
            first = False
        for p in (oracle, mc, svf, sdf):
            pvs.Delete(p)


def repaired_range():
    """Sign Voxel Filter flips signs in its copy of the array and stores the new
    range: the range ParaView reports must be that of its output values, not the
    one of its (corrupted) input, whose range ParaView computed first.
    Box 0.7 thick at Max Dimension 80: at most about 6.6 voxels deep and 3.9 out,
    so flipping far voxels (|d| > 4) changes the range."""
    box = pvs.Box(XLength=4.0, YLength=1.3, ZLength=0.7)
    sdf = pvs.MeshToSDF(Input=box, MaxDimension=80)
    bad = T.corrupt_signs(sdf)
    bad.UpdatePipeline()
    bad_range = bad.PointData["sdf"].GetRange()  # ParaView computes and caches it on the input
    svf = pvs.SignVoxelFilter(Input=bad)
    shown = svf.PointData["sdf"].GetRange()
    vals = vtk_to_numpy(servermanager.Fetch(pvs.SparseVolumeToImage(Input=svf)).GetPointData().GetArray("sdf"))
    clean = sdf.PointData["sdf"].GetRange()
    check(bad_range != clean, "corruption changes the range: clean %s, corrupted %s" % (clean, bad_range))
    check(shown == (float(vals.min()), float(vals.max())) == clean,
          "repaired range %s = values %s = clean %s" % (shown, (float(vals.min()), float(vals.max())), clean))
    for p in (svf, bad, sdf, box):
        pvs.Delete(p)


repaired_range()


def memory_messages(make, limit):
    """Updates the proxy make() returns under LVDIF_MEMORY_LIMIT=limit; returns
    (warnings, errors) its VTK object reported."""
    os.environ["LVDIF_MEMORY_LIMIT"] = limit
    try:
        proxy = make()
        got = {"WarningEvent": [], "ErrorEvent": []}

        def keep(kind):
            @calldata_type(VTK_STRING)  # the message comes as the call data
            def cb(obj, ev, calldata):
                # the text after "vtkMeshToSDF (0x...): " (the "ERROR:" prefix would fail the ctest)
                got[kind].append(str(calldata).split("): ", 1)[-1].strip())
            return cb
        algo = proxy.GetClientSideObject()  # builtin session: the VTK object itself
        for event in got:
            algo.AddObserver(event, keep(event))
        algo.GetExecutive().AddObserver("ErrorEvent", lambda *a: None)  # its "returned failure" echo
        proxy.UpdatePipeline()
        pvs.Delete(proxy)
        return got["WarningEvent"], got["ErrorEvent"]
    finally:
        del os.environ["LVDIF_MEMORY_LIMIT"]


def sphere_sdf():
    """Mesh To SDF of a sphere at Max Dimension 128: 128^3 points, 8 MiB of floats."""
    return pvs.MeshToSDF(Input=pvs.Sphere(ThetaResolution=32, PhiResolution=32), MaxDimension=128)


# a large dense image is announced before it is allocated, with its size ...
warnings, errors = memory_messages(sphere_sdf, "12M")
check(len(warnings) == 1 and "needs 8.00 MiB (memory limit 12.00 MiB" in warnings[0] and not errors,
      "Mesh To SDF warns before a large allocation: %s %s" % (warnings, errors))
# ... and refused above the limit, with one clear error
warnings, errors = memory_messages(sphere_sdf, "4M")
check(len(errors) >= 1 and "sdf array" in errors[0], "Mesh To SDF refuses above the memory limit: %s" % errors[:1])
# small images say nothing
warnings, errors = memory_messages(sphere_sdf, "1G")
check(not warnings and not errors, "no message for a small image: %s %s" % (warnings, errors))
# the .lvdv reader decodes into a dense image too (sdf and rgba: 8 bytes a point, 16 MiB here)
lvdv = os.path.join(tempfile.mkdtemp(), "sphere.lvdv")
written = sphere_sdf()
pvs.SaveData(lvdv, proxy=written)
pvs.Delete(written)
warnings, errors = memory_messages(lambda: pvs.OpenDataFile(lvdv), "24M")
check(len(warnings) == 1 and "needs 16.00 MiB (memory limit 24.00 MiB" in warnings[0] and not errors,
      "the .lvdv reader warns before a large allocation: %s %s" % (warnings, errors))

print("failures:", check.failures)
sys.exit(1 if check.failures else 0)
