// Internal state of ChunkedMarchingCubes shared by its source files.
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/DeviceVolumeView.h"

#include <memory>
#include <vector>

namespace lvdif
{

/// Device buffers of the CUDA path (MarchingCubes.cu); opaque elsewhere.
struct MarchingCubesCudaState;

class ChunkedMarchingCubes::Impl
{
public:
  /// Set at construction when options.device resolves to Cuda: mesh() runs on
  /// the GPU (one chunk at a time, serialized by the state's mutex).
  std::shared_ptr<MarchingCubesCudaState> Cuda;
  MarchingCubesOptions Options;
  /// Options.triangleTable checked and completed, or lvdif's own table.
  std::shared_ptr<const MarchingCubesTables> Tables;
  const DictionaryVolume* Volume = nullptr;
  std::int32_t IsoKey = 0; // Volume: value >= iso exactly when key >= IsoKey
  FloatGridView Grid;
  const Rgba* GridColors = nullptr;
  Index3 Dims{ 0, 0, 0 }; // points
  Index3 Cells{ 0, 0, 0 };
  Index3 Counts{ 0, 0, 0 };
  VoxelBox Region;              // the cells meshed (options.cellRegion clipped, or all)
  Index3 First{ 0, 0, 0 };      // global coordinate of local chunk (0,0,0)
  std::int64_t Total = 0;
  std::array<double, 3> Origin{ 0, 0, 0 }, Spacing{ 1, 1, 1 };
  std::array<float, 3> InvSpacing{ 1, 1, 1 };
  // float grids: min and max value of each chunk's points
  std::vector<float> MinValue, MaxValue;
  /// Level 1 (extractChunkCoarse): the geometry of the grid subsampled by 2
  /// (Dims, Spacing, InvSpacing, gridOffset halved; the same chunk ids, Counts
  /// and First), no corner colours; meshChunkCpu of a level-1 input runs with
  /// it. Null when the grid has fewer than 3 points on an axis or an odd gridOffset.
  std::shared_ptr<const Impl> Coarse;
  /// Level 1: the coarse cells chunk id owns (those whose lowest full point 2c
  /// lies in cells(id)), in coarse point indices; empty when none.
  VoxelBox coarseCells(std::int64_t id) const;
  void gatherCoarseInto(std::int64_t id, ChunkedMarchingCubes::ChunkInput& in) const;

  void init(const Index3& dims, const MarchingCubesOptions& options);
  /// Local chunk coordinate (0..Counts-1).
  Index3 coord(std::int64_t id) const
  {
    return { id % Counts[0], (id / Counts[0]) % Counts[1], id / (Counts[0] * Counts[1]) };
  }
  /// Global chunk coordinate (chunk grid aligned with options.gridOffset).
  Index3 globalCoord(std::int64_t id) const
  {
    const Index3 c = coord(id);
    return { c[0] + First[0], c[1] + First[1], c[2] + First[2] };
  }
  VoxelBox cells(std::int64_t id) const;
  /// The points the chunk's cells use: cells.lo .. cells.hi + 1.
  VoxelBox points(std::int64_t id) const;
  void rangeOfPoints(std::int64_t id, float& lo, float& hi) const;
  bool empty(std::int64_t id) const;
  /// ChunkedMarchingCubes::gather into an existing input (its buffers reused).
  void gatherInto(std::int64_t id, ChunkedMarchingCubes::ChunkInput& in) const;
  bool wantsColors() const { return Options.computeColors && (Volume || GridColors); }
  bool wantsCornerColors() const { return Options.cornerColors && Volume; }
  bool wantsTriangleCells() const { return Options.cornerColors; }
};

/// The block behind PackedChunkMeshes: one allocation holding every array.
struct PackedChunkMeshes::Storage
{
  std::shared_ptr<std::uint8_t> block;
  bool pinned = false;
  bool normalsOn = false, colorsOn = false, cellsOn = false, keysOn = false;
  std::uint64_t vcap = 0, tcap = 0;
  Vec3f* points = nullptr;
  std::uint64_t* edgeIds = nullptr;
  Vec3f* normals = nullptr;
  Rgba* colors = nullptr;
  std::array<std::uint32_t, 3>* tris = nullptr;
  std::int64_t* cells = nullptr;
  std::array<ColorKey, 8>* keys = nullptr;
  /// Room for v vertices and t triangles with these arrays; the first keepV
  /// vertices and keepT triangles survive a reallocation (same flags only).
  void reserve(std::uint64_t v, std::uint64_t t, std::uint64_t keepV, std::uint64_t keepT, bool pageLocked,
    bool normals, bool colors, bool cells, bool keys);
};

/// Page-locked host memory (CUDA builds; the nocuda stub throws).
std::shared_ptr<std::uint8_t> allocatePageLocked(std::size_t bytes);

/// Fills `out` from chunk meshes (the CPU path of extractAllPacked).
void packChunkMeshes(const ChunkedMarchingCubes::Impl& impl, const std::vector<ChunkMesh>& meshes,
  PackedChunkMeshes& out);

/// The CPU kernel: meshes one gathered chunk.
ChunkMesh meshChunkCpu(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in);

/// The CUDA kernels (same function as meshChunkCpu: bit-identical vertices,
/// the same triangles; vertex order differs). Inputs that view the float grid
/// read the grid's device copy (uploaded at the first call); gathered inputs
/// are uploaded. Stubs in nocuda/ throw (never called: see resolveDevice).
/// The state holds a device copy of `tables`' triangles (the mesher's case table).
std::shared_ptr<MarchingCubesCudaState> makeMarchingCubesCudaState(const MarchingCubesTables& tables);
ChunkMesh meshChunkCuda(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in);
/// Float grids: meshes the given chunks in batches (one launch sequence and one
/// copy back per batch instead of per chunk). One result per id, in order.
std::vector<ChunkMesh> meshChunksCuda(const ChunkedMarchingCubes::Impl& impl, const std::vector<std::int64_t>& ids,
  Interrupter& interrupter);
/// Float grids: meshes the given (non-empty) chunks into `out` with the
/// streamed pipeline (compute on one stream, copies into the page-locked block
/// on another). Chunks that turn out to have no triangles are dropped.
void packChunksCuda(const ChunkedMarchingCubes::Impl& impl, const std::vector<std::int64_t>& ids,
  PackedChunkMeshes& out, Interrupter& interrupter);
/// Dictionary volumes: meshes the given chunks from the volume's device-resident
/// copy (gathered on the device, one batch for a frame's chunks) into `out`;
/// chunks without triangles are dropped.
void packChunksFromDeviceVolumeCuda(const ChunkedMarchingCubes::Impl& impl, const DeviceVolumeView& volume,
  const std::vector<std::int64_t>& ids, PackedChunkMeshes& out);
/// Forgets the float grid's device copy (the grid changed: re-uploaded at the next call).
void dropMarchingCubesCudaGrid(MarchingCubesCudaState& state);

} // namespace lvdif
