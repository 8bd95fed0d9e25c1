// libFuzzer target: the legacy .bv importer on arbitrary bytes. The first
// byte chooses the file name (with or without a SDF_<N>_ token) so the name
// check is exercised too; the rest is the file.
#include "lvdif/LegacyBv.h"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  const std::string name = data[0] & 1 ? "SDF_" + std::to_string(data[0] >> 1) + "_fuzz.bv" : "fuzz.bv";
  lvdif::LegacyBvOptions options;
  options.memoryLimit = 64u << 20;
  options.chunkEdge = 8;
  options.swapXZ = (data[0] & 2) != 0;
  try
  {
    lvdif::MemorySource src(data + 1, size - 1);
    auto volume = lvdif::readLegacyBv(src, name, options);
    volatile std::uint32_t sum = 0;
    for (std::int64_t z = 0; z < volume->dims()[2]; ++z)
      sum = sum + volume->get(0, 0, z).sdf + volume->colors()[volume->get(z, 0, 0).color].g;
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}
