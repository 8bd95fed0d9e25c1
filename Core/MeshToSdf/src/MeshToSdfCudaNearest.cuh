// The mesh tree's nearest-triangle query on the GPU (Bvh::nearest's answer,
// bit for bit): read by the sessions' kernels (MeshToSdfCudaKernels.cuh) and
// by the sharp features' regions (MeshToSdfCudaSharp.cu).
#pragma once

#include "MeshToSdfCudaLayout.cuh"

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
namespace
{

/// Bvh::nearest; the hint and the result's place are leaf slots (bestSlot).
/// The stack keeps each node's box distance as a float rounded down: a lower
/// bound of the double, so a node is only ever dropped where Bvh::nearest
/// drops it too (at worst visited where the double would have dropped it,
/// which finds nothing nearer), and the stack takes half the local memory
/// (its spills were the kernel's main traffic; 13.3M triangles at 1024^3 on
/// an H200: distance pass 6 % shorter). Skipping a leaf's triangles by their
/// own boxes (with NearestIndex's tau) was measured too and cost more than it
/// saved, and so did a tree of child pairs (both children's boxes as floats
/// rounded outward in one 64-byte record: one load per visit instead of
/// three; the bunny's and the armadillo's distance pass 20-35 % longer, the
/// large meshes' unchanged; docs/BENCHMARKS.md).
__device__ NearestResult nearestDev(const DevBvh& b, V3 p, int hintSlot, double maxDist2, int& bestSlot)
{
  NearestResult best;
  best.dist2 = maxDist2;
  bestSlot = -1;
  if (hintSlot >= 0)
  {
    const GpuTri& t = b.leaf[hintSlot];
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 <= best.dist2)
    {
      best.dist2 = d2;
      best.tri = b.order[hintSlot];
      best.closest = c;
      bestSlot = hintSlot;
    }
  }
  int stackNode[64];
  float stackD2[64];
  int top = 0;
  stackNode[top] = 0;
  stackD2[top++] = __double2float_rd(pointBoxDist2(p, b.nodes[0].lo, b.nodes[0].hi));
  while (top > 0)
  {
    --top;
    if (static_cast<double>(stackD2[top]) > best.dist2) continue;
    const GpuNode n = b.nodes[stackNode[top]];
    if (n.left < 0)
    {
      for (int i = n.first; i < n.first + n.count; ++i)
      {
        const int ti = b.order[i];
        if (ti == best.tri) continue;
        const GpuTri& t = b.leaf[i];
        const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
        const V3 d = c.point - p;
        const double d2 = dot(d, d);
        if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || ti < best.tri)))
        {
          best.dist2 = d2;
          best.tri = ti;
          best.closest = c;
          bestSlot = i;
        }
      }
      continue;
    }
    const double dl = pointBoxDist2(p, b.nodes[n.left].lo, b.nodes[n.left].hi);
    const double dr = pointBoxDist2(p, b.nodes[n.right].lo, b.nodes[n.right].hi);
    const int nearC = dl <= dr ? n.left : n.right, farC = dl <= dr ? n.right : n.left;
    const double nearD = dl <= dr ? dl : dr, farD = dl <= dr ? dr : dl;
    // the pushes compare the exact doubles, as Bvh::nearest does
    if (farD <= best.dist2 && top < 64) { stackNode[top] = farC; stackD2[top++] = __double2float_rd(farD); }
    if (nearD <= best.dist2 && top < 64) { stackNode[top] = nearC; stackD2[top++] = __double2float_rd(nearD); }
  }
  return best;
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
