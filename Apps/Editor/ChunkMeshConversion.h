// lvdif::ChunkMesh -> vtkPolyData with the rendering contract of
// Rendering/Chunks: point data `Normals` and `rgba`, cell data
// `corner_rgba` (8 corners x RGBA from the colour dictionary) and `cell_ijk`.
// (The marching cubes VTK filter will produce the same arrays; this keeps
// the editor independent of it.)
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"

#include "vtkSmartPointer.h"

class vtkPolyData;

/// `pointDims` are the volume's point dimensions (to split the linear cell index).
vtkSmartPointer<vtkPolyData> chunkMeshToPolyData(
  const lvdif::ChunkMesh& mesh, const lvdif::ColorDictionary& colors, const lvdif::Index3& pointDims);
