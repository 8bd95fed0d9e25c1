// Which of an edit's changed voxels can change a marching cubes mesh (the
// brush's EditResult::surfaceChunkBoxes); the argument is in BrushSurface.cpp.
#pragma once

#include "lvdif/DictionaryVolume.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::edit
{

/// Chunk edges up to this keep a chunk's row, grown by 2 on each side, in one 64-bit word.
constexpr int SurfaceMaskMaxEdge = 60;

/// The changed voxels of one chunk whose side of the iso value did not change:
/// one bit per voxel, one word per row (row y + E z in the chunk, bit x).
struct SurfacePending
{
  std::vector<std::uint64_t> rows;
  void set(std::int64_t lx, std::int64_t ly, std::int64_t lz, std::int64_t edge)
  {
    if (this->rows.empty())
      this->rows.assign(static_cast<std::size_t>(edge * edge), 0);
    this->rows[static_cast<std::size_t>(ly + edge * lz)] |= std::uint64_t(1) << lx;
  }
};

/// Grows `box` by every pending voxel v of chunk `id` that a mesh could read
/// (BrushSurface.cpp): v's 3^3 box together with the 6 voxels 2 away from v
/// along an axis (those in the volume) hold keys on both sides of isoKey in the
/// volume as it is now. Reads only (safe in parallel once every write of the
/// edit is done).
void addMixedPending(const DictionaryVolume& volume, std::int32_t isoKey, std::int64_t id, const SurfacePending& pending,
  VoxelBox& box);

} // namespace detail::edit
} // namespace lvdif
