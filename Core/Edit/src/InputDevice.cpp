#include "lvdif/InputDevice.h"

#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"

#include "FlatJson.h"
#include "lvdif/Error.h"

#include <cmath>

namespace lvdif
{

ReplayDevice::ReplayDevice(std::vector<BrushSample> samples)
  : Samples(std::move(samples))
{
}

bool ReplayDevice::poll(BrushSample& out, int)
{
  if (this->Next >= this->Samples.size())
  {
    return false;
  }
  out = this->Samples[this->Next++];
  return true;
}

ScriptDevice::ScriptDevice(Generator generator)
  : Gen(std::move(generator))
{
  require(static_cast<bool>(this->Gen), "script device needs a generator");
}

bool ScriptDevice::poll(BrushSample& out, int)
{
  if (this->Done)
  {
    return false;
  }
  BrushSample s;
  if (!this->Gen(this->Index, s))
  {
    this->Done = true;
    return false;
  }
  ++this->Index;
  out = s;
  return true;
}

bool parseSampleJson(const std::string& line, BrushSample& out, std::string* error)
{
  std::map<std::string, detail::edit::FlatJsonValue> obj;
  if (!detail::edit::parseFlatJson(line, obj, error))
  {
    return false;
  }
  auto fail = [&](const std::string& what) {
    if (error)
      *error = what;
    return false;
  };
  auto find = [&](const char* a, const char* b) -> const detail::edit::FlatJsonValue* {
    auto it = obj.find(a);
    if (it == obj.end())
      it = obj.find(b);
    return it == obj.end() ? nullptr : &it->second;
  };
  BrushSample s;
  const detail::edit::FlatJsonValue* pos = find("position", "pos");
  if (!pos || pos->numbers.size() != 3 || pos->isString)
    return fail("\"position\" must be an array of 3 numbers");
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(pos->numbers[a]))
      return fail("\"position\" must be finite");
    s.position[a] = pos->numbers[a];
  }
  if (const detail::edit::FlatJsonValue* q = find("orientation", "quat"))
  {
    if (q->numbers.size() != 4 || q->isString)
      return fail("\"orientation\" must be an array of 4 numbers (w, x, y, z)");
    const double n = std::sqrt(q->numbers[0] * q->numbers[0] + q->numbers[1] * q->numbers[1] +
      q->numbers[2] * q->numbers[2] + q->numbers[3] * q->numbers[3]);
    if (!(n > 1e-12) || !std::isfinite(n))
      return fail("\"orientation\" must be a non-zero finite quaternion");
    for (int a = 0; a < 4; ++a)
      s.orientation[a] = q->numbers[a] / n;
  }
  if (const detail::edit::FlatJsonValue* p = find("pressure", "pressure"))
  {
    if (p->numbers.size() != 1 || p->isArray || p->isString)
      return fail("\"pressure\" must be a number");
    s.pressure = std::isfinite(p->numbers[0]) ? p->numbers[0] : -1.0;
  }
  if (const detail::edit::FlatJsonValue* b = find("buttons", "buttons"))
  {
    if (b->numbers.size() != 1 || b->isArray || b->isString || !(b->numbers[0] >= 0) || b->numbers[0] > 4294967295.0)
      return fail("\"buttons\" must be a number in [0, 2^32)");
    s.buttons = static_cast<std::uint32_t>(b->numbers[0]);
  }
  if (const detail::edit::FlatJsonValue* t = find("time", "t"))
  {
    if (t->numbers.size() != 1 || t->isArray || t->isString || !std::isfinite(t->numbers[0]))
      return fail("\"time\" must be a finite number");
    s.time = t->numbers[0];
  }
  try
  {
    validate(s); // the rules every edit input follows (lvdif/EditLimits.h)
  }
  catch (const Error& e)
  {
    return fail(e.what());
  }
  out = s;
  return true;
}

} // namespace lvdif
