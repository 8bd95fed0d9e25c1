// libFuzzer target for the script lexer, parser and interpreter. Any input
// must either run or fail with an lvdif::Error (ScriptError for syntax and run
// time mistakes); a crash, hang or other exception is a bug. Running is
// bounded: a 10,000-step limit and canvases of at most 64^3 voxels.
#include "lvdif/Script.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string source(reinterpret_cast<const char*>(data), size);
  try
  {
    lvdif::checkScript(source);
  }
  catch (const lvdif::Error&)
  {
    return 0; // a clean syntax error
  }
  lvdif::ScriptOptions o;
  o.maxSteps = 10000;
  o.maxCanvasVoxels = 64 * 64 * 64;
  o.print = [](const std::string&) {};
  try
  {
    lvdif::ScriptRunner runner(o);
    runner.run(source);
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}
