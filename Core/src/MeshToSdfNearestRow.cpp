// NearestIndex::nearestRow: four neighbouring voxels of a grid row share one
// traversal ("packet" traversal, as for coherent rays: Wald et al.,
// "Interactive rendering with coherent ray tracing", 2001). Each node's four
// child boxes are tested against the four points with SSE (the y and z parts
// once, the x part per point); a child is entered with the mask of the points
// it may still serve, so every point is pruned by its own bound. Per point
// the answer is exactly that of nearest() (same closest-point routine, same
// tie rule, conservative bounds); only the work is shared.
#include "MeshToSdfNearest.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define LVDIF_NEAREST_ROW_SSE 1
#endif

namespace lvdif
{
namespace sdfdetail
{

#ifndef LVDIF_NEAREST_ROW_SSE
void NearestIndex::nearestRow(const V3* p, int n, std::int32_t hint, NearestResult* out) const
{
  for (int i = 0; i < n; ++i) out[i] = this->nearest(p[i], i > 0 ? out[i - 1].tri : hint, 1e300);
}
#else
void NearestIndex::nearestRow(const V3* p, int n, std::int32_t hint, NearestResult* out) const
{
  double big = this->Scale;
  for (int i = 0; i < n; ++i)
  {
    out[i] = NearestResult{};
    out[i].dist2 = 1e300;
    big = std::max(big, std::max(std::fabs(p[i].x), std::max(std::fabs(p[i].y), std::fabs(p[i].z))));
  }
  if (this->Nodes.empty() || n <= 0) return;
  const double tau = 1e-10 * big; // as in nearest()
  const float epsF = static_cast<float>(big * 1.2e-7 * 4.0);
  double thr2[4] = { -1, -1, -1, -1 };
  alignas(16) float thrF[4] = { -1, -1, -1, -1 }; // unused lanes never pass
  auto setThreshold = [&](int i) {
    const double s = std::sqrt(out[i].dist2) + tau;
    thr2[i] = s * s;
    thrF[i] = roundUpToFloat(thr2[i]);
  };
  auto consider = [&](int i, const Packed& t) {
    NearestResult& best = out[i];
    if (t.index == best.tri) return;
    const V3 q = p[i];
    auto eval = [&](int k) { return t.plane[k][0] * q.x + t.plane[k][1] * q.y + t.plane[k][2] * q.z + t.plane[k][3]; };
    const double pd = eval(0);
    const double ed = std::max(0.0, std::max(eval(1), std::max(eval(2), eval(3))));
    if (pd * pd + ed * ed > thr2[i]) return;
    const Closest c = closestPointOnTriangle(q, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - q;
    const double d2 = dot(d, d);
    if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || t.index < best.tri)))
    {
      best.dist2 = d2;
      best.tri = t.index;
      best.closest = c;
      setThreshold(i);
    }
  };
  for (int i = 0; i < n; ++i)
  {
    if (hint >= 0)
    {
      const Packed& t = this->Tris[static_cast<std::size_t>(this->PosOf[static_cast<std::size_t>(hint)])];
      const Closest c = closestPointOnTriangle(p[i], t.v[0], t.v[1], t.v[2]);
      const V3 d = c.point - p[i];
      out[i].dist2 = dot(d, d);
      out[i].tri = hint;
      out[i].closest = c;
    }
    setThreshold(i);
  }
  float px[4];
  for (int i = 0; i < 4; ++i) px[i] = static_cast<float>(p[std::min(i, n - 1)].x);
  const __m128 vy = _mm_set1_ps(static_cast<float>(p[0].y)), vz = _mm_set1_ps(static_cast<float>(p[0].z));
  const __m128 veps = _mm_set1_ps(epsF), vseps = _mm_set1_ps(2.5f * epsF), zero = _mm_setzero_ps(),
               shrink = _mm_set1_ps(0.999999f);
  struct Item
  {
    std::int32_t node;
    std::int32_t mask; // points (bits) the node may still serve
    float key;         // smallest lower bound among them
  };
  Item stack[256];
  int top = 0;
  stack[top++] = { 0, (1 << n) - 1, 0.0f };
  while (top > 0)
  {
    const Item it = stack[--top];
    float worst = -1;
    for (int i = 0; i < 4; ++i)
      if (it.mask >> i & 1) worst = std::max(worst, thrF[i]);
    if (it.key > worst) continue;
    const Node& nd = this->Nodes[static_cast<std::size_t>(it.node)];
    auto gap2 = [&](int a, __m128 v) {
      const __m128 g = _mm_max_ps(_mm_sub_ps(_mm_load_ps(nd.lo[a]), v), _mm_sub_ps(v, _mm_load_ps(nd.hi[a])));
      const __m128 c = _mm_max_ps(_mm_sub_ps(g, veps), zero);
      return _mm_mul_ps(c, c);
    };
    const __m128 yz = _mm_add_ps(gap2(1, vy), gap2(2, vz));
    const __m128 snx = _mm_load_ps(nd.sn[0]), smin = _mm_load_ps(nd.smin), smax = _mm_load_ps(nd.smax);
    const __m128 dyz = _mm_add_ps(_mm_mul_ps(_mm_load_ps(nd.sn[1]), vy), _mm_mul_ps(_mm_load_ps(nd.sn[2]), vz));
    alignas(16) float lb[4][4]; // [point][child]
    int childMask[4] = { 0, 0, 0, 0 };
    for (int i = 0; i < 4; ++i)
    {
      if (!(it.mask >> i & 1)) continue;
      const __m128 vx = _mm_set1_ps(px[i]);
      const __m128 box = _mm_add_ps(gap2(0, vx), yz);
      const __m128 d = _mm_add_ps(_mm_mul_ps(snx, vx), dyz);
      const __m128 sg = _mm_max_ps(_mm_sub_ps(_mm_max_ps(_mm_sub_ps(smin, d), _mm_sub_ps(d, smax)), vseps), zero);
      const __m128 l = _mm_mul_ps(_mm_max_ps(box, _mm_mul_ps(sg, sg)), shrink);
      _mm_store_ps(lb[i], l);
      const int m = _mm_movemask_ps(_mm_cmple_ps(l, _mm_set1_ps(thrF[i])));
      for (int c = 0; c < 4; ++c) childMask[c] |= (m >> c & 1) << i;
    }
    Item kids[4];
    int nk = 0;
    for (int c = 0; c < nd.count; ++c)
    {
      const int m = childMask[c];
      if (m == 0) continue;
      const std::int32_t ch = nd.child[c];
      if (ch < 0)
      {
        const Packed& t = this->Tris[static_cast<std::size_t>(~ch)];
        for (int i = 0; i < 4; ++i)
          if (m >> i & 1) consider(i, t);
        continue;
      }
      float key = 3.4e38f;
      for (int i = 0; i < 4; ++i)
        if (m >> i & 1) key = std::min(key, lb[i][c]);
      int j = nk++;
      while (j > 0 && kids[j - 1].key < key)
      {
        kids[j] = kids[j - 1];
        --j;
      }
      kids[j] = { ch, m, key };
    }
    for (int i = 0; i < nk; ++i) stack[top++] = kids[i];
  }
}
#endif

} // namespace sdfdetail
} // namespace lvdif
