#include "lvdif/DictionaryVolume.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <new>
#include <sstream>

namespace lvdif
{

namespace
{
// Striped locks guard chunk expansion; reads never lock.
std::mutex& expansionLock(std::int64_t id)
{
  static std::mutex locks[256];
  return locks[static_cast<std::uint64_t>(id) & 255u];
}

std::shared_ptr<const SdfDictionary> dictionaryFor(const SdfDictionaryParams& p)
{
  if (p == SdfDictionaryParams())
  {
    // Share the default table instead of building 256 KiB per volume.
    return std::shared_ptr<const SdfDictionary>(&defaultSdfDictionary(), [](const SdfDictionary*) {});
  }
  return std::make_shared<const SdfDictionary>(p);
}

std::int64_t chunkSize(int edge)
{
  return static_cast<std::int64_t>(edge) * edge * edge;
}

// A chunk buffer: a reference count (the volumes sharing it, see clone) in a
// header of its own cache line, then the voxels.
struct BufferHeader
{
  std::atomic<std::int32_t> refs{ 1 };
};
constexpr std::size_t HeaderBytes = 64;
static_assert(sizeof(BufferHeader) <= HeaderBytes, "the header fits its line");

BufferHeader* headerOf(const Voxel* d)
{
  return reinterpret_cast<BufferHeader*>(reinterpret_cast<char*>(const_cast<Voxel*>(d)) - HeaderBytes);
}

Voxel* allocateBuffer(std::int64_t n)
{
  char* raw = static_cast<char*>(::operator new(HeaderBytes + static_cast<std::size_t>(n) * sizeof(Voxel)));
  new (raw) BufferHeader();
  return reinterpret_cast<Voxel*>(raw + HeaderBytes);
}

/// Drops one reference; the last one frees the buffer.
void releaseBuffer(Voxel* d)
{
  BufferHeader* h = headerOf(d);
  if (h->refs.fetch_sub(1, std::memory_order_acq_rel) == 1)
  {
    h->~BufferHeader();
    ::operator delete(reinterpret_cast<char*>(h));
  }
}
} // namespace

bool DictionaryVolume::ownsBuffer(const Voxel* d)
{
  return headerOf(d)->refs.load(std::memory_order_acquire) == 1;
}

VoxelBox VoxelBox::intersect(const VoxelBox& o) const
{
  VoxelBox r;
  for (int a = 0; a < 3; ++a)
  {
    r.lo[a] = std::max(lo[a], o.lo[a]);
    r.hi[a] = std::min(hi[a], o.hi[a]);
  }
  return r;
}

static void validateOptions(const VolumeOptions& o)
{
  for (int a = 0; a < 3; ++a)
  {
    if (o.dims[a] < 1 || o.dims[a] > DictionaryVolume::MaxDimension)
    {
      std::ostringstream msg;
      msg << "volume dimensions " << o.dims[0] << " x " << o.dims[1] << " x " << o.dims[2]
          << " are out of range (each must be 1.." << DictionaryVolume::MaxDimension << ")";
      throw Error(ErrorCode::InvalidArgument, msg.str());
    }
  }
  const std::string geometry = DictionaryVolume::checkGeometry(o);
  require(geometry.empty(), geometry);
  const int e = o.chunkEdge;
  if (e < 4 || e > 256 || (e & (e - 1)) != 0)
  {
    std::ostringstream msg;
    msg << "chunk edge " << e << " must be a power of two in [4, 256]";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
  require(o.bandWidth > 0 && !std::isnan(o.bandWidth), "band width must be > 0 (or infinity for full)");
  // narrower, every distance would be stored as 0: no sign, no surface
  if (o.bandWidth < o.dictionary.stepA)
  {
    std::ostringstream msg;
    msg << "band width " << o.bandWidth << " is below the distance dictionary's step of " << o.dictionary.stepA
        << " voxel: every distance would be stored as 0 and the signs lost";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
}

std::uint64_t DictionaryVolume::tableBytes(const VolumeOptions& o)
{
  validateOptions(o);
  std::uint64_t n = 1;
  for (int a = 0; a < 3; ++a)
  {
    n = checkedMultiply(n, static_cast<std::uint64_t>((o.dims[a] + o.chunkEdge - 1) / o.chunkEdge), "chunk table");
  }
  return checkedMultiply(n, sizeof(Chunk), "chunk table");
}

std::uint64_t DictionaryVolume::denseBytes(const VolumeOptions& o)
{
  const std::uint64_t table = tableBytes(o);
  const std::uint64_t chunks = table / sizeof(Chunk);
  return table + checkedMultiply(chunks, static_cast<std::uint64_t>(chunkSize(o.chunkEdge)) * sizeof(Voxel), "dense volume");
}

VolumeOptions volumeOptionsOn(const GridGeometry& grid)
{
  VolumeOptions o;
  o.dims = grid.dims;
  o.origin = grid.origin;
  o.spacing = grid.spacing;
  return o;
}

GridGeometry gridOf(const VolumeOptions& options)
{
  GridGeometry g;
  g.dims = options.dims;
  g.origin = options.origin;
  g.spacing = options.spacing;
  return g;
}

std::string DictionaryVolume::checkCanvasDimensions(const Index3& dims)
{
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < MinCanvasDimension || dims[a] > MaxDimension)
    {
      std::ostringstream msg;
      msg << "a canvas of " << dims[0] << " x " << dims[1] << " x " << dims[2] << " voxels cannot be edited: each axis needs "
          << MinCanvasDimension << ".." << MaxDimension << " voxels (marching cubes needs one cell per axis)";
      return msg.str();
    }
  }
  return "";
}

void DictionaryVolume::requireCanvasDimensions(const Index3& dims)
{
  const std::string problem = checkCanvasDimensions(dims);
  require(problem.empty(), problem);
}

std::shared_ptr<DictionaryVolume> DictionaryVolume::newCanvas(const VolumeOptions& options)
{
  requireCanvasDimensions(options.dims);
  return std::make_shared<DictionaryVolume>(options);
}

std::string DictionaryVolume::checkGeometry(const VolumeOptions& o)
{
  for (int a = 0; a < 3; ++a)
  {
    // the world coordinates of the first and the last voxel, as worldPosition()
    // computes them (|origin| + spacing x dims refused a grid of a mesh spanning
    // [-4e29, 4e29], every voxel of which is within the range)
    const double last = o.origin[a] + double(std::max<std::int64_t>(o.dims[a] - 1, 0)) * o.spacing[a];
    const double far = std::max(std::fabs(o.origin[a]), std::fabs(last));
    if (!std::isfinite(o.origin[a]) || !std::isfinite(o.spacing[a]) || !(o.spacing[a] >= MinSpacing) ||
      !(far <= MaxWorldCoordinate))
    {
      std::ostringstream msg;
      msg << "volume origin " << o.origin[a] << " and spacing " << o.spacing[a] << " on axis " << "xyz"[a]
          << " must be finite, spacing >= " << MinSpacing << ", and keep every voxel within +-"
          << MaxWorldCoordinate << " (float vertices)";
      return msg.str();
    }
  }
  return std::string();
}

DictionaryVolume::DictionaryVolume(const VolumeOptions& options)
{
  this->init(options, Voxel{}, false);
}

DictionaryVolume::DictionaryVolume(const VolumeOptions& options, Voxel fill)
{
  this->init(options, fill, true);
}

void DictionaryVolume::init(const VolumeOptions& options, Voxel fill, bool useFill)
{
  validateOptions(options);
  this->Options = options;
  this->Limit = options.memoryLimit ? options.memoryLimit : memoryLimitBytes();
  const std::uint64_t table = tableBytes(options);
  requireMemory(table, "chunk table of a " + std::to_string(options.dims[0]) + " x " +
      std::to_string(options.dims[1]) + " x " + std::to_string(options.dims[2]) + " volume",
    this->Limit);
  this->Sdf = dictionaryFor(options.dictionary);
  this->Shift = 0;
  while ((1 << this->Shift) < options.chunkEdge)
  {
    ++this->Shift;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->ChunkCounts[a] = (options.dims[a] + options.chunkEdge - 1) / options.chunkEdge;
  }
  this->ChunkTotal = this->ChunkCounts[0] * this->ChunkCounts[1] * this->ChunkCounts[2];
  this->Chunks.reset(new Chunk[static_cast<size_t>(this->ChunkTotal)]);
  const Voxel v = useFill ? fill : this->outsideVoxel();
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    this->Chunks[i].Uniform = v;
  }
}

