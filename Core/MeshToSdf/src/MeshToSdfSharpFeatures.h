// The normal sign on a solid's boundary by the winding path: the sharp
// features, where the two signs can differ, and the voxels of their regions.
//
// The normal sign of a voxel p is that of (p - c) . n_t, c the closest point,
// t the reported closest triangle, n_t its face normal. On a solid's boundary
// (MeshToSdfSolid.h) it equals the winding sign wherever
// - c lies inside t: p - c points along n_t, to the side p is on; or
// - c lies on an edge or vertex whose faces' normals all give one sign, by a
//   margin, on every direction p - c from which that feature can be closest
//   (its local cone: the directions d with d . (w - c) <= 0 for the
//   feature's neighbouring vertices w). Such a feature is "safe".
// Elsewhere, in the regions of the other ("sharp") edges and vertices, the
// normal sign can be anything: the Normal sign's defect beyond sharp
// features, which the Normal path reproduces as it is. So a Normal call on a
// solid runs the winding path, then recomputes the voxels of those regions
// exactly, as the Normal path does (docs/MESH_TO_SDF.md, "Normal signs of
// solids").
#pragma once

#include "MeshToSdfInternal.h"
#include "MeshToSdfSharpTests.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MeshToSdf.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// An edge (a, b) or a vertex (a == b) that is not safe.
struct SharpFeature
{
  V3 a, b;
  bool edge = false;
  /// Unit vectors u: the directions d from which the feature can be closest
  /// have d . u <= 0 (the edge's: the other vertices' offsets across it; the
  /// vertex's: its edges).
  std::vector<V3> limits;
  std::vector<V3> normals; // the face normals of the feature's faces (Tri::n)
  std::vector<std::int32_t> faces; // those faces (indices in the mesh's tris), ascending
  SharpFeatureView view() const;   // valid while this feature lives
};

struct SharpFeatures
{
  std::vector<SharpFeature> features;
  std::size_t sharpEdges = 0, sharpVertices = 0;
};

/// The sharp features of a mesh whose boundary check passed (every edge has
/// exactly two faces, of opposite orientation; one fan per vertex).
SharpFeatures findSharpFeatures(const PreparedMesh& mesh);

/// Whether every sharp feature lies in the box of the voxel centres of
/// `extent` (then every voxel of a feature's region is reachable from the
/// feature through voxels of the extent: sharpRegionBricks).
bool sharpFeaturesInside(const SharpFeatures& sharp, const GridGeometry& grid, const VoxelBox& extent);
/// Whether p lies in the box of the voxel centres of `extent` (a mesh whose
/// bounds do has every sharp feature inside, found or not).
bool insideExtent(V3 p, const GridGeometry& grid, const VoxelBox& extent);

/// One voxel of the regions with the Normal path's value (output units).
struct SharpVoxel
{
  std::int64_t i, j, k; // grid indices
  float value;
};

/// The regions are walked brick by brick (SharpBrickEdge^3 voxels).
constexpr int SharpBrickEdge = 8;

/// A brick (bi, bj, bk) of the extent that may hold voxels of feature
/// `feature`'s region, with the closest triangle to its centre.
struct SharpBrick
{
  std::int32_t feature;
  std::int32_t nearest;
  std::int64_t bi, bj, bk;
};

/// Step 1 of the regions: the bricks of `extent` that may hold a voxel of a
/// sharp feature's region, walked from each feature with margins that keep
/// the walk from missing one (MeshToSdfSharpFeatures.cpp); sorted by feature
/// and position. Needs sharpFeaturesInside. Interruptible.
std::vector<SharpBrick> sharpRegionBricks(
  const SharpFeatures& sharp, const Bvh& bvh, const GridGeometry& grid, const VoxelBox& extent, Interrupter& interrupter);

/// Step 2 on the CPU: the voxels of those bricks that may lie in their
/// feature's region (their closest point can lie on the feature, in a
/// direction where its faces' normals disagree, up to rounding:
/// MeshToSdfSharpTests.h), each with the value the Normal path stores there:
/// s * min(|p - c| * toOut, band), s the sign of (p - c) . n_t, c and t the
/// closest point and triangle (ties to the lowest index). Interruptible. The
/// CUDA twin is meshtosdf_cuda::sharpRegionVoxelsOnDevice.
std::vector<SharpVoxel> sharpRegionVoxels(const PreparedMesh& mesh, const SharpFeatures& sharp, const Bvh& bvh,
  const std::vector<SharpBrick>& bricks, const GridGeometry& grid, const VoxelBox& extent, double toOut, double band,
  Interrupter& interrupter);

/// The voxels of a brick of `extent`.
VoxelBox sharpBrickBox(const SharpBrick& brick, const GridGeometry& grid, const VoxelBox& extent);
/// A voxel's diagonal (the scale of the tests' rounding tolerance).
double sharpVoxelDiagonal(const GridGeometry& grid);

} // namespace detail::meshtosdf
} // namespace lvdif
