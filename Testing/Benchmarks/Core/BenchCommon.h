// Shared helpers for the benchmarks: a wall clock, the machine description
// every table starts with, and a plain-text table printer.
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
