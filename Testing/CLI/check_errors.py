"""Bad command lines get one clear line on stderr and a non-zero exit code: 2 for a command line refused
before the work (an option, an argument, an output's place or format), 1 for a failure while running."""
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]


def run(*args):
    r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=60)
    return r.returncode, r.stderr.strip()


# COMMAND --help: that command's usage on stdout, exit 0, nothing run (no file written)
r = subprocess.run([exe, "mesh-to-sdf", "--help"], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and r.stdout.startswith("usage: lvdif mesh-to-sdf MESH") and "--reorient" in r.stdout, r
# ... with the defaults an option takes when it is left out (the usage named none)
assert "--dims 128" in r.stdout and "--padding 2" in r.stdout and "--band 8" in r.stdout, r.stdout
r = subprocess.run([exe, "demo", "--out", out + "-help", "-h"], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and r.stdout.startswith("usage: lvdif demo") and not __import__("os").path.exists(out + "-help"), r

# the exit statuses are one rule, said in every help (a refused command line exited 1, the editor's 2)
status_line = ("exit status: 0 done, 1 failed while running, 2 command line refused (nothing read or written), "
               "130 cancelled (Ctrl-C)")
for cmd in (["help"], ["mesh", "--help"]):
    r = subprocess.run([exe, *cmd], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and status_line in r.stdout, r
# a wrong number of arguments and an output in a missing folder are refused command lines (2); an
# input that cannot be read is a failure while running (1)
code, err = run("mesh", "only-one.lvdv")
assert code == 2 and err.startswith("lvdif mesh: usage: lvdif mesh VOLUME"), (code, err)
code, err = run("mesh", "missing.lvdv", "/nonexistent_dir/x.ply")
assert code == 2 and "/nonexistent_dir" in err, (code, err)
code, err = run("mesh", "missing.lvdv", "x.ply")
assert code == 1 and "missing.lvdv" in err, (code, err)

# info on another volume format names it (it said "header: bad magic")
code, err = run("info", "volume.vti")
assert code == 2 and err == ("lvdif info: info describes .lvdv files, 'volume.vti' is a .vti file: convert it first "
                             "(lvdif convert volume.vti OUT.lvdv)"), (code, err)
# an option given twice is a mistake, not "the last one wins" (it silently did)
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "--dims", "16", "--dims", "24")
assert code == 2 and err == "lvdif mesh-to-sdf: option --dims given twice", (code, err)
code, err = run("info", "x.lvdv", "--header-only", "--header-only")
assert code == 2 and err == "lvdif info: option --header-only given twice", (code, err)
code, err = run("no-such-command")
assert code == 2 and "unknown command" in err, (code, err)
# --key=value is --key value, as in the editor's command line (it was "unknown option --dims=16"); a flag
# takes no value; an option written with one dash is named (it was taken for a file: the usage line came)
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "--dims=16", "--dims", "24")
assert code == 2 and err == "lvdif mesh-to-sdf: option --dims given twice", (code, err)
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "--dims=sixteen")
assert code == 2 and err == "lvdif mesh-to-sdf: option --dims expects an integer in [2, 1048576], got 'sixteen'", (code, err)
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "--svf=1")
assert code == 2 and err == "lvdif mesh-to-sdf: option --svf takes no value", (code, err)
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "-dims", "16")
assert code == 2 and err == "lvdif mesh-to-sdf: unknown option -dims (options start with two dashes: --dims)", (code, err)
code, err = run("demo", "--bogus", "1")
assert code == 2 and err == "lvdif demo: unknown option --bogus", (code, err)
# an unknown option is named where it stands: last on the line it said "needs a value",
# and before the positionals it took the mesh as its value
code, err = run("mesh-to-sdf", "in.obj", "out.lvdv", "--bogus")
assert code == 2 and err == "lvdif mesh-to-sdf: unknown option --bogus", (code, err)
code, err = run("mesh-to-sdf", "--svf", "--bogus", "in.obj", "out.lvdv")
assert code == 2 and err == "lvdif mesh-to-sdf: unknown option --bogus", (code, err)
code, err = run("demo", "--size", "ten")
assert code == 2 and "expects an integer" in err, (code, err)
code, err = run("demo", "--size", "100000000", "--out", out)
assert code == 2 and "each axis needs 2..1048576 voxels" in err, (code, err)
# a refused --size names the option, not the embedded script's line, and makes no folder
code, err = run("demo", "--size", "0", "--out", out + "-size0")
assert code == 2 and err.startswith("lvdif demo: --size") and "line" not in err, (code, err)
assert not __import__("os").path.exists(out + "-size0"), "demo --size 0 left its output folder"
# a --size whose canvas's chunk table alone passes the memory limit is a refused command line naming the
# option, before the folder is made (status 2; it was the volume's own "chunk table of a ... volume needs",
# status 1, after making the folder); so is script's --size
code, err = run("demo", "--size", "100000", "--out", out + "-size1e5")
assert code == 2 and err.startswith("lvdif demo: --size 100000 makes a canvas of 100000 x 100000 x 100000 voxels, "
                                    "whose chunk table alone needs ") and err.endswith(": use a smaller --size"), (code, err)
assert not __import__("os").path.exists(out + "-size1e5"), "demo --size 100000 left its output folder"
code, err = run("script", "no-such-script.lvs", "--size", "1048576", "--out", out + "-big.lvdv")
assert code == 2 and err.startswith("lvdif script: --size 1048576 makes a canvas of 1048576 x 1048576 x 1048576 voxels, "
                                    "whose chunk table alone needs 768.00 TiB, more than the limit of "), (code, err)
# a failure after the output folder was made (the build over a small memory limit) removes the folder it made
r = subprocess.run([exe, "demo", "--size", "512", "--out", out + "-size512"], capture_output=True, text=True, timeout=60,
                   env=dict(__import__("os").environ, LVDIF_MEMORY_LIMIT="2M"))
assert r.returncode == 1 and r.stderr.strip().startswith("lvdif demo: --size 512: ") and "line" not in r.stderr, r
assert not __import__("os").path.exists(out + "-size512"), "demo --size 512 left its output folder"
# an axis of 1 and one over 1048576: the canvas rule's one message (DictionaryVolume::checkCanvasDimensions)
code, err = run("demo", "--size", "1", "--out", out + "-size1")
assert code == 2 and err == ("lvdif demo: --size 1: a canvas of 1 x 1 x 1 voxels cannot be edited: each axis needs "
                             "2..1048576 voxels (marching cubes needs one cell per axis)"), (code, err)
code, err = run("demo", "--size", "1048577", "--out", out + "-size2e20")
assert code == 2 and err.startswith("lvdif demo: --size 1048577: a canvas of 1048577 x 1048577 x 1048577 voxels "
                                    "cannot be edited: each axis needs 2..1048576"), (code, err)
