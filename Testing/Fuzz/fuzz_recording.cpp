// libFuzzer target for the recording parser: any input either reads (and then
// plays onto a small volume under small budgets) or fails with one
// lvdif::Error; a crash, hang, sanitizer report or other exception is a bug.
#include "FuzzPlay.h"
#include "lvdif/Recording.h"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  lvdif::Recording r;
  try
  {
    r = lvdif::readRecording(in, "fuzz.lvr");
  }
  catch (const lvdif::Error&)
  {
    return 0;
  }
  playOnSmallVolume(r);
  return 0;
}
