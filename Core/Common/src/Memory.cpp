#include "lvdif/Memory.h"
#include "lvdif/CNumbers.h"

#include "lvdif/Error.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lvdif
{

/// A size in bytes, with an optional k, M, G or T (binary) suffix; 0 when the
/// text is none (not a number, not finite, not positive). Sizes beyond 64
/// bits are the largest one (no limit); the cast of such doubles, and of NaN
/// and infinity, was undefined.
static std::uint64_t parseSize(const char* text)
{
  char* end = nullptr;
  const double v = strtodC(text, &end);
  if (end == text || !std::isfinite(v) || v <= 0)
  {
    return 0;
  }
  double mult = 1;
  switch (*end)
  {
    case 'k': case 'K': mult = 1024.0; break;
    case 'm': case 'M': mult = 1024.0 * 1024; break;
    case 'g': case 'G': mult = 1024.0 * 1024 * 1024; break;
    case 't': case 'T': mult = 1024.0 * 1024 * 1024 * 1024; break;
    default: break;
  }
  const double bytes = v * mult;
  if (bytes >= 18446744073709551616.0) // 2^64
  {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(bytes));
}

std::uint64_t memoryLimitBytes()
{
  if (const char* env = std::getenv("LVDIF_MEMORY_LIMIT"))
  {
    if (std::uint64_t v = parseSize(env))
    {
      return v;
    }
    // a limit the user meant to set is never dropped without a word
    static std::atomic<bool> told{ false };
    if (!told.exchange(true))
      std::fprintf(stderr, "lvdif: LVDIF_MEMORY_LIMIT='%s' is not a size (bytes > 0, optionally with K, M, G or T): "
                           "ignored, the limit is 90%% of the available memory\n", env);
  }
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kb = 0;
  std::string unit;
  while (meminfo >> key >> kb >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kb * 1024 / 10 * 9;
    }
  }
  return 8ull << 30;
}

std::string formatBytes(std::uint64_t bytes)
{
  const char* units[] = { "B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 6)
  {
    v /= 1024.0;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof(buf), u == 0 ? "%.0f %s" : "%.2f %s", v, units[u]);
  return buf;
}

void requireMemory(std::uint64_t bytes, const std::string& what, std::uint64_t limit)
{
  if (bytes > limit)
  {
    throw Error(ErrorCode::OutOfMemory,
      what + " needs " + formatBytes(bytes) + ", more than the limit of " + formatBytes(limit) +
        " (set LVDIF_MEMORY_LIMIT to change it)");
  }
}

void requireMemory(std::uint64_t bytes, const std::string& what)
{
  requireMemory(bytes, what, memoryLimitBytes());
}

std::uint64_t checkedMultiply(std::uint64_t a, std::uint64_t b, const std::string& what)
{
  if (a != 0 && b > UINT64_MAX / a)
  {
    throw Error(ErrorCode::OutOfMemory, what + " size overflows 64 bits");
  }
  return a * b;
}

void adviseHugePages(void* p, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t Huge = std::uintptr_t(2) << 20;
  if (!p || bytes < 4 * Huge) return;
  const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t lo = (a + Huge - 1) & ~(Huge - 1), hi = (a + bytes) & ~(Huge - 1);
  // only pages wholly inside the block; a refusal (THP off) just leaves 4 KiB pages
  if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

void prefaultLarge(void* p, std::size_t bytes)
{
  constexpr std::size_t Threshold = std::size_t(8) << 20, Page = 4096, Piece = std::size_t(2) << 20;
  if (!p || bytes < Threshold) return;
  char* const c = static_cast<char*>(p);
  const std::int64_t pieces = static_cast<std::int64_t>((bytes + Piece - 1) / Piece);
  // one write per 4 KiB page faults it in (a whole huge page where the
  // advice took); pieces of 2 MiB so that each thread faults its own pages
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < pieces; ++i)
  {
    const std::size_t lo = static_cast<std::size_t>(i) * Piece, hi = std::min(bytes, lo + Piece);
    for (std::size_t b = lo; b < hi; b += Page) static_cast<volatile char*>(c)[b] = 0;
  }
}

namespace detail
{
void forPiecesOnThreads(std::size_t n, const std::function<void(std::size_t, std::size_t)>& fn)
{
  constexpr std::size_t Piece = std::size_t(1) << 16; // elements: large enough to amortize the call
  const std::int64_t pieces = static_cast<std::int64_t>((n + Piece - 1) / Piece);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < pieces; ++i)
  {
    const std::size_t first = static_cast<std::size_t>(i) * Piece;
    fn(first, std::min(n, first + Piece));
  }
}
} // namespace detail

std::uint64_t residentMemoryBytes()
{
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f)
  {
    return 0;
  }
  unsigned long size = 0, resident = 0;
  const int n = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return n == 2 ? static_cast<std::uint64_t>(resident) * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

} // namespace lvdif
