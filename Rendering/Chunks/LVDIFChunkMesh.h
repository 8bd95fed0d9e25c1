// lvdif::ChunkMesh -> vtkPolyData with the rendering contract of
// Rendering/Chunks: point data `Normals` and `rgba`, cell data
// `corner_rgba` (8 corners x RGBA from the colour dictionary) and `cell_ijk`.
// (The marching cubes VTK filter produces the same arrays for a whole
// volume; this converts the chunks of lvdif::MarchingCubesWorker one by one.)
#ifndef LVDIFChunkMesh_h
#define LVDIFChunkMesh_h

#include "lvdif/Brush.h"
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

/// The marching cubes chunks to re-mesh after an edit that dirtied these
/// storage chunks. A storage chunk only says "something in these 32^3 voxels
/// changed", which makes every neighbouring marching cubes chunk suspect (a
/// 2x2x2 block of dirty storage chunks gives 4^3 = 64). When the caller knows
/// a box that holds every changed voxel (a dab's centre +- radius + band),
/// only the chunks both rules name are returned (both are supersets of the
/// chunks whose mesh can change, so their intersection is too).
LVDIFRENDERINGCHUNKS_EXPORT std::vector<std::int64_t> ChunksToRemesh(const lvdif::ChunkedMarchingCubes& mc,
  const std::vector<std::int64_t>& dirtyStorageChunks, const lvdif::VoxelBox* changedBound = nullptr);

/// The marching cubes chunks to re-mesh after `edit` (an lvdif::Editor call's
/// lastWrite()) when these storage chunks are dirty: the exact set
/// chunksAffectedBy(edit.changedBox) for what the edit changed, and the
/// storage-chunk rule for dirty chunks the edit does not name (written by
/// something else since the last request). Sorted, unique.
LVDIFRENDERINGCHUNKS_EXPORT std::vector<std::int64_t> ChunksToRemesh(const lvdif::ChunkedMarchingCubes& mc,
  const std::vector<std::int64_t>& dirtyStorageChunks, const lvdif::EditResult& edit);
}

#endif
