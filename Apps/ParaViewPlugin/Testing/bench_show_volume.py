# pvpython benchmark: open a .lvdv (the sparse volume) and show it with the
# default representation (an outline), as a user does; prints the times and what
# ParaView's data information reports. Peak RSS: run under /usr/bin/time -v
# (scripts/bench-paraview-show.sh).
# Usage: pvpython --force-offscreen-rendering bench_show_volume.py PLUGIN FILE.lvdv
import lvdif_pvtest as T  # first: fixes sys.path for route B

import resource
import sys
import time


def rss():
    """(current, peak) resident memory in MiB."""
    with open("/proc/self/statm") as f:
        cur = int(f.read().split()[1]) * resource.getpagesize() / 2 ** 20
    return "%.0f MiB now, %.0f MiB peak" % (cur, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)


import paraview.simple as pvs

T.load_plugin(sys.argv[1], [], remote=False)
print("plugin loaded:", rss())
t0 = time.time()
reader = pvs.OpenDataFile(sys.argv[2])
reader.UpdatePipeline()
t1 = time.time()
print("read (UpdatePipeline, with ParaView's data information):", rss())
view = pvs.CreateRenderView()
view.ViewSize = [400, 400]
display = pvs.Show(reader, view)
pvs.Render(view)
t2 = time.time()
print("shown and rendered:", rss())
info = reader.GetDataInformation()
print("read %.2f s, show + render %.2f s; representation %s" % (t1 - t0, t2 - t1, display.Representation))
print("data information: %d points, %d cells, %d partitions, bounds %s, sdf range %s, memory %d KiB" % (
    info.GetNumberOfPoints(), info.GetNumberOfCells(), info.DataInformation.GetNumberOfDataSets(),
    info.GetBounds(), reader.PointData["sdf"].GetRange() if "sdf" in reader.PointData.keys() else None,
    info.GetMemorySize()))
pvs.Delete(display)
pvs.Delete(view)
del view
