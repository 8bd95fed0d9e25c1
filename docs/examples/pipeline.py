#!/usr/bin/python3
"""LVDIF from Python with the system VTK: mesh -> SDF -> sign repair -> surface -> file.

Run with Debian's interpreter (the pyenv `python3` cannot see VTK):
    PYTHONPATH=<build>/lib/python3/dist-packages /usr/bin/python3 docs/examples/pipeline.py OUTDIR

Every LVDIF class is an ordinary VTK algorithm: connect it with
SetInputConnection and call Update. Between the LVDIF filters the volume
travels as a vtkSparseDictionaryVolume (the sparse dictionary volume itself,
no dense image); vtkSparseVolumeToImage makes a dense vtkImageData when one
is really wanted, and generic VTK filters (Contour, Cutter) run on its
partitions.

Stages whose LVDIF class is not in this build yet use the plain-VTK equivalent
and say so (see docs/PYTHON.md); the printed numbers are checked by
Testing/Python against the analytic sphere.
"""
import math
import os
import sys

import vtkmodules.all as vtk  # noqa: F401 (VTK's own classes)
import lvdif
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D, vtkMassProperties, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkCommonDataModel import vtkSphere
from vtkmodules.vtkFiltersCore import vtkArrayCalculator
from vtkmodules.vtkImagingHybrid import vtkSampleFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter, vtkXMLPolyDataWriter

RADIUS, HALF, N = 1.0, 1.25, 64  # sphere radius, grid half-width, grid points per axis
H = 2 * HALF / (N - 1)           # voxel size


def mesh():
    s = vtkSphereSource()
    s.SetRadius(RADIUS)
    s.SetThetaResolution(96)
    s.SetPhiResolution(96)
    return s


def signed_distance(m):
    """Float point array `sdf`, voxel units, negative inside."""
    if hasattr(lvdif, "vtkMeshToSDF"):
        sdf = lvdif.vtkMeshToSDF()
        sdf.SetInputConnection(m.GetOutputPort())
        sdf.SetUseExplicitGrid(True)  # or a grid fitted to the mesh: SetMaxDimension(n), SetPadding(v)
        sdf.SetDimensions(N, N, N)
        sdf.SetOrigin(-HALF, -HALF, -HALF)
        sdf.SetSpacing(H, H, H)
        sdf.SetSignMode(lvdif.vtkMeshToSDF.WINDING_NUMBER)
        print("SDF: vtkMeshToSDF (winding-number signs)")
        return sdf
    # Stand-in until vtkMeshToSDF lands: the analytic sphere the mesh
    # approximates, sampled on the grid (vtkImplicitPolyDataDistance on the
    # mesh itself gets hundreds of voxel signs wrong on this sphere: exactly
    # what vtkSignVoxelFilter is for, but not a stand-in for a correct SDF).
    sphere = vtkSphere()
    sphere.SetRadius(RADIUS)
    sample = vtkSampleFunction()
    sample.SetImplicitFunction(sphere)
    sample.SetModelBounds(-HALF, HALF, -HALF, HALF, -HALF, HALF)
    sample.SetSampleDimensions(N, N, N)
    sample.SetOutputScalarTypeToFloat()
    sample.ComputeNormalsOff()
    sample.SetScalarArrayName("sdf")
    # vtkSphere evaluates |p|^2 - R^2; make it a distance in voxel units.
    calc = vtkArrayCalculator()
    calc.SetInputConnection(sample.GetOutputPort())
    calc.AddScalarArrayName("sdf")
    calc.SetFunction("(sqrt(sdf + %r) - %r) / %r" % (RADIUS * RADIUS, RADIUS, H))
    calc.SetResultArrayName("sdf")
    calc.SetResultArrayType(vtk.VTK_FLOAT)
    print("SDF: stand-in, analytic sphere (vtkMeshToSDF not in this build)")
    return calc


def repair_signs(sdf):
    if not hasattr(lvdif, "vtkSignVoxelFilter"):
        print("SVF: skipped (vtkSignVoxelFilter not in this build)")
        return sdf
    svf = lvdif.vtkSignVoxelFilter()
    svf.SetInputConnection(sdf.GetOutputPort())
    svf.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "sdf")
    svf.SetThreshold(2.0)  # never flip voxels within 2 voxels of the surface
    print("SVF: vtkSignVoxelFilter")
    return svf


def surface(field):
    if hasattr(lvdif, "vtkChunkedMarchingCubes"):
        mc = lvdif.vtkChunkedMarchingCubes()
        mc.SetInputConnection(field.GetOutputPort())
        mc.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "sdf")
        mc.SetIsoValue(0.0)
        mc.SetOutputModeToMerged()  # one watertight vtkPolyData (default: one per chunk)
        mc.SetChunkEdge(32)
        print("surface: vtkChunkedMarchingCubes")
        return mc
    fe = vtkFlyingEdges3D()
    fe.SetInputConnection(field.GetOutputPort())
    fe.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "sdf")
    fe.SetValue(0, 0.0)
    print("surface: vtkFlyingEdges3D (vtkChunkedMarchingCubes not in this build)")
    return fe


def write(field, surf, outdir):
    """The volume as a dictionary volume file (.lvdv), read back to check; the surface as .vtp."""
    path = os.path.join(outdir, "sphere.lvdv")
    if hasattr(lvdif, "vtkDictionaryVolumeWriter"):
        w = lvdif.vtkDictionaryVolumeWriter()
        w.SetInputConnection(field.GetOutputPort())
        w.SetFileName(path)
        # the sparse volume is written as it is (its band, 8 voxels by default, and chunks)
        w.SetVolumeName("sphere")
        if not w.Write():
            raise RuntimeError("writing %s failed" % path)
        r = lvdif.vtkDictionaryVolumeReader()
        r.SetFileName(path)
        r.Update()
        v = r.GetOutput()  # a vtkSparseDictionaryVolume: no dense image
        print("volume: %s, %d bytes, read back %d of %d chunks holding voxels, name '%s'" % (
            os.path.basename(path), os.path.getsize(path), v.GetNumberOfExpandedChunks(), v.GetNumberOfChunks(),
            r.GetMetadata("name")))
    else:
        path = os.path.join(outdir, "sphere_sdf.vti")
        w = vtkXMLImageDataWriter()
        w.SetInputConnection(field.GetOutputPort())
        w.SetFileName(path)
        w.Write()
        print("volume: %s (vtkDictionaryVolumeWriter not in this build)" % os.path.basename(path))
    p = vtkXMLPolyDataWriter()
    p.SetInputConnection(surf.GetOutputPort())
    p.SetFileName(os.path.join(outdir, "sphere_surface.vtp"))
    p.Write()


def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    field = repair_signs(signed_distance(mesh()))
    surf = surface(field)
    surf.Update()
    tri = vtkTriangleFilter()
    tri.SetInputConnection(surf.GetOutputPort())
    props = vtkMassProperties()
    props.SetInputConnection(tri.GetOutputPort())
    props.Update()
    write(field, surf, outdir)
    area, volume = props.GetSurfaceArea(), props.GetVolume()
    print("triangles %d  area %.5f (sphere %.5f)  volume %.5f (ball %.5f)" % (
        surf.GetOutput().GetNumberOfCells(), area, 4 * math.pi * RADIUS ** 2, volume, 4 / 3 * math.pi * RADIUS ** 3))
    return area, volume


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "pipeline-out")