assert not __import__("os").path.exists(out + "-size1") and not __import__("os").path.exists(out + "-size2e20")

import os  # noqa: E402

code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--sign", "pseudo", "--reorient")
assert code == 2 and err.endswith("--reorient needs --sign winding"), (code, err)
# a non-finite or negative --padding is named before the mesh is read (in.obj does not exist)
for p in ("nan", "inf", "-1", "1e999"):
    code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--padding", p)
    assert code == 2 and err == f"lvdif mesh-to-sdf: option --padding expects a number in [0, 1048576], got '{p}'", (code, err)
# every number option goes through one guard that quotes the text as written and the range:
# an integer beyond long's range was "not 9223372036854775807" (strtol's ERANGE ignored)
for value in ("99999999999999999999", "-99999999999999999999", "1048577", "1", "12x", "", "0x10"):
    code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--dims", value)
    assert code == 2 and err == f"lvdif mesh-to-sdf: option --dims expects an integer in [2, 1048576], got '{value}'", (code, err)
# the one guard refuses white space around a number (strtol/strtod skip leading blanks:
# --size " 32" was taken as 32) and a hexadecimal double (--padding 0x10 was 16)
for value in (" 32", "32 ", "\t32", "\n32"):
    code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--dims", value)
    assert code == 2 and err == (f"lvdif mesh-to-sdf: option --dims expects an integer in [2, 1048576], got '{value}' "
                                 "(no spaces around the number)"), (code, err)
code, err = run("demo", "--out", out + "-spaced", "--size", " 32")
assert code == 2 and err == ("lvdif demo: option --size expects an integer in [2, 1048576], got ' 32' "
                             "(no spaces around the number)"), (code, err)
assert not os.path.exists(out + "-spaced"), "demo --size ' 32' left its output folder"
code, err = run("script", "x.lvs", "--size", "32x 16x8")
assert code == 2 and err == ("lvdif script: option --size expects N or NXxNYxNZ, each an integer in [2, 1048576], "
                             "got '32x 16x8'"), (code, err)
for value in (" 2", "2 ", "0x10", "0X1p1"):
    code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--padding", value)
    hint = " (no spaces around the number)" if value.strip() != value else ""
    assert code == 2 and err == f"lvdif mesh-to-sdf: option --padding expects a number in [0, 1048576], got '{value}'{hint}", (code, err)
code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--band", " 4")
assert code == 2 and err == "lvdif mesh-to-sdf: option --band expects a number, got ' 4' (no spaces around the number)", (code, err)
# mesh-to-sdf --dims is one number (the longest axis): NXxNYxNZ, as script --size takes, was "expects an integer"
code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--dims", "7x300x2")
assert code == 2 and err == ("lvdif mesh-to-sdf: option --dims expects one integer, the voxels along the mesh's longest axis "
                             "(the other axes follow the mesh's proportions), got '7x300x2'"), (code, err)
code, err = run("demo", "--out", out + "-huge", "--size", "99999999999999999999")
assert code == 2 and err == ("lvdif demo: option --size expects an integer in [2, 1048576], "
                             "got '99999999999999999999'"), (code, err)
assert not os.path.exists(out + "-huge")
# script --size takes N or NXxNYxNZ, as the editor's --new (it took N only: '--size 32x16x8' was refused)
for value in ("99999999999999999999", "32x16", "32x16x", "x", "32x16x8x4", "32xtenx8"):
    code, err = run("script", "x.lvs", "--size", value)
    assert code == 2 and err == ("lvdif script: option --size expects N or NXxNYxNZ, each an integer in [2, 1048576], "
                                 f"got '{value}'"), (value, code, err)
code, err = run("script", "x.lvs", "--size", "32x1x8")
assert code == 2 and err.startswith("lvdif script: --size 32x1x8: a canvas of 32 x 1 x 8 voxels cannot be edited"), (code, err)
code, err = run("mesh-to-sdf", "in.obj", os.path.join(out, "x.lvdv"), "--band", "nan")
assert code == 2 and err == "lvdif mesh-to-sdf: option --band expects a number, got 'nan'", (code, err)

os.makedirs(out, exist_ok=True)
bad = os.path.join(out, "bad.lvs")
with open(bad, "w") as f:
    f.write("radius 3\nsphere 1, 2,\n")
code, err = run("script", bad)
assert code == 1 and f"{bad}:2:" in err, (code, err)
# --max-steps: a long script that is no endless loop can run (it was stopped at 50M steps with nothing to
# do about it), and the step-limit error names the option; a bad value is a refused command line
steps = os.path.join(out, "steps.lvs")
with open(steps, "w") as f:
    f.write("x = 0\nfor i in 0..1000 { x = x + 1 }\nprint x\n")
code, err = run("script", steps, "--max-steps", "500")
assert code == 1 and err == (f"lvdif script: {steps}:2:1: step limit of 500 exceeded (an endless loop? If not, raise "
                             "the limit with --max-steps N)"), (code, err)
