// Host and device memory of the CUDA mesh to SDF path (MeshToSdfCuda.cu, MeshToSdfCudaMesh.cu):
// device buffers freed with their owner, the process's pool of pinned host
// blocks, uploads that go through it, and a non-blocking stream.
#pragma once

#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

/// Host memory the keys' pieces are copied into. Pinned blocks are kept for
/// the process and shared by its sessions (one session per block at a time):
/// page-locking is slow (every page touched and locked), so warm calls reuse
/// what earlier ones locked; they are freed at exit. When pinned memory
/// is refused the block is plain malloc memory (the copies then wait for the
/// GPU and go through the driver's own staging), said once on stderr.
struct HostBlock
{
  std::uint16_t* p = nullptr;
  std::size_t bytes = 0;
  bool pinned = false;
};

class PinnedPool
{
public:
  ~PinnedPool()
  {
    // at exit the runtime may be gone already: nothing to report then
    for (const HostBlock& b : this->Free) cudaFreeHost(b.p);
  }
  /// A block of at least `bytes` (contents undefined).
  HostBlock take(std::size_t bytes)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (!this->Refuse)
    {
      // the largest kept block; one too small is replaced by a larger one
      std::size_t best = this->Free.size();
      for (std::size_t i = 0; i < this->Free.size(); ++i)
        if (best == this->Free.size() || this->Free[i].bytes > this->Free[best].bytes) best = i;
      if (best < this->Free.size())
      {
        HostBlock b = this->Free[best];
        this->Free.erase(this->Free.begin() + static_cast<std::ptrdiff_t>(best));
        if (b.bytes >= bytes) return b;
        LVDIF_CUDA_CHECK(cudaFreeHost(b.p));
      }
      void* p = nullptr;
      // portable: pinned for every device, whichever a later session runs on
      const cudaError_t e = cudaHostAlloc(&p, bytes, cudaHostAllocPortable);
      if (e == cudaSuccess) return { static_cast<std::uint16_t*>(p), bytes, true };
      (void)cudaGetLastError(); // not sticky: clear it so later launch checks do not see it
      if (!this->Noticed)
      {
        std::fprintf(stderr, "mesh to SDF: pinned host memory refused (%s); the chunk keys come back through "
                             "pageable memory (slower)\n", cudaGetErrorString(e));
        this->Noticed = true;
      }
    }
    void* p = std::malloc(bytes);
    require(p != nullptr, "mesh to SDF: out of host memory for the chunk keys' pieces");
    return { static_cast<std::uint16_t*>(p), bytes, false };
  }
  /// Back to the pool (pinned) or freed (pageable); no copy may still write into it.
  void give(const HostBlock& b)
  {
    if (!b.p) return;
    if (!b.pinned)
    {
      std::free(b.p);
      return;
    }
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Free.push_back(b);
  }
  void refuse(bool r)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Refuse = r;
  }

private:
  std::mutex Mutex;
  std::vector<HostBlock> Free;
  bool Refuse = false, Noticed = false;
};

/// The process's pool (one for all sessions; freed at exit).
PinnedPool& pinnedPool();

/// Large copies go through two pinned halves of 32 MiB from the pool, each
/// filled on the OpenMP threads while the GPU copies the other: from pageable
/// memory the driver stages on one thread (the 13.3M-triangle mesh's 1.8 GB
/// of tree and leaves took 260-350 ms on an H200 host). Small copies, and
/// any copy when pinned memory is refused, go directly.
void uploadBytes(void* dst, const void* src, std::size_t bytes, cudaStream_t stream);

/// Device buffers freed on scope exit (also on exceptions).
class DeviceArena
{
public:
  ~DeviceArena()
  {
    for (void* p : this->Ptrs) cudaFree(p);
  }
  template <typename T, typename A>
  T* upload(const std::vector<T, A>& v)
  {
    T* d = this->alloc<T>(v.size());
    if (!v.empty()) LVDIF_CUDA_CHECK(cudaMemcpy(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice));
    return d;
  }
  /// Copies v into `into` (capacity `cap` elements) or, if it does not fit, a
  /// new buffer, on a non-blocking stream: never waits for running kernels.
  template <typename T, typename A>
  T* uploadOn(cudaStream_t stream, const std::vector<T, A>& v, T* into = nullptr, std::size_t cap = 0)
  {
    T* d = into && v.size() <= cap ? into : this->alloc<T>(v.size());
    if (!v.empty()) uploadBytes(d, v.data(), v.size() * sizeof(T), stream); // waits: v may be freed after return
    return d;
  }
  template <typename T>
  T* alloc(std::size_t n)
  {
    void* p = nullptr;
    const std::size_t bytes = std::max<std::size_t>(n, 1) * sizeof(T);
    LVDIF_CUDA_CHECK(cudaMalloc(&p, bytes));
    this->Ptrs.push_back(p);
    this->Sizes.push_back(bytes);
    this->Bytes += bytes;
    return static_cast<T*>(p);
  }
  /// Frees one buffer now (a slab outgrown by a later call).
  void release(void* p)
  {
    for (std::size_t i = 0; i < this->Ptrs.size(); ++i)
    {
      if (this->Ptrs[i] != p) continue;
      LVDIF_CUDA_CHECK(cudaDeviceSynchronize());
      LVDIF_CUDA_CHECK(cudaFree(p));
      this->Bytes -= this->Sizes[i];
      this->Ptrs.erase(this->Ptrs.begin() + static_cast<std::ptrdiff_t>(i));
      this->Sizes.erase(this->Sizes.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  }
  std::uint64_t bytes() const { return this->Bytes.load(); }

private:
  std::vector<void*> Ptrs;
  std::vector<std::uint64_t> Sizes;
  std::atomic<std::uint64_t> Bytes{ 0 }; // read by sessions of other threads (statistics)
};

/// A non-blocking CUDA stream (no implicit ordering with the legacy stream).
struct Stream
{
  cudaStream_t s = nullptr;
  Stream() { LVDIF_CUDA_CHECK(cudaStreamCreateWithFlags(&this->s, cudaStreamNonBlocking)); }
  ~Stream() { cudaStreamDestroy(this->s); }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
};

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
