// libFuzzer target for the socket device's JSON lines: each line of the input
// is parsed like one line from a client; accepted samples drive an editor as
// Editor::pump does (button bit 0 opens, holds and closes strokes) on a small
// volume under small budgets. A bad line must be one clean refusal; a crash,
// hang, sanitizer report or exception other than lvdif::Error is a bug.
#include "lvdif/Editor.h"
#include "lvdif/InputDevice.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  lvdif::VolumeOptions o;
  o.dims = { 24, 24, 24 };
  o.chunkEdge = 8;
  lvdif::DictionaryVolume v(o);
  lvdif::Editor e(v);
  e.limits.maxDabsPerEdit = 2000;
  e.limits.maxTotalDabs = 4000;
  e.stroke.kind = size > 0 && (data[0] & 1) ? lvdif::BrushKind::Drill : lvdif::BrushKind::Basic;
  std::size_t start = 0;
  while (start <= text.size())
  {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos)
      nl = text.size();
    const std::string line = text.substr(start, nl - start);
    start = nl + 1;
    if (line.size() > lvdif::SocketDevice::MaxLine)
      continue; // the device drops these before parsing
    lvdif::BrushSample s;
    std::string why;
    if (!lvdif::parseSampleJson(line, s, &why))
    {
      if (why.empty())
        __builtin_trap(); // every refusal says why
      continue;
    }
    try
    {
      const bool down = (s.buttons & 1u) != 0;
      if (down && !e.strokeOpen())
        e.beginStroke();
      if (e.strokeOpen())
        e.addSample(s);
      if (!down && e.strokeOpen())
        e.endStroke();
    }
    catch (const lvdif::Error&)
    {
    }
  }
  try
  {
    if (e.strokeOpen())
      e.endStroke();
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}
