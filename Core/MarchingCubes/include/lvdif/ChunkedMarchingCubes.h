// Chunked marching cubes (paper Sect. 3.3, Table 2) over a dictionary volume
// or a dense float grid, seamless across chunks and re-meshable chunk by chunk.
//
// Cells and chunks. Cell (i,j,k) is the cube between points i..i+1, j..j+1,
// k..k+1 (nx-1 cells along x). A marching cubes chunk is a box of
// chunkEdge^3 cells (clipped at the volume's end), so every cell belongs to
// exactly one chunk and no triangle is produced twice. Neighbouring chunks
// read the same boundary points and compute their shared edge vertices with
// the same arithmetic from the same inputs, so the duplicated boundary
// vertices are bit-identical: merging equal positions (mergeChunkMeshes) makes
// the union of chunk meshes crack-free, and watertight for a closed surface.
// The marching cubes chunk need not equal the volume's storage chunk.
//
// Output per chunk: indexed triangles (one vertex per cut edge inside a chunk),
// counter-clockwise seen from outside (normals point from the negative inside
// to the positive outside), per-vertex unit normals from the SDF gradient
// (central differences, one-sided at the volume border, interpolated along the
// edge), per-vertex colours (interpolated along the edge from the two corner
// colours), and per triangle the 8 corner colour keys and the cell it came
// from (for the rendering's tetrahedral colour interpolation).
//
// Case table: see MarchingCubesTables.h (the same contour loops and triangle
// counts as VTK's vtkMarchingCubes / vtkFlyingEdges3D case by case; the
// diagonals inside 4- to 7-vertex loops differ in some cases). A caller may
// pass another triangulation of the same loops (MarchingCubesOptions::
// triangleTable; the VTK filter passes VTK's table, giving VTK's surface). A
// point is "above" (outside) when value >= iso, as in VTK.
//
// Skipping: a chunk whose points are all above or all below iso is empty and
// costs one range test (DictionaryVolume::chunkRange of the storage chunks it
// reads; a cached min/max per chunk for float grids).
#pragma once

