# pvbatch test of Image To Sparse Volume under MPI, as a new user would use it:
# ParaView's Wavelet on a non-cubic grid (a non-zero whole extent, anisotropic
# spacing, an origin off zero), a Calculator making a float field that crosses
# zero, Image To Sparse Volume (chunk edge 8), then ParaView's Integrate
# Variables and Contour on the sparse volume. Until session 27 each rank made
# its volume from its own image piece, with its own chunk grid: Contour was
# right but Integrate Variables (the partitions' volume, their points' sums)
# differed from the serial run. Now every piece is a block of the whole grid's
# chunks (the .lvdv reader's rule) and all of it equals the serial run, also
# the .lvdvp the ranks write (each writes its piece) read back.
#
#   pvbatch mpi_image_to_sparse.py PLUGIN TMPDIR --reference            (1 rank: writes the reference)
#   mpirun -np 2|4 pvbatch mpi_image_to_sparse.py PLUGIN TMPDIR --compare
import lvdif_pvtest as T  # first: fixes sys.path for route B

import json
import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, tmpdir, mode = sys.argv[1], sys.argv[2], sys.argv[3]
check = T.check
nranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("ranks:", nranks)
T.load_plugin(plugin, ["vtkImageToSparseVolume"], remote=True)
ref_path = os.path.join(tmpdir, "mpi_image_to_sparse_reference.json")

wavelet = pvs.Wavelet(WholeExtent=[-7, 53, 4, 43, 10, 62])  # 61 x 40 x 53 points
calc = pvs.Calculator(Input=wavelet, ResultArrayName="sdf", Function="(RTData - 160) / 10",
                      ResultArrayType="Float")
sparse = pvs.ImageToSparseVolume(Input=calc)
sparse.ChunkEdge = 8


def integrate(proxy):
    """ParaView's Integrate Variables: the volume and the integral of sdf (reduced to rank 0)."""
    out = servermanager.Fetch(pvs.IntegrateVariables(Input=proxy))
    vol = out.GetCellData().GetArray("Volume").GetValue(0)
    s = out.GetPointData().GetArray("sdf").GetValue(0)
    return [vol, s]


facts = {
    "integrate": integrate(sparse),
    "contour": len(T.triangle_key_list(T.contour_surface(sparse))),
}
# written as .lvdvp by these ranks (the writer asks each rank for its piece) and read back
written = os.path.join(tmpdir, "mpi_image_to_sparse_np%d.lvdvp" % nranks)
pvs.SaveData(written, proxy=sparse)
facts["written"] = integrate(pvs.OpenDataFile(written))
print("facts:", facts)

if mode == "--reference":
    check(nranks == 1, "reference run is single-process")
    check(facts["integrate"][0] > 0 and facts["contour"] > 1000, "serial: volume %g, %d triangles" % (
        facts["integrate"][0], facts["contour"]))
    with open(ref_path, "w") as f:
        json.dump(facts, f)
else:
    with open(ref_path) as f:
        ref = json.load(f)
    vol, s = facts["integrate"]
    rvol, rs = ref["integrate"]
    check(abs(vol - rvol) <= 1e-9 * abs(rvol), "Integrate Variables' volume %r over %d ranks equals the serial %r" % (
        vol, nranks, rvol))
    check(abs(s - rs) <= 1e-6 * max(1.0, abs(rs)), "Integrate Variables' sdf %r over %d ranks equals the serial %r" % (
        s, nranks, rs))
    check(facts["written"] == ref["written"], "the .lvdvp %d ranks wrote reads back as the serial one: %s, %s" % (
        nranks, facts["written"], ref["written"]))
    check(facts["contour"] == ref["contour"], "%d Contour triangles equal the serial %d" % (
        facts["contour"], ref["contour"]))

for v in pvs.GetViews():
    pvs.Delete(v)
print("FAILURES: %d" % T.check.failures if T.check.failures else "ALL PASSED")
if T.check.failures:
    sys.exit(1)
