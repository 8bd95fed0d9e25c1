// CUDA runtime queries. A CUDA build on a machine without a GPU (or driver)
// reports available() == false and everything runs on the CPU.
#include "lvdif/Cuda.h"

#include <cuda_runtime.h>

namespace lvdif
{
namespace cuda
{
bool compiled() { return true; }

bool available()
{
  static const bool ok = [] {
    int n = 0;
    if (cudaGetDeviceCount(&n) != cudaSuccess || n <= 0)
    {
      cudaGetLastError(); // clear the sticky error of a missing driver
      return false;
    }
    return true;
  }();
  return ok;
}

std::string deviceName()
{
  if (!available())
  {
    return "none";
  }
  cudaDeviceProp prop;
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess)
  {
    return "unknown";
  }
  return prop.name;
}

std::size_t freeMemory()
{
  if (!available())
  {
    return 0;
  }
  std::size_t freeBytes = 0, total = 0;
  if (cudaMemGetInfo(&freeBytes, &total) != cudaSuccess)
  {
    return 0;
  }
  return freeBytes;
}
} // namespace cuda
} // namespace lvdif
