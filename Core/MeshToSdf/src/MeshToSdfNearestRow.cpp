// NearestIndex::nearestRow: RowPoints (8) neighbouring voxels of a grid row
// share one traversal ("packet" traversal, as for coherent rays: Wald et al.,
// "Interactive rendering with coherent ray tracing", 2001). Each node's four
// child boxes are tested against the points four at a time with SSE (the y
// and z parts once, the x part per point; MeshToSdfNearestRowAvx2.cpp does
// the 8 points at once); a child is entered with the mask of the points it
// may still serve, so every point is pruned by its own bound. Per point the
// answer is exactly that of nearest() (same closest-point routine, same tie
// rule, conservative bounds); only the work is shared.
#include "MeshToSdfNearestRow.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define LVDIF_NEAREST_ROW_SSE 1
#endif

namespace lvdif
{
namespace detail::meshtosdf
{

bool nearestRowUseAvx2 = [] {
#if defined(__GNUC__) && defined(__x86_64__)
  __builtin_cpu_init(); // needed before __builtin_cpu_supports in static initialisers
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}();

void NearestIndex::nearestRow(
  const V3* p, int n, std::int32_t hint, const std::int32_t* laneHints, NearestResult* out) const
{
  if (n > RowPoints)
  {
    this->nearestRow(p, RowPoints, hint, laneHints, out);
    this->nearestRow(p + RowPoints, n - RowPoints, out[RowPoints - 1].tri, laneHints ? laneHints + RowPoints : nullptr,
      out + RowPoints);
    return;
  }
  NearestRowState s;
  s.p = p;
  s.n = n;
  s.out = out;
  double big = this->Scale;
  for (int i = 0; i < n; ++i)
  {
    out[i] = NearestResult{};
    out[i].dist2 = 1e300;
    big = std::max(big, std::max(std::fabs(p[i].x), std::max(std::fabs(p[i].y), std::fabs(p[i].z))));
  }
  if (this->Nodes.empty() || n <= 0) return;
  s.tau = 1e-10 * big; // as in nearest()
  s.epsF = static_cast<float>(big * 1.2e-7 * 4.0);
  // triangle planes in float: the error of a plane value is below 1.3e-6 big
  // (coefficients, offset and products rounded), so 4e-6 big is conservative
  s.planeEps = static_cast<float>(4e-6 * big);
  for (int i = 0; i < RowPoints; ++i) s.thr2[i] = s.thrF[i] = -1;
  for (int i = 0; i < n; ++i)
  {
    s.setThreshold(i); // 1e300 first: the seeds are taken as exact candidates
    if (hint >= 0) s.exact(i, this->Tris[static_cast<std::size_t>(this->PosOf[static_cast<std::size_t>(hint)])]);
    if (laneHints && laneHints[i] >= 0 && laneHints[i] != hint)
      s.exact(i, this->Tris[static_cast<std::size_t>(this->PosOf[static_cast<std::size_t>(laneHints[i])])]);
  }
  for (int i = 0; i < RowPoints; ++i) s.px[i] = static_cast<float>(p[std::min(i, n - 1)].x);
  s.py = static_cast<float>(p[0].y);
  s.pz = static_cast<float>(p[0].z);
#if defined(__GNUC__) && defined(__x86_64__)
  if (nearestRowUseAvx2)
  {
    this->traverseRowAvx2(s);
    return;
  }
#endif
  this->traverseRowSse(s);
}

#ifndef LVDIF_NEAREST_ROW_SSE
void NearestIndex::traverseRowSse(NearestRowState& s) const
{
  // no SSE: one-point queries seeded by the row's results so far
  for (int i = 0; i < s.n; ++i)
    s.out[i] = this->nearest(s.p[i], s.out[i].tri >= 0 ? s.out[i].tri : (i > 0 ? s.out[i - 1].tri : -1), 1e300);
}
#else
void NearestIndex::traverseRowSse(NearestRowState& s) const
{
  const int n = s.n;
  const float* px = s.px;
  const float* thrF = s.thrF;
  const __m128 vy = _mm_set1_ps(s.py), vz = _mm_set1_ps(s.pz);
  const __m128 veps = _mm_set1_ps(s.epsF), vseps = _mm_set1_ps(2.5f * s.epsF), zero = _mm_setzero_ps(),
               shrink = _mm_set1_ps(0.999999f), huge = _mm_set1_ps(3.4e38f);
  const __m128 vpeps = _mm_set1_ps(s.planeEps);
  const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  constexpr int Quads = RowPoints / 4;
  const int usedQuads = (n + 3) / 4;
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
    for (int i = 0; i < n; ++i)
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
    // l[q][c]: child c's bounds for the points of quad q (lanes = points)
    __m128 l[Quads][4];
    int cm[4] = { 0, 0, 0, 0 }; // per child: the points it may serve
    for (int q = 0; q < usedQuads; ++q)
    {
      if ((it.mask >> (4 * q) & 15) == 0)
      {
        for (int c = 0; c < 4; ++c) l[q][c] = huge;
        continue;
      }
      for (int i = 0; i < 4; ++i)
      {
        const __m128 vx = _mm_set1_ps(px[4 * q + i]);
        const __m128 box = _mm_add_ps(gap2(0, vx), yz);
        const __m128 d = _mm_add_ps(_mm_mul_ps(snx, vx), dyz);
        const __m128 sg = _mm_max_ps(_mm_sub_ps(_mm_max_ps(_mm_sub_ps(smin, d), _mm_sub_ps(d, smax)), vseps), zero);
        l[q][i] = _mm_mul_ps(_mm_max_ps(box, _mm_mul_ps(sg, sg)), shrink);
      }
      _MM_TRANSPOSE4_PS(l[q][0], l[q][1], l[q][2], l[q][3]);
      const __m128 vthr = _mm_load_ps(thrF + 4 * q);
      for (int c = 0; c < 4; ++c) cm[c] |= _mm_movemask_ps(_mm_cmple_ps(l[q][c], vthr)) << (4 * q);
    }
    Item kids[4];
    int nk = 0;
    for (int c = 0; c < nd.count; ++c)
    {
      const int m = cm[c] & it.mask;
      if (m == 0) continue;
      const std::int32_t ch = nd.child[c];
      if (ch < 0)
      {
        // the triangle's plane and edge bounds for four points at once
        const PlanesF& f = this->TriPlanes[static_cast<std::size_t>(~ch)];
        const __m128 base = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(f.y), vy), _mm_mul_ps(_mm_load_ps(f.z), vz)),
          _mm_load_ps(f.w));
        alignas(16) float b[4];
        _mm_store_ps(b, base);
        int mt = 0;
        for (int q = 0; q < usedQuads; ++q)
        {
          if ((m >> (4 * q) & 15) == 0) continue;
          const __m128 vpx = _mm_load_ps(px + 4 * q);
          auto val = [&](int k) { return _mm_add_ps(_mm_mul_ps(_mm_set1_ps(f.x[k]), vpx), _mm_set1_ps(b[k])); };
          const __m128 pd = _mm_max_ps(_mm_sub_ps(_mm_and_ps(val(0), absMask), vpeps), zero);
          const __m128 ed = _mm_max_ps(_mm_sub_ps(_mm_max_ps(val(1), _mm_max_ps(val(2), val(3))), vpeps), zero);
          const __m128 lt = _mm_mul_ps(_mm_add_ps(_mm_mul_ps(pd, pd), _mm_mul_ps(ed, ed)), shrink);
          mt |= _mm_movemask_ps(_mm_cmple_ps(lt, _mm_load_ps(thrF + 4 * q))) << (4 * q);
        }
        mt &= m;
        if (mt == 0) continue;
        const Packed& t = this->Tris[static_cast<std::size_t>(~ch)];
        for (int i = 0; i < n; ++i)
          if (mt >> i & 1) s.exact(i, t);
        continue;
      }
      // the smallest bound among the points that pass (the others set to huge)
      __m128 km = huge;
      for (int q = 0; q < usedQuads; ++q)
      {
        const int mq = m >> (4 * q);
        const __m128 keep = _mm_castsi128_ps(_mm_set_epi32(-(mq >> 3 & 1), -(mq >> 2 & 1), -(mq >> 1 & 1), -(mq & 1)));
        km = _mm_min_ps(km, _mm_or_ps(_mm_and_ps(keep, l[q][c]), _mm_andnot_ps(keep, huge)));
      }
      km = _mm_min_ps(km, _mm_shuffle_ps(km, km, _MM_SHUFFLE(2, 3, 0, 1)));
      km = _mm_min_ps(km, _mm_shuffle_ps(km, km, _MM_SHUFFLE(1, 0, 3, 2)));
      const float key = _mm_cvtss_f32(km);
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

} // namespace detail::meshtosdf
} // namespace lvdif
