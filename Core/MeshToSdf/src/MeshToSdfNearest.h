// CPU-only query structure for the exact nearest triangle of mesh to SDF: a
// 4-wide BVH (binned SAH, one triangle per slot) with float child boxes
// rounded outward, tested four at a time, over triangles stored contiguously
// in traversal order. Beside the binary Bvh (which the CUDA path uploads and
// the winding pass uses), never in its place. See docs/MESH_TO_SDF.md.
#pragma once

#include "MeshToSdfInternal.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// float bounds rounded outward (the boxes must contain the double ones);
/// inline: every improvement of a query's best distance rounds its threshold
inline float roundDownToFloat(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
inline float roundUpToFloat(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
  {
    // std::nextafter(f, +inf) without the libm call (1 % of the banded
    // call's instructions, from every threshold update): a float > 0 steps
    // to the next bit pattern (FLT_MAX to +inf), one < 0 (-inf included) to
    // the previous; zero (never here: x would round to it from above) keeps
    // the library call
    if (f > 0 || f < 0)
    {
      std::uint32_t b;
      std::memcpy(&b, &f, sizeof b);
      b = f > 0 ? b + 1 : b - 1;
      std::memcpy(&f, &b, sizeof f);
    }
    else
      f = std::nextafter(f, std::numeric_limits<float>::infinity());
  }
  return f;
}

struct NearestRowState; // MeshToSdfNearestRow.h

class NearestIndex
{
public:
  explicit NearestIndex(const TriList& tris);

  /// The same answer as a brute-force scan of closestPointOnTriangle over
  /// every triangle (ties to the lowest index), among the triangles whose
  /// squared distance is <= maxDist2 (tri = -1 when there is none). The hint
  /// (a triangle index, -1 for none) only seeds the bound. Pruning uses lower
  /// bounds with a margin (see Tau in the .cpp), so it never drops a triangle
  /// whose computed distance could win or tie.
  /// exactCount (may be null): incremented per exact closest point computed.
  NearestResult nearest(V3 p, std::int32_t hint, double maxDist2, std::uint64_t* exactCount = nullptr) const;

  /// nearest(p[i], ., 1e300) for n <= RowPoints points of one grid row
  /// (equal y and z), in one traversal: each node's boxes are tested for the
  /// points four at a time (MeshToSdfNearestRow.cpp). The hint seeds every
  /// point, laneHints[i] (may be null; -1 for none) point i only, e.g. the
  /// triangles of the row below.
  static constexpr int RowPoints = 8;
  void nearestRow(const V3* p, int n, std::int32_t hint, const std::int32_t* laneHints, NearestResult* out) const;

  /// nearest(p[i], ., maxDist2) for the n points of one small box (a brick
  /// of voxels within a band: maxDist2 finite), from one list of candidate
  /// triangles for the whole box (MeshToSdfNearestBrick.cpp), or, where that
  /// list would exceed BrickListMax triangles, by nearest() point by point.
  /// The hint seeds the query of the box's centre.
  static constexpr std::size_t BrickListMax = 256;
  struct BrickScratch
  {
    std::vector<std::pair<double, std::int32_t>> near; // squared box gap, position (without SSE)
    std::vector<std::uint64_t> keys;                    // the same as one sort key (SSE)
    std::vector<double> gaps;                           // the gaps in the list's order
    std::vector<std::int32_t> cand;
    std::vector<float> planes;
    // work, summed over the calls that used this scratch (tests): bricks and
    // points within reach of a triangle, bricks answered point by point,
    // candidates listed, exact closest points (seeds and centres included)
    std::uint64_t bricks = 0, points = 0, pointByPoint = 0, listed = 0, exact = 0;
  };
  void nearestBrick(const V3* p, int n, double maxDist2, std::int32_t hint, NearestResult* out,
    BrickScratch& scratch) const;

  struct alignas(16) Node
  {
    float lo[3][4], hi[3][4]; // child boxes, per axis, four lanes
    // child slabs: smin <= sn . x <= smax for every vertex below the child
    // (sn: the child's mean normal in float; exact for any sn, tight where flat)
    float sn[3][4], smin[4], smax[4];
    std::int32_t child[4];    // >= 0: node; < 0: ~(position in Packed)
    std::int32_t count = 0;   // used lanes (the first `count`)
  };
  struct Packed
  {
    std::int32_t index;  // in the prepared triangle list
    V3 v[3];             // exact copies of the triangle's vertices
    // lower bound planes: the unit normal, then the in-plane outward unit
    // normals of edges AB, BC, CA; the distance is at least
    // sqrt(plane^2 + max(0, edges)^2) (all zero for slivers: no bound)
    double plane[4][4];  // x, y, z, offset
  };

  const std::vector<Node>& nodes() const { return this->Nodes; }
  std::size_t depth() const { return this->Depth; }

private:
  void traverseRowSse(NearestRowState& s) const;
  void traverseRowAvx2(NearestRowState& s) const;
  std::vector<Node> Nodes;
  LargeVector<Packed> Tris;          // in traversal order
  /// Packed::plane rounded to float, per plane k: x[k] y[k] z[k] w[k]
  /// (nearestRow tests four points at once; its margin covers the rounding)
  struct alignas(16) PlanesF
  {
    float x[4], y[4], z[4], w[4];
  };
  LargeVector<PlanesF> TriPlanes;    // same order as Tris
  std::vector<std::int32_t> PosOf;   // triangle index -> position in Tris
  double Scale = 0;                  // largest |coordinate| of the mesh
  std::size_t Depth = 0;
};

} // namespace detail::meshtosdf
} // namespace lvdif
