// Memory estimates made before allocating. Large allocations in the core ask
// requireMemory() first, so an absurd request fails with a message naming the
// size asked and the limit instead of exhausting the machine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lvdif
{

/// Bytes the process may still use: the LVDIF_MEMORY_LIMIT environment
/// variable (bytes, or with a K/M/G suffix) if set, otherwise 90% of the
/// MemAvailable line of /proc/meminfo (or 8 GiB where that cannot be read).
std::uint64_t memoryLimitBytes();

/// Throws Error(OutOfMemory) when bytes > limit. `what` names the allocation.
void requireMemory(std::uint64_t bytes, const std::string& what, std::uint64_t limit);
void requireMemory(std::uint64_t bytes, const std::string& what);

/// Multiplies with overflow detection; throws Error(OutOfMemory) on overflow.
std::uint64_t checkedMultiply(std::uint64_t a, std::uint64_t b, const std::string& what);

/// "1.50 GiB" style formatting for messages and benchmark tables.
std::string formatBytes(std::uint64_t bytes);

/// Asks the kernel to back the whole 2 MiB pages inside [p, p + bytes) with
/// transparent huge pages before they are first touched (Linux:
/// madvise(MADV_HUGEPAGE); a no-op below 8 MiB and on other systems). A
/// first touch then faults once per 2 MiB instead of once per 4 KiB: the
/// page faults, not the writes, are what a serial fill of fresh memory pays.
void adviseHugePages(void* p, std::size_t bytes);

/// The first touch of every page of [p, p + bytes) on the OpenMP threads (a
/// no-op below 8 MiB): the kernel zeroes the pages it maps at the fault, so
/// a serial first touch of a large block is bound by one core's page faults
/// (256 MB on the H100 host: 122 ms on one thread, 43 ms with huge pages, 19
/// ms on 16 threads). Writes raw storage: call it only where no object lives yet.
void prefaultLarge(void* p, std::size_t bytes);

/// v.resize(n) where v grows into fresh memory (large arrays of the mesh
/// build): the new block is advised for huge pages, and its part past the
/// elements v keeps is faulted in on the threads (prefaultLarge), before
/// resize() constructs the new elements.
template <typename T, typename A>
void resizeLarge(std::vector<T, A>& v, std::size_t n)
{
  if (v.capacity() < n)
  {
    v.reserve(n);
    adviseHugePages(v.data(), n * sizeof(T));
    prefaultLarge(v.data() + v.size(), (n - v.size()) * sizeof(T));
  }
  v.resize(n);
}

/// Resident set size of this process in bytes (from /proc/self/statm), 0 if unknown.
std::uint64_t residentMemoryBytes();

} // namespace lvdif