DictionaryVolume::~DictionaryVolume()
{
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    if (Voxel* d = this->Chunks[i].Data.load())
    {
      releaseBuffer(d);
    }
  }
}

std::unique_ptr<DictionaryVolume> DictionaryVolume::clone() const
{
  auto copy = std::make_unique<DictionaryVolume>(this->Options);
  copy->Colors = this->Colors;
  std::int64_t shared = 0;
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    copy->Chunks[i].Uniform = this->Chunks[i].Uniform;
    if (Voxel* d = this->Chunks[i].Data.load(std::memory_order_acquire))
    {
      // copy-on-write: both volumes hold the buffer; a write copies it (expandChunk)
      headerOf(d)->refs.fetch_add(1, std::memory_order_relaxed);
      copy->Chunks[i].Data.store(d, std::memory_order_release);
      ++shared;
    }
  }
  copy->Expanded.store(shared);
  return copy;
}

std::int64_t DictionaryVolume::sharedChunkCount() const
{
  std::int64_t n = 0;
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    const Voxel* d = this->chunkData(i);
    n += d && !ownsBuffer(d) ? 1 : 0;
  }
  return n;
}

VoxelBox DictionaryVolume::bounds() const
{
  VoxelBox b;
  b.lo = { 0, 0, 0 };
  b.hi = { this->Options.dims[0] - 1, this->Options.dims[1] - 1, this->Options.dims[2] - 1 };
  return b;
}

