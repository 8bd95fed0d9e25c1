// The device-resident volume (lvdif/DeviceVolume.h). One launch per apply call:
// the host plans the dabs (BrushKernel.h, as the CPU and Brush.cu do), assigns
// pool slots (a fresh one for a uniform chunk, and inside a history step for
// the step's first write into a chunk: copy on write), packs the launch data
// into one buffer (one copy up), the kernel combines every voxel of every
// planned chunk from its source slot (or uniform value) into its destination
// slot and reduces per chunk the changed voxels and their bounding box (one
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
#include <deque>
#include <string>

namespace lvdif
{
namespace cuda
{
namespace
{

using Box = detail::edit::DeviceDabBox;

// Per planned chunk: where its voxels come from and go to.
struct ChunkJob
{
  long long origin[3];
  int src;            // slot read, or -1: the chunk was uniform `value`
  int dst;            // slot written (every voxel when src != dst, else the changed ones)
  std::uint32_t value;
  std::uint32_t pad;
};

// Per planned chunk: changed voxels and their box in chunk-local coordinates.
struct ChunkChange
{
  unsigned long long count;
  int lo[3], hi[3];
};

__global__ void residentDabKernel(std::uint32_t* pool, const ChunkJob* jobs, int edge, int shift, long long dx,
  long long dy, long long dz, const Dab* dabs, const Box* boxes, int nDabs, detail::edit::BrushContext ctx,
  const float* table, detail::edit::EncodeParams enc, ChunkChange* changes)
{
  __shared__ int sLo[3], sHi[3];
  __shared__ unsigned int sCount;
  if (threadIdx.x == 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      sLo[a] = 0x7fffffff;
      sHi[a] = -1;
    }
    sCount = 0;
  }
  __syncthreads();
  const long long n = static_cast<long long>(edge) * edge * edge;
  const long long local = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  const ChunkJob job = jobs[blockIdx.y];
  if (local < n)
  {
    const long long m = edge - 1;
    const int l[3] = { static_cast<int>(local & m), static_cast<int>((local >> shift) & m),
      static_cast<int>(local >> (2 * shift)) };
    const long long x = job.origin[0] + l[0], y = job.origin[1] + l[1], z = job.origin[2] + l[2];
    const std::uint32_t v = job.src < 0 ? job.value : pool[static_cast<long long>(job.src) * n + local];
    std::uint32_t nv = v;
    if (x < dx && y < dy && z < dz)
      nv = detail::edit::applyDabsToVoxel(v, x, y, z, dabs, boxes, nDabs, ctx, table, enc);
    if (job.src != job.dst || nv != v)
      pool[static_cast<long long>(job.dst) * n + local] = nv;
    if (nv != v)
    {
      atomicAdd(&sCount, 1u);
      for (int a = 0; a < 3; ++a)
      {
        atomicMin(&sLo[a], l[a]);
        atomicMax(&sHi[a], l[a]);
      }
    }
  }
  __syncthreads();
  if (threadIdx.x == 0 && sCount > 0)
  {
    ChunkChange& c = changes[blockIdx.y];
    atomicAdd(&c.count, static_cast<unsigned long long>(sCount));
    for (int a = 0; a < 3; ++a)
    {
      atomicMin(&c.lo[a], sLo[a]);
      atomicMax(&c.hi[a], sHi[a]);
    }
  }
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
  void* launch = nullptr; // packed launch data (dabs | boxes | jobs | changes)
  std::size_t launchBytes = 0;
  std::vector<int> slotOf;           // chunk -> slot, -1 when uniform on the device
  std::vector<std::uint32_t> uniform; // value of chunks without a slot
  std::vector<std::uint8_t> pending;  // changed on the device, not yet on the host
  std::vector<int> freeSlots;
  std::size_t pendingCount = 0;
  std::uint32_t* staging = nullptr; // pinned host buffer for sync
  std::size_t stagingBytes = 0;

  // device copies of the chunk table and of the colour dictionary, for view()
  int* devSlotOf = nullptr;
  std::uint32_t* devUniform = nullptr;
  std::uint32_t* devPalette = nullptr;
  std::size_t paletteUploaded = 0;
  bool tablesStale = true;

