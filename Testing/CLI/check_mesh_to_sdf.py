"""`lvdif mesh-to-sdf` on a UV sphere written here as .obj, checked against the
analytic sphere's signed distance (an oracle independent of the mesh-to-SDF
code): the volume is read back through vtkDictionaryVolumeReader, and every
voxel's distance must equal (|p - c| - r) / spacing, saturated at the band,
within the tessellation's sagitta plus the dictionary's precision. Each sign
mode is run (normal with the sign voxel filters); the progress bar is drawn on
stderr; bad options fail with one line and a non-zero exit code; an open sheet
gets the warning that it encloses no volume, the sphere none, the sphere with
a reversed patch the warning that names --reorient."""
import math
import os
import subprocess
import sys

import numpy as np
from vtk.util.numpy_support import vtk_to_numpy

exe, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)

C, R, SLICES, STACKS = (0.3, -0.1, 0.2), 1.5, 96, 48


def write_sphere(path):
    lines = [f"v {C[0]} {C[1]} {C[2] + R}", f"v {C[0]} {C[1]} {C[2] - R}"]
    for s in range(1, STACKS):
        t = math.pi * s / STACKS
        for l in range(SLICES):
            p = 2 * math.pi * l / SLICES
            lines.append(f"v {C[0] + R * math.sin(t) * math.cos(p)!r} {C[1] + R * math.sin(t) * math.sin(p)!r} "
                         f"{C[2] + R * math.cos(t)!r}")

    def ring(s, l):  # 1-based OBJ index
        return 3 + (s - 1) * SLICES + (l % SLICES)

    for l in range(SLICES):
        lines.append(f"f 1 {ring(1, l)} {ring(1, l + 1)}")
        lines.append(f"f 2 {ring(STACKS - 1, l + 1)} {ring(STACKS - 1, l)}")
        for s in range(1, STACKS - 1):
            lines.append(f"f {ring(s, l)} {ring(s + 1, l)} {ring(s + 1, l + 1)}")
            lines.append(f"f {ring(s, l)} {ring(s + 1, l + 1)} {ring(s, l + 1)}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


mesh = f"{out}/sphere.obj"
write_sphere(mesh)

from lvdif import vtkDictionaryVolumeReader, vtkSparseVolumeToImage  # noqa: E402

N, BAND = 48, 6.0
for sign, extra in (("winding", []), ("pseudo", []), ("normal", ["--svf"])):
    vol_path = f"{out}/sphere_{sign}.lvdv"
    cmd = [exe, "mesh-to-sdf", mesh, vol_path, "--dims", str(N), "--padding", "3", "--sign", sign,
           "--band", str(BAND), "--device", "cpu"] + extra
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    print(run.stdout)
    print(run.stderr, file=sys.stderr)
    assert run.returncode == 0, f"{cmd} exited with {run.returncode}"
    assert "mesh to SDF: done" in run.stderr, "no progress report on stderr (one line per stage off a terminal)"
    # "--device cpu" holds for every stage: no stage looks for a GPU (and says so)
    assert "CUDA" not in run.stderr, "a stage looked for a CUDA device under --device cpu"

    reader = vtkDictionaryVolumeReader()
    reader.SetFileName(vol_path)
    dense = vtkSparseVolumeToImage()  # the reader gives the sparse volume; the voxels are checked here
    dense.SetInputConnection(reader.GetOutputPort())
    dense.Update()
    img = dense.GetOutput()
    dims, origin, spacing = img.GetDimensions(), img.GetOrigin(), img.GetSpacing()
    assert dims == (N, N, N), dims
    assert spacing[0] == spacing[1] == spacing[2], spacing
    h = spacing[0]
    # fitted grid: the longest axis spans 2R plus 3 voxels of padding on each side
    assert abs((N - 1 - 6) * h - 2 * R) < 1e-4 * R, (h, R)
    sdf = vtk_to_numpy(img.GetPointData().GetArray("sdf")).reshape(N, N, N)  # z, y, x
    z, y, x = np.meshgrid(*(origin[a] + h * np.arange(N) for a in (2, 1, 0)), indexing="ij")
    exact = (np.sqrt((x - C[0]) ** 2 + (y - C[1]) ** 2 + (z - C[2]) ** 2) - R) / h
    exact = np.clip(exact, -BAND, BAND)
    sagitta = R * (1 - math.cos(math.pi / STACKS)) / h  # faces lie at most this far inside
    tol = sagitta + 1e-3 + 2e-2 * np.abs(exact)  # + the dictionary's quantisation
    err = np.abs(sdf - exact)
    print(f"{sign}: sagitta {sagitta:.4f} voxels, max |error| {err.max():.4f}, "
          f"inside voxels {np.count_nonzero(sdf < 0)} (analytic {np.count_nonzero(exact < 0)})")
    assert np.all(err <= tol), f"{sign}: {np.count_nonzero(err > tol)} voxels off, worst {err.max()}"
    assert np.count_nonzero(sdf < 0) > 1000

# .bv output (a cubic grid): the original's raw format, 4 N^3 bytes.
bv = f"{out}/SDF_{N}_sphere.bv"
run = subprocess.run([exe, "mesh-to-sdf", mesh, bv, "--dims", str(N), "--padding", "3", "--device", "cpu"],
                     capture_output=True, text=True, timeout=240)
assert run.returncode == 0, run.stderr
assert os.path.getsize(bv) == 4 * N ** 3

# refused options: one line on stderr, exit code 2 (a refused command line), nothing written
for bad, needle in ((["--sign", "inside"], "--sign must be"), (["--dims", "1"], "option --dims expects an integer in [2, 1048576], got '1'"),
                    (["--band", "-1"], "--band must be a number of voxels >= 0 (0: no band), not -1"),
                    (["--band", "nan"], "option --band expects a number, got 'nan'"),
                    (["--device", "tpu"], "--device must be"),
                    (["--colour", "red"], "colour")):
    target = f"{out}/bad.lvdv"
    run = subprocess.run([exe, "mesh-to-sdf", mesh, target] + bad, capture_output=True, text=True, timeout=60)
    assert run.returncode == 2 and needle in run.stderr, (bad, run.returncode, run.stderr)
    assert not os.path.exists(target), bad
# --band 0: no band, as the filters' and writers' BandWidth 0 (docs/USER_GUIDE.md); it was refused
target = f"{out}/noband.lvdv"
run = subprocess.run([exe, "mesh-to-sdf", mesh, target, "--dims", "24", "--band", "0", "--device", "cpu"],
                     capture_output=True, text=True, timeout=120)
assert run.returncode == 0, run.stderr
info = subprocess.run([exe, "info", target], capture_output=True, text=True, timeout=60)
assert info.returncode == 0 and ", band inf" in info.stdout, info.stdout + info.stderr
run = subprocess.run([exe, "mesh-to-sdf", f"{out}/missing.obj", f"{out}/bad.lvdv"], capture_output=True, text=True)
assert run.returncode == 1 and "missing.obj" in run.stderr, run.stderr

# warnings: an open sheet encloses no volume (written, exit 0, one warning
# naming the cause and the option); the closed sphere gets none
sheet = f"{out}/sheet.obj"
with open(sheet, "w") as f:
    n = 8
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = -1 + 2 * i / n, -1 + 2 * j / n
            f.write(f"v {x} {y} {0.02 * x - 0.05 * y + 0.013}\n")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            f.write(f"f {a} {a + 1} {a + n + 2}\nf {a} {a + n + 2} {a + n + 1}\n")
run = subprocess.run([exe, "mesh-to-sdf", sheet, f"{out}/sheet.lvdv", "--dims", "32", "--device", "cpu"],
                     capture_output=True, text=True, timeout=60)
assert run.returncode == 0 and os.path.exists(f"{out}/sheet.lvdv"), run.stderr
warnings = [l for l in run.stderr.splitlines() if l.startswith("warning: ")]
assert len(warnings) == 1 and "encloses no volume" in warnings[0] and "pseudo-normal" in warnings[0], run.stderr
# ... naming the option of this tool that helps (it named "the pseudo-normal sign" and "the unsigned distance
# meshed at a positive iso-value", neither by an option, and lvdif has no unsigned distance), and that
# option helps: no warning, and the volume meshes to a surface
assert "(--sign pseudo," in warnings[0] and "not in lvdif mesh-to-sdf" in warnings[0], warnings[0]
run = subprocess.run([exe, "mesh-to-sdf", sheet, f"{out}/sheet_pseudo.lvdv", "--dims", "32", "--device", "cpu",
                      "--sign", "pseudo"], capture_output=True, text=True, timeout=60)
assert run.returncode == 0 and "warning:" not in run.stderr, run.stderr
run = subprocess.run([exe, "mesh", f"{out}/sheet_pseudo.lvdv", f"{out}/sheet_pseudo.ply"], capture_output=True,
                     text=True, timeout=60)
assert run.returncode == 0 and "warning:" not in run.stderr and not run.stdout.startswith("0 "), run
run = subprocess.run([exe, "mesh-to-sdf", mesh, f"{out}/sphere_again.lvdv", "--dims", "24", "--device", "cpu"],
                     capture_output=True, text=True, timeout=60)
assert run.returncode == 0 and "warning:" not in run.stderr, run.stderr
# meshing that volume: an empty mesh, written, with one warning saying why;
# meshing the sphere's volume: triangles and no warning
run = subprocess.run([exe, "mesh", f"{out}/sheet.lvdv", f"{out}/sheet.ply"], capture_output=True, text=True, timeout=60)
warnings = [l for l in run.stderr.splitlines() if l.startswith("warning: ")]
assert run.returncode == 0 and os.path.exists(f"{out}/sheet.ply") and "0 triangles" in run.stdout, run
assert len(warnings) == 1 and "no surface" in warnings[0], run.stderr
run = subprocess.run([exe, "mesh", f"{out}/sphere_again.lvdv", f"{out}/sphere_again.ply"], capture_output=True,
                     text=True, timeout=60)
assert run.returncode == 0 and "warning:" not in run.stderr and not run.stdout.startswith("0 "), run

# warnings: the sphere with its faces near the top pole reversed (counted here
# from the file): one warning with that count naming --reorient, for the
# winding and the pseudo-normal sign; none with --reorient
with open(mesh) as f:
    obj = f.read().splitlines()
verts = [tuple(map(float, l.split()[1:4])) for l in obj if l.startswith("v ")]
flipped, reversed_faces = [], 0
for l in obj:
    if l.startswith("f "):
        a, b, c = l.split()[1:4]
        if all(verts[int(i) - 1][2] > C[2] + 0.7 * R for i in (a, b, c)):
            l, reversed_faces = f"f {a} {c} {b}", reversed_faces + 1
    flipped.append(l)
patch = f"{out}/sphere_patch.obj"
with open(patch, "w") as f:
    f.write("\n".join(flipped) + "\n")
assert reversed_faces > 0
for sign, reorient, expect in (("winding", [], f"{reversed_faces} of "), ("pseudo", [], "edges join faces of opposite"),
                               ("winding", ["--reorient"], None)):
    run = subprocess.run([exe, "mesh-to-sdf", patch, f"{out}/patch.lvdv", "--dims", "24", "--sign", sign,
                          "--device", "cpu"] + reorient, capture_output=True, text=True, timeout=60)
    warnings = [l for l in run.stderr.splitlines() if l.startswith("warning: ")]
    assert run.returncode == 0, run.stderr
    if expect is None:
        assert not warnings, run.stderr
    else:
        assert len(warnings) == 1 and expect in warnings[0] and "--reorient" in warnings[0], (sign, run.stderr)
print("mesh-to-sdf OK")

# the "creation parameters" a volume records (lvdif info) is a command line that
# runs and gives the same volume: it said --sign pseudonormal (which --sign
# refuses) and --padding 1.234568 for 1.2345678
import shlex  # noqa: E402
first = f"{out}/params.lvdv"
run = subprocess.run([exe, "mesh-to-sdf", mesh, first, "--dims", "20", "--padding", "1.2345678", "--sign", "pseudo",
                      "--band", "3.3", "--device", "cpu"], capture_output=True, text=True, timeout=120)
assert run.returncode == 0, run.stderr


def creation_parameters(path):
    info = subprocess.run([exe, "info", path], capture_output=True, text=True, timeout=60)
    assert info.returncode == 0, info.stderr
    lines = [ln.split(" = ", 1)[1] for ln in info.stdout.splitlines() if ln.startswith("meta        creation parameters = ")]
    assert len(lines) == 1, info.stdout
    return lines[0]


recorded = creation_parameters(first)
words = shlex.split(recorded)
assert words[:2] == ["lvdif", "mesh-to-sdf"], recorded
again = f"{out}/params_again.lvdv"
run = subprocess.run([exe, "mesh-to-sdf", mesh, again] + words[2:] + ["--device", "cpu"], capture_output=True, text=True,
                     timeout=120)
assert run.returncode == 0, (recorded, run.stderr)
assert creation_parameters(again) == recorded, (recorded, creation_parameters(again))
assert "--padding 1.2345678 " in recorded and "--sign pseudo " in recorded and "--band 3.3" in recorded, recorded


def sdf_of(path):
    r = vtkDictionaryVolumeReader()
    r.SetFileName(path)
    d = vtkSparseVolumeToImage()
    d.SetInputConnection(r.GetOutputPort())
    d.Update()
    return vtk_to_numpy(d.GetOutput().GetPointData().GetArray("sdf"))


assert np.array_equal(sdf_of(first), sdf_of(again)), "the recorded parameters give another volume"

# the summary's edge count says what it counts, in the warnings' words: the edges of non-zero net
# multiplicity, which a closed box with one quad doubled has (its 4 outer edges: the count is worked out
# here from the faces) though it has no hole; it said "4 boundary edges", calling the closed box open
box = f"{out}/box_doubled.obj"
corners = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]  # outward
tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
tris += tris[2:4]  # the top quad again, the same way round
net = {}
for t in tris:
    for k in range(3):
        p, q = t[k], t[(k + 1) % 3]
        net[(min(p, q), max(p, q))] = net.get((min(p, q), max(p, q)), 0) + (1 if p < q else -1)
unmatched = sum(1 for v in net.values() if v != 0)
assert unmatched == 4, unmatched
with open(box, "w") as f:
    f.write("".join(f"v {x} {y} {z}\n" for x, y, z in corners) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in tris))
run = subprocess.run([exe, "mesh-to-sdf", box, f"{out}/box_doubled.lvdv", "--dims", "16", "--sign", "pseudo",
                      "--device", "cpu"], capture_output=True, text=True, timeout=60)
assert run.returncode == 0, run.stderr
assert (f"{len(tris)} triangles (0 degenerate skipped, {unmatched} edges of non-zero net multiplicity: holes' rims "
        "or the edges of reversed or duplicated faces) -> ") in run.stdout and "boundary edges" not in run.stdout, run.stdout
assert f"(its {unmatched} edges of non-zero net multiplicity are the duplicates' edges, not holes)" in run.stderr, run.stderr
print("edge count OK")
