"""Runs docs/examples/pipeline.py and checks it against the analytic sphere
(area 4 pi R^2, volume 4/3 pi R^3) and the files it must write."""
import math
import os
import sys

sys.path.insert(0, sys.argv[1])
import pipeline  # noqa: E402

outdir = sys.argv[2]
area, volume = pipeline.main(outdir)
R = pipeline.RADIUS
# The SDF of a unit sphere on a 64^3 grid: marching cubes stays well within 1.5% of both.
ok = abs(area - 4 * math.pi * R * R) / (4 * math.pi * R * R) < 0.015
ok &= abs(volume - 4 / 3 * math.pi * R ** 3) / (4 / 3 * math.pi * R ** 3) < 0.015
files = [f for f in os.listdir(outdir) if os.path.getsize(os.path.join(outdir, f)) > 0]
print("files:", sorted(files))
ok &= len(files) >= 2
if hasattr(pipeline.lvdif, "vtkDictionaryVolumeWriter"):
    ok &= "sphere.lvdv" in files
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
