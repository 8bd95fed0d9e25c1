// libFuzzer target: the dictionary volume file reader on arbitrary bytes.
// Any input must either load or throw lvdif::Error; crashes, sanitizer
// reports, leaks and allocations past the limits are bugs.
#include "lvdif/VolumeFile.h"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  lvdif::VolumeFileReadOptions options;
  options.memoryLimit = 64u << 20; // far below libFuzzer's rss limit
  try
  {
    lvdif::MemorySource src(data, size);
    auto volume = lvdif::readVolume(src, options);
    // a volume that loaded must be fully readable, and a partial read of it too
    volatile std::uint32_t sum = 0;
    for (std::int64_t id = 0; id < volume->chunkCount(); ++id)
    {
      const lvdif::VoxelBox b = volume->chunkBox(id);
      sum = sum + volume->get(b.hi[0], b.hi[1], b.hi[2]).sdf + volume->colors()[volume->get(b.lo[0], b.lo[1], b.lo[2]).color].r;
    }
    options.wholeVolume = false;
    options.region.lo = { 1, 0, 1 };
    options.region.hi = { volume->dims()[0] / 2, volume->dims()[1] - 1, 3 };
    lvdif::MemorySource again(data, size);
    lvdif::readVolume(again, options);
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}
