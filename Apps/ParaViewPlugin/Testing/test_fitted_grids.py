# pvpython test: Mesh To SDF -> Sign Voxel Filter -> Chunked Marching Cubes with
# DEFAULT properties (only Max Dimension set, for time; Band Width 0 in two cases,
# as in the report) on grids fitted to elongated meshes (non-cubic), built both
# as the GUI does (each filter updated, as Apply does, before the next is made:
# then ParaView fills domain defaults from the data) and as a script does
# (chained without any update). The filters pass the sparse volume
# (vtkSparseDictionaryVolume). Oracle: ParaView's own Contour (iso value 0) of the
# explicit dense image of the same filtered volume (Sparse Volume To Image).
# Checks for every mesh and flow: the fitted grid is not cubic, the iso value is
# 0, the surface is closed and manifold (0 boundary and 0 non-manifold edges), it
# has exactly the Contour's triangles (plus the zero-area ones at grid points of
# distance exactly 0, which Contour drops), area and bounds, Contour on the
# sparse volume's own partitions gives the dense image's triangles, the surface
# lies on the input mesh (bounds within a voxel), and the sdf ranges ParaView
# reports are those of the values. Also: the defaults agree with `lvdif
# mesh-to-sdf`, the first display is an outline (volume) or a surface (mesh),
# never a volume rendering, the sparse producers allocate no dense image and the
# explicit dense conversion warns before a large one and refuses above the limit.
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


def split_degenerate(triangles):
    """(triangles with three distinct rounded vertices, the others)."""
    good = [t for t in triangles if len(set(t)) == 3]
    return good, [t for t in triangles if len(set(t)) < 3]


def unpaired_triangles(a, b, tol):
    """Triangles of a (or b) without a partner in the other whose vertices are each within tol."""
    import numpy as np
    left, right = list(a), list(b)
    unpaired = 0
    for t in left:
        p = np.array(t)
        match = [i for i, u in enumerate(right)
                 if all(np.abs(np.array(u) - v).max(axis=1).min() <= tol for v in p)]
        if match:
            right.pop(match[0])
        else:
            unpaired += 1
    return unpaired + len(right)


def zero_points(image, digits=5):
    """Positions (rounded as triangle_key_list rounds) of the grid points whose sdf is exactly 0."""
    import numpy as np
    v = vtk_to_numpy(image.GetPointData().GetArray("sdf"))
    return {tuple(round(c, digits) for c in image.GetPoint(int(i))) for i in np.flatnonzero(v == 0)}


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
        # the filters pass the sparse volume; the oracle contours its explicit dense image
        dense_img = servermanager.Fetch(pvs.SparseVolumeToImage(Input=svf))
        spacing = dense_img.GetSpacing()
        pts = list(dense_img.GetDimensions())
        check(len(set(pts)) > 1, "%s: fitted grid %s is not cubic" % (name, "x".join(map(str, pts))))
        dense = pvs.SparseVolumeToImage(Input=svf)
        oracle = pvs.Contour(Input=dense, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0,
                             ComputeScalars=0, ComputeGradients=0)
        ref = servermanager.Fetch(oracle)
        # ParaView's Contour on the sparse object itself (its image partitions), merged into one polydata
        on_parts = pvs.ExtractSurface(Input=pvs.MergeBlocks(Input=pvs.Contour(Input=svf, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0],
                                                     ComputeNormals=0, ComputeScalars=0, ComputeGradients=0)))
        parts = servermanager.Fetch(on_parts)
        b_mc, n_mc = open_edges(surface)
        b_ref, n_ref = open_edges(ref)
        check(b_ref == 0 and n_ref == 0, "%s: oracle Contour is closed and manifold (%d boundary, %d non-manifold edges)"
              % (name, b_ref, n_ref))
        check(b_mc == 0 and n_mc == 0, "%s: Chunked Marching Cubes is closed and manifold (%d boundary, %d non-manifold edges)"
              % (name, b_mc, n_mc))
        # the same surface: the same triangles (vertices to 1e-5, orientation kept); where a voxel's
        # decoded distance is exactly 0, marching cubes also keeps the zero-area triangles that meet
        # at that grid point (Contour drops them): they must be exactly those
        t_ref = T.triangle_key_list(ref)
        check(T.triangle_key_list(parts) == t_ref, "%s: Contour on the sparse volume's partitions = Contour on its "
              "dense image (%d triangles)" % (name, len(t_ref)))
        t_mc, degenerate = split_degenerate(T.triangle_key_list(surface))
        # marching cubes orients its triangles counter-clockwise seen from outside (the sdf's
        # negative side is inside), VTK's Contour the other way: compare with Contour's reversed
        t_rev = sorted((t[0], t[2], t[1]) for t in t_ref)
        zeros = zero_points(dense_img)
        # keys rounded to 1e-5 split a vertex that the two compute a few ulps apart across a
        # rounding boundary (bunny: z = -0.1336050034 and -0.1336049885): such triangles must
        # pair up within the rounding step plus a thousandth of a voxel
        only_mc, only_ref = set(t_mc) - set(t_rev), set(t_rev) - set(t_mc)
        unpaired = unpaired_triangles(only_mc, only_ref, 1e-5 + 1e-3 * min(spacing))
        check(len(t_mc) == len(t_rev) and unpaired == 0,
              "%s: Chunked Marching Cubes has Contour's %d triangles, reversed (%d; %d differ in the 5th digit, "
              "%d of them unpaired)" % (name, len(t_ref), len(t_mc), len(only_mc), unpaired))
        at_zero = all(any(v in zeros for v in t) for t in degenerate)
        check(at_zero, "%s: its %d further triangles have zero area, at grid points of distance 0 (%d such points)"
              % (name, len(degenerate), len(zeros)))
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
        for p in (on_parts, oracle, dense, mc, svf, sdf):
            pvs.Delete(p)


