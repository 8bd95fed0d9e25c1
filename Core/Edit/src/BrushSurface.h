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

/// Bit i = (row[i].sdf >= isoKey), n <= 64.
std::uint64_t sideBits(const Voxel* row, std::int64_t n, std::int32_t isoKey);

/// What the brush noted in one chunk: its changed voxels whose side of the iso
/// value did not change (`rows`), and the sides after the edit of the voxels it
/// computed (`sides` where `known`): one bit per voxel, one word per row (row
/// y + E z in the chunk, bit x). Empty vectors: nothing noted.
struct SurfacePending
{
  std::vector<std::uint64_t> rows, sides, known;
  void set(std::int64_t lx, std::int64_t ly, std::int64_t lz, std::int64_t edge)
  {
    if (this->rows.empty())
      this->rows.assign(static_cast<std::size_t>(edge * edge), 0);
    this->rows[static_cast<std::size_t>(ly + edge * lz)] |= std::uint64_t(1) << lx;
  }
  /// The final sides of voxels lx0 .. lx0 + n - 1 of a row (bits from bit 0).
  void noteSides(std::int64_t lx0, std::int64_t n, std::int64_t ly, std::int64_t lz, std::uint64_t bits, std::int64_t edge)
  {
    if (this->known.empty())
    {
      this->known.assign(static_cast<std::size_t>(edge * edge), 0);
      this->sides.assign(static_cast<std::size_t>(edge * edge), 0);
    }
    const std::size_t r = static_cast<std::size_t>(ly + edge * lz);
    const std::uint64_t span = (n >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1) << lx0;
    this->known[r] |= span;
    this->sides[r] = (this->sides[r] & ~span) | (bits << lx0);
  }
};

/// Grows `box` by every pending voxel v of chunk `id` (pending[i] belongs to
/// chunks[i], increasing ids) that a mesh could read (BrushSurface.cpp): v's
/// 3^3 box together with the 6 voxels 2 away from v along an axis (those in the
/// volume) hold both sides of isoKey in the volume as it is now (the noted sides
/// where known, else read). Reads only (safe in parallel once every write of the
/// edit is done).
void addMixedPending(const DictionaryVolume& volume, std::int32_t isoKey, std::int64_t id,
  const std::vector<std::int64_t>& chunks, const std::vector<SurfacePending>& pending, VoxelBox& box);

} // namespace detail::edit
} // namespace lvdif
