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
/// Chooses the writer from the extension (.ply .obj .stl .vtp); throws lvdif::Error on failure.
void WriteMesh(vtkPolyData* mesh, const std::string& path);
/// Renders the coloured mesh from a 3/4 view into a PNG of the given size.
void RenderPng(vtkPolyData* mesh, const std::string& path, int width = 800, int height = 600);
