"""Shared code of the LVDIF pvpython / pvbatch tests. Import it FIRST.

Route B (docs/PARAVIEW.md): python3-paraview is unpacked in a private prefix,
and the interpreter would otherwise find python3-vtk9's `vtkmodules` (VTK 9.1)
first and crash. So ParaView's dist-packages goes to the front of sys.path;
/usr/lib/python3/dist-packages stays behind it (numpy, mpi4py).

The pipeline is mesh -> SDF -> sign voxel filter -> contour -> .lvdv write -> read.
Each LVDIF stage is used when its proxy is in the plugin (the plugin registers a
class's XML only once the class exists, and the tests are told which ones are
registered: they fail if a registered one is missing). A stage whose filter has
not landed yet uses a stand-in that is said so in the output:
  SDF      -> a ProgrammableSource evaluating the analytic sphere SDF (honours
              UPDATE_EXTENT, so it distributes like vtkMeshToSDF)
  SVF      -> skipped
  contour  -> ParaView's Contour (always computed too: it is the oracle for MC)
  write/read -> skipped
"""
import os
import sys

PV_PYTHONPATH = os.environ.get("LVDIF_PV_PYTHONPATH", "/opt/lvdif-pvshim/pvpy/usr/lib/python3/dist-packages")
sys.path = [PV_PYTHONPATH] + [p for p in sys.path if p != PV_PYTHONPATH]

import math  # noqa: E402

import paraview.simple as pvs  # noqa: E402
from paraview import servermanager  # noqa: E402
from lvdif_check import check  # noqa: E402,F401  (the tests call T.check)

# VTK class -> (proxy group, proxy name); in Python a filter or reader is
# paraview.simple.<name> (the XML label without spaces). Add a line here when a
# class's XML lands in Apps/ParaViewPlugin/XML/.
PROXIES = {
    "vtkMeshToSDF": ("filters", "MeshToSDF"),
    "vtkSignVoxelFilter": ("filters", "SignVoxelFilter"),
    "vtkChunkedMarchingCubes": ("filters", "ChunkedMarchingCubes"),
    "vtkDictionaryVolumeReader": ("sources", "LVDIFDictionaryVolumeReader"),
    "vtkDictionaryVolumeWriter": ("writers", "LVDIFDictionaryVolumeWriter"),
    "vtkPDictionaryVolumeReader": ("sources", "LVDIFParallelDictionaryVolumeReader"),
    "vtkLegacyBvReader": ("sources", "LVDIFLegacyBvReader"),
    "vtkXMLSparseVolumeReader": ("sources", "LVDIFSparseVolumeVTPDReader"),  # a saved sparse volume's .vtpd
    "vtkPDictionaryVolumeWriter": ("writers", "LVDIFParallelDictionaryVolumeWriter"),
    "vtkVolumeEditFilter": ("filters", "VolumeEditFilter"),
    "vtkLVDIFMeshReader": ("sources", "LVDIFMeshReader"),
    "vtkSparseVolumeToImage": ("filters", "SparseVolumeToImage"),
    "vtkImageToSparseVolume": ("filters", "ImageToSparseVolume"),
    # a representation (the Slice of LVDIFSparseVolumeRepresentation), not a filter
    "vtkSparseVolumeSliceRepresentation": ("representations", "LVDIFSparseVolumeSliceRepresentation"),
}
PROXY_NAMES = {cls: name for cls, (group, name) in PROXIES.items()}
LVD_EXTENSION = "lvdv"
PLVD_EXTENSION = "lvdvp"  # the distributed volume's index

# The test scene: a sphere of radius R centred in a cube grid of N^3 points.
RADIUS = 1.0
HALF = 1.25  # the grid covers [-HALF, HALF]^3
N = 48


def spacing():
    return 2.0 * HALF / (N - 1)


