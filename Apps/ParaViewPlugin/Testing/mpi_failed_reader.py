"""pvbatch on N ranks: a reader of a missing .lvdv feeding the distributed Sign
Voxel Filter and Chunked Marching Cubes. Every rank reports the reader's one
error and nothing else: the filters treat the empty input as VTK's own filters
do (an empty output, no error); the sign filter's ranks agree that all of them
are empty (one all-reduce) and none waits for another. Before, each filter below
the reader added an error of its own on every rank.
Usage: mpi_failed_reader.py PLUGIN TMPDIR"""
import lvdif_pvtest  # noqa: F401  (first: ParaView's Python on sys.path)

import os
import sys

import paraview.simple as pvs
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from lvdif_check import check

plugin, tmp = sys.argv[1], sys.argv[2]
pvs.LoadPlugin(plugin, remote=True, ns=globals())
rank = servermanager.vtkProcessModule.GetProcessModule().GetPartitionId()
window = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(window)
sys.stdout, sys.stderr = sys.__stdout__, sys.__stderr__

missing = os.path.join(tmp, "mpi_failed_reader_missing.lvdv")
reader = LVDIFDictionaryVolumeReader(FileName=missing)  # noqa: F821 (LoadPlugin's ns)
svf = SignVoxelFilter(Input=reader)  # noqa: F821
mc = ChunkedMarchingCubes(Input=svf)  # noqa: F821
for proxy in (reader, svf, mc):  # as the GUI's Apply: every proxy updated
    proxy.UpdatePipeline()
text = window.GetOutput()
errors = [" ".join(m.split())[:300] for m in text.split("ERROR: In ")[1:] if "returned failure for request" not in m]
check(len(errors) == 1 and "cannot open '%s'" % missing in errors[0],
      "rank %d: the reader's one error, got %d: %s" % (rank, len(errors), errors))
check(mc.GetDataInformation().GetNumberOfPoints() == 0, "rank %d: an empty surface" % rank)
print("rank %d: %d failed checks" % (rank, check.failures), flush=True)
if check.failures:  # (no sys.exit on success: pvbatch finalizes MPI after the script)
    sys.exit(1)
