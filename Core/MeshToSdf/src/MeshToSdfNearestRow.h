// The state of one NearestIndex::nearestRow call, shared by its SSE and AVX2
// traversals (MeshToSdfNearestRow.cpp, MeshToSdfNearestRowAvx2.cpp).
#pragma once

#include "MeshToSdfNearest.h"

#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

struct NearestRowState
{
  static constexpr int N = NearestIndex::RowPoints;
  const V3* p = nullptr;
  int n = 0;
  NearestResult* out = nullptr;
  double tau = 0;                 // slack on every bound (see nearest())
  float epsF = 0;                 // float box margin
  float planeEps = 0;             // float triangle-plane margin
  double thr2[N];
  alignas(32) float thrF[N];      // unused lanes: -1, never pass
  alignas(32) float px[N];        // x of the points (the last one repeated)
  float py = 0, pz = 0;

  void setThreshold(int i)
  {
    const double s = std::sqrt(this->out[i].dist2) + this->tau;
    this->thr2[i] = s * s;
    this->thrF[i] = roundUpToFloat(this->thr2[i]);
  }
  /// The exact test of triangle t for point i (its bounds already passed).
  void exact(int i, const NearestIndex::Packed& t)
  {
    NearestResult& best = this->out[i];
    if (t.index == best.tri) return;
    const Closest c = closestPointOnTriangle(this->p[i], t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - this->p[i];
    const double d2 = dot(d, d);
    // ties to the lowest index, like the brute force and the GPU
    if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || t.index < best.tri)))
    {
      best.dist2 = d2;
      best.tri = t.index;
      best.closest = c;
      this->setThreshold(i);
    }
  }
};

/// Whether nearestRow uses its AVX2 traversal (set from the CPU at start-up;
/// tests switch it off to cover the SSE one).
extern bool nearestRowUseAvx2;

} // namespace detail::meshtosdf
} // namespace lvdif
