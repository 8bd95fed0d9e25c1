// Shared helpers for the benchmarks: a wall clock, the machine description
// every table starts with, a plain-text table printer, and the error guard
// of their main functions.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace bench
{

class Stopwatch
{
public:
  Stopwatch() : Start(std::chrono::steady_clock::now()) {}
  void reset() { this->Start = std::chrono::steady_clock::now(); }
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
  double ms() const { return this->seconds() * 1e3; }

private:
  std::chrono::steady_clock::time_point Start;
};

/// "CPU model, N threads (OpenMP), RAM; GPU name or none" for the table header.
std::string machineDescription();

/// Prints a header row, a rule and the rows, columns padded to fit.
void printTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

std::string fmt(double value, int decimals = 2);

/// Runs a benchmark's body: an exception (a missing or malformed mesh, a refused size) becomes one line
/// "NAME: message" on stderr and exit status 1, not std::terminate.
int guardedMain(int argc, char** argv, int (*body)(int, char**));

/// The p-quantile (0..1, nearest rank) of the values; 0 for none.
inline double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  const double rank = p * static_cast<double>(v.size());
  std::size_t i = static_cast<std::size_t>(rank);
  if (static_cast<double>(i) < rank)
    ++i; // ceil
  return v[std::min(v.size() - 1, i > 0 ? i - 1 : 0)];
}

/// Median of repeated timings of fn (in milliseconds).
template <typename F>
double medianMs(int repeats, F&& fn)
{
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i)
  {
    Stopwatch w;
    fn();
    t.push_back(w.ms());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

} // namespace bench