def load_plugin(path, expected_classes, remote):
    """Loads the plugin and checks that every registered class has its proxy."""
    pvs.LoadPlugin(path, remote=remote)  # adds the proxies to paraview.simple
    defs = servermanager.ProxyManager().SMProxyManager.GetProxyDefinitionManager()
    present = {cls: bool(defs.HasDefinition(group, name)) for cls, (group, name) in PROXIES.items()}
    for cls in expected_classes:
        if cls not in PROXIES:
            raise AssertionError("class %s has XML but no entry in lvdif_pvtest.PROXIES" % cls)
        if not present[cls]:
            raise AssertionError("plugin registered XML for %s but proxy %s is missing" % (cls, PROXY_NAMES[cls]))
    for cls, ok in present.items():
        print("stage %-28s %s" % (cls, "plugin proxy " + PROXY_NAMES[cls] if ok else "NOT IN PLUGIN (stand-in or skipped)"))
    return present


_SDF_INFO_SCRIPT = """
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm, vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.vtkCommonDataModel import vtkDataObject
info = self.GetOutputInformation(0)
info.Set(sddp.WHOLE_EXTENT(), 0, %(n1)d, 0, %(n1)d, 0, %(n1)d)
info.Set(vtkDataObject.ORIGIN(), %(o)r, %(o)r, %(o)r)
info.Set(vtkDataObject.SPACING(), %(h)r, %(h)r, %(h)r)
info.Set(vtkAlgorithm.CAN_PRODUCE_SUB_EXTENT(), 1)
"""

_SDF_SCRIPT = """
import numpy as np
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.util.numpy_support import numpy_to_vtk
info = self.GetOutputInformation(0)
e = info.Get(sddp.UPDATE_EXTENT())
out = self.GetOutput()
out.SetExtent(e)
out.SetOrigin(%(o)r, %(o)r, %(o)r)
out.SetSpacing(%(h)r, %(h)r, %(h)r)
z, y, x = np.meshgrid(*[np.arange(e[2 * a], e[2 * a + 1] + 1) * %(h)r + %(o)r for a in (2, 1, 0)], indexing='ij')
d = ((np.sqrt(x * x + y * y + z * z) - %(r)r) / %(h)r).astype(np.float32).ravel()
a = numpy_to_vtk(d, deep=1)
a.SetName('sdf')
out.GetPointData().SetScalars(a)
"""


def dense(proxy):
    """The explicit dense conversion of a sparse dictionary volume (the .lvdv
    reader's and Mesh To SDF's output) for the stages that read voxels."""
    return pvs.SparseVolumeToImage(Input=proxy)


def sdf_stage(present, sparse=False):
    """mesh -> SDF (image with float point array `sdf`, voxel units, negative inside);
    with sparse=True Mesh To SDF's own output, the sparse volume."""
    h = spacing()
    if present["vtkMeshToSDF"]:
        mesh = pvs.Sphere(Radius=RADIUS, ThetaResolution=128, PhiResolution=128)
        sdf = getattr(pvs, PROXY_NAMES["vtkMeshToSDF"])(Input=mesh)
        configure_mesh_to_sdf(sdf, h)
        if sparse:
            return sdf, "vtkMeshToSDF (sparse volume)"
        # the stages below corrupt and compare voxels: they take the dense image
        return dense(sdf), "vtkMeshToSDF (sparse volume) -> SparseVolumeToImage"
    p = {"n1": N - 1, "o": -HALF, "h": h, "r": RADIUS}
    src = pvs.ProgrammableSource(OutputDataSetType="vtkImageData")
    src.ScriptRequestInformation = _SDF_INFO_SCRIPT % p
    src.Script = _SDF_SCRIPT % p
    return src, "stand-in: analytic sphere SDF (ProgrammableSource)"


def configure_mesh_to_sdf(proxy, h):
    """The test scene's grid, explicitly (the same points as the stand-in)."""
    proxy.UseExplicitGrid = 1
    proxy.Dimensions = [N, N, N]
    proxy.Origin = [-HALF, -HALF, -HALF]
    proxy.Spacing = [h, h, h]
    proxy.SignMode = "Winding Number"


