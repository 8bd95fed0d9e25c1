#include "lvdif/Cuda.h"

#include <atomic>
#include <cstdio>

namespace lvdif
{

Device resolveDevice(Device requested)
{
  if (requested == Device::Cpu)
  {
    return Device::Cpu;
  }
  if (cuda::available())
  {
    return Device::Cuda;
  }
  static std::atomic<bool> noticed{ false };
  if (!noticed.exchange(true) && (requested == Device::Cuda || cuda::compiled()))
  {
    std::fprintf(stderr, "lvdif: %s; using the CPU\n",
      cuda::compiled() ? "no usable CUDA device" : "built without CUDA");
  }
  return Device::Cpu;
}

const char* toString(Device d)
{
  switch (d)
  {
    case Device::Auto: return "auto";
    case Device::Cpu: return "cpu";
    case Device::Cuda: return "cuda";
  }
  return "?";
}

} // namespace lvdif
