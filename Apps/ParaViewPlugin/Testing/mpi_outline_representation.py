# The Outline of the sparse volume under pvbatch pieces (run with --symmetric: every rank
# checks its own part). ParaView's outline of a distributed image draws the whole
# extent's box on piece 0 and nothing elsewhere (vtkPVGeometryFilter::ImageDataExecute);
# vtkSparseVolumeOutlineRepresentation does the same. Oracle: the bounds of the dense image
# of the same volume, written by the serial test_outline_representation.py with the .lvdv.
#
# Usage: mpiexec -np N pvbatch --symmetric --force-offscreen-rendering mpi_outline_representation.py PLUGIN TMPDIR
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, tmpdir = sys.argv[1], sys.argv[2]
T.load_plugin(plugin, ["vtkDictionaryVolumeReader"], remote=True)
check = T.check
pm = servermanager.vtkProcessModule.GetProcessModule()
rank, ranks = pm.GetPartitionId(), pm.GetNumberOfLocalPartitions()
with open(os.path.join(tmpdir, "outline_rep_bounds.txt")) as f:
    bounds = [float(x) for x in f.read().split()]
reader = pvs.OpenDataFile(os.path.join(tmpdir, "outline_rep.lvdv"))
view = pvs.CreateRenderView()
display = pvs.Show(reader, view)
pvs.Render(view)
rep = display.GetClientSideObject().GetActiveRepresentation()
check(rep.GetClassName() == "vtkSparseVolumeOutlineRepresentation" and display.Representation == "Outline",
      "rank %d/%d: first display %s by %s" % (rank, ranks, display.Representation, rep.GetClassName()))
data = rep.GetRenderedDataObject(0)
it = data.NewIterator()
it.InitTraversal()
points = lines = 0
got = None
while not it.IsDoneWithTraversal():
    leaf = it.GetCurrentDataObject()
    points += leaf.GetNumberOfPoints()
    lines += leaf.GetNumberOfLines()
    if leaf.GetNumberOfPoints():
        got = leaf.GetBounds()
    it.GoToNextItem()
if rank == 0:
    check(points == 8 and lines == 12 and got is not None
          and all(abs(got[i] - bounds[i]) <= 1e-9 * max(1.0, abs(bounds[i])) for i in range(6)),
          "rank 0/%d: the whole volume's box: %d points, %d lines, bounds %s (dense image: %s)"
          % (ranks, points, lines, got, bounds))
else:
    check(points == 0 and lines == 0, "rank %d/%d: nothing drawn (%d points, %d lines)" % (rank, ranks, points, lines))
print("rank %d failures: %d" % (rank, check.failures))
if check.failures:
    sys.exit(1)
