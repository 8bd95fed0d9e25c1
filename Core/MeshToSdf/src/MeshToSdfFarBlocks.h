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

/// Blocks of FarBlock^3 voxels are tried first, those that fail as their 8
/// halves, those as their 8 cells of FarCell^3; cells that fail too are
/// computed voxel by voxel.
constexpr int FarBlock = 8;
constexpr int FarCell = 2;
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

/// Whether a triangle is shaped: (|AB|^2 + |AC|^2) <= FarKappaMax |AB x AC|.
LVDIF_HD bool farShaped(const Tri& t)
{
  const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
  return dot(ab, ab) + dot(ac, ac) <= FarKappaMax * norm(cross(ab, ac)); // false for NaN too
}

/// The side (+1 / -1) every point of the box is on, by more than margin +
/// delta, of the plane through a with normal n; 0 when neither.
LVDIF_HD int farPlane(V3 a, V3 n, double delta, const FarBox& box, double margin)
{
  const double g = dot(box.centre - a, n);
  const double spread = std::fabs(n.x) * box.half.x + std::fabs(n.y) * box.half.y + std::fabs(n.z) * box.half.z;
  const double m = margin + delta;
  return g - spread > m ? 1 : (g + spread < -m ? -1 : 0);
}

/// The face plane's allowance of farTriAgrees (region: the rounding band of
/// the closest point's regions, h the smallest height, L bounding |p - vertex|).
LVDIF_HD double farFaceDelta(double faceDot, double reachL, double h)
{
  const double region = 1e-14 * reachL * reachL / h;
  return faceDot * (2 + region / h);
}

/// Whether triangle t leaves every voxel of the box the sign `side` if it is
/// their nearest: each plane its sign may be taken against (the face; with
/// pseudo-normals also its edges' and vertices', through the feature, with
/// their stored normals) puts the box on that side. delta covers where the
/// computed closest point lies on the feature (the sign is taken at it, the
/// plane passes through a vertex): |B-A|.n for an edge (parameter in [0,1]),
/// (|AB.n| + |AC.n|) (2 + region / h) for the face (barycentrics, with their
/// rounding), 0 at a vertex. Otherwise true only when t is provably farther than reach
/// from the centre (by its exact distance if shaped, else its bounding box).
LVDIF_HD bool farTriAgrees(const Tri& t, bool pseudo, const FarBox& box, double reach, double margin, int side)
{
  const bool shaped = farShaped(t);
  if (shaped)
  {
    const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
    // the closest-point routine's region tests and barycentrics round like
    // products of distances: their error in position grows as L^2 / h (L
    // bounds |p - vertex| over the box, h the triangle's smallest height)
    const double area2 = norm(cross(ab, ac));
    const double longest = std::fmax(norm(ab), std::fmax(norm(ac), norm(t.v[2] - t.v[1])));
    const double h = area2 / longest;
    const double reachL = norm(box.centre - t.v[0]) + box.radius + longest;
    const double region = 1e-14 * reachL * reachL / h; // as in farFaceDelta
    // with pseudo-normals the face's own plane counts only where the face's
    // interior can be nearest: in its prism (the projection inside the face)
    bool face = true;
    for (int k = 0; k < 3 && face && pseudo; ++k)
    {
      const V3 out = normalized(cross(t.v[(k + 1) % 3] - t.v[k], t.n)); // in-plane, outward of edge k
      face = farPlane(t.v[k], out, region, box, margin) != 1;           // not all beyond edge k
    }
    // in the face, c' = A + v AB + w AC with |v|, |w| <= 1 + region / h
    const double faceDelta = farFaceDelta(std::fabs(dot(ab, t.n)) + std::fabs(dot(ac, t.n)), reachL, h);
    bool ok = !face || farPlane(t.v[0], t.n, faceDelta, box, margin) == side;
    for (int k = 0; k < 3 && ok && pseudo; ++k)
    {
      const V3 a = t.v[k], b = t.v[(k + 1) % 3];
      ok = farPlane(a, t.en[k], std::fabs(dot(b - a, t.en[k])), box, margin) == side &&
        farPlane(a, t.vn[k], 0.0, box, margin) == side;
    }
    if (ok) return true;
    const Closest q = closestPointOnTriangle(box.centre, t.v[0], t.v[1], t.v[2]);
    const V3 d = q.point - box.centre;
    return dot(d, d) > reach * reach;
  }
  const double lo[3] = { std::fmin(t.v[0].x, std::fmin(t.v[1].x, t.v[2].x)),
    std::fmin(t.v[0].y, std::fmin(t.v[1].y, t.v[2].y)), std::fmin(t.v[0].z, std::fmin(t.v[1].z, t.v[2].z)) };
  const double hi[3] = { std::fmax(t.v[0].x, std::fmax(t.v[1].x, t.v[2].x)),
    std::fmax(t.v[0].y, std::fmax(t.v[1].y, t.v[2].y)), std::fmax(t.v[0].z, std::fmax(t.v[1].z, t.v[2].z)) };
  return pointBoxDist2(box.centre, lo, hi) > reach * reach;
}

