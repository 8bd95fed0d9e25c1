# pvpython benchmark: a mesh file -> Mesh To SDF with DEFAULT properties (only
# Max Dimension set), as a user of the plugin runs it. Prints one BENCH line:
#   BENCH read_s=.. sdf_s=.. dims=AxBxC band=.. sign=..
# Usage: pvpython --force-offscreen-rendering bench_mesh_to_sdf.py PLUGIN MESH N [BAND]
#   BAND: optional Band Width (e.g. 0 for the previous default, no band)
import lvdif_pvtest as T  # first: fixes sys.path for route B

import sys
import time

import paraview.simple as pvs

plugin, mesh, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
pvs.LoadPlugin(plugin, remote=False)
t0 = time.perf_counter()
reader = getattr(pvs, T.PROXY_NAMES["vtkLVDIFMeshReader"])(FileName=mesh)
reader.UpdatePipeline()
t1 = time.perf_counter()
sdf = pvs.MeshToSDF(Input=reader, MaxDimension=n)
if len(sys.argv) > 4:
    sdf.BandWidth = float(sys.argv[4])
sdf.UpdatePipeline()
t2 = time.perf_counter()
e = sdf.GetDataInformation().GetExtent()
print("BENCH read_s=%.2f sdf_s=%.2f dims=%dx%dx%d band=%g sign=%s" % (
    t1 - t0, t2 - t1, e[1] + 1, e[3] + 1, e[5] + 1, sdf.BandWidth, str(sdf.SignMode).replace(" ", "_")))
