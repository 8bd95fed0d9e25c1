// The CPU engine of mesh to SDF: the per-call state (the prepared mesh's
// structures for this grid, band and sign) and the distance and sign passes
// over a box of voxels on OpenMP threads (MeshToSdfEngine.cpp). The calls in
// MeshToSdf.cpp choose the device and the output (float extent, dictionary
// volume) and run these passes, or the CUDA session, box by box.
#pragma once

#include "MeshToSdfFarBlocks.h"
#include "MeshToSdfInternal.h"
#include "lvdif/Cuda.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MeshToSdf.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Throws unless the grid's dimensions, origin and spacing are usable.
void validateGrid(const GridGeometry& g);

/// World distance -> output units: 1 / the smallest spacing for voxel units.
double outputScale(const GridGeometry& grid, const MeshToSdfOptions& options);

/// What one call computes with: the grid, the options and the structures it
/// reads (built on first use by makeEngine), in output units.
struct Engine
{
  const PreparedMesh* mesh = nullptr;
  const NearestIndex* index = nullptr;
  const WindingSigner* winding = nullptr;
  std::unique_ptr<FaithfulGrid> grid;
  GridGeometry geom;
  MeshToSdfOptions opts;
  bool far = false;       // far blocks (Normal/PseudoNormal, finite band, CPU BVH; MeshToSdfOptions::farBlocks)
  const Bvh* farBvh = nullptr;                 // their tree and node cones
  const std::vector<FarCone>* farCones = nullptr;
  bool bandCells = false; // the same blocks by distance alone (WindingNumber/Unsigned, finite band, CPU BVH)
  double toOut = 1;       // world distance -> output units
  double band = 0;        // output units (may be infinite)
  double bandWorld2 = 0;  // squared band in world units, for bounded queries

  V3 position(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return { this->geom.origin[0] + i * this->geom.spacing[0], this->geom.origin[1] + j * this->geom.spacing[1],
      this->geom.origin[2] + k * this->geom.spacing[2] };
  }

  NearestResult nearest(V3 p, std::int32_t hint) const;

  /// -1 inside, +1 outside, from the closest triangle (Normal / PseudoNormal).
  float localSign(V3 p, const NearestResult& r) const;

  void distanceBricks(const VoxelBox& box, float* out, const FarCells& far, Interrupter& intr, double progressBase,
    double progressSpan) const;

  /// Distances (and the local sign) of one row; out holds output units.
  /// With a finite band and no normal-based sign, the distance being
  /// 1-Lipschitz lets far voxels skip the query: each query past the band
  /// looks a margin beyond it, and the following voxels stay saturated while
  /// the lower bound (previous distance - steps) is still past the band.
  /// rowTris (nx entries): on entry the nearest triangles of the row below
  /// when belowValid (they seed the bounds), on exit this row's.
  /// far (optional): the far cells of this row (FarCell voxels each from i0)
  /// and their masks; farBit: the row's bit in them (2 y + 4 z inside the
  /// cell): a voxel whose bit farBit + x is set is +-band without a query.
  void distanceRow(std::int64_t j, std::int64_t k, std::int64_t i0, std::int64_t i1, float* out,
    std::int32_t* rowTris, bool belowValid, const std::int8_t* far = nullptr, const std::uint8_t* farMask = nullptr,
    int farBit = 0) const;
};

/// The engine of a call (validates the grid and options; builds what the
/// device and sign need on first use, its time added to stats.buildSeconds).
/// On CUDA the winding structures are left to openCuda, which builds them
/// (if not prepared yet) while the GPU computes distances.
std::unique_ptr<Engine> makeEngine(const MeshToSdfPrepared& prepared, const GridGeometry& geom,
  const MeshToSdfOptions& opts, float band, Device device, MeshToSdfStats& stats);

/// The distance and sign passes over one box of voxels into out (box layout).
void computeBox(const Engine& e, const VoxelBox& box, float* out, MeshToSdfStats& stats, Interrupter& intr,
  double progressBase, double progressSpan);

} // namespace detail::meshtosdf
} // namespace lvdif