/// A normal cone of a BVH node: every sign plane normal of every triangle
/// below (face, edges, vertices) lies within angle T of the axis, and every
/// triangle is shaped (ok = 0: no cone).
struct FarCone
{
  double axis[3] = { 0, 0, 0 };
  double cosT = 0, sinT = 1;
  // for the deltas of farTriAgrees below: the largest edge delta, the largest
  // |AB.n| + |AC.n|, the smallest height and the longest edge
  double edgeDelta = 0, faceDot = 0, minHeight = 0, longest = 0;
  int ok = 0;
};

/// +1 / -1 when every point of the box is on that side, by more than margin,
/// of the plane of every triangle under a node (box lo..hi, cone c); else 0.
/// With w = p - v (p in the box, v a vertex in the node's box) and n within T
/// of the axis a: s n.w >= cos T (s a.w) - sin T |w - (a.w) a| when s a.w >= 0.
LVDIF_HD int farConeSide(const FarCone& c, const double lo[3], const double hi[3], const FarBox& box, double margin)
{
  if (!c.ok) return 0;
  const V3 a{ c.axis[0], c.axis[1], c.axis[2] };
  const V3 cw{ box.centre.x - 0.5 * (lo[0] + hi[0]), box.centre.y - 0.5 * (lo[1] + hi[1]),
    box.centre.z - 0.5 * (lo[2] + hi[2]) };
  const V3 hw{ box.half.x + 0.5 * (hi[0] - lo[0]), box.half.y + 0.5 * (hi[1] - lo[1]),
    box.half.z + 0.5 * (hi[2] - lo[2]) };
  const double along = dot(a, cw);
  const double spread = std::fabs(a.x) * hw.x + std::fabs(a.y) * hw.y + std::fabs(a.z) * hw.z;
  const double across = norm(cw - along * a) + norm(hw);
  const double reachL = norm(cw) + norm(hw) + box.radius + c.longest; // bounds |p - vertex| below
  const double m = margin + std::fmax(c.edgeDelta, farFaceDelta(c.faceDot, reachL, c.minHeight));
  if (along - spread > 0 && c.cosT * (along - spread) - c.sinT * across > m) return 1;
  if (-along - spread > 0 && c.cosT * (-along - spread) - c.sinT * across > m) return -1;
  return 0;
}

/// The side every triangle within `reach` of the box's centre puts the whole
/// box on (+1 / -1), or 0: the binary BVH (Node: Bvh::Node or the GPU's copy,
/// leaf: its leaf-ordered triangles) walked with the node cones, so that a
/// subtree whose cone decides needs no triangle. side: the expected side (the
/// nearest triangle's), so that no farther one sets it; 0 for none.
template <typename Node, typename TriAt>
LVDIF_HD int farTreeSide(const Node* nodes, const FarCone* cones, TriAt&& triAt, bool pseudo, const FarBox& box,
  double reach, double margin, int side)
{
  if (side == 0) return 0;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const Node& n = nodes[stack[--top]];
    const int id = static_cast<int>(&n - nodes);
    if (pointBoxDist2(box.centre, n.lo, n.hi) > reach * reach) continue;
    if (farConeSide(cones[id], n.lo, n.hi, box, margin) == side) continue;
    if (n.left < 0)
    {
      for (int i = n.first; i < n.first + n.count; ++i)
        if (!farTriAgrees(triAt(i), pseudo, box, reach, margin, side)) return 0;
      continue;
    }
    if (top + 2 > 64) return 0; // deeper than the stack: undecided, never wrong
    stack[top++] = n.right;
    stack[top++] = n.left;
  }
  return side;
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

/// The verdict on a box whose centre's nearest distance lies in [dLo, dHi]:
/// side (+1 / -1) when all its voxels are side * band, 0 when undecided.
template <typename Node, typename TriAt>
LVDIF_HD int farBoxSide(const Node* nodes, const FarCone* cones, TriAt&& triAt, bool pseudo, const FarBox& box,
  double dLo, double dHi, double bandWorld, double margin, int side)
{
  if (!farPastBand(dLo, box, bandWorld, margin)) return 0;
  return farTreeSide(nodes, cones, triAt, pseudo, box, farRadius(dHi, box, margin), margin, side);
}

