// The device-resident volume (lvdif/DeviceVolume.h). One launch per apply call:
// the host plans the dabs (BrushKernel.h, as the CPU and Brush.cu do), assigns
// pool slots to the uniform chunks the dabs reach, packs the launch data into
// one buffer (one copy up), the kernel combines every voxel of every planned
// chunk in place in its slot and counts the changed voxels per chunk (one
// small copy down). Compiled with --fmad=false (Core/CMakeLists.txt) so the
// double arithmetic rounds like the host's.
#include "lvdif/DeviceVolume.h"

#include "BrushKernel.h"
#include "BrushVoxelDevice.cuh"
#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace lvdif
{
namespace cuda
{
namespace
{

using Box = detail::edit::DeviceDabBox;

// Per planned chunk: its slot, origin, and the value to start from when the slot is fresh.
struct ChunkJob
{
  long long origin[3];
  int slot;
  int fresh;          // 1: the slot was uniform `value` before this call
  std::uint32_t value;
  std::uint32_t pad;
};

__global__ void residentDabKernel(std::uint32_t* pool, const ChunkJob* jobs, int edge, int shift, long long dx,
  long long dy, long long dz, const Dab* dabs, const Box* boxes, int nDabs, detail::edit::BrushContext ctx,
  const float* table, detail::edit::EncodeParams enc, unsigned long long* changed)
{
  const long long n = static_cast<long long>(edge) * edge * edge;
  const long long local = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (local >= n)
    return;
  const ChunkJob job = jobs[blockIdx.y];
  const long long m = edge - 1;
  const long long x = job.origin[0] + (local & m);
  const long long y = job.origin[1] + ((local >> shift) & m);
  const long long z = job.origin[2] + (local >> (2 * shift));
  std::uint32_t* p = pool + static_cast<long long>(job.slot) * n + local;
  const std::uint32_t v = job.fresh ? job.value : *p;
  std::uint32_t nv = v;
  if (x < dx && y < dy && z < dz)
  {
    nv = detail::edit::applyDabsToVoxel(v, x, y, z, dabs, boxes, nDabs, ctx, table, enc);
  }
  if (job.fresh || nv != v)
    *p = nv;
  if (nv != v)
    atomicAdd(&changed[blockIdx.y], 1ull);
}

std::size_t alignUp(std::size_t x)
{
  return (x + 255) & ~std::size_t(255);
}

std::uint32_t bitsOf(Voxel v)
{
  std::uint32_t u;
  std::memcpy(&u, &v, sizeof(u));
  return u;
}

/// Writes one chunk's device copy `src` (storage order, n voxels) into the host
/// volume: the first changed voxel goes through set() (expands, marks dirty and the
/// range stale, after the observer's snapshot), the rest straight into the chunk's
/// data as the CPU brush does (this thread owns the chunk). Returns the changed voxels.
/// Voxels outside the volume never differ (the kernel leaves them as uploaded).
std::int64_t writeBack(DictionaryVolume& volume, std::int64_t id, const std::uint32_t* src, std::size_t n,
  ChunkWriteObserver* observer)
{
  const Voxel* data = volume.chunkData(id);
  const std::uint32_t uniformBits = bitsOf(volume.uniformValue(id));
  std::size_t i = 0;
  if (data)
  {
    const std::uint32_t* host = reinterpret_cast<const std::uint32_t*>(data);
    while (i < n && src[i] == host[i])
      ++i;
  }
  else
  {
    while (i < n && src[i] == uniformBits)
      ++i;
  }
  if (i == n)
    return 0;
  if (observer)
    observer->beforeChunkWrite(volume, id);
  const int edge = volume.chunkEdge();
  const Index3 c = volume.chunkCoord(id);
  const std::int64_t lx = static_cast<std::int64_t>(i % edge), ly = static_cast<std::int64_t>((i / edge) % edge),
                     lz = static_cast<std::int64_t>(i / (static_cast<std::size_t>(edge) * edge));
  Voxel v;
  std::memcpy(static_cast<void*>(&v), src + i, sizeof(Voxel));
  volume.set(c[0] * edge + lx, c[1] * edge + ly, c[2] * edge + lz, v);
  std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(volume.expandChunk(id));
  std::int64_t changed = 1;
  for (++i; i < n; ++i)
    if (dst[i] != src[i])
    {
      dst[i] = src[i];
      ++changed;
    }
  volume.tryCollapseChunk(id);
  return changed;
}

} // namespace

struct DeviceVolume::Impl
{
  std::size_t n = 0;          // voxels per chunk
  std::size_t chunkBytes = 0;
  int edge = 0, shift = 0;
  std::size_t capacity = 0;
  std::uint32_t* pool = nullptr;
  float* table = nullptr;
  void* launch = nullptr; // packed launch data (dabs | boxes | jobs | counts)
  std::size_t launchBytes = 0;
  std::vector<int> slotOf;           // chunk -> slot, -1 when uniform on the device
  std::vector<std::uint32_t> uniform; // value of chunks without a slot
  std::vector<std::uint8_t> pending;  // changed on the device, not yet on the host
  std::vector<int> freeSlots;
  std::size_t pendingCount = 0;
  std::uint32_t* staging = nullptr; // pinned host buffer for sync
  std::size_t stagingBytes = 0;

  void reserveStaging(std::size_t want)
  {
    if (want <= this->stagingBytes)
      return;
    if (this->staging)
      LVDIF_CUDA_CHECK(cudaFreeHost(this->staging));
    this->staging = nullptr;
    this->stagingBytes = 0;
    void* ptr = nullptr;
    LVDIF_CUDA_CHECK(cudaMallocHost(&ptr, want));
    this->staging = static_cast<std::uint32_t*>(ptr);
    this->stagingBytes = want;
  }

  void reserveLaunch(std::size_t want)
  {
    if (want <= this->launchBytes)
      return;
    if (this->launch)
      LVDIF_CUDA_CHECK(cudaFree(this->launch));
    this->launch = nullptr;
    this->launchBytes = 0;
    LVDIF_CUDA_CHECK(cudaMalloc(&this->launch, want));
    this->launchBytes = want;
  }

  int takeSlot()
  {
    const int s = this->freeSlots.back();
    this->freeSlots.pop_back();
    return s;
  }

  /// Copies host chunk `id` (expanded) into its slot, taking one if needed.
  void upload(const DictionaryVolume& v, std::int64_t id)
  {
    const Voxel* d = v.chunkData(id);
    if (!d)
    {
      if (this->slotOf[id] >= 0)
      {
        this->freeSlots.push_back(this->slotOf[id]);
        this->slotOf[id] = -1;
      }
      this->uniform[id] = bitsOf(v.uniformValue(id));
      return;
    }
    if (this->slotOf[id] < 0)
    {
      if (this->freeSlots.empty())
        throw Error(ErrorCode::OutOfMemory, "the device pool of " + std::to_string(this->capacity) +
            " chunks is full (raise DeviceVolume::Options::maxDeviceBytes)");
      this->slotOf[id] = this->takeSlot();
    }
    LVDIF_CUDA_CHECK(cudaMemcpy(this->pool + static_cast<std::size_t>(this->slotOf[id]) * this->n, d,
      this->chunkBytes, cudaMemcpyHostToDevice));
  }

  void release()
  {
    // errors are ignored here: a destructor must not throw
    if (this->pool)
      cudaFree(this->pool);
    if (this->table)
      cudaFree(this->table);
    if (this->launch)
      cudaFree(this->launch);
    if (this->staging)
      cudaFreeHost(this->staging);
    this->staging = nullptr;
    this->pool = nullptr;
    this->table = nullptr;
    this->launch = nullptr;
  }
};

DeviceVolume::DeviceVolume(DictionaryVolume& volume)
  : DeviceVolume(volume, Options())
{
}

DeviceVolume::DeviceVolume(DictionaryVolume& volume, const Options& options)
  : Volume(volume)
  , P(std::make_unique<Impl>())
{
  if (!available())
    throw Error(ErrorCode::Unsupported, "no CUDA device is available for a device-resident volume");
  Impl& p = *this->P;
  p.edge = volume.chunkEdge();
  while ((1 << p.shift) < p.edge)
    ++p.shift;
  p.n = static_cast<std::size_t>(p.edge) * p.edge * p.edge;
  p.chunkBytes = p.n * sizeof(std::uint32_t);
  const std::int64_t chunks = volume.chunkCount();
  std::size_t expanded = 0;
  for (std::int64_t id = 0; id < chunks; ++id)
    expanded += volume.isUniform(id) ? 0 : 1;

  // the bound: the caller's, and never more than half of what the device has free
  const std::uint64_t freeBytes = freeMemory();
  std::uint64_t bound = freeBytes / 2;
  if (options.maxDeviceBytes > 0)
    bound = std::min<std::uint64_t>(bound, options.maxDeviceBytes);
  const std::uint64_t fixed = sizeof(float) * SdfDictionary::KeyCount + (1u << 20);
  const std::uint64_t slotsFit = bound > fixed ? (bound - fixed) / p.chunkBytes : 0;
  if (slotsFit < expanded)
    throw Error(ErrorCode::OutOfMemory, "a device-resident copy needs " +
        formatBytes(static_cast<std::uint64_t>(expanded) * p.chunkBytes + fixed) + " of device memory (" +
        std::to_string(expanded) + " expanded chunks), more than the bound of " + formatBytes(bound) +
        " (free: " + formatBytes(freeBytes) + ")");
  p.capacity = static_cast<std::size_t>(
    std::min<std::uint64_t>({ slotsFit, expanded + options.headroomSlots, static_cast<std::uint64_t>(chunks), 2147483647ull }));
  p.capacity = std::max<std::size_t>(p.capacity, 1);
  // host-side tables too: a few bytes per chunk
  requireMemory(static_cast<std::uint64_t>(chunks) * 9 + p.capacity * sizeof(int), "the device volume's chunk table");
  p.slotOf.assign(static_cast<std::size_t>(chunks), -1);
  p.uniform.resize(static_cast<std::size_t>(chunks));
  p.pending.assign(static_cast<std::size_t>(chunks), 0);
  p.freeSlots.resize(p.capacity);
  for (std::size_t i = 0; i < p.capacity; ++i)
    p.freeSlots[i] = static_cast<int>(p.capacity - 1 - i); // slot 0 first
  try
  {
    LVDIF_CUDA_CHECK(cudaMalloc(&p.pool, p.capacity * p.chunkBytes));
    LVDIF_CUDA_CHECK(cudaMalloc(&p.table, sizeof(float) * SdfDictionary::KeyCount));
    LVDIF_CUDA_CHECK(cudaMemcpy(p.table, volume.sdfDictionary().table(), sizeof(float) * SdfDictionary::KeyCount,
      cudaMemcpyHostToDevice));
    for (std::int64_t id = 0; id < chunks; ++id)
      p.upload(volume, id);
    LVDIF_CUDA_CHECK(cudaDeviceSynchronize());
  }
  catch (...)
  {
    p.release();
    throw;
  }
}

DeviceVolume::~DeviceVolume()
{
  if (this->P)
    this->P->release();
}

EditResult DeviceVolume::applyDabs(const std::vector<Dab>& dabs, const BrushSettings& settings)
{
  Impl& p = *this->P;
  DictionaryVolume& volume = this->Volume;
  // Flatten measures its plane and soft paint its colours on the host volume,
  // which is stale here until sync(): both stay on Brush.cu's round trip.
  if (settings.op == BrushOp::Flatten ||
    (settings.op == BrushOp::Paint && !(settings.strength == 1 && settings.falloff == Falloff::Constant)))
    throw Error(ErrorCode::Unsupported, "the device-resident volume applies add, subtract, hard paint, inflate and "
                                        "crease; use lvdif::applyDabs(Device::Cuda, ...) for flatten and soft paint");
  const detail::edit::DabPlan plan = detail::edit::planDabs(volume, dabs, settings);
  EditResult result;
  if (plan.chunks.empty())
    return result;
  std::size_t needSlots = 0;
  for (std::int64_t id : plan.chunks)
    needSlots += p.slotOf[static_cast<std::size_t>(id)] < 0 ? 1 : 0;
  if (needSlots > p.freeSlots.size())
    throw Error(ErrorCode::OutOfMemory, "the edit reaches " + std::to_string(needSlots) +
        " uniform chunks but the device pool has " + std::to_string(p.freeSlots.size()) +
        " free slots (sync and rebuild with a larger bound)");

  const std::size_t nChunks = plan.chunks.size();
  std::vector<ChunkJob> jobs(nChunks);
  for (std::size_t i = 0; i < nChunks; ++i)
  {
    const std::size_t id = static_cast<std::size_t>(plan.chunks[i]);
    ChunkJob& j = jobs[i];
    const Index3 c = volume.chunkCoord(static_cast<std::int64_t>(id));
    for (int a = 0; a < 3; ++a)
      j.origin[a] = c[a] * p.edge;
    j.fresh = p.slotOf[id] < 0 ? 1 : 0;
    j.value = p.uniform[id];
    j.pad = 0;
    if (j.fresh)
      p.slotOf[id] = p.takeSlot();
    j.slot = p.slotOf[id];
  }
  std::vector<Box> boxes(plan.boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k)
    for (int a = 0; a < 3; ++a)
    {
      boxes[k].lo[a] = plan.boxes[k].lo[a];
      boxes[k].hi[a] = plan.boxes[k].hi[a];
    }
  // one packed upload: dabs | boxes | jobs ; counts are zeroed on the device
  const std::size_t oBoxes = alignUp(sizeof(Dab) * plan.dabs.size());
  const std::size_t oJobs = alignUp(oBoxes + sizeof(Box) * boxes.size());
  const std::size_t oCounts = alignUp(oJobs + sizeof(ChunkJob) * nChunks);
  const std::size_t total = alignUp(oCounts + sizeof(unsigned long long) * nChunks);
  std::vector<char> host(oCounts);
  std::memcpy(host.data(), plan.dabs.data(), sizeof(Dab) * plan.dabs.size());
  std::memcpy(host.data() + oBoxes, boxes.data(), sizeof(Box) * boxes.size());
  std::memcpy(host.data() + oJobs, jobs.data(), sizeof(ChunkJob) * nChunks);
  std::vector<unsigned long long> counts(nChunks, 0);
  try
  {
    p.reserveLaunch(total);
    char* dev = static_cast<char*>(p.launch);
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(dev, host.data(), oCounts, cudaMemcpyHostToDevice, 0));
    LVDIF_CUDA_CHECK(cudaMemsetAsync(dev + oCounts, 0, sizeof(unsigned long long) * nChunks, 0));
    const detail::edit::EncodeParams enc = detail::edit::EncodeParams::of(volume.sdfDictionary(), volume.bandWidth());
    const Index3& dims = volume.dims();
    for (std::size_t first = 0; first < nChunks; first += 65535) // gridDim.y limit
    {
      const std::size_t count = std::min<std::size_t>(65535, nChunks - first);
      const dim3 block(256);
      const dim3 grid(static_cast<unsigned>((p.n + 255) / 256), static_cast<unsigned>(count));
      residentDabKernel<<<grid, block>>>(p.pool, reinterpret_cast<const ChunkJob*>(dev + oJobs) + first, p.edge,
        p.shift, dims[0], dims[1], dims[2], reinterpret_cast<const Dab*>(dev), reinterpret_cast<const Box*>(dev + oBoxes),
        static_cast<int>(plan.dabs.size()), plan.ctx, p.table, enc,
        reinterpret_cast<unsigned long long*>(dev + oCounts) + first);
      LVDIF_CUDA_CHECK(cudaGetLastError());
    }
    LVDIF_CUDA_CHECK(cudaMemcpy(counts.data(), dev + oCounts, sizeof(unsigned long long) * nChunks, cudaMemcpyDeviceToHost));
  }
  catch (...)
  {
    // the pool may be half written: the host volume is still right, so re-read the planned chunks
    for (std::size_t i = 0; i < nChunks; ++i)
    {
      const std::size_t id = static_cast<std::size_t>(plan.chunks[i]);
      if (jobs[i].fresh)
      {
        p.freeSlots.push_back(p.slotOf[id]);
        p.slotOf[id] = -1;
      }
    }
    throw;
  }
  for (std::size_t i = 0; i < nChunks; ++i)
  {
    const std::size_t id = static_cast<std::size_t>(plan.chunks[i]);
    if (counts[i] > 0)
    {
      result.changedChunks.push_back(static_cast<std::int64_t>(id));
      result.changedVoxels += static_cast<std::int64_t>(counts[i]);
      if (!p.pending[id])
      {
        p.pending[id] = 1;
        ++p.pendingCount;
      }
    }
    else if (jobs[i].fresh && !p.pending[id])
    {
      // still uniform: give the slot back
      p.freeSlots.push_back(p.slotOf[id]);
      p.slotOf[id] = -1;
    }
  }
  return result;
}

EditResult DeviceVolume::sync(ChunkWriteObserver* observer)
{
  Impl& p = *this->P;
  DictionaryVolume& volume = this->Volume;
  EditResult result;
  if (p.pendingCount == 0)
    return result;
  std::vector<std::int64_t> ids;
  ids.reserve(p.pendingCount);
  for (std::size_t id = 0; id < p.pending.size(); ++id)
    if (p.pending[id])
      ids.push_back(static_cast<std::int64_t>(id));
  // in batches of at most 64 MiB of pinned host staging (one asynchronous copy per slot, one wait)
  const std::size_t batch = std::max<std::size_t>(1, std::min<std::size_t>(ids.size(), (std::size_t(64) << 20) / p.chunkBytes));
  p.reserveStaging(batch * p.chunkBytes);
  for (std::size_t first = 0; first < ids.size(); first += batch)
  {
    const std::size_t count = std::min(batch, ids.size() - first);
    for (std::size_t t = 0; t < count; ++t)
      LVDIF_CUDA_CHECK(cudaMemcpyAsync(p.staging + t * p.n,
        p.pool + static_cast<std::size_t>(p.slotOf[static_cast<std::size_t>(ids[first + t])]) * p.n, p.chunkBytes,
        cudaMemcpyDeviceToHost, 0));
    LVDIF_CUDA_CHECK(cudaStreamSynchronize(0));
    std::vector<std::int64_t> perChunk(count, 0);
    const std::int64_t nCount = static_cast<std::int64_t>(count);
    bool failed = false;
    Error firstError(ErrorCode::InvalidArgument, "");
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < nCount; ++t)
    {
      try
      {
        const std::int64_t id = ids[first + static_cast<std::size_t>(t)];
        perChunk[static_cast<std::size_t>(t)] =
          writeBack(volume, id, p.staging + static_cast<std::size_t>(t) * p.n, p.n, observer);
      }
      catch (const Error& e)
      {
#pragma omp critical(lvdif_device_sync)
        if (!failed)
        {
          failed = true;
          firstError = e;
        }
      }
    }
    if (failed)
      throw firstError; // the chunks stay pending: a later sync retries them
    for (std::size_t t = 0; t < count; ++t)
    {
      const std::size_t id = static_cast<std::size_t>(ids[first + t]);
      p.pending[id] = 0;
      --p.pendingCount;
      if (perChunk[t] > 0)
      {
        result.changedChunks.push_back(ids[first + t]);
        result.changedVoxels += perChunk[t];
      }
      if (volume.isUniform(static_cast<std::int64_t>(id)))
      {
        // collapsed on the host: free the slot, the device keeps the value
        p.freeSlots.push_back(p.slotOf[id]);
        p.slotOf[id] = -1;
        p.uniform[id] = bitsOf(volume.uniformValue(static_cast<std::int64_t>(id)));
      }
    }
  }
  return result;
}

void DeviceVolume::refresh(const std::vector<std::int64_t>& ids)
{
  Impl& p = *this->P;
  for (std::int64_t id : ids)
  {
    require(id >= 0 && id < this->Volume.chunkCount(), "refresh: chunk id " + std::to_string(id) + " out of range");
    require(!p.pending[static_cast<std::size_t>(id)],
      "refresh: chunk " + std::to_string(id) + " has device edits not synced (call sync() first)");
  }
  for (std::int64_t id : ids)
    p.upload(this->Volume, id);
}

std::size_t DeviceVolume::pendingChunks() const
{
  return this->P->pendingCount;
}

std::size_t DeviceVolume::slotsUsed() const
{
  return this->P->capacity - this->P->freeSlots.size();
}

std::size_t DeviceVolume::slotCapacity() const
{
  return this->P->capacity;
}

std::uint64_t DeviceVolume::deviceBytes() const
{
  return static_cast<std::uint64_t>(this->P->capacity) * this->P->chunkBytes +
    sizeof(float) * SdfDictionary::KeyCount + this->P->launchBytes;
}

} // namespace cuda
} // namespace lvdif
