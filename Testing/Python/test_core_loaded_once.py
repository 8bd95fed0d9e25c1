"""Core is linked once per process: after importing every lvdif VTK module, the
process maps exactly one LVDIFCore library, and no module carries a copy of
Core's code (its symbols are undefined in every module, defined only in the
library). Before, each of the nine modules linked a static Core, so a process
held up to nine copies of its globals (the memory limit, the device notice)."""
import glob
import os
import subprocess
import sys

import lvdif  # noqa: F401  (loads every module of the package)
from lvdif import (lvdifFiltersEditing, lvdifFiltersMeshing, lvdifFiltersSDF,  # noqa: F401
                   lvdifFiltersVolume, lvdifIOVolume, lvdifIOMesh)

maps = open("/proc/self/maps").read().splitlines()
core = sorted({line.split()[-1] for line in maps if "libLVDIFCore" in line})
assert len(core) == 1, "expected one LVDIFCore mapped, found: %s" % core
modules = sorted({line.split()[-1] for line in maps if "/liblvdif" in line and "LVDIFCore" not in line})
assert modules, "no lvdif VTK module library mapped"

# lvdif::libraryVersion() is defined in LVDIFCore only
symbol = "_ZN5lvdif14libraryVersionEv"
def defines(path):
    out = subprocess.run(["nm", "-D", "--defined-only", path], capture_output=True, text=True, check=True).stdout
    return any(line.split()[-1] == symbol for line in out.splitlines() if line.strip())
assert defines(core[0]), "%s does not define %s" % (core[0], symbol)
copies = [m for m in modules if defines(m)]
assert not copies, "modules with their own copy of Core: %s" % copies
print("one LVDIFCore (%s) shared by %d modules" % (os.path.basename(core[0]), len(modules)))
