// The dictionary volume (paper Sect. 3.3.2): every voxel is 4 bytes, a 16-bit
// SDF dictionary key and a 16-bit colour dictionary key, stored sparsely as a
// grid of cubic chunks.
//
// * A chunk whose voxels are all equal is stored as that one value
//   ("uniform"); others hold chunkEdge^3 voxels (4 bytes each).
// * A band width (in voxels, the unit of every stored distance) saturates
//   distances: setSdf() stores clamp(d, -band, +band), so far chunks become
//   uniform +band (outside) or -band (inside) and collapse. band = infinity
//   keeps every distance the dictionary can represent ("full", as the paper).
// * Sign convention: negative inside. Voxel index (x, y, z), x fastest, 64-bit.
// * Dirty flags per chunk record which chunks were written since the last
//   takeDirtyChunks(), for incremental marching cubes.
// * Per-chunk key ranges (min/max SDF key) are recomputed lazily after
//   writes, so chunkRange() is always exact.
//
// * clone() is copy-on-write: the copy shares the expanded chunks' voxel
//   buffers (reference counted); the first write to a shared chunk, in either
//   volume, copies that chunk only. So a filter that must leave its input
//   alone (VTK) clones it and pays only for the chunks it changes.
//
// Threading: reads are safe from any thread. Writes to different chunks are
// safe concurrently; concurrent writes to one chunk are safe only if the
// chunk was expanded first (expandChunk) and the threads write distinct voxels.
// clone() reads: it must not run while another thread writes the volume.
#pragma once

#include "lvdif/ColorDictionary.h"
#include "lvdif/DenseGrid.h"
#include "lvdif/SdfDictionary.h"
#include "lvdif/TriangleMesh.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

namespace lvdif
{

struct Voxel
{
  SdfKey sdf = 0;
  ColorKey color = 0;
  bool operator==(const Voxel& o) const { return sdf == o.sdf && color == o.color; }
  bool operator!=(const Voxel& o) const { return !(*this == o); }
};
static_assert(sizeof(Voxel) == 4, "a voxel is 4 bytes");

using Index3 = std::array<std::int64_t, 3>;

/// An inclusive box of voxel indices [lo, hi] per axis; empty if any hi < lo.
struct VoxelBox
{
  Index3 lo{ 0, 0, 0 };
  Index3 hi{ -1, -1, -1 };
  bool empty() const { return hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2]; }
  std::int64_t voxelCount() const
  {
    return empty() ? 0 : (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
  }
  bool contains(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x >= lo[0] && x <= hi[0] && y >= lo[1] && y <= hi[1] && z >= lo[2] && z <= hi[2];
  }
  VoxelBox intersect(const VoxelBox& o) const;
  /// The smallest box holding both (an empty box is neutral).
  VoxelBox unite(const VoxelBox& o) const
  {
    if (o.empty()) return *this;
    if (empty()) return o;
    VoxelBox b;
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] = lo[a] < o.lo[a] ? lo[a] : o.lo[a];
      b.hi[a] = hi[a] > o.hi[a] ? hi[a] : o.hi[a];
    }
    return b;
  }
  /// Grows the box to hold the voxel (x, y, z).
  void include(std::int64_t x, std::int64_t y, std::int64_t z)
  {
    *this = unite(VoxelBox{ { x, y, z }, { x, y, z } });
  }
};

struct VolumeOptions
{
  Index3 dims{ 64, 64, 64 };
  int chunkEdge = 32;                      // 4..256
  std::array<double, 3> origin{ 0, 0, 0 }; // world position of voxel (0,0,0)
  std::array<double, 3> spacing{ 1, 1, 1 };
  /// Distances saturate to +-bandWidth (voxel units). Default 8 serves marching
  /// cubes (needs |d| < 1), the sign filters (threshold 2) and brushes of any
  /// radius (CSG only needs the field near the new surface). Use
  /// std::numeric_limits<float>::infinity() for "full".
  float bandWidth = 8.0f;
  SdfDictionaryParams dictionary;
  /// Bytes this volume may allocate; 0 means memoryLimitBytes() at construction.
  std::uint64_t memoryLimit = 0;
};

/// The options of a volume on `grid` (its dimensions, origin and spacing; the
/// rest as the defaults above), and back: the one conversion between the two.
VolumeOptions volumeOptionsOn(const GridGeometry& grid);
GridGeometry gridOf(const VolumeOptions& options);