_CORRUPT_SCRIPT = """
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk
inp = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
out.ShallowCopy(inp)
e = inp.GetExtent()
d = vtk_to_numpy(inp.GetPointData().GetArray('sdf')).copy()
k, j, i = np.meshgrid(*[np.arange(e[2 * a], e[2 * a + 1] + 1) for a in (2, 1, 0)], indexing='ij')
hit = ((i * 7 + j * 13 + k * 29) %% %(period)d == 0).ravel() & (np.abs(d) > %(far)r)
lo, hi = %(slab_lo)r, %(slab_hi)r
if lo is not None:
    hit |= ((i >= lo[0]) & (i <= hi[0]) & (j >= lo[1]) & (j <= hi[1]) & (k >= lo[2]) & (k <= hi[2])).ravel() & (d < -%(far)r)
d[hit] = -d[hit]
a = numpy_to_vtk(d, deep=1)
a.SetName('sdf')
out.GetPointData().SetScalars(a)
"""


def corrupt_signs(source, period=97, far=4.0, slab=None):
    """Flips the sign of isolated voxels far (|d| > far) from the surface, on a
    fixed lattice pattern: the wrong signs a sign voxel filter must repair.
    slab=((i0, j0, k0), (i1, j1, k1)) also makes the inside voxels of that box
    (d < -far) positive: a wrong region that can cross the pieces' cuts."""
    f = pvs.ProgrammableFilter(Input=source, OutputDataSetType="vtkImageData")
    f.Script = _CORRUPT_SCRIPT % {"period": period, "far": far,
                                  "slab_lo": slab[0] if slab else None, "slab_hi": slab[1] if slab else None}
    return f


def sign_voxel_stage(source):
    svf = getattr(pvs, PROXY_NAMES["vtkSignVoxelFilter"])(Input=source)
    svf.Scalars = ["POINTS", "sdf"]
    return svf


def is_sparse(proxy):
    """True when the proxy's output is a partitioned dataset (the sparse volume)."""
    return proxy.GetDataInformation().GetCompositeDataClassName() is not None


def as_image(proxy):
    """The proxy itself for an image, its explicit dense conversion for the sparse volume."""
    return dense(proxy) if is_sparse(proxy) else proxy


def contour_surface(proxy):
    """ParaView's Contour at 0 of an image or of the sparse volume's partitions, as one polydata."""
    c = pvs.Contour(Input=proxy, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0, ComputeScalars=0)
    if is_sparse(proxy):
        c = pvs.ExtractSurface(Input=pvs.MergeBlocks(Input=c))
    return servermanager.Fetch(c)


