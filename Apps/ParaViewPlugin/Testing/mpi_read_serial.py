# pvpython, one process: the .lvdvp written by NP ranks (paraview.mpi.npNP)
# read serially equals the serial pipeline's volume (the .lvdv the 1-rank
# reference run wrote with the serial writer): same points, identical sdf and
# rgba. Also: the index lists NP pieces.
# Usage: pvpython --force-offscreen-rendering mpi_read_serial.py PLUGIN TMPDIR NP [classes]
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import sys

import paraview.simple as pvs
from paraview import servermanager

plugin, tmpdir, np_ = sys.argv[1], sys.argv[2], int(sys.argv[3])
present = T.load_plugin(plugin, [a for a in sys.argv[4:] if a.startswith("vtk")], remote=False)
check = T.check
if present["vtkPDictionaryVolumeReader"] and present["vtkDictionaryVolumeReader"]:
    index = os.path.join(tmpdir, "mpi_volume_np%d.%s" % (np_, T.PLVD_EXTENSION))
    serial = os.path.join(tmpdir, "mpi_volume_N%d.%s" % (T.N, T.LVD_EXTENSION))
    with open(index) as f:
        listed = [line for line in f if line.startswith("piece ")]
    check(len(listed) == np_, "%s lists %d pieces (%d)" % (os.path.basename(index), len(listed), np_))
    rd = pvs.OpenDataFile(index)
    check(T.is_sparse(rd), "the .lvdvp reader gives the sparse volume")
    a = servermanager.Fetch(T.dense(rd))
    b = servermanager.Fetch(T.dense(getattr(pvs, T.PROXY_NAMES["vtkDictionaryVolumeReader"])(FileName=serial)))
    same, why = T.same_volume(a, b)
    check(same, "serial read of the %d-rank .lvdvp equals the serial pipeline's .lvdv: %s" % (np_, why))
else:
    print("skipped: the parallel reader is not in the plugin")
print("failures:", check.failures)
sys.exit(1 if check.failures else 0)