std::array<double, 3> DictionaryVolume::worldPosition(double x, double y, double z) const
{
  const auto& o = this->Options;
  return { o.origin[0] + x * o.spacing[0], o.origin[1] + y * o.spacing[1], o.origin[2] + z * o.spacing[2] };
}

void DictionaryVolume::set(std::int64_t x, std::int64_t y, std::int64_t z, Voxel v)
{
  const std::int64_t id = this->chunkOf(x, y, z);
  Chunk& c = this->Chunks[id];
  Voxel* d = c.Data.load(std::memory_order_acquire);
  if (!d)
  {
    if (c.Uniform == v)
    {
      return; // writing the uniform value changes nothing
    }
    d = this->expandChunk(id);
  }
  else if (!ownsBuffer(d))
  {
    d = this->expandChunk(id); // shared with a clone: copy it first
  }
  d[this->localIndex(x, y, z)] = v;
  c.RangeStale.store(1, std::memory_order_relaxed);
  c.Dirty.store(1, std::memory_order_relaxed);
}

void DictionaryVolume::setSdf(std::int64_t x, std::int64_t y, std::int64_t z, float d)
{
  Voxel v = this->get(x, y, z);
  v.sdf = this->encode(d);
  this->set(x, y, z, v);
}

Voxel DictionaryVolume::at(std::int64_t x, std::int64_t y, std::int64_t z) const
{
  if (!this->inside(x, y, z))
  {
    std::ostringstream msg;
    msg << "voxel (" << x << ", " << y << ", " << z << ") is outside the volume " << this->Options.dims[0]
        << " x " << this->Options.dims[1] << " x " << this->Options.dims[2];
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
  return this->get(x, y, z);
}

Index3 DictionaryVolume::chunkCoord(std::int64_t id) const
{
  const std::int64_t cx = id % this->ChunkCounts[0];
  const std::int64_t rest = id / this->ChunkCounts[0];
  return { cx, rest % this->ChunkCounts[1], rest / this->ChunkCounts[1] };
}

VoxelBox DictionaryVolume::chunkBox(std::int64_t id) const
{
  const Index3 c = this->chunkCoord(id);
  VoxelBox b;
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = c[a] * this->Options.chunkEdge;
    b.hi[a] = std::min(b.lo[a] + this->Options.chunkEdge, this->Options.dims[a]) - 1;
  }
  return b;
}

