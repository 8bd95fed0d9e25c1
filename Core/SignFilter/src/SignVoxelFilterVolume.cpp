// Sign voxel filters on a DictionaryVolume: decode to a dense grid, filter,
// write back the flipped voxels chunk by chunk (one thread per chunk, so no
// two threads write one chunk).
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Memory.h"
#include "lvdif/SignVoxelFilter.h"

#include <exception>
#include <vector>

namespace lvdif
{

SignVoxelFilterStats signVoxelFilter(
  DictionaryVolume& volume, const SignVoxelFilterParams& params, Interrupter& interrupter)
{
  const Index3 d = volume.dims();
  const std::uint64_t bytes =
    checkedMultiply(static_cast<std::uint64_t>(volume.voxelCount()), sizeof(float), "sign voxel filter grid");
  requireMemory(bytes, "dense copy of the volume for the sign voxel filters");
  std::vector<float> grid(static_cast<std::size_t>(volume.voxelCount()));
#pragma omp parallel for schedule(static)
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        grid[static_cast<std::size_t>(x + d[0] * (y + d[1] * z))] = volume.sdf(x, y, z);

  FloatGridView view;
  view.data = grid.data();
  view.geometry.dims = d;
  const SignVoxelFilterStats stats = signVoxelFilter(view, params, interrupter);

  const SdfKey zero = volume.sdfDictionary().zeroKey();
  // expandChunk may throw OutOfMemory; an exception must not leave the OpenMP
  // region, so the first one is kept and rethrown after it
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t id = 0; id < volume.chunkCount(); ++id)
  {
    try
    {
      const VoxelBox b = volume.chunkBox(id);
      bool wrote = false;
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          {
            const float v = grid[static_cast<std::size_t>(x + d[0] * (y + d[1] * z))];
            Voxel old = volume.get(x, y, z);
            // the filters only negate, so a changed sign is a flipped voxel
            if ((v < 0.0f) != (old.sdf < zero))
            {
              old.sdf = volume.encode(v);
              volume.set(x, y, z, old);
              wrote = true;
            }
          }
      if (wrote)
      {
        volume.tryCollapseChunk(id);
      }
    }
    catch (...)
    {
#pragma omp critical(lvdif_svf_volume_failure)
      if (!failure)
      {
        failure = std::current_exception();
      }
    }
  }
  if (failure)
  {
    std::rethrow_exception(failure); // the volume then holds part of the flips
  }
  return stats;
}

} // namespace lvdif