def inside_count(proxy):
    """Voxels with sdf < 0 of a (single-process) image or sparse volume proxy."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    img = servermanager.Fetch(as_image(proxy))
    return int((vtk_to_numpy(img.GetPointData().GetArray("sdf")) < 0).sum())


def contour(source, present):
    """Returns (ParaView Contour proxy, LVDIF MC proxy or None)."""
    c = pvs.Contour(Input=source, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0,
                    ComputeScalars=0, ComputeGradients=0)
    mc = None
    if present["vtkChunkedMarchingCubes"]:
        mc = getattr(pvs, PROXY_NAMES["vtkChunkedMarchingCubes"])(Input=source)
        mc.Scalars = ["POINTS", "sdf"]
        mc.OutputMode = "Merged"  # one polydata per rank (the comparisons want triangles)
        mc.IsoValue = 0.0
    return c, mc


def area(proxy):
    iv = pvs.IntegrateVariables(Input=proxy)
    d = servermanager.Fetch(iv)
    return d.GetCellData().GetArray("Area").GetValue(0)


def sphere_area():
    return 4.0 * math.pi * RADIUS * RADIUS


def triangle_key_list(polydata, digits=5):
    """Every triangle as a tuple of rounded vertex coordinates, rotated so the
    smallest vertex comes first (orientation kept), sorted: two meshes with the
    same triangles give equal lists whatever their point numbering or piece.
    Cells flagged DUPLICATECELL in vtkGhostType are skipped: they are copies of
    a neighbour piece's triangles, made when a consumer asked for ghost levels
    (ParaView's parallel writer does), and belong to that neighbour."""
    pts = polydata.GetPoints()
    tris = []
    ids = polydata.GetPolys()
    ghosts = polydata.GetCellData().GetArray("vtkGhostType")
    if polydata.GetNumberOfVerts() or polydata.GetNumberOfLines() or polydata.GetNumberOfStrips():
        raise AssertionError("surface has cells other than polygons")
    from vtkmodules.vtkCommonCore import vtkIdList
    idl = vtkIdList()
    ids.InitTraversal()
    cell = -1
    while ids.GetNextCell(idl):
        cell += 1
        if ghosts is not None and int(ghosts.GetValue(cell)) & 1:  # vtkDataSetAttributes::DUPLICATECELL
            continue
        if idl.GetNumberOfIds() != 3:
            raise AssertionError("non-triangle cell with %d points" % idl.GetNumberOfIds())
        v = [tuple(round(c, digits) for c in pts.GetPoint(idl.GetId(i))) for i in range(3)]
        k = v.index(min(v))
        tris.append(tuple(v[k:] + v[:k]))
    tris.sort()
    return tris


def write_read_stage(field, path, check):
    """SaveData picks our writer by extension, OpenDataFile our reader; the
    read field must equal the written one within the SDF dictionary's
    quantisation (Core/Volume/include/lvdif/SdfDictionary.h: step 0.001 up to |d| 4,
    0.1 beyond, saturated at the band, 8 voxels by default)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    if os.path.exists(path):
        os.remove(path)
    pvs.SaveData(path, proxy=field)
    check(os.path.exists(path) and os.path.getsize(path) > 0, "SaveData wrote %s (%d bytes)" % (
        path, os.path.getsize(path) if os.path.exists(path) else 0))
    reader = pvs.OpenDataFile(path)
    check(reader is not None and reader.GetXMLName() == PROXY_NAMES["vtkDictionaryVolumeReader"],
          "OpenDataFile chose %s" % (reader.GetXMLName() if reader is not None else None))
    a = vtk_to_numpy(servermanager.Fetch(as_image(field)).GetPointData().GetArray("sdf")).astype(np.float64)
    img = servermanager.Fetch(dense(reader))
    b = vtk_to_numpy(img.GetPointData().GetArray("sdf")).astype(np.float64)
    check(a.shape == b.shape, "read back %d voxels, wrote %d" % (b.size, a.size))
    if a.shape != b.shape:
        return reader
    near, mid, far = np.abs(a) <= 4.0, (np.abs(a) > 4.2) & (np.abs(a) < 7.9), np.abs(a) >= 8.0
    check(np.abs(a - b)[near].max() <= 0.0006, "|d| <= 4: max error %.5f (<= 0.0005 + float)" % np.abs(a - b)[near].max())
    check(np.abs(a - b)[mid].max() <= 0.051, "4.2 < |d| < 7.9: max error %.4f (<= 0.05)" % np.abs(a - b)[mid].max())
    check(bool(np.all(np.sign(b[far]) == np.sign(a[far]))) and np.abs(np.abs(b[far]) - 8.0).max() < 0.051,
          "beyond the band: sign kept, |d| saturated to 8")
    return reader


def _session():
    return servermanager.ActiveConnection.Session


def check_reader_hints(check, path=None):
    """The reader is in the Open dialog: the reader factory lists *.lvdv and,
    for a written file, picks our reader."""
    rf = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    types = rf.GetSupportedFileTypes(_session())
    check("*.%s" % LVD_EXTENSION in types, "Open dialog lists *.%s (%s)" % (
        LVD_EXTENSION, [t for t in types.split(";;") if "LVDIF" in t]))
    if path:
        ok = rf.CanReadFile(path, _session())
        check(bool(ok) and rf.GetReaderName() == PROXY_NAMES["vtkDictionaryVolumeReader"],
              "reader factory picks %s for %s" % (rf.GetReaderName() if ok else None, os.path.basename(path)))


def check_writer_hints(source, check):
    """The writer is in the Save Data dialog for image data."""
    wf = servermanager.vtkSMProxyManager.GetProxyManager().GetWriterFactory()
    types = wf.GetSupportedFileTypes(source.SMProxy, 0)
    check("*.%s" % LVD_EXTENSION in types, "Save dialog lists *.%s for image data (%s)" % (
        LVD_EXTENSION, [t for t in types.split(";;") if "LVDIF" in t]))
    w = wf.CreateWriter("x." + LVD_EXTENSION, source.SMProxy, 0)
    check(w is not None and w.GetXMLName() == PROXY_NAMES["vtkDictionaryVolumeWriter"],
          "writer factory creates %s for .%s" % (w.GetXMLName() if w is not None else None, LVD_EXTENSION))


def closed_volume(polydata):
    """Volume enclosed by a closed, consistently oriented triangle surface
    (divergence theorem: sum of signed tetrahedra against the origin)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pts = vtk_to_numpy(polydata.GetPoints().GetData()).astype(np.float64)
    conn = vtk_to_numpy(polydata.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    a, b, c = pts[conn[:, 0]], pts[conn[:, 1]], pts[conn[:, 2]]
    return abs(float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0)


def lens_volume(R, r, d):
    """Volume of the intersection of two balls of radii R and r whose centres are d apart (0 < d < R + r)."""
    if d >= R + r:
        return 0.0
    if d <= abs(R - r):
        return 4.0 / 3.0 * math.pi * min(R, r) ** 3
    return math.pi * (R + r - d) ** 2 * (d * d + 2 * d * r - 3 * r * r + 2 * d * R + 6 * r * R - 3 * R * R) / (12 * d)


def edit_stage(field, check):
    """The editing filter: a script subtracts a ball of radius r (voxels) centred
    on the sphere's surface; oracle: the analytic volume 4/3 pi R^3 minus the lens
    of the two balls. The default script (comments only) must change nothing."""
    h = spacing()
    c = 0.5 * (N - 1)  # the sphere's centre in voxel indices
    r_vox = 8.0
    ed = getattr(pvs, PROXY_NAMES["vtkVolumeEditFilter"])(Input=field)
    default_script = ed.Script
    check(default_script.lstrip().startswith("#") and "sphere" in default_script,
          "Volume Edit Filter's default script is a commented example")
    v_field = closed_volume(contour_surface(field))
    v_pass = closed_volume(contour_surface(ed))
    check(abs(v_pass - v_field) / v_field < 0.002, "default script passes the volume through: %.5f vs %.5f" % (v_pass, v_field))
    ed.Script = "# cut a ball on the sphere's +x pole\nop subtract\nsphere %r, %r, %r, %r\n" % (c + RADIUS / h, c, c, r_vox)
    ed.BandWidth = 8.0
    v_edit = closed_volume(contour_surface(ed))
    r_world = r_vox * h
    lens = lens_volume(RADIUS, r_world, RADIUS)
    v_ref = 4.0 / 3.0 * math.pi * RADIUS ** 3 - lens
    check(abs(v_edit - v_ref) / v_ref < 0.01, "edited volume %.5f vs analytic %.5f (sphere minus lens)" % (v_edit, v_ref))
    removed = v_field - v_edit
    check(abs(removed - lens) / lens < 0.05, "removed volume %.5f vs analytic lens %.5f" % (removed, lens))
    rgba = ed.PointData["rgba"] if "rgba" in ed.PointData.keys() else None
    check(rgba is not None, "Volume Edit Filter outputs rgba (With Color on)")
    return ed


_CUBE_OFF = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n" \
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"
_CUBE_OBJ = "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0 0 2\nv 2 0 2\nv 2 2 2\nv 0 2 2\n" \
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"


def mesh_reader_stage(tmpdir, check):
    """The validating mesh reader: a unit cube (OFF) and a cube of edge 2 (OBJ),
    quads fanned to 12 triangles; oracles: the analytic area and volume. The
    Open dialog lists it under its own description, distinct from ParaView's
    OBJ/STL/PLY readers; for .off (no ParaView reader) the factory picks it."""
    name = PROXY_NAMES["vtkLVDIFMeshReader"]
    for fname, text, edge in (("cube.off", _CUBE_OFF, 1.0), ("cube.obj", _CUBE_OBJ, 2.0)):
        path = os.path.join(tmpdir, fname)
        with open(path, "w") as f:
            f.write(text)
        rd = getattr(pvs, name)(FileName=path)
        pd = servermanager.Fetch(rd)
        check(pd.GetNumberOfPolys() == 12, "%s: %d triangles (12)" % (fname, pd.GetNumberOfPolys()))
        a = area(rd)
        check(abs(a - 6 * edge * edge) < 1e-5, "%s: area %.6f vs %.1f" % (fname, a, 6 * edge * edge))
        v = closed_volume(pd)
        check(abs(v - edge ** 3) < 1e-5, "%s: volume %.6f vs %.1f" % (fname, v, edge ** 3))
    rf = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    types = rf.GetSupportedFileTypes(_session())
    ours = [t for t in types.split(";;") if t.startswith("LVDIF Mesh Reader")]
    check(len(ours) == 1 and all("*.%s" % e in ours[0] for e in ("obj", "off", "stl", "ply")),
          "Open dialog lists the LVDIF mesh reader under its own name: %s" % ours)
    ok = rf.CanReadFile(os.path.join(tmpdir, "cube.off"), _session())
    check(bool(ok) and rf.GetReaderName() == name, "reader factory picks %s for .off" % (rf.GetReaderName() if ok else None))


def check_parallel_io_hints(source, check, path=None):
    """The distributed writer and reader in the Save/Open dialogs (.lvdvp)."""
    wf = servermanager.vtkSMProxyManager.GetProxyManager().GetWriterFactory()
    types = wf.GetSupportedFileTypes(source.SMProxy, 0)
    check("*.%s" % PLVD_EXTENSION in types, "Save dialog lists *.%s (%s)" % (
        PLVD_EXTENSION, [t for t in types.split(";;") if "LVDIF" in t]))
    w = wf.CreateWriter("x." + PLVD_EXTENSION, source.SMProxy, 0)
    check(w is not None and w.GetXMLName() == PROXY_NAMES["vtkPDictionaryVolumeWriter"],
          "writer factory creates %s for .%s" % (w.GetXMLName() if w is not None else None, PLVD_EXTENSION))
    if path:
        rf = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
        ok = rf.CanReadFile(path, _session())
        check(bool(ok) and rf.GetReaderName() == PROXY_NAMES["vtkPDictionaryVolumeReader"],
              "reader factory picks %s for %s" % (rf.GetReaderName() if ok else None, os.path.basename(path)))


def same_volume(a_img, b_img):
    """(equal, message): same extent, origin, spacing and exactly the same sdf and rgba values."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    if tuple(a_img.GetExtent()) != tuple(b_img.GetExtent()):
        # the serial .lvdv reader gives 0-based extents: compare shapes and world positions instead
        da, db = a_img.GetDimensions(), b_img.GetDimensions()
        if da != db:
            return False, "dimensions %s vs %s" % (da, db)
    pa = [a_img.GetPoint(0), a_img.GetPoint(a_img.GetNumberOfPoints() - 1)]
    pb = [b_img.GetPoint(0), b_img.GetPoint(b_img.GetNumberOfPoints() - 1)]
    if max(abs(x - y) for p, q in zip(pa, pb) for x, y in zip(p, q)) > 1e-9:
        return False, "corners %s vs %s" % (pa, pb)
    for name in ("sdf", "rgba"):
        x, y = a_img.GetPointData().GetArray(name), b_img.GetPointData().GetArray(name)
        if (x is None) != (y is None):
            return False, "array %s in one volume only" % name
        if x is not None and not np.array_equal(vtk_to_numpy(x), vtk_to_numpy(y)):
            return False, "array %s differs at %d values" % (name, int((vtk_to_numpy(x) != vtk_to_numpy(y)).sum()))
    return True, "%d points, sdf and rgba identical" % a_img.GetNumberOfPoints()