/// The sign the mode would give the point p from its nearest triangle t and
/// closest point c (the side a box around p is expected on; 0 on the plane).
LVDIF_HD int farSideAt(const Tri& t, const Closest& c, V3 p, bool pseudo)
{
  const double g = dot(p - c.point, pseudo ? featureNormal(t, c.feature) : t.n);
  return g > 0 ? 1 : (g < 0 ? -1 : 0);
}

/// The offset of a sub-box's centre from the block's (bounds its nearest
/// distance from the block's: the distance is 1-Lipschitz), rounded up.
LVDIF_HD double farOffset(const FarBox& sub, const FarBox& block, double big)
{
  return norm(sub.centre - block.centre) * (1 + 1e-12) + 1e-15 * big;
}

/// An upper bound of the nearest distance of a sub-box's centre from that of
/// the box enclosing it (parentDist: its computed distance, or its own bound).
/// A sub-box with bound - radius <= band is certainly not past the band: it is
/// left undecided without a query (a shortcut only: undecided is never wrong).
LVDIF_HD double farChildBound(double parentDist, const FarBox& sub, const FarBox& parent, double big)
{
  return parentDist + farOffset(sub, parent, big);
}

/// The cells of one block (voxel origin v0, box-relative; n: the box's size):
/// side(origin, edge) decides the box of edge^3 voxels there (clipped to n),
/// set(cell, sign) records a decided cell (cell = origin / FarCell). The block
/// is tried whole, then its halves, then their cells. Returns the voxels decided.
template <typename Side, typename Set>
LVDIF_HD long long farClassifyBlock(const long long v0[3], const long long n[3], Side&& side, Set&& set)
{
  long long decided = 0;
  auto fill = [&](const long long o[3], long long edge, int s) {
    for (long long z = o[2]; z < o[2] + edge && z < n[2]; z += FarCell)
      for (long long y = o[1]; y < o[1] + edge && y < n[1]; y += FarCell)
        for (long long x = o[0]; x < o[0] + edge && x < n[0]; x += FarCell)
        {
          const long long cell[3] = { x / FarCell, y / FarCell, z / FarCell };
          set(cell, s);
        }
    long long count = 1;
    for (int a = 0; a < 3; ++a) count *= (o[a] + edge < n[a] ? o[a] + edge : n[a]) - o[a];
    decided += count;
  };
  const int whole = side(v0, static_cast<long long>(FarBlock));
  if (whole != 0)
  {
    fill(v0, FarBlock, whole);
    return decided;
  }
  constexpr long long Half = FarBlock / 2;
  for (int h = 0; h < 8; ++h)
  {
    const long long o1[3] = { v0[0] + Half * (h & 1), v0[1] + Half * ((h >> 1) & 1), v0[2] + Half * (h >> 2) };
    if (o1[0] >= n[0] || o1[1] >= n[1] || o1[2] >= n[2]) continue;
    const int s1 = side(o1, Half);
    if (s1 != 0)
    {
      fill(o1, Half, s1);
      continue;
    }
    for (int q = 0; q < 8; ++q)
    {
      const long long o2[3] = { o1[0] + FarCell * (q & 1), o1[1] + FarCell * ((q >> 1) & 1), o1[2] + FarCell * (q >> 2) };
      if (o2[0] >= n[0] || o2[1] >= n[1] || o2[2] >= n[2]) continue;
      const int s2 = side(o2, static_cast<long long>(FarCell));
      if (s2 != 0) fill(o2, FarCell, s2);
    }
  }
  return decided;
}
static_assert(FarBlock == 4 * FarCell, "three levels: block, halves, cells");

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

/// The normal cones of the BVH's nodes over the sign planes of `tris`.
std::vector<FarCone> farCones(const Bvh& bvh, const std::vector<Tri>& tris);

/// CPU: fills cells for `box` (on OpenMP threads); returns the voxels decided.
/// pseudo: PseudoNormal (else Normal) signs.
std::int64_t classifyFarCells(const NearestIndex& index, const Bvh& bvh, const std::vector<FarCone>& cones,
  const PreparedMesh& mesh, const GridGeometry& grid, const VoxelBox& box, double bandWorld, bool pseudo,
  FarCells& cells);

/// CPU, the signs not taken from the nearest triangle (WindingNumber,
/// Unsigned: the sign pass comes after): fills cells with +1 where every voxel
/// is past the band, so +band before its sign, by the same blocks, halves and
/// cells and the same margins (farPastBand) without the side test; returns
/// the voxels decided. Each box costs one query bounded a little past the band.
std::int64_t classifyBandCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
  const VoxelBox& box, double bandWorld, FarCells& cells);

} // namespace detail::meshtosdf
} // namespace lvdif