Voxel* DictionaryVolume::expandChunk(std::int64_t id)
{
  Chunk& c = this->Chunks[id];
  Voxel* d = c.Data.load(std::memory_order_acquire);
  if (d && ownsBuffer(d))
  {
    return d;
  }
  std::lock_guard<std::mutex> lock(expansionLock(id));
  d = c.Data.load(std::memory_order_acquire);
  const std::int64_t n = chunkSize(this->Options.chunkEdge);
  if (d)
  {
    if (ownsBuffer(d))
    {
      return d;
    }
    // shared with a clone: this volume gets its own copy (already counted in
    // its memory), the other keeps the buffer
    Voxel* own = allocateBuffer(n);
    std::memcpy(own, d, static_cast<std::size_t>(n) * sizeof(Voxel));
    c.Data.store(own, std::memory_order_release);
    releaseBuffer(d);
    return own;
  }
  const std::uint64_t bytes = static_cast<std::uint64_t>(n) * sizeof(Voxel);
  // Reserve the chunk only if it fits, in one compare-and-swap: threads
  // expanding different chunks at once then never pass the limit together (a
  // check before counting let 16 threads overshoot by 15 chunks) and never
  // refuse a chunk that fits (a count before checking made threads refuse
  // each other's transient reservations: 3 of 5 fitting chunks on a 16-core host).
  std::int64_t expanded = this->Expanded.load();
  while (true)
  {
    const std::uint64_t used = this->memoryBytesWith(expanded);
    if (used + bytes > this->Limit)
    {
      std::ostringstream msg;
      msg << "expanding chunk " << id << " needs " << formatBytes(bytes) << " more; the volume holds "
          << formatBytes(used) << " of its " << formatBytes(this->Limit) << " limit";
      throw Error(ErrorCode::OutOfMemory, msg.str());
    }
    if (this->Expanded.compare_exchange_weak(expanded, expanded + 1)) break;
  }
  try
  {
    d = allocateBuffer(n);
  }
  catch (...)
  {
    this->Expanded.fetch_sub(1);
    throw;
  }
  std::fill(d, d + n, c.Uniform);
  c.Data.store(d, std::memory_order_release);
  return d;
}

void DictionaryVolume::freeChunkData(Chunk& c)
{
  Voxel* d = c.Data.exchange(nullptr);
  if (d)
  {
    releaseBuffer(d);
    this->Expanded.fetch_sub(1);
  }
}

void DictionaryVolume::fillChunk(std::int64_t id, Voxel v)
{
  Chunk& c = this->Chunks[id];
  this->freeChunkData(c);
  c.Uniform = v;
  c.RangeStale.store(1);
  c.Dirty.store(1);
}

bool DictionaryVolume::tryCollapseChunk(std::int64_t id)
{
  Chunk& c = this->Chunks[id];
  const Voxel* d = c.Data.load(std::memory_order_acquire);
  if (!d)
  {
    return true;
  }
  const VoxelBox b = this->chunkBox(id);
  const Voxel first = d[this->localIndex(b.lo[0], b.lo[1], b.lo[2])];
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
  {
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
    {
      const Voxel* row = d + this->localIndex(b.lo[0], y, z);
      const std::int64_t n = b.hi[0] - b.lo[0] + 1;
      for (std::int64_t i = 0; i < n; ++i)
      {
        if (row[i] != first)
        {
          return false;
        }
      }
    }
  }
  c.Uniform = first;
  this->freeChunkData(c);
  c.RangeStale.store(1);
  return true;
}