class DictionaryVolume
{
public:
  static constexpr std::int64_t MaxDimension = 1 << 20;
  /// Largest |world coordinate| of any voxel (origin + index x spacing), and the
  /// smallest spacing: meshes have float vertices, so every world position must
  /// stay far inside float range (no Inf or NaN vertex, no collapsed axis).
  static constexpr double MaxWorldCoordinate = lvdif::MaxWorldCoordinate; // TriangleMesh.h
  static constexpr double MinSpacing = 1e-30;
  /// The rule above for these options; "" if they pass, else the reason.
  static std::string checkGeometry(const VolumeOptions& o);
  /// The smallest volume an edit session (and so every editor front end: the
  /// script's `canvas`, the Qt editor, vtkLVDIFEditor, `lvdif demo --size`)
  /// takes, per axis: the session meshes its volume, and marching cubes needs
  /// one cell, 2 points, per axis. Files may hold thinner volumes (they mesh to
  /// nothing); only editing refuses them.
  static constexpr std::int64_t MinCanvasDimension = 2;
  /// "" if every axis is in [MinCanvasDimension, MaxDimension], else the one
  /// message each front end reports (option parsers that prefix or place it).
  static std::string checkCanvasDimensions(const Index3& dims);
  /// The same rule, throwing Error(InvalidArgument) with that message: what
  /// EditSession enforces on every volume it is given.
  static void requireCanvasDimensions(const Index3& dims);
  /// A new all-outside canvas for an editor: requireCanvasDimensions first,
  /// so an unusable canvas is refused with the canvas words before the
  /// volume's own (wider) range check or any allocation.
  static std::shared_ptr<DictionaryVolume> newCanvas(const VolumeOptions& options);

  /// Creates an all-outside volume (every voxel +band, colour 0), or filled with
  /// `fill` when given. Validates the options and refuses absurd sizes before
  /// allocating (Error InvalidArgument / OutOfMemory).
  explicit DictionaryVolume(const VolumeOptions& options);
  DictionaryVolume(const VolumeOptions& options, Voxel fill);
  ~DictionaryVolume();
  DictionaryVolume(const DictionaryVolume&) = delete;
  DictionaryVolume& operator=(const DictionaryVolume&) = delete;

  /// A copy (the same chunks expanded, same dictionaries, flags cleared) that
  /// shares the expanded chunks' buffers until one side writes to a chunk
  /// (copy-on-write): cloning costs the chunk table only.
  std::unique_ptr<DictionaryVolume> clone() const;
  /// Expanded chunks whose buffer another volume (a clone) shares now.
  std::int64_t sharedChunkCount() const;

  // ---- geometry ---------------------------------------------------------
  const VolumeOptions& options() const { return this->Options; }
  const Index3& dims() const { return this->Options.dims; }
  std::int64_t voxelCount() const { return this->Options.dims[0] * this->Options.dims[1] * this->Options.dims[2]; }
  int chunkEdge() const { return this->Options.chunkEdge; }
  const Index3& chunkCounts() const { return this->ChunkCounts; }
  std::int64_t chunkCount() const { return this->ChunkTotal; }
  float bandWidth() const { return this->Options.bandWidth; }
  VoxelBox bounds() const;
  std::array<double, 3> worldPosition(double x, double y, double z) const;
  bool inside(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x >= 0 && y >= 0 && z >= 0 && x < this->Options.dims[0] && y < this->Options.dims[1] &&
      z < this->Options.dims[2];
  }

  // ---- dictionaries -----------------------------------------------------
  const SdfDictionary& sdfDictionary() const { return *this->Sdf; }
  ColorDictionary& colors() { return this->Colors; }
  const ColorDictionary& colors() const { return this->Colors; }
  /// Band-clamped encoding used by every write of a distance.
  SdfKey encode(float d) const { return this->Sdf->encodeClamped(d, this->Options.bandWidth); }
  float decode(SdfKey k) const { return this->Sdf->decode(k); }
  Voxel outsideVoxel() const { return Voxel{ this->encode(this->Options.bandWidth), 0 }; }
  Voxel insideVoxel() const { return Voxel{ this->encode(-this->Options.bandWidth), 0 }; }

  // ---- voxel access (indices must be inside; checked only in debug) ----
  Voxel get(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    const std::int64_t id = this->chunkOf(x, y, z);
    const Voxel* d = this->Chunks[id].Data.load(std::memory_order_acquire);
    return d ? d[this->localIndex(x, y, z)] : this->Chunks[id].Uniform;
  }
  void set(std::int64_t x, std::int64_t y, std::int64_t z, Voxel v);
  float sdf(std::int64_t x, std::int64_t y, std::int64_t z) const { return this->decode(this->get(x, y, z).sdf); }
  /// Writes a distance (band-clamped, encoded), keeping the colour.
  void setSdf(std::int64_t x, std::int64_t y, std::int64_t z, float d);
  /// Bounds-checked read: throws Error(InvalidArgument) outside the volume.
  Voxel at(std::int64_t x, std::int64_t y, std::int64_t z) const;

