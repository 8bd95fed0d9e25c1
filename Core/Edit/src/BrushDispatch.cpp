#include "lvdif/BrushCuda.h"

namespace lvdif
{

EditResult applyDabs(Device device, DictionaryVolume& volume, const std::vector<Dab>& dabs,
  const BrushSettings& settings, ChunkWriteObserver* observer)
{
  if (resolveDevice(device) == Device::Cuda)
  {
    return cuda::applyDabs(volume, dabs, settings, observer);
  }
  return applyDabs(volume, dabs, settings, observer);
}

} // namespace lvdif
