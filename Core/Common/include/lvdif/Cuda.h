// Where work runs: the CPU (OpenMP) or a CUDA device. CUDA is optional at
// build time (LVDIF_CUDA) and at run time: resolveDevice() falls back to the
// CPU, with a one-line notice on stderr, when no device can be used.
#pragma once

#include <string>

namespace lvdif
{

enum class Device
{
  Auto, // CUDA when a device is present, else CPU
  Cpu,
  Cuda  // CUDA if at all possible; falls back to CPU with a notice
};

namespace cuda
{
/// True when this build contains CUDA kernels.
bool compiled();
/// True when compiled() and a CUDA device answers (checked once, cached).
bool available();
/// Name of device 0, or "none".
std::string deviceName();
/// Bytes of free device memory (0 without a device).
std::size_t freeMemory();
} // namespace cuda

/// Cpu or Cuda, never Auto. Prints the fallback notice at most once per process.
Device resolveDevice(Device requested);
const char* toString(Device d);

} // namespace lvdif
