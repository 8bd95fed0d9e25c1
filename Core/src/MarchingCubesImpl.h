// Internal state of ChunkedMarchingCubes shared by its source files.
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"

#include <vector>

namespace lvdif
{

class ChunkedMarchingCubes::Impl
{
public:
  MarchingCubesOptions Options;
  const DictionaryVolume* Volume = nullptr;
  FloatGridView Grid;
  const Rgba* GridColors = nullptr;
  Index3 Dims{ 0, 0, 0 }; // points
  Index3 Cells{ 0, 0, 0 };
  Index3 Counts{ 0, 0, 0 };
  std::int64_t Total = 0;
  std::array<double, 3> Origin{ 0, 0, 0 }, Spacing{ 1, 1, 1 };
  std::array<float, 3> InvSpacing{ 1, 1, 1 };
  // float grids: min and max value of each chunk's points
  std::vector<float> MinValue, MaxValue;

  void init(const Index3& dims, const MarchingCubesOptions& options);
  Index3 coord(std::int64_t id) const
  {
    return { id % Counts[0], (id / Counts[0]) % Counts[1], id / (Counts[0] * Counts[1]) };
  }
  VoxelBox cells(std::int64_t id) const;
  /// The points the chunk's cells use: cells.lo .. cells.hi + 1.
  VoxelBox points(std::int64_t id) const;
  void rangeOfPoints(std::int64_t id, float& lo, float& hi) const;
  bool empty(std::int64_t id) const;
  bool wantsColors() const { return Options.computeColors && (Volume || GridColors); }
  bool wantsCornerColors() const { return Options.cornerColors && Volume; }
};

/// The CPU kernel: meshes one gathered chunk.
ChunkMesh meshChunkCpu(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in);

} // namespace lvdif
