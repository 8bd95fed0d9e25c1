// Memory estimates made before allocating. Large allocations in the core ask
// requireMemory() first, so an absurd request fails with a message naming the
// size asked and the limit instead of exhausting the machine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
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

namespace detail
{
/// fn(first, last) over pieces of [0, n) on the OpenMP threads (Memory.cpp).
void forPiecesOnThreads(std::size_t n, const std::function<void(std::size_t, std::size_t)>& fn);
/// True while resizeLarge grows a LargeVector: resize() then leaves the new
/// elements to resizeLarge, which constructs them on the threads.
inline thread_local bool constructLater = false;
} // namespace detail

/// std::allocator, except that the elements a LargeVector's resizeLarge adds
/// are constructed on the OpenMP threads rather than one by one by resize():
/// value-initializing 273 MB of triangle records (832k) was a serial memset
/// of 20-40 ms, and 3.3 GB for a 10M-triangle mesh. Every other growth
/// (resize, insert, push_back) constructs as usual. Only for types with no
/// destructor and trivial copies, so that storage without a constructed
/// element yet is just bytes.
template <typename T>
struct ParallelInitAllocator : std::allocator<T>
{
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
    "ParallelInitAllocator: elements are constructed later, on the threads");
  template <typename U>
  struct rebind
  {
    using other = ParallelInitAllocator<U>;
  };
  ParallelInitAllocator() noexcept = default;
  template <typename U>
  ParallelInitAllocator(const ParallelInitAllocator<U>&) noexcept
  {
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    if constexpr (sizeof...(Args) == 0)
    {
      if (detail::constructLater) return; // resizeLarge constructs it
    }
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <typename T, typename U>
bool operator==(const ParallelInitAllocator<T>&, const ParallelInitAllocator<U>&) noexcept
{
  return true;
}
template <typename T, typename U>
bool operator!=(const ParallelInitAllocator<T>&, const ParallelInitAllocator<U>&) noexcept
{
  return false;
}

/// A large array of the mesh build (triangle records, tree nodes).
template <typename T>
using LargeVector = std::vector<T, ParallelInitAllocator<T>>;

/// v.resize(n) for storage that its producer overwrites whole, on the threads
/// (the mesh BVH's nodes, leaves and keys): the new elements are left
/// unconstructed (these types are trivially copyable and destructible, so
/// their storage is just bytes until written), so the pages are first
/// touched by the writes themselves, on the threads that make them, instead
/// of by a zeroing pass before them. Reading an element before it is
/// written is a bug.
template <typename T>
void resizeLargeForOverwrite(LargeVector<T>& v, std::size_t n)
{
  if (n <= v.size())
  {
    v.resize(n);
    return;
  }
  if (v.capacity() < n)
  {
    v.reserve(n);
    adviseHugePages(v.data(), n * sizeof(T));
  }
  detail::constructLater = true;
  v.resize(n); // reserved above: no reallocation, no construction
  detail::constructLater = false;
}

/// resizeLarge for a LargeVector: the same elements as v.resize(n) (each new
/// one value-initialized), constructed in pieces on the OpenMP threads, which
/// also fault the fresh pages in there.
template <typename T>
void resizeLarge(LargeVector<T>& v, std::size_t n)
{
  const std::size_t old = v.size();
  resizeLargeForOverwrite(v, n);
  if (n <= old) return;
  T* const fresh = v.data() + old;
  detail::forPiecesOnThreads(n - old, [fresh](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) ::new (static_cast<void*>(fresh + i)) T();
  });
}

/// Resident set size of this process in bytes (from /proc/self/statm), 0 if unknown.
std::uint64_t residentMemoryBytes();

} // namespace lvdif
