// The pinned pool and the staged uploads of MeshToSdfCudaMemory.cuh.
#include "MeshToSdfCudaMemory.cuh"
#include "MeshToSdfInternal.h"

#include "lvdif/Memory.h"

#include <chrono>
#include <cstring>
#include <string>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

PinnedPool& pinnedPool()
{
  static PinnedPool pool;
  return pool;
}

void uploadBytes(void* dst, const void* src, std::size_t bytes, cudaStream_t stream)
{
  constexpr std::size_t Half = std::size_t(32) << 20;
  HostBlock block;
  const auto t0 = std::chrono::steady_clock::now();
  if (bytes >= 2 * Half) block = pinnedPool().take(2 * Half);
  const auto took = std::chrono::steady_clock::now();
  // large uploads on the trace: the time to take the staging block, the copy's
  struct Report
  {
    std::size_t bytes;
    std::chrono::steady_clock::time_point t0, took;
    bool pinned;
    ~Report()
    {
      if (this->bytes < (std::size_t(64) << 20)) return;
      const auto t1 = std::chrono::steady_clock::now();
      const std::string what = "upload of " + std::to_string(this->bytes >> 20) + " MiB" +
        (this->pinned ? " through pinned halves" : " from pageable memory") + " (taking the staging block: " +
        std::to_string(std::chrono::duration<double, std::milli>(this->took - this->t0).count()) + " ms)";
      detail::meshtosdf::trace(what.c_str(), std::chrono::duration<double>(t1 - this->t0).count());
    }
  } report{ bytes, t0, took, block.pinned };
  if (!block.pinned)
  {
    pinnedPool().give(block);
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyHostToDevice, stream));
    LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream));
    return;
  }
  struct Staging
  {
    HostBlock block;
    cudaStream_t stream;
    cudaEvent_t done[2] = { nullptr, nullptr };
    ~Staging()
    {
      // on every exit: no copy may still read the block when it goes back
      cudaStreamSynchronize(this->stream);
      for (cudaEvent_t e : this->done)
        if (e) cudaEventDestroy(e);
      pinnedPool().give(this->block);
    }
  } staging{ block, stream };
  for (cudaEvent_t& e : staging.done) LVDIF_CUDA_CHECK(cudaEventCreateWithFlags(&e, cudaEventDisableTiming));
  char* const halves[2] = { reinterpret_cast<char*>(block.p), reinterpret_cast<char*>(block.p) + Half };
  std::size_t piece = 0;
  for (std::size_t off = 0; off < bytes; off += Half, ++piece)
  {
    const int h = static_cast<int>(piece % 2);
    const std::size_t n = std::min(Half, bytes - off);
    if (piece >= 2) LVDIF_CUDA_CHECK(cudaEventSynchronize(staging.done[h])); // its last copy has read it
    const char* from = static_cast<const char*>(src) + off;
    char* to = halves[h];
    lvdif::detail::forPiecesOnThreads(n, [from, to](std::size_t a, std::size_t b) { std::memcpy(to + a, from + a, b - a); });
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(static_cast<char*>(dst) + off, to, n, cudaMemcpyHostToDevice, stream));
    LVDIF_CUDA_CHECK(cudaEventRecord(staging.done[h], stream));
  }
  LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream));
}

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