std::int64_t DictionaryVolume::collapseUniformChunks()
{
  std::int64_t collapsed = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : collapsed)
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    if (this->Chunks[i].Data.load() && this->tryCollapseChunk(i))
    {
      ++collapsed;
    }
  }
  return collapsed;
}

std::vector<std::int64_t> DictionaryVolume::chunksInBox(const VoxelBox& box) const
{
  std::vector<std::int64_t> ids;
  this->forEachChunkInBox(box, [&](std::int64_t id) { ids.push_back(id); });
  return ids;
}

void DictionaryVolume::forEachChunkInBox(
  const VoxelBox& box, const std::function<void(std::int64_t)>& fn) const
{
  const VoxelBox b = box.intersect(this->bounds());
  if (b.empty())
  {
    return;
  }
  Index3 lo, hi;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = b.lo[a] >> this->Shift;
    hi[a] = b.hi[a] >> this->Shift;
  }
  for (std::int64_t cz = lo[2]; cz <= hi[2]; ++cz)
    for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy)
      for (std::int64_t cx = lo[0]; cx <= hi[0]; ++cx)
        fn(this->chunkId(cx, cy, cz));
}

std::pair<SdfKey, SdfKey> DictionaryVolume::chunkRange(std::int64_t id) const
{
  const Chunk& c = this->Chunks[id];
  if (c.RangeStale.load(std::memory_order_acquire))
  {
    const Voxel* d = c.Data.load(std::memory_order_acquire);
    SdfKey lo = c.Uniform.sdf, hi = c.Uniform.sdf;
    if (d)
    {
      const VoxelBox b = this->chunkBox(id);
      lo = hi = d[this->localIndex(b.lo[0], b.lo[1], b.lo[2])].sdf;
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        {
          const Voxel* row = d + this->localIndex(b.lo[0], y, z);
          for (std::int64_t i = 0, n = b.hi[0] - b.lo[0] + 1; i < n; ++i)
          {
            lo = std::min(lo, row[i].sdf);
            hi = std::max(hi, row[i].sdf);
          }
        }
    }
    c.MinKey = lo;
    c.MaxKey = hi;
    c.RangeStale.store(0, std::memory_order_release);
  }
  return { c.MinKey, c.MaxKey };
}

void DictionaryVolume::markDirty(const VoxelBox& box)
{
  this->forEachChunkInBox(box, [this](std::int64_t id) { this->markDirty(id); });
}

std::vector<std::int64_t> DictionaryVolume::takeDirtyChunks()
{
  std::vector<std::int64_t> ids;
  for (std::int64_t i = 0; i < this->ChunkTotal; ++i)
  {
    if (this->Chunks[i].Dirty.exchange(0, std::memory_order_relaxed))
    {
      ids.push_back(i);
    }
  }
  return ids;
}

std::uint64_t DictionaryVolume::memoryBytes() const
{
  return this->memoryBytesWith(this->Expanded.load());
}

std::uint64_t DictionaryVolume::memoryBytesWith(std::int64_t expanded) const
{
  const std::uint64_t table = static_cast<std::uint64_t>(this->ChunkTotal) * sizeof(Chunk);
  const std::uint64_t data = static_cast<std::uint64_t>(expanded) *
    static_cast<std::uint64_t>(chunkSize(this->Options.chunkEdge)) * sizeof(Voxel);
  const std::uint64_t dict = this->Colors.size() * (sizeof(Rgba) + 16);
  return table + data + dict;
}

} // namespace lvdif
