#include "Arguments.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cstdlib>

Arguments::Arguments(int argc, char** argv, int first, const std::vector<std::string>& flags)
{
  for (int i = first; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a.rfind("--", 0) == 0 && a.size() > 2)
    {
      const std::string key = a.substr(2);
      // "--dims 16 ... --dims 24" is a mistake in the command line, not "the last wins"
      if (this->Options.count(key))
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " given twice");
      if (std::find(flags.begin(), flags.end(), key) != flags.end())
      {
        this->Options[key] = "1";
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
      this->Positional.push_back(a);
    }
  }
}

std::string Arguments::get(const std::string& key, const std::string& fallback) const
{
  auto it = this->Options.find(key);
  return it == this->Options.end() ? fallback : it->second;
}

long Arguments::getInt(const std::string& key, long fallback) const
{
  if (!this->has(key)) return fallback;
  const std::string v = this->get(key, "");
  char* end = nullptr;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (end == v.c_str() || *end != '\0')
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " expects an integer, got '" + v + "'");
  return x;
}

long Arguments::getCanvasSize(const std::string& key, long fallback) const
{
  const long n = this->getInt(key, fallback);
  // DictionaryVolume::checkCanvasDimensions is the one canvas rule of every editor
  const std::string problem = lvdif::DictionaryVolume::checkCanvasDimensions({ n, n, n });
  if (!problem.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--" + key + " " + std::to_string(n) + ": " + problem);
  return n;
}

double Arguments::getDouble(const std::string& key, double fallback) const
{
  if (!this->has(key)) return fallback;
  const std::string v = this->get(key, "");
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0')
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --" + key + " expects a number, got '" + v + "'");
  return x;
}

void Arguments::allowOnly(const std::vector<std::string>& known) const
{
  for (const auto& kv : this->Options)
  {
    if (std::find(known.begin(), known.end(), kv.first) == known.end())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "unknown option --" + kv.first);
  }
}