r = subprocess.run([exe, "script", steps, "--max-steps", "5000"], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and r.stdout.startswith("1000\n"), r
code, err = run("script", steps, "--max-steps", "0")
assert code == 2 and err.startswith("lvdif script: option --max-steps expects an integer in [1, "), (code, err)
# the (small) script is read and its syntax checked before the (possibly large) --in volume is
# loaded, as play reads its recording first: a missing script or a syntax error was found only
# after the volume was read (here the volume cannot be read: the script's error is the one said)
missing_in = os.path.join(out, "no-such-in.lvdv")
code, err = run("script", os.path.join(out, "no-such.lvs"), "--in", missing_in)
assert code == 1 and "no-such.lvs" in err and missing_in not in err and "read volume" not in err, (code, err)
code, err = run("script", bad, "--in", missing_in)
assert code == 1 and f"{bad}:2:" in err and missing_in not in err and "read volume" not in err, (code, err)
# `script --size` (the start canvas of a script without `canvas`) follows demo's
# canvas rule, refused up front: before the script is read or any output written
sized = os.path.join(out, "sized.lvs")
with open(sized, "w") as f:
    f.write("radius 1\ndab 0 0 0\n")
for n in ("1", "0", "1048577"):
    sized_vol = os.path.join(out, "sized-" + n + ".lvdv")
    if os.path.exists(sized_vol):
        os.remove(sized_vol)  # from an earlier run
    code, err = run("script", sized, "--size", n, "--out", sized_vol)
    assert code == 2 and err == (f"lvdif script: --size {n}: a canvas of {n} x {n} x {n} voxels cannot be edited: "
                                 "each axis needs 2..1048576 voxels (marching cubes needs one cell per axis)"), (code, err)
    assert not os.path.exists(sized_vol), n
code, err = run("script", os.path.join(out, "no-such.lvs"), "--size", "1")
assert code == 2 and err.startswith("lvdif script: --size 1: a canvas of 1 x 1 x 1"), (code, err)
# ... and a box canvas runs: the volume written has those dimensions (oracle: lvdif info)
box_vol = os.path.join(out, "sized-box.lvdv")
assert run("script", sized, "--size", "24x16x8", "--out", box_vol)[0] == 0
r = subprocess.run([exe, "info", box_vol], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and "24 x 16 x 8" in r.stdout, r
# --size with --in: refused (it was ignored: the script ran on the volume's grid),
# before the volume or the script is read and before any output is written
in_size_vol = os.path.join(out, "in-size.lvdv")
code, err = run("script", os.path.join(out, "no-such.lvs"), "--in", os.path.join(out, "no-such.lvdv"), "--size", "64",
                "--out", in_size_vol)
assert code == 2 and err == ("lvdif script: --size (the size of an empty start canvas) cannot be used with --in "
                             "(the script starts from that volume)"), (code, err)
assert not os.path.exists(in_size_vol)
# demo --out: a folder that cannot be made, or a file, is named as such (a failed mkdir was swallowed:
# "the folder '/proc/lvdif-demo' does not exist", and a file FILE gave "FILE/demo.ply")
code, err = run("demo", "--out", "/proc/lvdif-demo")
assert code == 2 and err.startswith("lvdif demo: cannot create the output folder '/proc/lvdif-demo': "), (code, err)
not_dir = os.path.join(out, "not-a-folder")
with open(not_dir, "w") as f:
    f.write("keep")
code, err = run("demo", "--out", not_dir)
assert code == 2 and err == f"lvdif demo: --out '{not_dir}' exists and is not a folder", (code, err)
assert open(not_dir).read() == "keep"
# .bv holds cubic volumes only (the original's N^3): mesh-to-sdf makes the fitted grid cubic, --dims
# voxels on every axis around the same centre with the same voxels. Every mesh but a cube's was
# refused ("this one is 25 x 15 x 15"), with no option that could make its grid cubic. The oracle:
# the .lvdv of the fitted grid, whose voxels are the cubic grid's with 5 more on each side of y and z.
box = os.path.join(out, "box.obj")
with open(box, "w") as f:
    f.write("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nv 2 0 1\nv 2 1 1\nv 0 1 1\n"
            "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")
box_bv, box_lvdv = os.path.join(out, "box.bv"), os.path.join(out, "box.lvdv")
for target in (box_bv, box_lvdv):
    r = subprocess.run([exe, "mesh-to-sdf", box, target, "--dims", "25", "--device", "cpu"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r
assert os.path.getsize(box_bv) == 4 * 25 ** 3
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def sdf_of(volume):
    vti = volume + ".vti"
    assert subprocess.run([exe, "convert", volume, vti], capture_output=True, timeout=60).returncode == 0
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(vti)
    reader.Update()
    image = reader.GetOutput()
    nx, ny, nz = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetArray("sdf")).reshape(nz, ny, nx), image


cubic, cubic_image = sdf_of(box_bv)
fitted, fitted_image = sdf_of(box_lvdv)
assert cubic.shape == (25, 25, 25) and fitted.shape == (15, 15, 25), (cubic.shape, fitted.shape)
# distances in voxels in both (the .bv keeps no spacing); within the .bv dictionary's step of 0.001
assert abs(fitted_image.GetSpacing()[0] - 0.1) < 1e-12, fitted_image.GetSpacing()
inner = cubic[5:20, 5:20, :]
assert np.count_nonzero(fitted < 0) > 100 and np.allclose(inner, fitted, atol=2e-3), np.abs(inner - fitted).max()
# the voxels the cubic grid adds are outside, farther than the fitted grid's border
assert cubic[:5].min() > 0 and cubic[20:].min() > 0 and cubic[:, :5].min() > 0 and cubic[:, 20:].min() > 0
tet = os.path.join(out, "tet.obj")
with open(tet, "w") as f:
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
named = os.path.join(out, "SDF_32_tet.bv")
# a .bv's grid is --dims on every axis whatever the mesh: its name's N is checked before the mesh is read,
# as a refused command line (status 2; it was read first, status 1, "(the grid fitted to the mesh)")
for mesh in (tet, os.path.join(out, "no-such-mesh.obj")):
    code, err = run("mesh-to-sdf", mesh, named, "--dims", "16")
    assert code == 2 and err == (f"lvdif mesh-to-sdf: cannot write '{named}': file name says N = 32 "
                                 "but the volume's edge is 16 (--dims 16 on every axis)"), (code, err)
assert run("mesh-to-sdf", tet, named, "--dims", "32")[0] == 0
# --dims is checked against the volumes' axis limit (2^20 = 1048576) before the mesh is read (status 2, above);
# a --dims within it is refused by the memory its grid needs: a .bv's cubic grid before the mesh is read
# (status 2), another grid, which the mesh's proportions decide, after (status 1, the memory error), both
# naming --dims (it was "chunk table of a 1000000 x 1000000 x 1000000 volume needs ...", naming no option)
env = dict(os.environ, LVDIF_MEMORY_LIMIT="1G")
for target, mesh, expect in ((os.path.join(out, "big.bv"), os.path.join(out, "no-such-mesh.obj"), 2),
                             (os.path.join(out, "big.lvdv"), tet, 1)):
    r = subprocess.run([exe, "mesh-to-sdf", mesh, target, "--dims", "1000000"], capture_output=True, text=True,
                       timeout=120, env=env)
    whose = "the cubic grid" if expect == 2 else "this mesh's grid"
    assert r.returncode == expect and r.stderr.splitlines()[-1] == (
        f"lvdif mesh-to-sdf: --dims 1000000 makes {whose} of 1000000 x 1000000 x 1000000 voxels, whose chunk table alone "
        "needs 666.13 TiB, more than the limit of 1.00 GiB (set LVDIF_MEMORY_LIMIT to change it): use fewer --dims"), (r.returncode, r.stderr)
    assert not os.path.exists(target)
# a long thin mesh at the same --dims has a small grid: not refused for its table
needle = os.path.join(out, "needle.obj")
with open(needle, "w") as f:
    f.write("v 0 0 0\nv 1000 0 0\nv 0 0.001 0\nv 0 0 0.001\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
r = subprocess.run([exe, "mesh-to-sdf", needle, os.path.join(out, "needle.lvdv"), "--dims", "1000000"],
                   capture_output=True, text=True, timeout=120, env=dict(os.environ, LVDIF_MEMORY_LIMIT="64M"))
assert r.returncode == 1 and "chunk table alone" not in r.stderr and "mesh to SDF: a 1000000 x 6 x 6 volume of this mesh needs at least" in r.stderr, (r.returncode, r.stderr)
# play says what it replayed, and warns when nothing is written (it was silent, exit 0)
rec = os.path.join(out, "one.lvr")
with open(rec, "w") as f:
    f.write("LVDIF-RECORDING 2\nedit time=0 op=add shape=sphere kind=single spacing=1.6 blend=0 coloroffset=1.5 "
            "rounding=0 color=200,40,40,255 dabs=1\nd 12 12 12 5\nend records=1\n")
play_in = os.path.join(out, "play-in.lvdv")
with open(os.path.join(out, "play-in.lvs"), "w") as f:
    f.write("canvas 24\n")
assert run("script", os.path.join(out, "play-in.lvs"), "--out", play_in)[0] == 0
r = subprocess.run([exe, "play", rec, "--in", play_in], capture_output=True, text=True, timeout=60)
warnings = [line for line in r.stderr.splitlines() if line.startswith("warning:")]
assert r.returncode == 0 and f"{rec}: 1 records replayed on {play_in}" in r.stdout and len(warnings) == 1 \
    and "nothing written" in warnings[0], r
r = subprocess.run([exe, "play", rec, "--in", play_in, "--out", play_in], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and "warning" not in r.stderr, r
# a recording cut short (here: before its end record) is one error; a version 1 recording (no end
# record) plays with one warning that says so (both played without a word before version 2)
cut = os.path.join(out, "cut.lvr")
with open(rec) as f, open(cut, "w") as g:
    g.write(f.read().replace("end records=1\n", ""))
code, err = run("play", cut, "--in", play_in, "--out", play_in)
assert code == 1 and err == (f"lvdif play: {cut}:4:1: the recording is cut short: no 'end records=N' line "
                             "(a version 2 recording ends with one)"), (code, err)
with open(cut, "w") as g:
    g.write(open(rec).read().replace("LVDIF-RECORDING 2", "LVDIF-RECORDING 1").replace("end records=1\n", ""))
r = subprocess.run([exe, "play", cut, "--in", play_in, "--out", play_in], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and r.stderr.count("warning:") == 1 and \
    "a version 1 recording has no end record" in r.stderr, r
# a script given to play and a recording given to script say what the file is and the command that
# takes it (they said only "expected the version line" and "unknown command 'LVDIF'")
play_script = os.path.join(out, "play-in.lvs")
code, err = run("play", play_script, "--in", play_in)
assert code == 1 and err == (f"lvdif play: {play_script}:1:1: expected the version line 'LVDIF-RECORDING 2' "
                             f"(this is a script: run it with lvdif script {play_script})"), (code, err)
code, err = run("script", rec)
assert code == 1 and err == (f"lvdif script: {rec}:1:1: unknown command 'LVDIF' (this is a recording: replay it "
                             f"with lvdif play {rec}, on the canvas it names or with --in VOLUME)"), (code, err)
# ... and so does script (it ran the whole script and kept nothing without a word)
r = subprocess.run([exe, "script", os.path.join(out, "play-in.lvs")], capture_output=True, text=True, timeout=60)
warnings = [line for line in r.stderr.splitlines() if line.startswith("warning:")]
assert r.returncode == 0 and warnings == ["warning: nothing written (no --out, --mesh or --png): the script's edits "
                                          "are not kept"], r
# --size with a script that makes its own canvas: refused at that line before anything runs or is
# written (the script's canvas silently won); without --size the script's canvas is the canvas
own_canvas = os.path.join(out, "own-canvas.lvs")
with open(own_canvas, "w") as f:
    f.write("radius 3\ncanvas 24 16 8\ndab 4 4 4\n")
own_vol = os.path.join(out, "own-canvas.lvdv")
with open(own_vol, "wb") as f:
    f.write(b"old")
code, err = run("script", own_canvas, "--size", "64", "--out", own_vol)
assert code == 1 and err == (f"lvdif script: {own_canvas}:2:1: 'canvas' makes its own canvas, but the start canvas's "
                             "size was given (--size 64): remove one of them"), (code, err)
assert open(own_vol, "rb").read() == b"old"
os.remove(own_vol)
code, err = run("script", own_canvas, "--out", own_vol)
assert code == 0, (code, err)
r = subprocess.run([exe, "info", own_vol, "--header-only"], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and "dimensions  24 x 16 x 8" in r.stdout, r
code, err = run("info", os.path.join(out, "missing.lvdv"))
assert code == 1 and "missing.lvdv" in err, (code, err)
with open(os.path.join(out, "junk.lvdv"), "wb") as f:
    f.write(b"not a volume file at all" * 10)
code, err = run("info", os.path.join(out, "junk.lvdv"))
assert code == 1 and err.count("\n") == 0, (code, err)
# a volume whose header is sound but one chunk's payload has a flipped bit: `info`
# checks every chunk (as `mesh` reads them) and fails naming the file and the chunk;
# --header-only does not look at the payload and says so
import struct  # noqa: E402
small_script, small_vol = os.path.join(out, "small.lvs"), os.path.join(out, "small.lvdv")
with open(small_script, "w") as f:
    f.write("canvas 40\nradius 8\ndab 20 20 20\n")
code, err = run("script", small_script, "--out", small_vol)
assert code == 0, (code, err)
r = subprocess.run([exe, "info", small_vol], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and "every chunk's checksum" in r.stdout, r
with open(small_vol, "rb") as f:
    data = bytearray(f.read())
table_offset = struct.unpack_from("<Q", data, len(data) - 32)[0]
payloads = [struct.unpack_from("<QI", data, e) for e in range(table_offset, len(data) - 32, 24)]
chunk, (at, size) = next((i, p) for i, p in enumerate(payloads) if p[1] > 0)
data[at + size // 2] ^= 0x04
damaged = os.path.join(out, "damaged.lvdv")
with open(damaged, "wb") as f:
    f.write(data)
code, err = run("info", damaged)
assert code == 1 and err == f"lvdif info: cannot read '{damaged}': chunk {chunk}: checksum mismatch (payload damaged)", (code, err)
code, err = run("mesh", damaged, os.path.join(out, "damaged.ply"))
assert code == 1 and f"chunk {chunk}: checksum mismatch" in err, (code, err)
r = subprocess.run([exe, "info", damaged, "--header-only"], capture_output=True, text=True, timeout=60)
assert r.returncode == 0 and "--header-only" in r.stdout, r
# a mesh file that cannot be read names the file once, whatever the fault
for name, data in (("empty.obj", b""), ("junk.ply", b"ply\nformat ascii 1.0\nelement vertex 4000000000\n"),
                   ("junk.stl", b"\x00" * 90), ("junk.off", b"OFF\n3 1 0\n0 0 0\n")):
    mesh_path = os.path.join(out, name)
    with open(mesh_path, "wb") as f:
        f.write(data)
    code, err = run("mesh-to-sdf", mesh_path, os.path.join(out, "m.lvdv"), "--dims", "8")
    assert code == 1 and err.count("\n") == 0 and err.count(mesh_path) == 1, (name, code, err)
# coordinates near float's limit: the mesh's bounds, named when it is read (it was "volume origin
# -4.87805e+36 and spacing 2.43902e+36 on axis x must be finite ..."); a mesh inside the range whose
# padded grid is not names --padding; a face of one vertex in plain words ("face with 1 vertices")
for name, text, want in (
        ("far.obj", "v 3e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
         "OBJ: mesh coordinates span x [0, 3e+38], y [0, 1], z [0, 0]: every coordinate must lie within +-1e+30"),
        ("one.obj", "v 0 0 0\nf 1\n", "OBJ line 2: a face needs at least 3 vertices, this one has 1")):
    mesh_path = os.path.join(out, name)
    with open(mesh_path, "w") as f:
        f.write(text)
    code, err = run("mesh-to-sdf", mesh_path, os.path.join(out, "m.lvdv"), "--dims", "8")
    assert code == 1 and err.startswith(f"lvdif mesh-to-sdf: cannot read '{mesh_path}': {want}") and "origin" not in err, (code, err)
near = os.path.join(out, "near.obj")
with open(near, "w") as f:
    f.write("v -9e29 0 0\nv 9e29 0 0\nv 0 9e29 0\nf 1 2 3\n")
code, err = run("mesh-to-sdf", near, os.path.join(out, "m.lvdv"), "--dims", "8", "--padding", "3")
assert code == 1 and err == ("lvdif mesh-to-sdf: the mesh reaches 9e+29 and --padding 3 around it takes the grid beyond "
                             "+-1e+30 (the volumes' world range): use less padding (--padding 0 fits) or scale the "
                             "mesh down"), (code, err)
# the range is the voxels' world coordinates: with --padding 0 they span [-9e29, 9e29] and the grid
# fits (it counted |origin| + spacing x dims and refused it, as it refused a mesh spanning
# [-4e29, 4e29] at the default padding)
near_vol = os.path.join(out, "near.lvdv")
code, err = run("mesh-to-sdf", near, near_vol, "--dims", "8", "--padding", "0")
assert code == 0 and os.path.exists(near_vol), (code, err)
os.remove(near_vol)
wide = os.path.join(out, "wide.obj")
with open(wide, "w") as f:
    f.write("v -4e29 -4e29 -4e29\nv 4e29 -4e29 -4e29\nv -4e29 4e29 -4e29\nv -4e29 -4e29 4e29\n"
            "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
code, err = run("mesh-to-sdf", wide, near_vol, "--dims", "16")
assert code == 0 and os.path.exists(near_vol), (code, err)
os.remove(near_vol)
# less padding is advised only where it helps (it was advised with --padding 0): a .bv's cubic grid
# around a flat mesh at y = 9e29 reaches y = 1.8e30 with any padding
flat = os.path.join(out, "flat.obj")
with open(flat, "w") as f:
    f.write("v -9e29 9e29 0\nv 9e29 9e29 0\nv 0 9e29 1e28\nf 1 2 3\n")
for pad in ("3", "0"):
    code, err = run("mesh-to-sdf", flat, os.path.join(out, "SDF_8_m.bv"), "--dims", "8", "--padding", pad)
    assert code == 1 and err == (f"lvdif mesh-to-sdf: the mesh reaches 9e+29 and --padding {pad} around it takes the grid "
                                 "beyond +-1e+30 (the volumes' world range): scale the mesh down (less padding cannot "
                                 "help: even --padding 0 takes the grid beyond it)"), (code, err)
assert not os.path.exists(os.path.join(out, "m.lvdv")) and not os.path.exists(os.path.join(out, "SDF_8_m.bv"))
corner = os.path.join(out, "corner.obj")
corner_vol = os.path.join(out, "corner.lvdv")  # (not m.lvdv: that one must not exist above and below)
if os.path.exists(corner_vol):
    os.remove(corner_vol)  # from an earlier run
with open(corner, "w") as f:
    f.write("v 0 0 0\nv 9e29 0 0\nv 0 9e29 0\nv 0 0 9e29\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
code, err = run("mesh-to-sdf", corner, corner_vol, "--padding", "15")
assert code == 1 and err == ("lvdif mesh-to-sdf: the mesh reaches 9e+29 and --padding 15 around it takes the grid beyond "
                             "+-1e+30 (the volumes' world range): use less padding (--padding 0 fits) or scale the "
                             "mesh down"), (code, err)
assert not os.path.exists(corner_vol)
code, err = run("mesh-to-sdf", corner, corner_vol, "--padding", "0")  # the advice works
assert code == 0 and os.path.exists(corner_vol), (code, err)
os.remove(corner_vol)
code, err = run("mesh-to-sdf", corner, corner_vol, "--padding=0", "--dims=16")  # --key=value
info = subprocess.run([exe, "info", corner_vol], capture_output=True, text=True, timeout=60).stdout
assert code == 0 and "dimensions  16 x 16 x 16" in info and "--dims 16 --padding 0 " in info, (code, err, info)
# what a command prints on stdout (info's description, --help) is its output: when it cannot be
# written the run failed (`lvdif info v.lvdv > /dev/full` exited 0 with nothing written)
if os.path.exists("/dev/full"):
    for args in (["info", corner_vol], ["help"], ["mesh", "--help"]):
        with open("/dev/full", "w") as full:
            r = subprocess.run([exe, *args], stdout=full, stderr=subprocess.PIPE, text=True, timeout=60)
        assert r.returncode == 1 and "cannot write the standard output: No space left on device" in r.stderr, (args, r)
os.remove(corner_vol)
# a mesh whose points are one point as read (they differ in the file only beyond float's ~7 digits) says
# so (a unit cube at 1e29 was "fit grid: the mesh bounds have zero size")
collapsed = os.path.join(out, "collapsed.obj")
with open(collapsed, "w") as f:
    f.write("v 1e29 1e29 1e29\nv 100000000000000000000000000001 1e29 1e29\nv 1e29 100000000000000000000000000001 1e29\n"
            "v 1e29 1e29 100000000000000000000000000001\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
code, err = run("mesh-to-sdf", collapsed, os.path.join(out, "m.lvdv"))
assert code == 1 and err == (f"lvdif mesh-to-sdf: mesh '{collapsed}': all its 4 points are the one point (1.00000002e+29, "
                             "1.00000002e+29, 1.00000002e+29) as read, so it has no size (coordinates are read as 32-bit "
                             "floats, about 7 significant digits: points that differ only beyond that, such as 1e29 and "
                             "1e29 + 1, are one point)"), (code, err)
assert not os.path.exists(os.path.join(out, "m.lvdv"))
# a mesh so small that its voxels fall below the volumes' smallest spacing (1e-30) says so (it was "the
# mesh reaches 1e-30 and --padding 2 around it takes the grid beyond +-1e+30")
tiny = os.path.join(out, "tiny.obj")
with open(tiny, "w") as f:
    f.write("v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nv 0 0 1e-30\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
code, err = run("mesh-to-sdf", tiny, os.path.join(out, "m.lvdv"), "--dims", "24")
assert code == 1 and err == ("lvdif mesh-to-sdf: the mesh is 1e-30 across, so --dims 24 gives voxels of 5.26316e-32, below "
                             "the volumes' smallest spacing of 1e-30: scale the mesh up or use fewer --dims"), (code, err)
assert not os.path.exists(os.path.join(out, "m.lvdv"))
# --dims too small for the padding names both options (not fitGridToMesh's "maxDim")
code, err = run("mesh-to-sdf", os.path.join(out, "empty.obj"), os.path.join(out, "m.lvdv"), "--dims", "3")
assert code == 2 and "--dims 3" in err and "--padding 2" in err and "maxDim" not in err, (code, err)
# a .vti that is not XML: one line (VTK's XML parser printed its own error in
# VTK's log format before it)
with open(os.path.join(out, "junk.vti"), "w") as f:
    f.write("not xml\n")
code, err = run("mesh", os.path.join(out, "junk.vti"), os.path.join(out, "junk.ply"))
lines = [line for line in err.splitlines() if not line.endswith(": done")]
assert code == 1 and len(lines) == 1 and lines[0].startswith("lvdif mesh: cannot read") and "ERR|" not in err, (code, err)
# a .vti whose header claims 10^6 (10^8) points a side (three values follow): refused
# before VTK's reader allocates them, with the size and the limit (it ended in
# "lvdif mesh: std::bad_alloc"); the old output file is untouched
with open(os.path.join(out, "forged.vti"), "w") as f:
    f.write('<VTKFile type="ImageData"><ImageData WholeExtent="0 999999 0 999999 0 999999" Origin="0 0 0" '
            'Spacing="1 1 1"><Piece Extent="0 999999 0 999999 0 999999"><PointData Scalars="sdf">'
            '<DataArray type="Float32" Name="sdf" format="ascii">1 2 3</DataArray></PointData></Piece></ImageData>'
            '</VTKFile>\n')
with open(os.path.join(out, "forged.lvdv"), "wb") as f:
    f.write(b"old")
for cmd in (["mesh", os.path.join(out, "forged.vti"), os.path.join(out, "forged.ply")],
            ["convert", os.path.join(out, "forged.vti"), os.path.join(out, "forged.lvdv")]):
    code, err = run(*cmd)
    assert code == 1 and err.count("\n") == 0 and "1000000 x 1000000 x 1000000 points needs" in err \
        and "LVDIF_MEMORY_LIMIT" in err, (code, err)
with open(os.path.join(out, "forged.vti")) as f:
    text = f.read().replace("999999", "99999999")
with open(os.path.join(out, "forged8.vti"), "w") as f:
    f.write(text)
code, err = run("mesh", os.path.join(out, "forged8.vti"), os.path.join(out, "forged.ply"))
assert code == 1 and err.count("\n") == 0 and "100000000 x 100000000 x 100000000 points size overflows" in err, (code, err)
assert open(os.path.join(out, "forged.lvdv"), "rb").read() == b"old"
# a volume that cannot be read is never "read volume: done" before the error
code, err = run("mesh", os.path.join(out, "junk.lvdv"), os.path.join(out, "junk.ply"))
assert code == 1 and err.count("\n") == 0 and "junk.lvdv" in err, (code, err)
code, err = run("convert", os.path.join(out, "junk.lvdv"), os.path.join(out, "junk2.lvdv"))
assert code == 1 and err.count("\n") == 0 and not os.path.exists(os.path.join(out, "junk2.lvdv")), (code, err)
# A volume with no surface (every distance on one side of 0): the mesh is
# written, empty, and one warning line says why (it was silent: "0 triangles").
empty_script = os.path.join(out, "empty.lvs")
with open(empty_script, "w") as f:
    f.write("canvas 40 7 19\n")
empty_vol, empty_ply = os.path.join(out, "empty.lvdv"), os.path.join(out, "empty.ply")
code, err = run("script", empty_script, "--out", empty_vol, "--mesh", empty_ply)
warnings = [line for line in err.splitlines() if line.startswith("warning:")]
assert code == 0 and len(warnings) == 1 and "no surface" in warnings[0] and os.path.exists(empty_ply), (code, err)
code, err = run("mesh", empty_vol, os.path.join(out, "empty.stl"))
warnings = [line for line in err.splitlines() if line.startswith("warning:")]
assert code == 0 and len(warnings) == 1 and "no surface" in warnings[0], (code, err)
# the same for a one-voxel volume, in every mesh format (it had no points
# object and the writers refused it, naming the temporary file). No editor
# makes one (a canvas needs 2 voxels per axis, the same words in every front
# end): it comes from a one-point .vti.
one_script, one_vti, one_vol = os.path.join(out, "one.lvs"), os.path.join(out, "one.vti"), os.path.join(out, "one.lvdv")
with open(one_script, "w") as f:
    f.write("canvas 1 1 1\n")
if os.path.exists(one_vol):
    os.remove(one_vol)  # made by the convert below in an earlier run
code, err = run("script", one_script, "--out", one_vol)
assert code == 1 and err.startswith(f"lvdif script: {one_script}:1:") and err.endswith(
    ": a canvas of 1 x 1 x 1 voxels cannot be edited: each axis needs 2..1048576 voxels (marching cubes needs one cell per axis)"
) and not os.path.exists(one_vol), (code, err)
wide_script = os.path.join(out, "wide.lvs")
with open(wide_script, "w") as f:
    f.write("canvas 1048577 2 2\n")
code, err = run("script", wide_script, "--out", one_vol)
assert code == 1 and err.startswith(f"lvdif script: {wide_script}:1:") and err.endswith(
    ": a canvas of 1048577 x 2 x 2 voxels cannot be edited: each axis needs 2..1048576 voxels (marching cubes needs one cell per axis)"
) and not os.path.exists(one_vol), (code, err)
with open(one_vti, "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
            '<ImageData WholeExtent="0 0 0 0 0 0" Origin="0 0 0" Spacing="1 1 1"><Piece Extent="0 0 0 0 0 0">\n'
            '<PointData Scalars="sdf"><DataArray type="Float32" Name="sdf" format="ascii">2</DataArray></PointData>\n'
            '<CellData></CellData></Piece></ImageData></VTKFile>\n')
code, err = run("convert", one_vti, one_vol)
assert code == 0, (code, err)
for ext in ("ply", "obj", "stl", "vtp"):
    code, err = run("mesh", one_vol, os.path.join(out, "one." + ext))
    assert code == 0 and "tmp" not in err and os.path.exists(os.path.join(out, "one." + ext)), (ext, code, err)
# a save that fails is not "save volume: done" either (.bv holds cubic volumes only)
code, err = run("convert", empty_vol, os.path.join(out, "empty.bv"))
assert code == 1 and "save volume: done" not in err and "cubic" in err and not os.path.exists(os.path.join(out, "empty.bv")), (code, err)
# lvdif script --out x.bv: the output's rule on the result's dimensions before the script's edits
# (a non-cubic canvas failed only when saving, after the whole script: "script: done" came first)
ns_script = os.path.join(out, "noncubic.lvs")
with open(ns_script, "w") as f:
    f.write("canvas 32 32 16\nsphere 16 16 8 5\n")
ns_bv = os.path.join(out, "noncubic.bv")
r = subprocess.run([exe, "script", ns_script, "--out", ns_bv], capture_output=True, text=True, timeout=60)
assert r.returncode == 1 and "edits" not in r.stdout and r.stderr.strip() == (
    f"lvdif script: {ns_script}:1:1: cannot write '{ns_bv}': .bv holds only cubic volumes; this one is 32 x 32 x 16"
), r
assert not os.path.exists(ns_bv)
ns_vol = os.path.join(out, "noncubic.lvdv")
assert run("script", ns_script, "--out", ns_vol)[0] == 0
keep_script = os.path.join(out, "keep.lvs")
with open(keep_script, "w") as f:
    f.write("sphere 16 16 8 5\n")
r = subprocess.run([exe, "script", keep_script, "--in", ns_vol, "--out", ns_bv], capture_output=True, text=True, timeout=60)
assert r.returncode == 1 and "edits" not in r.stdout and r.stderr.strip().splitlines()[-1] == (
    f"lvdif script: cannot write '{ns_bv}': .bv holds only cubic volumes; this one is 32 x 32 x 16"), r
r = subprocess.run([exe, "play", rec, "--in", ns_vol, "--out", ns_bv], capture_output=True, text=True, timeout=60)
assert r.returncode == 1 and "replayed" not in r.stdout and r.stderr.strip().splitlines()[-1] == (
    f"lvdif play: cannot write '{ns_bv}': .bv holds only cubic volumes; this one is 32 x 32 x 16 (the volume of --in)"), r
# a .lvdv's dimensions come from its header: refused before the volume is read (it was read whole first,
# "read volume: done", and convert's refusal came from the writer)
assert "read volume" not in r.stderr, r
r = subprocess.run([exe, "convert", ns_vol, ns_bv], capture_output=True, text=True, timeout=60)
assert r.returncode == 1 and r.stderr.strip() == (
    f"lvdif convert: cannot write '{ns_bv}': .bv holds only cubic volumes; this one is 32 x 32 x 16 (the volume of {ns_vol})"), r
assert not os.path.exists(ns_bv)
code, err = run("script", keep_script, "--size", "32", "--out", os.path.join(out, "SDF_64_keep.bv"))
assert code == 1 and err.endswith("file name says N = 64 but the volume's edge is 32"), (code, err)
# a face of more corners than lvdif::MaxPolygonCorners (65,536): one error naming the file, the line and the count
big_face = os.path.join(out, "bigface.obj")
with open(big_face, "w") as f:
    f.write("".join(f"v {i} {i % 7} 0\n" for i in range(65537)))
    f.write("f " + " ".join(str(i + 1) for i in range(65537)) + "\n")
code, err = run("mesh-to-sdf", big_face, os.path.join(out, "bigface.lvdv"), "--dims", "16")
assert code == 1 and err.splitlines()[-1] == (
    f"lvdif mesh-to-sdf: cannot read '{big_face}': OBJ line 65538: a face of 65537 corners: at most 65536 corners a face "
    "(lvdif::MaxPolygonCorners; split or triangulate it first)"), (code, err)
# .vdb keeps the volume's band (the writer's default of 3 narrowed a band of 8 to 3 without a word)
cube_vol = os.path.join(out, "cube8.lvdv")
assert run("script", keep_script, "--size", "32", "--out", cube_vol)[0] == 0
code, err = run("convert", cube_vol, os.path.join(out, "cube8.vdb"))
if "vdb" in err and "format" in err and code != 0:
    print("no OpenVDB in this build: .vdb band not checked")
else:
    assert code == 0 and "warning" not in err, (code, err)
    back = os.path.join(out, "cube8-back.lvdv")
    assert run("convert", os.path.join(out, "cube8.vdb"), back)[0] == 0
    r = subprocess.run([exe, "info", back], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and ", band 8\n" in r.stdout, r.stdout
    # a .lvdv of unequal spacing (which a level set cannot hold) to .vdb: refused from the header, before
    # the volume is read (it was read whole, then the writer refused it). The oracle: a chunk's payload
    # is damaged, so a whole read fails on it; the refusal comes first, naming the spacing.
    n = 16
    values = " ".join(f"{((x - 7.5) ** 2 + (2 * (y - 7.5)) ** 2 + (z - 7.5) ** 2) ** 0.5 - 6:.4f}"
                      for z in range(n) for y in range(n) for x in range(n))
    aniso_vti = os.path.join(out, "aniso.vti")
    with open(aniso_vti, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
                f'<ImageData WholeExtent="0 {n - 1} 0 {n - 1} 0 {n - 1}" Origin="0 0 0" Spacing="1 2 1">\n'
                f'<Piece Extent="0 {n - 1} 0 {n - 1} 0 {n - 1}"><PointData Scalars="sdf">\n'
                f'<DataArray type="Float32" Name="sdf" format="ascii">{values}</DataArray>\n'
                "</PointData></Piece></ImageData></VTKFile>\n")
    aniso = os.path.join(out, "aniso.lvdv")
    code, err = run("convert", aniso_vti, aniso)
    assert code == 0, (code, err)
    r = subprocess.run([exe, "info", aniso, "--header-only"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "spacing 1 2 1" in r.stdout, r
    with open(aniso, "rb") as f:
        data = bytearray(f.read())
    table_offset = struct.unpack_from("<Q", data, len(data) - 32)[0]
    payloads = [struct.unpack_from("<QI", data, e) for e in range(table_offset, len(data) - 32, 24)]
    at, size = next(p for p in payloads if p[1] > 0)
    data[at + size // 2] ^= 0x04
    aniso_damaged = os.path.join(out, "aniso-damaged.lvdv")
    with open(aniso_damaged, "wb") as f:
        f.write(data)
    assert run("info", aniso_damaged)[0] == 1  # a whole read fails on the payload
    aniso_vdb = os.path.join(out, "aniso.vdb")
    with open(aniso_vdb, "wb") as f:
        f.write(b"old")
    refusal = (f"cannot write '{aniso_vdb}': OpenVDB export needs isotropic spacing (a level set has one distance "
               "unit); the volume has spacing 1.000000, 2.000000, 1.000000")
    r = subprocess.run([exe, "convert", aniso_damaged, aniso_vdb], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and "read volume" not in r.stderr and r.stderr.strip() == (
        f"lvdif convert: {refusal} (the volume of {aniso_damaged})"), r
    # play likewise, before its volume is read and the recording replayed
    r = subprocess.run([exe, "play", rec, "--in", aniso_damaged, "--out", aniso_vdb], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 1 and "read volume" not in r.stderr and "replayed" not in r.stdout and \
        r.stderr.strip().splitlines()[-1] == f"lvdif play: {refusal} (the volume of --in)", r
    assert open(aniso_vdb, "rb").read() == b"old"
    # script --in likewise, before the script runs (it ran the whole script, then the save refused it)
    r = subprocess.run([exe, "script", keep_script, "--in", aniso, "--out", aniso_vdb], capture_output=True,
                       text=True, timeout=60)
    assert r.returncode == 1 and "edits" not in r.stdout and r.stderr.strip().splitlines()[-1] == (
        f"lvdif script: {refusal}"), r
    assert open(aniso_vdb, "rb").read() == b"old"
    # a .vti of unequal spacing likewise, from its header (it was read whole, then refused): its data is
    # cut short (a whole read fails on it), and the refusal comes first, naming the spacing
    with open(aniso_vti) as f:
        text = f.read()
    cut_vti = os.path.join(out, "aniso-cut.vti")
    with open(cut_vti, "w") as f:
        f.write(text.replace(values, values[:len(values) // 2]))
    assert run("convert", cut_vti, os.path.join(out, "aniso-cut.lvdv"))[0] == 1  # a whole read fails on it
    r = subprocess.run([exe, "convert", cut_vti, aniso_vdb], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and r.stderr.strip() == f"lvdif convert: {refusal} (the volume of {cut_vti})", r
    assert open(aniso_vdb, "rb").read() == b"old"
print("error handling OK")
# errors about the mesh found after reading it say which file (they named none: "fit grid: the mesh
# bounds have zero size", "mesh has no triangle of non-zero area")
flat = os.path.join(out, "one-point.obj")
with open(flat, "w") as f:
    f.write("v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n")
code, err = run("mesh-to-sdf", flat, os.path.join(out, "flat.lvdv"), "--dims", "16")
assert code == 1 and err.splitlines()[-1].startswith(f"lvdif mesh-to-sdf: mesh '{flat}': "), (code, err)
assert not os.path.exists(os.path.join(out, "flat.lvdv"))
line = os.path.join(out, "line.obj")
with open(line, "w") as f:
    f.write("v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n")
code, err = run("mesh-to-sdf", line, os.path.join(out, "line.lvdv"), "--dims", "16")
# the last line: a CUDA build without a usable GPU prints its one notice first
assert code == 1 and err.splitlines()[-1] == f"lvdif mesh-to-sdf: mesh '{line}': the mesh's only triangle has zero area " \
    "(its corners coincide or lie on one line), so there is no surface to convert: check the file's points and faces", (code, err)
# the usage of mesh-to-sdf names every volume format it writes (it left out .lvdvp, which it writes)
r = subprocess.run([exe, "mesh-to-sdf", "--help"], capture_output=True, text=True, timeout=60)
listed = r.stdout.split("OUT.(", 1)[1].split(")", 1)[0].split("|")
r = subprocess.run([exe, "help"], capture_output=True, text=True, timeout=60)
assert "mesh-to-sdf MESH OUT.(" + "|".join(listed) + ")" in r.stdout, (listed, r.stdout)
tetra = os.path.join(out, "tetra.obj")
with open(tetra, "w") as f:
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
for ext in ("lvdv", "lvdvp", "bv", "vti", "vdb"):
    code, err = run("mesh-to-sdf", tetra, os.path.join(out, "tetra-out." + ext), "--dims", "12")
    assert (code == 0) == (ext in listed), (ext, listed, code, err)
# files named as pieces of a .lvdvp that has no index yet (a user's scan_1.lvdv beside a first write of
# scan.lvdvp) are another volume's: refused before the work, kept byte for byte (scan_0.lvdv was
# overwritten and the others removed as the set's old pieces)
users = os.path.join(out, "scan_1.lvdv")
assert run("mesh-to-sdf", tetra, users, "--dims", "12")[0] == 0
with open(users, "rb") as f:
    users_bytes = f.read()
scan = os.path.join(out, "scan.lvdvp")
if os.path.exists(scan):
    os.remove(scan)
code, err = run("convert", users, scan)
assert code == 2 and err.splitlines()[-1] == (
    f"lvdif convert: cannot write '{scan}': 'scan_1.lvdv' lies beside it, named as a piece of its set, but no index "
    "lists them (another volume's files?), and writing the set would overwrite or remove them: move them, or choose "
    "another name"), (code, err)
assert not os.path.exists(scan) and open(users, "rb").read() == users_bytes
# a refused command line's usage is the synopsis of the command's help (the usage lines were copies of
# it that drifted: play's and script's said --mesh OUT.ply, mesh-to-sdf's left out .lvdvp)
for cmd in ("info", "mesh", "convert", "mesh-to-sdf", "script", "play"):
    r = subprocess.run([exe, cmd, "--help"], capture_output=True, text=True, timeout=60)
    synopsis = r.stdout.splitlines()[0].split("   ")[0]
    code, err = run(cmd)
    assert code == 2 and err.splitlines()[-1] == "lvdif " + cmd + ": " + synopsis, (cmd, code, err, synopsis)
# a save on a full disk (here a file size limit: the writes fail with EFBIG, as with ENOSPC) fails with one line
# naming the file and keeps the old file byte for byte: the PLY and OBJ writers and OpenVDB said nothing and the cut
# file replaced the old one (status 0), and VTK's XML writers' failure was the executive's dump of a dozen lines
import resource  # noqa: E402
import signal  # noqa: E402


def file_size_limit():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (4096, resource.RLIM_INFINITY))


full_vol = os.path.join(out, "full.lvdv")
assert run("mesh-to-sdf", tetra, full_vol, "--dims", "48")[0] == 0
for name, cmd in (("full.ply", "mesh"), ("full.obj", "mesh"), ("full.stl", "mesh"), ("full.vtp", "mesh"),
                  ("full.vdb", "convert"), ("full.vti", "convert")):
    target = os.path.join(out, name)
    with open(target, "w") as f:
        f.write("the old file")
    r = subprocess.run([exe, cmd, full_vol, target], capture_output=True, text=True, timeout=120,
                       preexec_fn=file_size_limit)
    if name == "full.vdb" and "vdb" in r.stderr and "format" in r.stderr and "cannot write" not in r.stderr:
        os.remove(target)
        continue  # no OpenVDB in this build
    said = [line for line in r.stderr.splitlines() if not line.endswith(": done") and "CUDA" not in line]
    assert (r.returncode == 1 and len(said) == 1 and said[0].startswith(f"lvdif {cmd}: ")
            and f"cannot write '{target}': " in said[0]), (name, r.returncode, r.stderr)
    with open(target, "rb") as f:
        assert f.read() == b"the old file", name
    os.remove(target)
os.remove(full_vol)
