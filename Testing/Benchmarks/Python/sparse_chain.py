#!/usr/bin/python3
"""The sparse chain in Python: .lvdv -> vtkDictionaryVolumeReader -> vtkChunkedMarchingCubes -> .ply.

Usage: sparse_chain.py VOLUME.lvdv OUT.ply
Prints one line: triangles, seconds, whether the reader's output was ever made dense
(it must not be: the volume travels as a vtkSparseDictionaryVolume). Run it under
/usr/bin/time -v for the peak RSS (scripts/bench-sparse-chain.sh does).
"""
import sys
import time

import lvdif
from vtkmodules.vtkIOPLY import vtkPLYWriter

t0 = time.time()
reader = lvdif.vtkDictionaryVolumeReader()
reader.SetFileName(sys.argv[1])
mc = lvdif.vtkChunkedMarchingCubes()
mc.SetInputConnection(reader.GetOutputPort())
mc.SetOutputModeToMerged()
mc.ComputeCornerColorsOff()  # per-triangle shader data; a .ply has no place for it
writer = vtkPLYWriter()
writer.SetInputConnection(mc.GetOutputPort())
writer.SetFileName(sys.argv[2])
writer.SetFileTypeToBinary()
writer.SetArrayName("rgba")
writer.SetEnableAlpha(True)
if not writer.Write():
    sys.exit("writing %s failed" % sys.argv[2])
volume = reader.GetOutput()
print("triangles %d  seconds %.2f  partitions_built %s  volume_bytes %d" % (
    mc.GetOutput().GetNumberOfCells(), time.time() - t0, volume.GetPartitionsBuilt(), volume.GetVolumeMemoryBytes()))
