// The crossings of a ray with a BVH's triangles as host/device functions:
// Bvh::rayHits' slab and triangle tests, the walk of one subtree, and the
// frontier that splits one walk over the lanes of a warp (the GPU's sign
// kernels; the tests run them on the CPU against Bvh::rayHits).
//
// Why a split walk finds what one walk finds: a triangle is tested iff every
// box on its path from the root is hit, and each test depends only on the
// node and the ray, not on the order or the lane. So the crossings (as a
// set), their signed sum, and whether some test was ambiguous are the same;
// only the order the crossings are found in differs (they are sorted by t
// afterwards, and crossings with equal t are consumed at the same voxel).
#pragma once

#include "MeshToSdfGeometry.h"

#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Bvh::rayHits' slab test of one node (tmin 0, padded).
template <typename NodeT>
LVDIF_HD bool rayMeetsBox(const NodeT& n, V3 o, V3 dir, const double inv[3])
{
  double t0 = 0.0, t1 = 1e300;
  for (int a = 0; a < 3; ++a)
  {
    const double da = dir[a], oa = o[a];
    if (da == 0)
    {
      if (oa < n.lo[a] || oa > n.hi[a]) return false;
      continue;
    }
    double ta = (n.lo[a] - oa) * inv[a], tb = (n.hi[a] - oa) * inv[a];
    if (ta > tb)
    {
      const double x = ta;
      ta = tb;
      tb = x;
    }
    const double pad = 1e-9 * (std::fabs(ta) + std::fabs(tb)) + 1e-300;
    t0 = std::fmax(t0, ta - pad);
    t1 = std::fmin(t1, tb + pad);
    if (t0 > t1) return false;
  }
  return true;
}

/// Bvh::rayHits' triangle test (tmin 0): 0 no crossing, 1 a crossing at tt
/// with sign (+1 leaving through the front face), -1 ambiguous (near an edge,
/// a vertex or the origin, or the ray in the triangle's plane).
LVDIF_HD int rayCrossesTriangle(const LeafTri& t, V3 o, V3 dir, double& tt, int& sign)
{
  constexpr double Eps = 1e-9;
  const double tmin = 0.0;
  const V3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
  const V3 pv = cross(dir, e2);
  const double det = dot(e1, pv);
  const double scale = norm(e1) * norm(e2) * norm(dir);
  const V3 tv = o - t.v[0];
  if (std::fabs(det) <= Eps * scale) return std::fabs(dot(tv, t.n)) <= Eps * (norm(tv) + norm(e1)) ? -1 : 0;
  const double invDet = 1.0 / det;
  const double u = dot(tv, pv) * invDet;
  const V3 qv = cross(tv, e1);
  const double v = dot(dir, qv) * invDet;
  tt = dot(e2, qv) * invDet;
  const double w = 1 - u - v;
  if (u < -Eps || v < -Eps || w < -Eps) return 0;
  const double tScale = 1e-9 * (std::fabs(tt) + std::fabs(tmin) + norm(e1) / norm(dir));
  if (tt < tmin - tScale) return 0;
  if (u <= Eps || v <= Eps || w <= Eps || std::fabs(tt - tmin) <= tScale) return -1;
  sign = dot(dir, t.n) > 0 ? 1 : -1;
  return 1;
}

/// The walk of the subtree at `start` (a stack of 64): sum += each
/// crossing's sign and sink(t, tri, sign) for each (false: stop, not
/// counted as found). False when a test was ambiguous, the sink refused or
/// the stack would overflow.
template <typename NodeT, typename Sink>
LVDIF_HD bool rayWalk(const NodeT* nodes, const LeafTri* leaf, const int* order, int start, V3 o, V3 dir,
  const double inv[3], int& sum, Sink&& sink)
{
  int stack[64];
  int top = 0;
  stack[top++] = start;
  while (top > 0)
  {
    const NodeT n = nodes[stack[--top]];
    if (!rayMeetsBox(n, o, dir, inv)) continue;
    if (n.left >= 0)
    {
      if (top + 2 > 64) return false;
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (int i = n.first; i < n.first + n.count; ++i)
    {
      double tt = 0;
      int sg = 0;
      const int r = rayCrossesTriangle(leaf[i], o, dir, tt, sg);
      if (r < 0) return false;
      if (r == 0) continue;
      sum += sg;
      if (!sink(tt, order[i], sg)) return false;
    }
  }
  return true;
}

/// Splits the walk from the root into at most `cap` subtrees: inner nodes
/// whose boxes the ray meets are replaced by their children it meets, level
/// by level, while the count stays within cap. Every leaf the walk from the
/// root reaches lies under exactly one of them. out: cap ints, scratch:
/// 2 cap ints. Returns how many (0: the ray misses the root's box).
template <typename NodeT>
LVDIF_HD int rayFrontier(const NodeT* nodes, V3 o, V3 dir, const double inv[3], int cap, int* out, int* scratch)
{
  int n = 0;
  if (rayMeetsBox(nodes[0], o, dir, inv)) out[n++] = 0;
  for (;;)
  {
    int m = 0;
    bool split = false;
    for (int i = 0; i < n; ++i)
    {
      const NodeT& nd = nodes[out[i]];
      if (nd.left < 0)
      {
        scratch[m++] = out[i];
        continue;
      }
      split = true;
      if (rayMeetsBox(nodes[nd.left], o, dir, inv)) scratch[m++] = nd.left;
      if (rayMeetsBox(nodes[nd.right], o, dir, inv)) scratch[m++] = nd.right;
    }
    if (!split || m > cap) return n;
    for (int i = 0; i < m; ++i) out[i] = scratch[i];
    n = m;
  }
}

} // namespace detail::meshtosdf
} // namespace lvdif
