# pvbatch test of the sign voxel filters on the SPARSE volume under MPI: each
# rank filters only its chunk layers along the filter axis (docs/PARAVIEW.md,
# "The sign voxel filters on pieces of chunks"), and the results equal the
# serial ones exactly.
#
#   pvbatch mpi_sparse_svf.py PLUGIN TMPDIR --reference            (1 rank: writes the reference)
#   mpirun -np 2|4 pvbatch mpi_sparse_svf.py PLUGIN TMPDIR --compare
#
# The input: Mesh To SDF of a sphere (48^3, chunk edge 8: 6 chunk layers per
# axis) with wrong signs (isolated far voxels and a box of them crossing the
# ranks' cuts), made sparse again (Image To Sparse Volume). The 1-rank run
# writes it as .lvdv. Two inputs for the filter (axis Z with all four
# filters, so SVF1's rows are cut by the ranks' layers; and axis X with SVF2 to
# SVF4 only, whose planes and SVF4's ghost planes then do the repair):
#   "pipeline": the corrupted volume computed on every rank;
#   "reader":   the .lvdv read by every rank: a rank loads only the chunks of
#               its layers plus one ghost plane on each side.
# For each: Chunked Marching Cubes (each rank meshes its block) and ParaView's
# Contour (a generic filter: each rank contours the block of chunks the
# filter hands it) must give exactly the serial triangles, every rank must
# contribute, and the field data `svf_piece` of each rank (fetched through a
# programmable filter) must show the rank's own planes, the layers split
# without gap or overlap, and for the reader fewer loaded chunks than the file
# holds; the filters' flip counts are the serial ones.
import lvdif_pvtest as T  # first: fixes sys.path for route B

import builtins
import json
import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, tmpdir, mode = sys.argv[1], sys.argv[2], sys.argv[3]
check = T.check
nranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks:", nranks)
classes = ["vtkMeshToSDF", "vtkSignVoxelFilter", "vtkChunkedMarchingCubes", "vtkDictionaryVolumeReader",
           "vtkDictionaryVolumeWriter", "vtkSparseVolumeToImage", "vtkImageToSparseVolume"]
present = T.load_plugin(plugin, classes, remote=True)
EDGE = 8
lvd = os.path.join(tmpdir, "mpi_sparse_svf_input.lvdv")
ref_path = os.path.join(tmpdir, "mpi_sparse_svf_reference.json")

