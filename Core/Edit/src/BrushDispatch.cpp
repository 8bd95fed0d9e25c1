#include "lvdif/BrushCuda.h"

namespace lvdif
{

EditResult applyDabs(Device device, DictionaryVolume& volume, const std::vector<Dab>& dabs,
  const BrushSettings& settings, ChunkWriteObserver* observer)
{
  // Smooth, Grab and Pinch read neighbouring voxels and have no CUDA path: Auto runs
  // them on the CPU, an explicit Cuda is refused by cuda::applyDabs.
  if (resolveDevice(device) == Device::Cuda && !(device == Device::Auto && readsNeighbours(settings.op)))
  {
    return cuda::applyDabs(volume, dabs, settings, observer);
  }
  return applyDabs(volume, dabs, settings, observer);
}

} // namespace lvdif
