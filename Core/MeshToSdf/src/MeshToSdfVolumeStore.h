// Storing a mesh-to-SDF pass into a dictionary volume (MeshToSdf.cpp's volume
// calls): the CPU's and a chunk region's bands of chunks encoded on the host,
// and the CUDA pass's groups of chunk layers encoded on the GPU, stored while
// the GPU computes the next group.
#pragma once

#include "MeshToSdfCuda.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MeshToSdf.h"

#include <cstdint>
#include <functional>

namespace lvdif
{
namespace detail::meshtosdf
{

/// The chunks of `region` (chunk coordinates), band by band: `compute` fills
/// each band's float box, which is encoded and stored on the host threads.
void volumeRegion(DictionaryVolume& volume, const VoxelBox& region, std::uint64_t bandBytes, MeshToSdfStats& stats,
  Interrupter& intr, const std::function<void(const VoxelBox&, float*, double, double)>& compute);

/// The whole volume through a CUDA session, group by group;
/// `beforeEachGroup` runs before a group's keys are fetched and stored (it
/// may throw to stop the pass there).
void volumeOnCuda(meshtosdf_cuda::Session& session, DictionaryVolume& volume, const MeshToSdfOptions& opts,
  MeshToSdfStats& stats, Interrupter& intr, const std::function<void()>& beforeEachGroup);

} // namespace detail::meshtosdf
} // namespace lvdif