# the corrupted sparse input, as every rank computes it
mesh = pvs.Sphere(Radius=T.RADIUS, ThetaResolution=128, PhiResolution=128)
sdf = getattr(pvs, T.PROXY_NAMES["vtkMeshToSDF"])(Input=mesh)
T.configure_mesh_to_sdf(sdf, T.spacing())
sdf.ChunkEdge = EDGE
SLAB = ((T.N * 3 // 8, T.N * 3 // 8, T.N * 5 // 24), (T.N * 5 // 8, T.N * 5 // 8, T.N * 19 // 24))
bad = T.corrupt_signs(T.dense(sdf), slab=SLAB)
sparse = getattr(pvs, T.PROXY_NAMES["vtkImageToSparseVolume"])(Input=bad)
sparse.ChunkEdge = EDGE

if mode == "--reference":
    check(nranks == 1, "reference run is single-process")
    if os.path.exists(lvd):
        os.remove(lvd)
    pvs.SaveData(lvd, proxy=sparse)
    check(os.path.exists(lvd), "the corrupted input written as %s" % os.path.basename(lvd))

PIECE_SCRIPT = """
from vtkmodules.vtkCommonCore import vtkPoints, vtkIdTypeArray
inp = self.GetInputDataObject(0, 0)
a = inp.GetFieldData().GetArray('svf_piece')
f = inp.GetFieldData().GetArray('svf_flips')
out = self.GetPolyDataOutput()
pts = vtkPoints()
pts.InsertNextPoint(0, 0, 0)
out.SetPoints(pts)
for name, src in (('svf_piece', a), ('svf_flips', f)):
    arr = vtkIdTypeArray()
    arr.SetName(name)
    arr.SetNumberOfComponents(src.GetNumberOfTuples() if src else 1)
    arr.InsertNextTuple([src.GetValue(i) for i in range(src.GetNumberOfTuples())] if src else [-1])
    out.GetPointData().AddArray(arr)
"""


def run(volume_proxy, axis, label):
    """Sign Voxel Filter -> (Chunked Marching Cubes, Contour); returns the facts to compare.
    (Names such as source, sum, max are avoided: ParaView's programmable filters
    import numpy_interface.algorithms into the script's namespace.)"""
    svf = T.sign_voxel_stage(volume_proxy)
    svf.Axis = axis
    if axis == "X":
        svf.SVF1RowScan = 0  # SVF2-SVF4 alone: their planes and SVF4's ghost planes do the work
    mc = getattr(pvs, T.PROXY_NAMES["vtkChunkedMarchingCubes"])(Input=svf)
    mc.OutputMode = "Merged"
    mc.IsoValue = 0.0
    mc_tris = T.triangle_key_list(servermanager.Fetch(mc))
    mc_pids = servermanager.Fetch(pvs.ProcessIdScalars(Input=mc)).GetPointData().GetArray("ProcessId").GetRange()
    c = pvs.ExtractSurface(Input=pvs.MergeBlocks(Input=pvs.Contour(
        Input=svf, ContourBy=["POINTS", "sdf"], Isosurfaces=[0.0], ComputeNormals=0, ComputeScalars=0,
        ComputeGradients=0)))
    c_tris = T.triangle_key_list(servermanager.Fetch(c))
    c_pids = servermanager.Fetch(pvs.ProcessIdScalars(Input=c)).GetPointData().GetArray("ProcessId").GetRange()
    pf = pvs.ProgrammableFilter(Input=svf, OutputDataSetType="vtkPolyData")
    pf.Script = PIECE_SCRIPT
    facts = servermanager.Fetch(pf)
    pieces = sorted(tuple(int(facts.GetPointData().GetArray("svf_piece").GetComponent(i, k)) for k in range(6))
                    for i in range(facts.GetNumberOfPoints()))
    flips = tuple(int(facts.GetPointData().GetArray("svf_flips").GetComponent(0, k)) for k in range(4))
    print("%s, axis %s: %d MC triangles (ranks %s), %d Contour triangles (ranks %s), flips %s" % (
        label, axis, len(mc_tris), mc_pids, len(c_tris), c_pids, flips))
    for p in pieces:
        print("   rank %d of %d: planes %d..%d, input %d expanded chunks, output %d" % p)
    return {"mc": mc_tris, "contour": c_tris, "mc_pids": list(mc_pids), "c_pids": list(c_pids), "pieces": pieces,
            "flips": flips}


results = {}
for axis in ("Z", "X"):
    results["pipeline " + axis] = run(sparse, axis, "pipeline")
# one reader per filter: a sparse volume is composite data, whose producer the
# executive re-runs for a new piece but not for a new extent of the same piece
for axis in ("Z", "X"):
    reader = getattr(pvs, T.PROXY_NAMES["vtkDictionaryVolumeReader"])(FileName=lvd)
    results["reader " + axis] = run(reader, axis, "reader")

if mode == "--reference":
    for key, r in results.items():
        check(len(r["mc"]) > 1000 and len(set(r["mc"])) == len(r["mc"]), "%s: serial surface, %d distinct triangles" % (
            key, len(r["mc"])))
        check(builtins.sum(r["flips"]) > 100, "%s: the filters flipped %d voxels" % (key, builtins.sum(r["flips"])))
    check(results["pipeline Z"]["mc"] == results["reader Z"]["mc"], "the read input filters like the computed one")
    with open(ref_path, "w") as f:
        json.dump({k: {"mc": r["mc"], "contour": r["contour"], "flips": r["flips"]} for k, r in results.items()}, f)
else:
    with open(ref_path) as f:
        ref = json.load(f)
    layers = (T.N + EDGE - 1) // EDGE
    for key, r in results.items():
        want = ref[key]
        as_tris = lambda ts: [tuple(tuple(v) for v in t) for t in ts]  # noqa: E731
        check(r["mc"] == as_tris(want["mc"]), "%s: %d Chunked Marching Cubes triangles from %d ranks equal the serial %d" % (
            key, len(r["mc"]), nranks, len(want["mc"])))
        check(r["contour"] == as_tris(want["contour"]), "%s: %d Contour triangles equal the serial %d" % (
            key, len(r["contour"]), len(want["contour"])))
        check(r["mc_pids"] == [0.0, nranks - 1.0] and r["c_pids"] == [0.0, nranks - 1.0],
              "%s: every rank made triangles (%s, %s)" % (key, r["mc_pids"], r["c_pids"]))
        check(list(r["flips"]) == list(want["flips"]), "%s: flips %s equal the serial %s" % (key, r["flips"], want["flips"]))
        pieces = r["pieces"]
        check(len(pieces) == nranks and [p[0] for p in pieces] == list(range(nranks)) and builtins.all(
            p[1] == nranks for p in pieces), "%s: one svf_piece per rank" % key)
        spans = sorted((p[2], p[3]) for p in pieces if p[3] >= p[2])
        tiled = spans[0][0] == 0 and spans[-1][1] == T.N - 1 and builtins.all(
            a[1] + 1 == b[0] for a, b in zip(spans, spans[1:])) and builtins.all(s[0] % EDGE == 0 for s in spans)
        check(tiled and len(spans) == builtins.min(nranks, layers), "%s: the ranks' planes tile 0..%d in chunk layers: %s" % (
            key, T.N - 1, spans))
        if key.startswith("reader"):
            loaded = [p[4] for p in pieces]
            most = builtins.max(loaded)
            # a rank's layers plus the ghost layers hold fewer chunks than the whole file
            whole = results["pipeline " + key.split()[1]]["pieces"][0][4]
            check(most < whole, "%s: every rank loaded fewer expanded chunks than the file's %d: %s" % (key, whole, loaded))

for v in pvs.GetViews():
    pvs.Delete(v)
print("FAILURES: %d" % T.check.failures if T.check.failures else "ALL PASSED")
if T.check.failures:
    sys.exit(1)