#include "lvdif/ColorDictionary.h"
#include "lvdif/Cuda.h"
#include "lvdif/DenseGrid.h"
#include "lvdif/DeviceVolumeView.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MarchingCubesTables.h"
#include "lvdif/TriangleMesh.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace lvdif
{

struct MarchingCubesOptions
{
  float isoValue = 0.0f;
  /// Cells per chunk edge, 16..256 (any value, not only powers of two).
  int chunkEdge = 64;
  bool computeNormals = true;
  /// Per-vertex colours (dictionary volume, or a float grid given with colours).
  bool computeColors = true;
  /// Per triangle: the cell it came from (triangleCells), and on a dictionary
  /// volume the 8 corner colour keys (cornerColors).
  bool cornerColors = true;
  /// Only the cells in this box (grid point indices of the cells' lowest
  /// corners) are meshed; empty (the default) means every cell. Used by the
  /// VTK filter to mesh only the cells a piece owns while reading its ghost
  /// points for the gradients.
  VoxelBox cellRegion;
  /// When the grid is one piece of a larger volume: the global index of the
  /// grid's point (0,0,0). Chunks are aligned to multiples of chunkEdge in global
  /// cell indices and positions are origin + spacing * (global index + t), the
  /// origin being that of the global point 0, so every piece computes the same
  /// chunk grid and bit-identical shared vertices. chunkCoord() is global; chunk
  /// ids, edgeIds and triangleCells stay local to the grid.
  Index3 gridOffset{ 0, 0, 0 };
  /// Cpu, or Cuda/Auto: the GPU when one can be used (resolveDevice), one chunk
  /// at a time; same vertices bit for bit and the same triangles as the CPU.
  Device device = Device::Cpu;
  /// Triangles per case in place of lvdif's own (MarchingCubesTables.h), e.g.
  /// VTK's table converted to our numbering. Checked when the mesher is built
  /// (marchingCubesTablesWith: the same loops, only other diagonals; else
  /// Error InvalidArgument). Null (the default): lvdif's table. Used by the
  /// CPU and the CUDA paths alike.
  std::shared_ptr<const MarchingCubesTriangleTable> triangleTable;
  /// CUDA, extractAllPacked/extractAll: grid points per batch of chunks (the
  /// device staging buffers hold one batch; two batches are in flight). 0 (the
  /// default) means 64 Mi points. Smaller batches use less device memory.
  std::int64_t cudaBatchPoints = 0;
};

/// The mesh of one chunk. Empty (no triangles) when the surface does not cross it.
struct ChunkMesh
{
  std::int64_t chunkId = -1;
  /// Level of detail: 0 full resolution; 1 coarse (ChunkedMarchingCubes::
  /// extractChunkCoarse: every 2nd point per axis, no corner colours, edgeIds
  /// of the coarse grid's edges named by their lower full-resolution point).
  int level = 0;
  Index3 chunkCoord{ 0, 0, 0 };
  /// The cells this chunk owns (inclusive); cell (i,j,k) spans points i..i+1 etc.
  VoxelBox cells;
  /// World coordinates: origin + spacing * point index (vtkImageData convention).
  std::vector<Vec3f> points;
  /// One per point: 3 * (linear index of the edge's lower point) + axis, the
  /// global identity of the cut edge the point lies on. Duplicated boundary
  /// points of neighbouring chunks have equal ids (and equal coordinates).
  std::vector<std::uint64_t> edgeIds;
  /// One unit normal per point (empty if normals are off); outward (along the SDF gradient).
  std::vector<Vec3f> normals;
  /// One colour per point (empty if there are none).
  std::vector<Rgba> colors;
  /// Counter-clockwise seen from outside (the positive side).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Per triangle (empty unless cornerColors on a dictionary volume): colour keys
  /// of the cell's 8 corners, corner c at offset (c&1, (c>>1)&1, (c>>2)&1).
  std::vector<std::array<ColorKey, 8>> cornerColors;
  /// Per triangle (with cornerColors, any source): linear point index
  /// x + nx*(y + ny*z) of the cell's corner 0 (its lowest point) in the grid.
  std::vector<std::int64_t> triangleCells;

  bool empty() const { return this->triangles.empty(); }
  std::uint64_t memoryBytes() const;
};

/// Many chunk meshes in one set of arrays (what extractAllPacked fills): chunk
/// i owns vertices vertexStart[i] .. vertexStart[i+1]-1 and triangles
/// triangleStart[i] .. triangleStart[i+1]-1; triangle vertex indices are local
/// to the chunk, as in ChunkMesh. The arrays live in one host block that is
/// reused by the next extractAllPacked into the same object when it is large
/// enough (on the GPU path the block is page-locked, so the device copies its
/// results straight into it while it computes the next batch). Copyable; copies
/// share the block, and an extraction into an object whose block is shared
/// allocates a new one, so copies stay valid.
class PackedChunkMeshes
{
public:
  std::vector<std::int64_t> chunkIds; // increasing
  std::vector<Index3> chunkCoords;
  std::vector<VoxelBox> chunkCells;
  std::vector<std::uint64_t> vertexStart{ 0 }, triangleStart{ 0 }; // chunkCount() + 1 entries

  std::size_t chunkCount() const { return chunkIds.size(); }
  std::uint64_t vertexCount() const { return vertexStart.back(); }
  std::uint64_t triangleCount() const { return triangleStart.back(); }
  /// Null when the array is off (see MarchingCubesOptions) or there is nothing.
  const Vec3f* points() const;
  const std::uint64_t* edgeIds() const;
  const Vec3f* normals() const;
  const Rgba* colors() const;
  const std::array<std::uint32_t, 3>* triangles() const;
  const std::int64_t* triangleCells() const;
  const std::array<ColorKey, 8>* cornerColors() const;
  /// True when the block is page-locked host memory (filled by the GPU path).
  bool pageLocked() const;
  /// A copy of chunk i as a ChunkMesh.
  ChunkMesh chunk(std::size_t i) const;

  struct Storage; // MarchingCubesImpl.h
  std::shared_ptr<Storage> storage;
};

class ChunkedMarchingCubes
{
public:
  /// Meshes a dictionary volume (distances decoded with its dictionary,
  /// colours from its colour dictionary). The volume must outlive this object.
  ChunkedMarchingCubes(const DictionaryVolume& volume, const MarchingCubesOptions& options = {});
  /// Meshes a dense float grid with optional per-point colours (same layout).
  /// The data must outlive this object; call invalidate() after changing it.
  ChunkedMarchingCubes(const FloatGridView& grid, const Rgba* colors = nullptr,
    const MarchingCubesOptions& options = {});
  ~ChunkedMarchingCubes();
  ChunkedMarchingCubes(const ChunkedMarchingCubes&) = delete;
  ChunkedMarchingCubes& operator=(const ChunkedMarchingCubes&) = delete;

  const MarchingCubesOptions& options() const;
  const Index3& pointDims() const;
  const Index3& chunkCounts() const;
  std::int64_t chunkCount() const;
  VoxelBox chunkCells(std::int64_t id) const;
  Index3 chunkCoord(std::int64_t id) const;

  /// True if the chunk's points are all on one side of iso (no triangles).
  bool chunkIsEmpty(std::int64_t id) const;

  /// Meshes one chunk (thread-safe while nobody writes the source).
  ChunkMesh extractChunk(std::int64_t id) const;
  /// Level of detail 1, a preview (the editor's stroke frames): the chunk
  /// meshed on every 2nd grid point per axis, i.e. exactly the full-resolution
  /// mesh of the grid subsampled by 2 (points 0,2,4,..., spacing doubled, same
  /// origin: the same world coordinates) over the coarse cells whose lowest
  /// point lies in this chunk's cells: 1/8 of the cells, about 1/4 of the
  /// triangles. Normals and point colours as at full resolution (of the
  /// subsampled grid); no corner colours nor triangleCells (the renderer then
  /// colours by vertex). Coarse chunks are seamless among themselves; against
  /// a full-resolution neighbour the surface has cracks. A grid with an odd
  /// number of cells loses its last layer of cells. CPU kernel on any mesher;
  /// needs an even gridOffset (Error InvalidArgument otherwise).
  ChunkMesh extractChunkCoarse(std::int64_t id) const;
  /// Meshes the given chunks (OpenMP over chunks); one result per id, in order,
  /// empty meshes included (so the caller can drop a chunk that lost its surface).
  std::vector<ChunkMesh> extractChunks(const std::vector<std::int64_t>& ids,
    Interrupter& interrupter = nullInterrupter()) const;
  /// Meshes every chunk; returns only the non-empty meshes, by increasing id.
  std::vector<ChunkMesh> extractAll(Interrupter& interrupter = nullInterrupter()) const;
  /// The same meshes packed into one set of arrays (no per-chunk vectors), in
  /// `out`, reusing its block when large enough. On the GPU with a float grid
  /// this is the fast path: batches are computed on one stream while the
  /// previous batch's results are copied on another straight into the
  /// page-locked block. Elsewhere it packs extractAll()'s meshes.
  void extractAllPacked(PackedChunkMeshes& out, Interrupter& interrupter = nullInterrupter()) const;

  /// True when this mesher runs on the GPU (options.device resolved to Cuda).
  bool onDevice() const;
  /// Meshes the given chunks of the dictionary volume this mesher was built
  /// for from its device-resident copy (DeviceVolume::view(), the same voxels as
  /// the host volume would have after a sync) without reading the host volume:
  /// each chunk's input box is decoded on the device and all chunks go through
  /// one launch sequence; only the meshes come back, into `out`'s page-locked
  /// block (reused when large enough). Chunks without triangles are left out.
  /// The same meshes as extractChunks on the synced host volume. Needs
  /// onDevice() and the dictionary constructor (Error InvalidArgument).
  void extractChunksFromDevice(const DeviceVolumeView& volume, const std::vector<std::int64_t>& ids,
    PackedChunkMeshes& out) const;

  // ---- incremental --------------------------------------------------------
  /// The chunks whose meshes can change when the given points change: cells
  /// [lo-1, hi] use those points, and the gradient stencil widens it to [lo-2, hi+1].
  std::vector<std::int64_t> chunksAffectedBy(const VoxelBox& changedPoints) const;
  /// The same for the storage chunk ids a DictionaryVolume reported dirty
  /// (takeDirtyChunks). Only for the dictionary constructor.
  std::vector<std::int64_t> chunksAffectedByStorageChunks(const std::vector<std::int64_t>& storageIds) const;
  /// Float grids: recompute the cached min/max of the chunks reading these points.
  void invalidate(const VoxelBox& changedPoints);

  // ---- low level: copy the input a chunk needs, then mesh the copy --------
  /// What one chunk reads: its points plus the gradient margin (clipped to the
  /// volume), decoded to floats, with colours; a snapshot independent of the source.
  struct ChunkInput
  {
    std::int64_t chunkId = -1;
    VoxelBox cells;
    Index3 lo{ 0, 0, 0 };   // first point of the copied box
    Index3 size{ 0, 0, 0 }; // points per axis of the copied box
    std::vector<float> values;
    std::vector<Rgba> colors;         // empty without colours, or when given as keys + palette
    /// Dictionary volumes for a GPU mesher: colour keys (for corner colours).
    std::vector<ColorKey> colorKeys;
    std::vector<Rgba> palette;        // CPU: copy of the colour dictionary (colour = palette[voxel colour key])
    /// Dictionary volumes on the CPU: the voxels themselves (distance key, colour
    /// key), copied row by row; the mesher decodes only what it reads (sides by
    /// key, values through sdfTable, colours through the palette). values,
    /// colours and colorKeys are then empty.
    std::vector<Voxel> voxels;
    const float* sdfTable = nullptr; // the volume's SDF dictionary (immutable)
    std::int32_t isoKey = 0;         // value >= iso exactly when key >= isoKey
    /// Points of storage chunks whose neighbourhood lies on one side of iso hold
    /// one placeholder value (key) of that side and stale colours (never read by the mesher).
    /// Scratch of gather() (the storage chunks' sides of iso), kept for reuse.
    std::vector<std::int8_t> sideScratch;
    std::vector<float> quietScratch;
    /// Instead of the copies above: the source's own float grid (and colours),
    /// lo = 0 and size = the grid's dims. extractChunk() meshes float grids
    /// this way (no copy); gather() always copies (the worker's snapshot).
    const float* view = nullptr;
    const Rgba* viewColors = nullptr;
    /// 0: as above. 1 (gather(id, into, 1)): the coarse grid of
    /// extractChunkCoarse; lo, size and cells in coarse point indices, values
    /// (and colours) decoded.
    int level = 0;
    const float* valueData() const { return view ? view : values.data(); }
    const Rgba* colorData() const { return view ? viewColors : (colors.empty() ? nullptr : colors.data()); }
    std::int64_t local(std::int64_t x, std::int64_t y, std::int64_t z) const
    {
      return (x - lo[0]) + size[0] * ((y - lo[1]) + size[1] * (z - lo[2]));
    }
  };
  /// Copies the chunk's input (the only step that reads the source: do it under
  /// the lock that guards writers). Returns null when the chunk is empty.
  std::unique_ptr<ChunkInput> gather(std::int64_t id) const;
  /// The same into an existing input (its buffers reused: no allocation once
  /// warm). Returns false (and leaves `into` unchanged) when the chunk is empty.
  bool gather(std::int64_t id, ChunkInput& into) const;
  /// The same at a level of detail (0 or 1, see extractChunkCoarse); mesh()
  /// meshes the input at its level.
  bool gather(std::int64_t id, ChunkInput& into, int level) const;
  /// Meshes a gathered input (reads nothing else; any thread).
  ChunkMesh mesh(const ChunkInput& input) const;

  class Impl;

private:
  std::unique_ptr<Impl> P;
};

enum class MergeBy
{
  EdgeId,  // one point per cut edge: exact topology even where a point value equals iso
  Position // bit-identical coordinates (also joins the vertices of edges meeting at a point of value iso)
};

/// Merges chunk meshes into one mesh, joining the duplicated chunk-boundary
/// points. Normals are kept. Degenerate triangles (a point value exactly at
/// iso) are kept, as VTK's marching cubes keeps them.
TriangleMesh mergeChunkMeshes(const std::vector<ChunkMesh>& meshes, MergeBy by = MergeBy::EdgeId);

} // namespace lvdif