def repaired_range():
    """Sign Voxel Filter flips signs in its copy of the array and stores the new
    range: the range ParaView reports must be that of its output values, not the
    one of its (corrupted) input, whose range ParaView computed first.
    Box 0.7 thick at Max Dimension 80: at most about 6.6 voxels deep and 3.9 out,
    so flipping far voxels (|d| > 4) changes the range."""
    box = pvs.Box(XLength=4.0, YLength=1.3, ZLength=0.7)
    sdf = pvs.MeshToSDF(Input=box, MaxDimension=80)
    # corrupted voxels: the programmable filter needs the dense image; the sign filter gets it sparse again
    bad_img = T.corrupt_signs(T.dense(sdf))
    bad = pvs.ImageToSparseVolume(Input=bad_img)
    bad.UpdatePipeline()
    bad_range = bad.PointData["sdf"].GetRange()  # ParaView computes and caches it on the input
    svf = pvs.SignVoxelFilter(Input=bad)
    shown = svf.PointData["sdf"].GetRange()
    vals = vtk_to_numpy(servermanager.Fetch(pvs.SparseVolumeToImage(Input=svf)).GetPointData().GetArray("sdf"))
    clean = sdf.PointData["sdf"].GetRange()
    check(bad_range != clean, "corruption changes the range: clean %s, corrupted %s" % (clean, bad_range))
    check(shown == (float(vals.min()), float(vals.max())) == clean,
          "repaired range %s = values %s = clean %s" % (shown, (float(vals.min()), float(vals.max())), clean))
    for p in (svf, bad, bad_img, sdf, box):
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
    """Mesh To SDF of a sphere at Max Dimension 128: a sparse volume of 128^3 points."""
    return pvs.MeshToSDF(Input=pvs.Sphere(ThetaResolution=32, PhiResolution=32), MaxDimension=128)


def sphere_dense():
    """Its explicit dense image: float sdf + rgba, 8 bytes a point, 16 MiB."""
    return pvs.SparseVolumeToImage(Input=sphere_sdf())


# the sparse producers allocate no dense image: nothing to announce under a 12 MiB limit
warnings, errors = memory_messages(sphere_sdf, "12M")
check(not warnings and not errors, "Mesh To SDF (sparse) says nothing under a 12 MiB limit: %s %s" % (warnings, errors))
# the explicit dense conversion announces a large image before it allocates it, with its size ...
warnings, errors = memory_messages(sphere_dense, "24M")
check(len(warnings) == 1 and "needs 16.00 MiB (memory limit 24.00 MiB" in warnings[0] and not errors,
      "Sparse Volume To Image warns before a large allocation: %s %s" % (warnings, errors))
# ... and refuses above the limit, with one clear error
warnings, errors = memory_messages(sphere_dense, "12M")
check(len(errors) >= 1 and "dense image of 128 x 128 x 128 points" in errors[0],
      "Sparse Volume To Image refuses above the memory limit: %s" % errors[:1])
# small images say nothing
warnings, errors = memory_messages(sphere_dense, "1G")
check(not warnings and not errors, "no message for a small image: %s %s" % (warnings, errors))
# the .lvdv reader gives the sparse volume: no dense image, no message, even under a small limit
lvdv = os.path.join(tempfile.mkdtemp(), "sphere.lvdv")
written = sphere_sdf()
pvs.SaveData(lvdv, proxy=written)
pvs.Delete(written)
warnings, errors = memory_messages(lambda: pvs.OpenDataFile(lvdv), "12M")
check(not warnings and not errors, "the .lvdv reader (sparse) says nothing under a 12 MiB limit: %s %s" % (warnings, errors))

print("failures:", check.failures)
sys.exit(1 if check.failures else 0)