  // history: per step, the snapshots (a chunk's slot or uniform value before the step)
  struct Snapshot
  {
    std::int64_t id;
    int slot;
    std::uint32_t value;
  };
  struct Step
  {
    std::vector<Snapshot> chunks;
    std::uint64_t bytes = 0; // as the host UndoStack counts: a chunk's voxels, or a few bytes for a value
  };
  std::deque<Step> undo, redo;
  std::unique_ptr<Step> open;
  std::vector<std::uint8_t> inOpen; // chunk already snapshotted in the open step
  std::uint64_t historyBytes = 0; // undo and redo steps
  std::uint64_t historyCap = 0;
  std::size_t minHistorySteps = 1;
  std::vector<std::int64_t> lastRestored;

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

  void markPending(std::size_t id)
  {
    if (!this->pending[id])
    {
      this->pending[id] = 1;
      ++this->pendingCount;
    }
  }

  std::uint64_t snapshotBytes(const Snapshot& s) const
  {
    return s.slot >= 0 ? this->chunkBytes : sizeof(Snapshot);
  }

  void freeStep(Step& st)
  {
    for (const Snapshot& s : st.chunks)
      if (s.slot >= 0)
        this->freeSlots.push_back(s.slot);
    this->historyBytes -= st.bytes;
    st.chunks.clear();
    st.bytes = 0;
  }

  void clearRedo()
  {
    for (Step& st : this->redo)
      this->freeStep(st);
    this->redo.clear();
  }

  /// Drops the oldest undo steps while the history is over its cap (keeping
  /// minHistorySteps), or until `needFree` slots are free (keeping none).
  void trimHistory(std::size_t needFree)
  {
    while (!this->undo.empty() &&
      ((this->historyBytes > this->historyCap && this->undo.size() > this->minHistorySteps) ||
        this->freeSlots.size() < needFree))
    {
      this->freeStep(this->undo.front());
      this->undo.pop_front();
    }
    while (!this->redo.empty() && this->freeSlots.size() < needFree)
    {
      this->freeStep(this->redo.back());
      this->redo.pop_back();
    }
  }

