// Meshing a dictionary volume for the CLI: chunked marching cubes merged into
// one vtkPolyData (points, normals, rgba), written as PLY/OBJ/STL/VTP, or
// rendered off-screen to a PNG.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include "vtkSmartPointer.h"

#include <string>

class vtkPolyData;

vtkSmartPointer<vtkPolyData> MeshVolume(const lvdif::DictionaryVolume& volume, lvdif::Interrupter& interrupter);
/// Checks a mesh output before any expensive work: a known extension and a
/// writable place (lvdif::requireWritable); throws lvdif::Error.
void CheckMeshOutput(const std::string& path);
/// Checks a picture output before any expensive work: .png and writable;
/// throws lvdif::Error.
void CheckPngOutput(const std::string& path);
/// Opens the X display that rendering the picture `path` needs (Debian's VTK
/// aborts without one), held until the process exits; throws lvdif::Error.
/// Not part of the command line's check: no display is a failure (status 1).
void RequireDisplay(const std::string& path);
/// Chooses the writer from the extension (.ply .obj .stl .vtp); throws lvdif::Error on failure.
void WriteMesh(vtkPolyData* mesh, const std::string& path);
/// Both write through lvdif::saveAtomicallyByName (a failed write is an error,
/// the previous file stays). Renders the coloured mesh from a 3/4 view into a PNG of the given size.
void RenderPng(vtkPolyData* mesh, const std::string& path, int width = 800, int height = 600);
