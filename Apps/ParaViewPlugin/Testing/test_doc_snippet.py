# pvpython: runs the Python example of docs/PARAVIEW.md ("Using the filters")
# exactly as printed, with only its three paths replaced (the plugin, the mesh,
# the output), and checks what it wrote: a closed surface on the mesh.
# Usage: pvpython --force-offscreen-rendering test_doc_snippet.py PLUGIN PARAVIEW.md TMPDIR
import lvdif_pvtest as T  # first: fixes sys.path for route B

import os
import re
import sys

plugin, doc, tmpdir = sys.argv[1:4]
check = T.check
text = open(doc).read()
section = text[text.index("## Using the filters"):]
snippet = re.search(r"```python\n(.*?)```", section, re.S).group(1)
# the documented paths, replaced by real ones (the rest runs verbatim)
mesh = os.path.join(tmpdir, "doc_cube.off")
with open(mesh, "w") as f:
    f.write(T._CUBE_OFF)
ply = os.path.join(tmpdir, "doc_snippet.ply")
if os.path.exists(ply):
    os.remove(ply)
for old, new in (("/path/to/build-pv/lib/paraview-5.11/plugins/LVDIF/LVDIF.so", plugin), ("bunny.off", mesh),
                 ("bunny.ply", ply)):
    check(snippet.count("'%s'" % old) == 1, "the documented example names '%s' once" % old)
    snippet = snippet.replace("'%s'" % old, repr(new))
print(snippet)
exec(compile(snippet, "docs/PARAVIEW.md", "exec"), {})

from vtkmodules.vtkIOPLY import vtkPLYReader  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkFeatureEdges  # noqa: E402
r = vtkPLYReader()
r.SetFileName(ply)
r.Update()
pd = r.GetOutput()
check(pd.GetNumberOfPolys() > 1000, "the example wrote %s with %d triangles" % (os.path.basename(ply),
                                                                               pd.GetNumberOfPolys()))
fe = vtkFeatureEdges()
fe.SetInputData(pd)
fe.SetBoundaryEdges(1)
fe.SetNonManifoldEdges(1)
fe.SetFeatureEdges(0)
fe.SetManifoldEdges(0)
fe.Update()
check(fe.GetOutput().GetNumberOfLines() == 0, "its surface is closed and manifold (%d open edges)"
      % fe.GetOutput().GetNumberOfLines())
b = pd.GetBounds()
# the unit cube, 128 points on its longest axis: the surface within one voxel of its faces
h = (1.0 + 4.0 / 127.0) / 127.0  # the fitted grid's spacing bound (padding 2 voxels each side)
check(max(abs(b[0]), abs(b[2]), abs(b[4]), abs(b[1] - 1), abs(b[3] - 1), abs(b[5] - 1)) <= h,
      "its bounds %s are the cube's" % (["%.4f" % v for v in b],))
# the example's view, closed here: a live view at exit aborts on X (GLXBadContext)
import paraview.simple as pvs  # noqa: E402
for v in pvs.GetViews():
    pvs.Delete(v)
print("failures:", check.failures)
sys.exit(1 if check.failures else 0)
