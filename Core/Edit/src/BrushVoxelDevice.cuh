// The per-voxel dab loop shared by the two CUDA brush paths (Brush.cu, which
// round-trips chunks per call, and DeviceVolume.cu, which keeps them resident):
// applies every dab group (a dab and its mirror images) whose box holds the voxel, with the CPU's rule
// (BrushKernel.h), and returns the voxel's new packed value (sdf | colour << 16).
#pragma once

#include "BrushKernel.h"

#include <cstdint>

namespace lvdif
{
namespace detail::edit
{

/// A dab's inclusive voxel box on the device.
struct DeviceDabBox
{
  long long lo[3], hi[3];
};

__device__ inline std::uint32_t applyDabsToVoxel(std::uint32_t v, long long x, long long y, long long z,
  const Dab* dabs, const DeviceDabBox* boxes, int nDabs, const BrushContext& ctx, const float* table,
  const EncodeParams& enc)
{
  std::uint16_t sdf = static_cast<std::uint16_t>(v & 0xffffu);
  std::uint16_t color = static_cast<std::uint16_t>(v >> 16);
  const int nGroups = nDabs / ctx.groupSize;
  for (int g = 0; g < nGroups; ++g)
    applyGroupToVoxel(sdf, color, x, y, z, dabs, boxes, g, ctx, table, enc);
  return static_cast<std::uint32_t>(sdf) | (static_cast<std::uint32_t>(color) << 16);
}

} // namespace detail::edit
} // namespace lvdif
