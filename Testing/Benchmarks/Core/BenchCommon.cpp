#include "BenchCommon.h"

#include "lvdif/Cuda.h"
#include "lvdif/Memory.h"

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace bench
{

std::string machineDescription()
{
  std::string model = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
  {
    if (line.rfind("model name", 0) == 0)
    {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  int threads = static_cast<int>(std::thread::hardware_concurrency());
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::ostringstream s;
  s << model << ", " << threads << " OpenMP threads, memory limit "
    << lvdif::formatBytes(lvdif::memoryLimitBytes()) << "; GPU: " << lvdif::cuda::deviceName();
  return s.str();
}

std::string fmt(double value, int decimals)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, value);
  return buf;
}

void printTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows)
{
  std::vector<size_t> w(header.size());
  for (size_t i = 0; i < header.size(); ++i) w[i] = header[i].size();
  for (const auto& r : rows)
    for (size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], r[i].size());
  auto printRow = [&](const std::vector<std::string>& r) {
    std::cout << "|";
    for (size_t i = 0; i < w.size(); ++i)
    {
      const std::string c = i < r.size() ? r[i] : "";
      std::cout << " " << c << std::string(w[i] - c.size(), ' ') << " |";
    }
    std::cout << "\n";
  };
  printRow(header);
  std::cout << "|";
  for (size_t i = 0; i < w.size(); ++i) std::cout << std::string(w[i] + 2, '-') << "|";
  std::cout << "\n";
  for (const auto& r : rows) printRow(r);
  std::cout.flush();
}

int guardedMain(int argc, char** argv, int (*body)(int, char**))
{
  try
  {
    return body(argc, argv);
  }
  catch (const std::exception& e)
  {
    std::string name = argc > 0 ? argv[0] : "benchmark";
    name = name.substr(name.find_last_of('/') + 1);
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return 1;
  }
}

} // namespace bench