  // ---- chunks -----------------------------------------------------------
  std::int64_t chunkId(std::int64_t cx, std::int64_t cy, std::int64_t cz) const
  {
    return cx + this->ChunkCounts[0] * (cy + this->ChunkCounts[1] * cz);
  }
  Index3 chunkCoord(std::int64_t id) const;
  std::int64_t chunkOf(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return this->chunkId(x >> this->Shift, y >> this->Shift, z >> this->Shift);
  }
  /// Offset of voxel (x,y,z) inside its chunk's data: lx + E*(ly + E*lz).
  std::int64_t localIndex(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    const std::int64_t m = this->Options.chunkEdge - 1;
    return (x & m) + (static_cast<std::int64_t>(y & m) << this->Shift) +
      (static_cast<std::int64_t>(z & m) << (2 * this->Shift));
  }
  /// The voxels a chunk owns, clipped to the volume.
  VoxelBox chunkBox(std::int64_t id) const;
  bool isUniform(std::int64_t id) const { return this->Chunks[id].Data.load(std::memory_order_acquire) == nullptr; }
  Voxel uniformValue(std::int64_t id) const { return this->Chunks[id].Uniform; }
  /// Data of an expanded chunk (chunkEdge^3 voxels, layout of localIndex), or
  /// nullptr if uniform. Read-only: it may be shared with a clone.
  const Voxel* chunkData(std::int64_t id) const { return this->Chunks[id].Data.load(std::memory_order_acquire); }
  /// Expands a uniform chunk (thread-safe, idempotent) and returns its data,
  /// writable: a buffer shared with a clone is copied first. Does not mark
  /// the chunk dirty. Throws Error(OutOfMemory) past the limit.
  Voxel* expandChunk(std::int64_t id);
  /// Makes the chunk uniform with value v (frees its data); marks it dirty.
  void fillChunk(std::int64_t id, Voxel v);
  /// Frees the chunk's data if all its voxels (inside the volume) are equal.
  bool tryCollapseChunk(std::int64_t id);
  /// tryCollapseChunk on every chunk (OpenMP); returns how many collapsed.
  std::int64_t collapseUniformChunks();
  /// Ids of the chunks that own at least one voxel of the box (x fastest).
  std::vector<std::int64_t> chunksInBox(const VoxelBox& box) const;
  void forEachChunkInBox(const VoxelBox& box, const std::function<void(std::int64_t)>& fn) const;
  std::int64_t expandedChunkCount() const { return this->Expanded.load(); }

  /// Exact min and max SDF key of the chunk's voxels (recomputed if written since).
  std::pair<SdfKey, SdfKey> chunkRange(std::int64_t id) const;

  // ---- dirty flags --------------------------------------------------------
  void markDirty(std::int64_t id) { this->Chunks[id].Dirty.store(1, std::memory_order_relaxed); }
  /// Marks every chunk whose voxels a box touches.
  void markDirty(const VoxelBox& box);
  bool isDirty(std::int64_t id) const { return this->Chunks[id].Dirty.load(std::memory_order_relaxed) != 0; }
  /// Returns the dirty chunk ids in increasing order and clears their flags.
  std::vector<std::int64_t> takeDirtyChunks();

  // ---- memory -------------------------------------------------------------
  /// Bytes held: chunk table, expanded chunks, dictionaries.
  std::uint64_t memoryBytes() const;
  std::uint64_t memoryLimit() const { return this->Limit; }
  /// Bytes a volume with these options needs with every chunk expanded.
  static std::uint64_t denseBytes(const VolumeOptions& options);
  /// Bytes of the chunk table alone (what the constructor allocates).
  static std::uint64_t tableBytes(const VolumeOptions& options);

private:
  struct Chunk
  {
    std::atomic<Voxel*> Data{ nullptr };
    Voxel Uniform;
    mutable std::atomic<std::uint8_t> RangeStale{ 1 };
    std::atomic<std::uint8_t> Dirty{ 0 };
    mutable SdfKey MinKey = 0, MaxKey = 0;
  };

  void init(const VolumeOptions& options, Voxel fill, bool useFill);
  void freeChunkData(Chunk& c);
  /// memoryBytes() with `expanded` chunks expanded.
  std::uint64_t memoryBytesWith(std::int64_t expanded) const;
  /// True when no other volume holds the buffer (so it may be written).
  static bool ownsBuffer(const Voxel* d);

  VolumeOptions Options;
  std::shared_ptr<const SdfDictionary> Sdf;
  ColorDictionary Colors;
  Index3 ChunkCounts{ 0, 0, 0 };
  std::int64_t ChunkTotal = 0;
  int Shift = 5;
  std::uint64_t Limit = 0;
  std::unique_ptr<Chunk[]> Chunks;
  std::atomic<std::int64_t> Expanded{ 0 };
};

} // namespace lvdif
