// The CUDA path for applying dabs: the same result as lvdif::applyDabs, bit for
// bit (the per-voxel rule and the dictionary encoder are shared with the CPU,
// see src/BrushKernel.h; Brush.cu is compiled without FMA contraction so the
// double arithmetic rounds like the host's). The touched chunks go to the
// device in batches bounded by free device memory; only expanded chunks are
// uploaded (uniform ones are sent as their value), only changed chunks come
// back, and the host writes the changed voxels through DictionaryVolume::set
// (dirty flags, ranges, undo observer exactly as on the CPU).
#pragma once

#include "lvdif/Brush.h"
#include "lvdif/Cuda.h"

namespace lvdif
{
namespace cuda
{
/// Error(Unsupported) in builds without CUDA; Error(DeviceFailure) on CUDA errors.
EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer = nullptr);
} // namespace cuda

/// Dispatches to the CPU or the GPU (resolveDevice: Auto picks CUDA when available).
EditResult applyDabs(Device device, DictionaryVolume& volume, const std::vector<Dab>& dabs,
  const BrushSettings& settings, ChunkWriteObserver* observer = nullptr);

} // namespace lvdif