  /// Copies host chunk `id` (expanded) into its slot, taking one if needed.
  void upload(const DictionaryVolume& v, std::int64_t id)
  {
    this->tablesStale = true;
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

  /// Swaps the step's snapshots with the chunks' current states (undo and redo alike).
  void swapIn(Step& st)
  {
    this->lastRestored.clear();
    std::uint64_t bytes = 0;
    for (Snapshot& s : st.chunks)
    {
      const std::size_t id = static_cast<std::size_t>(s.id);
      std::swap(this->slotOf[id], s.slot);
      std::swap(this->uniform[id], s.value);
      bytes += this->snapshotBytes(s);
      this->markPending(id);
      this->lastRestored.push_back(s.id);
    }
    this->historyBytes = this->historyBytes - st.bytes + bytes;
    st.bytes = bytes;
    std::sort(this->lastRestored.begin(), this->lastRestored.end());
    this->tablesStale = true;
  }

  void release()
  {
    // errors are ignored here: a destructor must not throw
    for (void* p : { static_cast<void*>(this->pool), static_cast<void*>(this->table), this->launch,
           static_cast<void*>(this->devSlotOf), static_cast<void*>(this->devUniform),
           static_cast<void*>(this->devPalette) })
      if (p)
        cudaFree(p);
    if (this->staging)
      cudaFreeHost(this->staging);
    this->staging = nullptr;
    this->pool = nullptr;
    this->table = nullptr;
    this->launch = nullptr;
    this->devSlotOf = nullptr;
    this->devUniform = nullptr;
    this->devPalette = nullptr;
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
  const std::uint64_t fixed = sizeof(float) * SdfDictionary::KeyCount + sizeof(std::uint32_t) * 65536 +
    static_cast<std::uint64_t>(chunks) * 8 + (1u << 20);
  const std::uint64_t slotsFit = bound > fixed ? (bound - fixed) / p.chunkBytes : 0;
  if (slotsFit < expanded)
    throw Error(ErrorCode::OutOfMemory, "a device-resident copy needs " +
        formatBytes(static_cast<std::uint64_t>(expanded) * p.chunkBytes + fixed) + " of device memory (" +
        std::to_string(expanded) + " expanded chunks), more than the bound of " + formatBytes(bound) +
        " (free: " + formatBytes(freeBytes) + ")");
  const std::uint64_t historySlots = options.historyBytes / p.chunkBytes;
  // the history's copies may exceed the chunk count (the same chunk in many steps)
  p.capacity = static_cast<std::size_t>(std::min<std::uint64_t>(
    { slotsFit, expanded + options.headroomSlots + historySlots, 2147483647ull }));
  p.capacity = std::max<std::size_t>(p.capacity, 1);
  p.historyCap = options.historyBytes;
  p.minHistorySteps = options.minHistorySteps;
  // host-side tables too: a few bytes per chunk
  requireMemory(static_cast<std::uint64_t>(chunks) * 10 + p.capacity * sizeof(int), "the device volume's chunk table");
  p.slotOf.assign(static_cast<std::size_t>(chunks), -1);
  p.uniform.resize(static_cast<std::size_t>(chunks));
  p.pending.assign(static_cast<std::size_t>(chunks), 0);
  p.inOpen.assign(static_cast<std::size_t>(chunks), 0);
  p.freeSlots.resize(p.capacity);
  for (std::size_t i = 0; i < p.capacity; ++i)
    p.freeSlots[i] = static_cast<int>(p.capacity - 1 - i); // slot 0 first
  try
  {
    LVDIF_CUDA_CHECK(cudaMalloc(&p.pool, p.capacity * p.chunkBytes));
    LVDIF_CUDA_CHECK(cudaMalloc(&p.table, sizeof(float) * SdfDictionary::KeyCount));
    LVDIF_CUDA_CHECK(cudaMemcpy(p.table, volume.sdfDictionary().table(), sizeof(float) * SdfDictionary::KeyCount,
      cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMalloc(&p.devSlotOf, sizeof(int) * static_cast<std::size_t>(chunks)));
    LVDIF_CUDA_CHECK(cudaMalloc(&p.devUniform, sizeof(std::uint32_t) * static_cast<std::size_t>(chunks)));
    LVDIF_CUDA_CHECK(cudaMalloc(&p.devPalette, sizeof(std::uint32_t) * 65536));
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
  if (!appliesOnDevice(settings))
    throw Error(ErrorCode::Unsupported, "the device-resident volume applies add, subtract, hard paint, inflate and "
                                        "crease; use lvdif::applyDabs(Device::Cuda, ...) for flatten and soft paint");
  const detail::edit::DabPlan plan = detail::edit::planDabs(volume, dabs, settings);
  EditResult result;
  if (plan.chunks.empty())
    return result;
  const bool cow = p.open != nullptr;
  std::size_t needSlots = 0;
  for (std::int64_t id : plan.chunks)
  {
    const std::size_t i = static_cast<std::size_t>(id);
    needSlots += (p.slotOf[i] < 0 || (cow && !p.inOpen[i])) ? 1 : 0;
  }
  if (needSlots > p.freeSlots.size())
    p.trimHistory(needSlots);
  if (needSlots > p.freeSlots.size())
    throw Error(ErrorCode::OutOfMemory, "the edit needs " + std::to_string(needSlots) +
        " free chunk slots but the device pool has " + std::to_string(p.freeSlots.size()) +
        " (raise DeviceVolume::Options::maxDeviceBytes or headroomSlots)");

  const std::size_t nChunks = plan.chunks.size();
  std::vector<ChunkJob> jobs(nChunks);
  for (std::size_t i = 0; i < nChunks; ++i)
  {
    const std::size_t id = static_cast<std::size_t>(plan.chunks[i]);
    ChunkJob& j = jobs[i];
    const Index3 c = volume.chunkCoord(static_cast<std::int64_t>(id));
    for (int a = 0; a < 3; ++a)
      j.origin[a] = c[a] * p.edge;
    j.src = p.slotOf[id];
    j.value = p.uniform[id];
    j.pad = 0;
    j.dst = (j.src < 0 || (cow && !p.inOpen[id])) ? p.takeSlot() : j.src;
  }
  std::vector<Box> boxes(plan.boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k)
    for (int a = 0; a < 3; ++a)
    {
      boxes[k].lo[a] = plan.boxes[k].lo[a];
      boxes[k].hi[a] = plan.boxes[k].hi[a];
    }
  std::vector<ChunkChange> changes(nChunks);
  for (ChunkChange& c : changes)
  {
    c.count = 0;
    for (int a = 0; a < 3; ++a)
    {
      c.lo[a] = 0x7fffffff;
      c.hi[a] = -1;
    }
  }
  // one packed upload: dabs | boxes | jobs | changes (initial values) | soft paint's mix tables
  const std::size_t oBoxes = alignUp(sizeof(Dab) * plan.dabs.size());
  const std::size_t oJobs = alignUp(oBoxes + sizeof(Box) * boxes.size());
  const std::size_t oChanges = alignUp(oJobs + sizeof(ChunkJob) * nChunks);
  const std::size_t oMixFrom = alignUp(oChanges + sizeof(ChunkChange) * nChunks);
  const std::size_t oMixTo = alignUp(oMixFrom + sizeof(std::uint16_t) * plan.mixFrom.size());
  const std::size_t total = alignUp(oMixTo + sizeof(std::uint16_t) * plan.mixTo.size());
  std::vector<char> host(total);
  std::memcpy(host.data(), plan.dabs.data(), sizeof(Dab) * plan.dabs.size());
  std::memcpy(host.data() + oBoxes, boxes.data(), sizeof(Box) * boxes.size());
  std::memcpy(host.data() + oJobs, jobs.data(), sizeof(ChunkJob) * nChunks);
  std::memcpy(host.data() + oChanges, changes.data(), sizeof(ChunkChange) * nChunks);
  if (!plan.mixFrom.empty())
    std::memcpy(host.data() + oMixFrom, plan.mixFrom.data(), sizeof(std::uint16_t) * plan.mixFrom.size());
  if (!plan.mixTo.empty())
    std::memcpy(host.data() + oMixTo, plan.mixTo.data(), sizeof(std::uint16_t) * plan.mixTo.size());
  try
  {
    p.reserveLaunch(2 * total); // slack: a larger call next time needs no cudaFree (a device sync)
    char* dev = static_cast<char*>(p.launch);
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(dev, host.data(), total, cudaMemcpyHostToDevice, 0));
    detail::edit::BrushContext ctx = plan.ctx;
    if (!plan.mixFrom.empty())
    {
      ctx.mixFrom = reinterpret_cast<const std::uint16_t*>(dev + oMixFrom);
      ctx.mixTo = reinterpret_cast<const std::uint16_t*>(dev + oMixTo);
    }
    const detail::edit::EncodeParams enc = detail::edit::EncodeParams::of(volume.sdfDictionary(), volume.bandWidth());
    const Index3& dims = volume.dims();
    for (std::size_t first = 0; first < nChunks; first += 65535) // gridDim.y limit
    {
      const std::size_t count = std::min<std::size_t>(65535, nChunks - first);
      const dim3 block(256);
      const dim3 grid(static_cast<unsigned>((p.n + 255) / 256), static_cast<unsigned>(count));
      residentDabKernel<<<grid, block>>>(p.pool, reinterpret_cast<const ChunkJob*>(dev + oJobs) + first, p.edge,
        p.shift, dims[0], dims[1], dims[2], reinterpret_cast<const Dab*>(dev), reinterpret_cast<const Box*>(dev + oBoxes),
        static_cast<int>(plan.dabs.size()), ctx, p.table, enc,
        reinterpret_cast<ChunkChange*>(dev + oChanges) + first);
      LVDIF_CUDA_CHECK(cudaGetLastError());
    }
    LVDIF_CUDA_CHECK(cudaMemcpy(changes.data(), dev + oChanges, sizeof(ChunkChange) * nChunks, cudaMemcpyDeviceToHost));
  }
  catch (...)
  {
    // the destination slots may be half written, the sources are intact: give the new slots back
    for (std::size_t i = 0; i < nChunks; ++i)
      if (jobs[i].dst != jobs[i].src)
        p.freeSlots.push_back(jobs[i].dst);
    throw;
  }
  for (std::size_t i = 0; i < nChunks; ++i)
  {
    const std::size_t id = static_cast<std::size_t>(plan.chunks[i]);
    const ChunkJob& j = jobs[i];
    const ChunkChange& c = changes[i];
    if (c.count == 0)
    {
      // unchanged: keep the source, give a new slot back
      if (j.dst != j.src)
        p.freeSlots.push_back(j.dst);
      continue;
    }
    result.changedChunks.push_back(static_cast<std::int64_t>(id));
    result.changedVoxels += static_cast<std::int64_t>(c.count);
    VoxelBox b;
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] = j.origin[a] + c.lo[a];
      b.hi[a] = j.origin[a] + c.hi[a];
    }
    result.changedBox = result.changedBox.unite(b);
    result.changedChunkBoxes.push_back(b);
    p.markPending(id);
    if (j.dst != j.src)
    {
      if (cow && !p.inOpen[id])
      {
        // the old state is the step's snapshot
        p.open->chunks.push_back({ static_cast<std::int64_t>(id), j.src, j.value });
        const std::uint64_t b = p.snapshotBytes(p.open->chunks.back());
        p.open->bytes += b;
        p.historyBytes += b;
        p.inOpen[id] = 1;
      }
      else if (j.src >= 0)
        p.freeSlots.push_back(j.src); // cannot happen (in place outside a step) but keeps the pool whole
      p.slotOf[id] = j.dst;
      p.tablesStale = true;
    }
  }
  return result;
}

void DeviceVolume::beginStep()
{
  require(!this->P->open, "a device history step is already open");
  this->P->open = std::make_unique<Impl::Step>();
}

bool DeviceVolume::endStep()
{
  Impl& p = *this->P;
  require(p.open != nullptr, "no device history step is open");
  std::unique_ptr<Impl::Step> st = std::move(p.open);
  for (const Impl::Snapshot& s : st->chunks)
    p.inOpen[static_cast<std::size_t>(s.id)] = 0;
  if (st->chunks.empty())
    return false; // (its bytes are 0)
  p.clearRedo();
  p.undo.push_back(std::move(*st));
  p.trimHistory(0);
  return true;
}

bool DeviceVolume::inStep() const
{
  return this->P->open != nullptr;
}

bool DeviceVolume::canUndo() const
{
  return !this->P->undo.empty();
}

bool DeviceVolume::canRedo() const
{
  return !this->P->redo.empty();
}

std::size_t DeviceVolume::undoCount() const
{
  return this->P->undo.size();
}

std::size_t DeviceVolume::redoCount() const
{
  return this->P->redo.size();
}

bool DeviceVolume::undo()
{
  Impl& p = *this->P;
  require(!p.open, "finish the open step before undo");
  if (p.undo.empty())
    return false;
  Impl::Step st = std::move(p.undo.back());
  p.undo.pop_back();
  p.swapIn(st);
  p.redo.push_back(std::move(st));
  return true;
}

bool DeviceVolume::redo()
{
  Impl& p = *this->P;
  require(!p.open, "finish the open step before redo");
  if (p.redo.empty())
    return false;
  Impl::Step st = std::move(p.redo.back());
  p.redo.pop_back();
  p.swapIn(st);
  p.undo.push_back(std::move(st));
  return true;
}

const std::vector<std::int64_t>& DeviceVolume::lastRestoredChunks() const
{
  return this->P->lastRestored;
}

void DeviceVolume::clearHistory()
{
  Impl& p = *this->P;
  require(!p.open, "finish the open step before clearing the history");
  for (Impl::Step& st : p.undo)
    p.freeStep(st);
  p.undo.clear();
  p.clearRedo();
}

std::uint64_t DeviceVolume::historyDeviceBytes() const
{
  return this->P->historyBytes;
}

DeviceVolumeView DeviceVolume::view()
{
  Impl& p = *this->P;
  const std::size_t chunks = p.slotOf.size();
  if (p.tablesStale)
  {
    LVDIF_CUDA_CHECK(cudaMemcpy(p.devSlotOf, p.slotOf.data(), sizeof(int) * chunks, cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemcpy(p.devUniform, p.uniform.data(), sizeof(std::uint32_t) * chunks, cudaMemcpyHostToDevice));
    p.tablesStale = false;
  }
  const std::vector<Rgba>& colors = this->Volume.colors().colors();
  if (colors.size() > p.paletteUploaded)
  {
    static_assert(sizeof(Rgba) == sizeof(std::uint32_t), "a colour is 4 bytes");
    LVDIF_CUDA_CHECK(cudaMemcpy(p.devPalette + p.paletteUploaded, colors.data() + p.paletteUploaded,
      sizeof(Rgba) * (colors.size() - p.paletteUploaded), cudaMemcpyHostToDevice));
    p.paletteUploaded = colors.size();
  }
  DeviceVolumeView v;
  v.pool = p.pool;
  v.slotOf = p.devSlotOf;
  v.uniform = p.devUniform;
  v.sdfTable = p.table;
  v.palette = p.devPalette;
  const Index3& dims = this->Volume.dims();
  const Index3& cc = this->Volume.chunkCounts();
  for (int a = 0; a < 3; ++a)
  {
    v.dims[a] = dims[a];
    v.chunkCounts[a] = cc[a];
  }
  v.chunkEdge = p.edge;
  v.shift = p.shift;
  // the uploads above are from pageable memory: make sure they landed before
  // other streams (the marching cubes') read the tables
  LVDIF_CUDA_CHECK(cudaStreamSynchronize(0));
  return v;
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
    {
      const std::size_t id = static_cast<std::size_t>(ids[first + t]);
      if (p.slotOf[id] >= 0)
        LVDIF_CUDA_CHECK(cudaMemcpyAsync(p.staging + t * p.n, p.pool + static_cast<std::size_t>(p.slotOf[id]) * p.n,
          p.chunkBytes, cudaMemcpyDeviceToHost, 0));
      else
        std::fill(p.staging + t * p.n, p.staging + (t + 1) * p.n, p.uniform[id]); // restored by undo as uniform
    }
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
        result.changedBox = result.changedBox.unite(volume.chunkBox(static_cast<std::int64_t>(id)));
        result.changedChunkBoxes.push_back(volume.chunkBox(static_cast<std::int64_t>(id)));
      }
      if (volume.isUniform(static_cast<std::int64_t>(id)) && p.slotOf[id] >= 0)
      {
        // collapsed on the host: free the slot, the device keeps the value (the
        // history's snapshots are other slots)
        p.freeSlots.push_back(p.slotOf[id]);
        p.slotOf[id] = -1;
        p.uniform[id] = bitsOf(volume.uniformValue(static_cast<std::int64_t>(id)));
        p.tablesStale = true;
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

void DeviceVolume::adoptHostChunks(const std::vector<std::int64_t>& ids)
{
  Impl& p = *this->P;
  for (std::int64_t id : ids)
  {
    require(id >= 0 && id < this->Volume.chunkCount(), "adoptHostChunks: chunk id " + std::to_string(id) + " out of range");
    require(!p.pending[static_cast<std::size_t>(id)], "adoptHostChunks: chunk " + std::to_string(id) + " is pending (sync first)");
  }
  p.trimHistory(ids.size());
  for (std::int64_t id : ids)
  {
    const std::size_t i = static_cast<std::size_t>(id);
    if (p.open && !p.inOpen[i])
    {
      // copy on write: the device's state is the step's snapshot, the host's comes into a fresh slot
      p.open->chunks.push_back({ id, p.slotOf[i], p.uniform[i] });
      const std::uint64_t b = p.snapshotBytes(p.open->chunks.back());
      p.open->bytes += b;
      p.historyBytes += b;
      p.inOpen[i] = 1;
      p.slotOf[i] = -1;
    }
    p.upload(this->Volume, id);
  }
}

void DeviceVolume::reload()
{
  Impl& p = *this->P;
  require(!p.open, "finish the open step before reloading");
  this->clearHistory();
  std::fill(p.pending.begin(), p.pending.end(), 0);
  p.pendingCount = 0;
  // first free every slot of a chunk that is uniform on the host, then upload the rest
  const std::int64_t chunks = this->Volume.chunkCount();
  for (std::int64_t id = 0; id < chunks; ++id)
    if (this->Volume.isUniform(id))
      p.upload(this->Volume, id);
  for (std::int64_t id = 0; id < chunks; ++id)
    if (!this->Volume.isUniform(id))
      p.upload(this->Volume, id);
  p.paletteUploaded = 0;
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
    sizeof(float) * SdfDictionary::KeyCount + this->P->launchBytes + sizeof(std::uint32_t) * 65536 +
    static_cast<std::uint64_t>(this->P->slotOf.size()) * 8;
}

} // namespace cuda
} // namespace lvdif
