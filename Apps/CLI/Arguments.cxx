#include "Arguments.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/CNumbers.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstdio>

Arguments::Arguments(
  int argc, char** argv, int first, const std::vector<std::string>& valued, const std::vector<std::string>& flags)
{
  auto listed = [](const std::vector<std::string>& list, const std::string& key) {
    return std::find(list.begin(), list.end(), key) != list.end();
  };
  for (int i = first; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a.rfind("--", 0) == 0 && a.size() > 2)
    {
      std::string key = a.substr(2);
      // --dims=64 is --dims 64, as in the editor's command line (it was "unknown option --dims=64")
      const std::size_t eq = key.find('=');
      std::string inlineValue;
      const bool hasInlineValue = eq != std::string::npos;
      if (hasInlineValue)
      {
        inlineValue = key.substr(eq + 1);
        key.erase(eq);
      }
      // known before its value is taken: an unknown last option said "needs a
      // value", and an unknown one before a positional swallowed it
      if (!listed(valued, key) && !listed(flags, key))
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "unknown option --" + key);
      // "--dims 16 ... --dims 24" is a mistake in the command line, not "the last wins"
      if (this->Options.count(key))
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " given twice");
      if (listed(flags, key))
      {
        if (hasInlineValue)
          throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " takes no value");
        this->Options[key] = "1";
      }
      else if (hasInlineValue)
      {
        this->Options[key] = inlineValue;
      }
      else if (i + 1 < argc)
      {
        this->Options[key] = argv[++i];
      }
      else
      {
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " needs a value");
      }
    }
    else
    {
      // -dims 64: an option with one dash, taken for a file name (the usage line came, not why)
      const std::string key = a.size() > 1 && a[0] == '-' && a[1] != '-' ? a.substr(1, a.find('=') - 1) : std::string();
      if (!key.empty() && (listed(valued, key) || listed(flags, key)))
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "unknown option " + a + " (options start with two dashes: --" + key + ")");
      this->Positional.push_back(a);
    }
  }
}

std::string Arguments::get(const std::string& key, const std::string& fallback) const
{
  auto it = this->Options.find(key);
  return it == this->Options.end() ? fallback : it->second;
}

bool plainNumberText(const std::string& v)
{
  if (v.empty() || std::isspace(static_cast<unsigned char>(v.front())) || std::isspace(static_cast<unsigned char>(v.back())))
    return false;
  return v.find_first_of("xX") == std::string::npos;
}

std::string numberTextHint(const std::string& v)
{
  // a quoted " 32" reads like 32 in a terminal: say what is wrong with it
  const bool spaced = !v.empty() && (std::isspace(static_cast<unsigned char>(v.front())) || std::isspace(static_cast<unsigned char>(v.back())));
  return spaced ? " (no spaces around the number)" : "";
}

namespace
{

/// The text as a long: false unless all of it is one, within long's range
/// (strtol saturates at LONG_MAX with ERANGE: --dims 99999999999999999999
/// was reported as "not 9223372036854775807").
bool parseLong(const std::string& v, long& x)
{
  if (!plainNumberText(v)) return false;
  char* end = nullptr;
  errno = 0;
  x = std::strtol(v.c_str(), &end, 10);
  return end != v.c_str() && *end == '\0' && errno != ERANGE;
}

[[noreturn]] void refuse(const std::string& key, const std::string& what, const std::string& v)
{
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " expects " + what + ", got '" + v + "'" +
      numberTextHint(v));
}

std::string rangeText(long lo, long hi)
{
  return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}
}

long Arguments::getInt(const std::string& key, long fallback, long lo, long hi) const
{
  if (!this->has(key)) return fallback;
  const std::string v = this->get(key, "");
  long x = 0;
  if (!parseLong(v, x) || x < lo || x > hi) refuse(key, rangeText(lo, hi), v);
  return x;
}

long Arguments::getCanvasSize(const std::string& key, long fallback) const
{
  if (!this->has(key)) return fallback;
  const std::string v = this->get(key, "");
  long n = 0;
  if (!parseLong(v, n)) refuse(key, rangeText(lvdif::DictionaryVolume::MinCanvasDimension, lvdif::DictionaryVolume::MaxDimension), v);
  // DictionaryVolume::checkCanvasDimensions is the one canvas rule of every editor
  const std::string problem = lvdif::DictionaryVolume::checkCanvasDimensions({ n, n, n });
  if (!problem.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--" + key + " " + std::to_string(n) + ": " + problem);
  return n;
}

lvdif::Index3 Arguments::getCanvasDims(const std::string& key, long fallback) const
{
  if (!this->has(key)) return { fallback, fallback, fallback };
  // N (a cube) or NXxNYxNZ, as the editor's --new (it took N only)
  const std::string v = this->get(key, "");
  std::vector<std::string> parts(1);
  for (char c : v)
    if (c == 'x') parts.emplace_back();
    else parts.back() += c;
  lvdif::Index3 dims{ 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    long n = 0;
    if ((parts.size() != 1 && parts.size() != 3) || !parseLong(parts[parts.size() == 1 ? 0 : a], n))
      refuse(key, "N or NXxNYxNZ, each " + rangeText(lvdif::DictionaryVolume::MinCanvasDimension, lvdif::DictionaryVolume::MaxDimension), v);
    dims[a] = n;
  }
  // DictionaryVolume::checkCanvasDimensions is the one canvas rule of every editor
  const std::string problem = lvdif::DictionaryVolume::checkCanvasDimensions(dims);
  if (!problem.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--" + key + " " + v + ": " + problem);
  return dims;
}

double Arguments::getDouble(const std::string& key, double fallback, double lo, double hi) const
{
  if (!this->has(key)) return fallback;
  const std::string v = this->get(key, "");
  // the C locale's decimal point, whatever LC_NUMERIC says (one conversion in Core)
  char* end = nullptr;
  const double x = lvdif::strtodC(v.c_str(), &end);
  if (!plainNumberText(v) || end == v.c_str() || *end != '\0' || !(x >= lo && x <= hi)) // NaN fails every comparison
  {
    char range[96] = "";
    if (lo > -HUGE_VAL || hi < HUGE_VAL)
    {
      char a[40], b[40];
      lvdif::formatDoubleC(a, sizeof a, "%.17g", lo);
      lvdif::formatDoubleC(b, sizeof b, "%.17g", hi);
      std::snprintf(range, sizeof range, " in [%s, %s]", a, b);
    }
    refuse(key, std::string("a number") + range, v);
  }
  return x;
}
