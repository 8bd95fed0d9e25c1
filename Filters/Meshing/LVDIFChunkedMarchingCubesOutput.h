/**
 * @file   LVDIFChunkedMarchingCubesOutput.h
 * @brief  lvdif::ChunkMesh -> vtkPolyData (one chunk, or all chunks merged)
 *
 * The one conversion of Core's chunk meshes: vtkChunkedMarchingCubes' outputs
 * and the editors' chunk actors (VolumeChunkToPolyData). Array names: point
 * `Normals`, `rgba`; cell `cell_ijk` (int x3), `corner_rgba` (unsigned char
 * x32), the rendering contract of Rendering/Chunks.
 */
#ifndef LVDIFChunkedMarchingCubesOutput_h
#define LVDIFChunkedMarchingCubesOutput_h

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdifFiltersMeshingModule.h" // for export macro

#include "vtkSmartPointer.h"

#include <functional>
#include <vector>

class vtkPolyData;
namespace lvdif
{
class DictionaryVolume;
}

namespace LVDIFChunkedMarchingCubesOutput
{
struct Context
{
  lvdif::Index3 gridDims{ 0, 0, 0 }; // points of the meshed grid (decodes edgeIds, triangleCells)
  int extentLo[3] = { 0, 0, 0 };     // structured index of the grid's point 0
  const lvdif::Rgba* colors = nullptr; // one per grid point (corner_rgba), or null
  const lvdif::Rgba* palette = nullptr; // or: colour of each key of ChunkMesh::cornerColors (dictionary volumes)
  bool normals = false;
  bool pointColors = false;
  bool cellData = false; // cell_ijk (+ corner_rgba when colors)
};

/// One chunk's mesh as it is (boundary vertices not shared with neighbours).
vtkSmartPointer<vtkPolyData> ChunkToPolyData(const lvdif::ChunkMesh& mesh, const Context& ctx);

/// One chunk mesh of a dictionary volume (from lvdif::MarchingCubesWorker or an
/// edit session) with the arrays it carries: normals, point colours, and the
/// corner colours (keys of the volume's colour dictionary) with `cell_ijk`.
LVDIFFILTERSMESHING_EXPORT vtkSmartPointer<vtkPolyData> VolumeChunkToPolyData(
  const lvdif::ChunkMesh& mesh, const lvdif::DictionaryVolume& volume);

/// All chunks in one mesh, one point per cut grid edge: only the points on a
/// chunk's faces are looked up in a hash map, the rest are unique by construction.
vtkSmartPointer<vtkPolyData> MergeChunks(const std::vector<lvdif::ChunkMesh>& meshes, const Context& ctx);

/// The same merge over chunk meshes made batch by batch, so only one batch
/// is held at a time: batch(b, pass) returns batch b's meshes and is called
/// twice for every batch (pass 0 counts, pass 1 fills the arrays, allocated
/// once at their final size). For volumes far larger than their surface:
/// the face points' edge ids are kept in a sorted array (16 bytes a point
/// with their ids), which is held while the output is filled.
vtkSmartPointer<vtkPolyData> MergeBatches(
  const std::function<std::vector<lvdif::ChunkMesh>(std::size_t, int)>& batch, std::size_t batches,
  const Context& ctx);
}

#endif
