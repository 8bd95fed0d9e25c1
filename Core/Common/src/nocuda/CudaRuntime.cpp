// CUDA runtime queries for builds without CUDA.
#include "lvdif/Cuda.h"

namespace lvdif
{
namespace cuda
{
bool compiled() { return false; }
bool available() { return false; }
std::string deviceName() { return "none"; }
std::size_t freeMemory() { return 0; }
} // namespace cuda
} // namespace lvdif
