// Far blocks of the Normal and PseudoNormal signs, shared by the CPU
// (MeshToSdfFarBlocks.cpp) and the CUDA kernels (MeshToSdfCudaFar.cuh).
// Outside the band a voxel stores only +-band, so it needs only its sign. A
// box of voxels whose centre x is at distance D from the mesh and whose
// half-diagonal is r has every voxel's nearest feature within D + 2r of x;
// if every triangle that close has the whole box strictly on one side of its
// plane, that side is every voxel's sign (the sign is taken against a
// positive combination of the normals of triangles containing the closest
// point, all of them that close), and if D - r is past the band, every voxel
// is the clamped value. Margins and the proof: docs/MESH_TO_SDF.md, "Far blocks".
#pragma once

#include "MeshToSdfInternal.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Blocks of FarBlock^3 voxels are tried first, those that fail as cells of
/// FarCell^3; cells that fail too are computed voxel by voxel.
constexpr int FarBlock = 8;
constexpr int FarCell = 4;
/// Triangles less well shaped than this ((|AB|^2 + |AC|^2) / |AB x AC|, about
/// 1 / sin of the smallest angle) make a box undecided: the rounding of their
/// normal and closest point is bounded only for shaped ones.
constexpr double FarKappaMax = 1e4;

/// The margin (world units) of every far-block test: far above the rounding
/// of the positions, normals, closest points and pseudo-normal sums (whose
/// rounding grows with the faces at a vertex, at most `triangles`), far below
/// a voxel. big: the largest |coordinate| of the mesh and the grid.
LVDIF_HD double farMargin(double big, double triangles)
{
  return big * (1e-8 + 1e-15 * triangles);
}

struct FarBox
{
  V3 centre, half; // half extents, grown by the rounding of the centre
  double radius = 0;
};

/// The box of the voxel positions p0 <= p <= p1 (positions computed as the
/// rows compute them are monotonic in the index, so every voxel lies inside).
LVDIF_HD FarBox farBox(V3 p0, V3 p1, double big)
{
  FarBox b;
  b.centre = 0.5 * (p0 + p1);
  const double s = 1e-15 * big;
  b.half = { 0.5 * (p1.x - p0.x) + s, 0.5 * (p1.y - p0.y) + s, 0.5 * (p1.z - p0.z) + s };
  b.radius = norm(b.half);
  return b;
}

/// One triangle's verdict on a box: +1 / -1 when every point of the box is on
/// that side of the triangle's plane (n its stored unit normal) by more than
/// margin, 2 when the triangle is farther than R from the centre (no
/// candidate), 0 otherwise or when it is ill-shaped.
LVDIF_HD int farFaceSide(V3 a, V3 b, V3 c, V3 n, const FarBox& box, double R, double margin)
{
  const V3 ab = b - a, ac = c - a;
  const double area2 = norm(cross(ab, ac));
  const double sides = dot(ab, ab) + dot(ac, ac);
  if (!(sides <= FarKappaMax * area2)) // ill-shaped (or NaN): only its bounding box is trusted
  {
    const double lo[3] = { std::fmin(a.x, std::fmin(b.x, c.x)), std::fmin(a.y, std::fmin(b.y, c.y)), std::fmin(a.z, std::fmin(b.z, c.z)) };
    const double hi[3] = { std::fmax(a.x, std::fmax(b.x, c.x)), std::fmax(a.y, std::fmax(b.y, c.y)), std::fmax(a.z, std::fmax(b.z, c.z)) };
    return pointBoxDist2(box.centre, lo, hi) > R * R ? 2 : 0;
  }
  const Closest q = closestPointOnTriangle(box.centre, a, b, c);
  const V3 d = q.point - box.centre;
  if (dot(d, d) > R * R) return 2;
  const double g = dot(box.centre - a, n);
  const double spread = std::fabs(n.x) * box.half.x + std::fabs(n.y) * box.half.y + std::fabs(n.z) * box.half.z;
  if (g - spread > margin) return 1;
  if (g + spread < -margin) return -1;
  return 0;
}

/// The radius within which the candidates of a box lie: D (the centre's
/// computed nearest distance) + 2r, plus the margin.
LVDIF_HD double farRadius(double nearestDist, const FarBox& box, double margin)
{
  return nearestDist * (1 + 1e-12) + 2 * box.radius + margin;
}

/// Whether the box lies past the band (world units) by more than the margin.
LVDIF_HD bool farPastBand(double nearestDist, const FarBox& box, double bandWorld, double margin)
{
  return nearestDist * (1 - 1e-12) - box.radius - margin > bandWorld * (1 + 1e-12);
}

/// The far cells of a box of voxels (box-relative, FarCell^3 voxels each,
/// cx + count[0] * (cy + count[1] * cz)): -1 or +1 when every voxel of the
/// cell is -band or +band, 0 when its voxels are computed one by one.
struct FarCells
{
  std::int64_t count[3] = { 0, 0, 0 };
  std::vector<std::int8_t> sign;
};

/// The largest |coordinate| of the mesh and of the grid's voxel positions.
double farScale(const PreparedMesh& mesh, const GridGeometry& grid);

/// CPU: fills cells for `box` (on OpenMP threads); returns the voxels decided.
std::int64_t classifyFarCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
  const VoxelBox& box, double bandWorld, FarCells& cells);

} // namespace detail::meshtosdf
} // namespace lvdif
