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

# VTK class -> (proxy group, proxy name); in Python a filter or reader is
# paraview.simple.<name> (the XML label without spaces). Add a line here when a
# class's XML lands in Apps/ParaViewPlugin/XML/.
PROXIES = {
    "vtkMeshToSDF": ("filters", "MeshToSDF"),
    "vtkSignVoxelFilter": ("filters", "SignVoxelFilter"),
    "vtkChunkedMarchingCubes": ("filters", "ChunkedMarchingCubes"),
    "vtkDictionaryVolumeReader": ("sources", "LVDIFDictionaryVolumeReader"),
    "vtkDictionaryVolumeWriter": ("writers", "LVDIFDictionaryVolumeWriter"),
}
PROXY_NAMES = {cls: name for cls, (group, name) in PROXIES.items()}
LVD_EXTENSION = "lvdv"

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


def sdf_stage(present):
    """mesh -> SDF (image with float point array `sdf`, voxel units, negative inside)."""
    h = spacing()
    if present["vtkMeshToSDF"]:
        mesh = pvs.Sphere(Radius=RADIUS, ThetaResolution=128, PhiResolution=128)
        sdf = getattr(pvs, PROXY_NAMES["vtkMeshToSDF"])(Input=mesh)
        configure_mesh_to_sdf(sdf, h)
        return sdf, "vtkMeshToSDF"
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
d[hit] = -d[hit]
a = numpy_to_vtk(d, deep=1)
a.SetName('sdf')
out.GetPointData().SetScalars(a)
"""


def corrupt_signs(source, period=97, far=4.0):
    """Flips the sign of isolated voxels far (|d| > far) from the surface, on a
    fixed lattice pattern: the wrong signs a sign voxel filter must repair."""
    f = pvs.ProgrammableFilter(Input=source, OutputDataSetType="vtkImageData")
    f.Script = _CORRUPT_SCRIPT % {"period": period, "far": far}
    return f


def sign_voxel_stage(source):
    svf = getattr(pvs, PROXY_NAMES["vtkSignVoxelFilter"])(Input=source)
    svf.Scalars = ["POINTS", "sdf"]
    return svf


def inside_count(proxy):
    """Voxels with sdf < 0 of a (single-process) image proxy."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    img = servermanager.Fetch(proxy)
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


def check(cond, msg):
    print(("PASS " if cond else "FAIL ") + msg)
    if not cond:
        check.failures += 1


check.failures = 0


def write_read_stage(field, path, check):
    """SaveData picks our writer by extension, OpenDataFile our reader; the
    read field must equal the written one within the SDF dictionary's
    quantisation (Core/include/lvdif/SdfDictionary.h: step 0.001 up to |d| 4,
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
    a = vtk_to_numpy(servermanager.Fetch(field).GetPointData().GetArray("sdf")).astype(np.float64)
    img = servermanager.Fetch(reader)
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
