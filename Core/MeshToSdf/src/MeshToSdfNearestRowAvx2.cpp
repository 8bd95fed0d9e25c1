// NearestIndex::traverseRowAvx2: the row traversal of MeshToSdfNearestRow.cpp
// with the 8 points in the 8 lanes of one AVX register (child by child), for
// CPUs with AVX2 (chosen at run time; the file is built without -mavx2 and
// only this function carries the target attribute). Float bounds only: the
// double closest-point routine it calls is the same code as everywhere, and
// no multiply-add is contracted (-ffp-contract=off), so results are identical.
#include "MeshToSdfNearestRow.h"

#include <algorithm>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

namespace lvdif
{
namespace detail::meshtosdf
{

static_assert(NearestIndex::RowPoints == 8, "one AVX register of points");

__attribute__((target("avx2"))) void NearestIndex::traverseRowAvx2(NearestRowState& s) const
{
  const int n = s.n;
  const __m256 px = _mm256_load_ps(s.px);
  const __m256 eps = _mm256_set1_ps(s.epsF), seps = _mm256_set1_ps(2.5f * s.epsF), zero = _mm256_setzero_ps(),
               shrink = _mm256_set1_ps(0.999999f), huge = _mm256_set1_ps(3.4e38f),
               peps = _mm256_set1_ps(s.planeEps),
               absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m128 vy = _mm_set1_ps(s.py), vz = _mm_set1_ps(s.pz), veps = _mm_set1_ps(s.epsF), zero4 = _mm_setzero_ps();
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
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
      if (it.mask >> i & 1) worst = std::max(worst, s.thrF[i]);
    if (it.key > worst) continue;
    const Node& nd = this->Nodes[static_cast<std::size_t>(it.node)];
    // the y and z parts, the same for every point: lanes = children
    alignas(16) float yz[4], dyz[4];
    {
      const __m128 gy = _mm_max_ps(_mm_sub_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(nd.lo[1]), vy),
                                     _mm_sub_ps(vy, _mm_load_ps(nd.hi[1]))), veps), zero4);
      const __m128 gz = _mm_max_ps(_mm_sub_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(nd.lo[2]), vz),
                                     _mm_sub_ps(vz, _mm_load_ps(nd.hi[2]))), veps), zero4);
      _mm_store_ps(yz, _mm_add_ps(_mm_mul_ps(gy, gy), _mm_mul_ps(gz, gz)));
      _mm_store_ps(dyz, _mm_add_ps(_mm_mul_ps(_mm_load_ps(nd.sn[1]), vy), _mm_mul_ps(_mm_load_ps(nd.sn[2]), vz)));
    }
    const __m256 thr = _mm256_load_ps(s.thrF);
    Item kids[4];
    int nk = 0;
    for (int c = 0; c < nd.count; ++c)
    {
      // child c's bound for the 8 points: lanes = points
      const __m256 g = _mm256_max_ps(_mm256_sub_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_set1_ps(nd.lo[0][c]), px),
                                       _mm256_sub_ps(px, _mm256_set1_ps(nd.hi[0][c]))), eps), zero);
      const __m256 box = _mm256_add_ps(_mm256_mul_ps(g, g), _mm256_set1_ps(yz[c]));
      const __m256 d = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(nd.sn[0][c]), px), _mm256_set1_ps(dyz[c]));
      const __m256 sg = _mm256_max_ps(_mm256_sub_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_set1_ps(nd.smin[c]), d),
                                        _mm256_sub_ps(d, _mm256_set1_ps(nd.smax[c]))), seps), zero);
      const __m256 lb = _mm256_mul_ps(_mm256_max_ps(box, _mm256_mul_ps(sg, sg)), shrink);
      const int m = _mm256_movemask_ps(_mm256_cmp_ps(lb, thr, _CMP_LE_OQ)) & it.mask;
      if (m == 0) continue;
      const std::int32_t ch = nd.child[c];
      if (ch < 0)
      {
        // the triangle's plane and edge bounds for the 8 points
        const PlanesF& f = this->TriPlanes[static_cast<std::size_t>(~ch)];
        alignas(16) float b[4];
        _mm_store_ps(b, _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(f.y), vy), _mm_mul_ps(_mm_load_ps(f.z), vz)),
                          _mm_load_ps(f.w)));
        const __m256 v0 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(f.x[0]), px), _mm256_set1_ps(b[0]));
        const __m256 v1 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(f.x[1]), px), _mm256_set1_ps(b[1]));
        const __m256 v2 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(f.x[2]), px), _mm256_set1_ps(b[2]));
        const __m256 v3 = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(f.x[3]), px), _mm256_set1_ps(b[3]));
        const __m256 pd = _mm256_max_ps(_mm256_sub_ps(_mm256_and_ps(v0, absMask), peps), zero);
        const __m256 ed = _mm256_max_ps(_mm256_sub_ps(_mm256_max_ps(v1, _mm256_max_ps(v2, v3)), peps), zero);
        const __m256 lt = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(pd, pd), _mm256_mul_ps(ed, ed)), shrink);
        const int mt = m & _mm256_movemask_ps(_mm256_cmp_ps(lt, thr, _CMP_LE_OQ));
        if (mt == 0) continue;
        const Packed& t = this->Tris[static_cast<std::size_t>(~ch)];
        for (int i = 0; i < n; ++i)
          if (mt >> i & 1) s.exact(i, t);
        continue;
      }
      // the smallest bound among the points that pass
      const __m256 keep = _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(m), bits), bits));
      const __m256 k8 = _mm256_blendv_ps(huge, lb, keep);
      __m128 k4 = _mm_min_ps(_mm256_castps256_ps128(k8), _mm256_extractf128_ps(k8, 1));
      k4 = _mm_min_ps(k4, _mm_shuffle_ps(k4, k4, _MM_SHUFFLE(2, 3, 0, 1)));
      k4 = _mm_min_ps(k4, _mm_shuffle_ps(k4, k4, _MM_SHUFFLE(1, 0, 3, 2)));
      const float key = _mm_cvtss_f32(k4);
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

} // namespace detail::meshtosdf
} // namespace lvdif

#else
namespace lvdif
{
namespace detail::meshtosdf
{
void NearestIndex::traverseRowAvx2(NearestRowState& s) const { this->traverseRowSse(s); }
} // namespace detail::meshtosdf
} // namespace lvdif
#endif
