// Helpers shared by the tests that check what a save left on disk (Core's and
// the VTK modules' tests alike: they are VTK-free).
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace filetest
{

/// The whole content of the file at `path` (empty when it cannot be read).
inline std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// True when a file at `path` exists and can be opened for reading.
inline bool fileExists(const std::string& path)
{
  return std::ifstream(path).good();
}

} // namespace filetest
