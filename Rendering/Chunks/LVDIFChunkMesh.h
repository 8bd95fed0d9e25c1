// lvdif::ChunkMesh -> vtkPolyData with the rendering contract of
// Rendering/Chunks: point data `Normals` and `rgba`, cell data
// `corner_rgba` (8 corners x RGBA from the colour dictionary) and `cell_ijk`.
// (The marching cubes VTK filter produces the same arrays for a whole
// volume; this converts the chunks of lvdif::MarchingCubesWorker one by one.)
#ifndef LVDIFChunkMesh_h
#define LVDIFChunkMesh_h

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdifRenderingChunksModule.h" // for export macro

#include "vtkSmartPointer.h"

#include <vector>

class vtkPolyData;

namespace LVDIFChunkMesh
{
/// `pointDims` are the volume's point dimensions (to split the linear cell index).
LVDIFRENDERINGCHUNKS_EXPORT vtkSmartPointer<vtkPolyData> ToPolyData(
  const lvdif::ChunkMesh& mesh, const lvdif::ColorDictionary& colors, const lvdif::Index3& pointDims);

}

#endif
