// libFuzzer target for the import of the original LVDIF recorder's CSV: any
// input imports (skipping broken rows) or fails with one lvdif::Error; what it
// imports must play onto a small volume (or be refused by the edit rules).
// The first byte picks the original and target sizes, so scaling is fuzzed too.
#include "FuzzPlay.h"
#include "lvdif/Recording.h"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
    return 0;
  static const double sizes[4] = { 128, 1, 1e-300, 4096 };
  lvdif::CsvImportOptions opt;
  opt.originalSize = sizes[data[0] & 3];
  opt.targetSize = sizes[(data[0] >> 2) & 3];
  std::istringstream in(std::string(reinterpret_cast<const char*>(data + 1), size - 1));
  lvdif::CsvImportResult r;
  try
  {
    r = lvdif::importOriginalCsv(in, opt);
  }
  catch (const lvdif::Error&)
  {
    return 0;
  }
  playOnSmallVolume(r.recording);
  return 0;
}
