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

// the lambdas below need the target too (an attribute would not reach them)
#pragma GCC push_options
#pragma GCC target("avx2")
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi" // internal lambdas, all built for AVX2
namespace
{
/// NearestRowState::exact for the points of mask m (bits 4q..4q+3 of quad q)
/// against one triangle, four points per AVX register of doubles: Ericson's
/// region tests of closestPointOnTriangle evaluated for every region at once
/// and blended in the routine's order (vertex A first, the face last), each
/// region's point by the routine's own expression in the same order of
/// operations, so every lane holds the bits the scalar routine returns
/// (contraction is off, no FMA). The branches of the scalar routine are
/// data-dependent and mispredict often; here only regions some lane takes
/// pay their division. Then the same update as exact(), point by point.
void exactQuads(NearestRowState& s, const NearestIndex::Packed& t, int m)
{
  const V3 a = t.v[0], b = t.v[1], c = t.v[2];
  const V3 ab = b - a, ac = c - a, cb = c - b;
  const __m256d zero = _mm256_setzero_pd();
  auto b4 = [](double x) { return _mm256_set1_pd(x); };
  const __m256d ax = b4(a.x), ay = b4(a.y), az = b4(a.z), bx = b4(b.x), by = b4(b.y), bz = b4(b.z), cx = b4(c.x),
                cy = b4(c.y), cz = b4(c.z), abx = b4(ab.x), aby = b4(ab.y), abz = b4(ab.z), acx = b4(ac.x),
                acy = b4(ac.y), acz = b4(ac.z), cbx = b4(cb.x), cby = b4(cb.y), cbz = b4(cb.z);
  auto dot4 = [](__m256d ux, __m256d uy, __m256d uz, __m256d vx, __m256d vy, __m256d vz) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ux, vx), _mm256_mul_pd(uy, vy)), _mm256_mul_pd(uz, vz));
  };
  auto le = [](__m256d x, __m256d y) { return _mm256_cmp_pd(x, y, _CMP_LE_OQ); };
  auto ge = [](__m256d x, __m256d y) { return _mm256_cmp_pd(x, y, _CMP_GE_OQ); };
  auto both = [](__m256d x, __m256d y) { return _mm256_and_pd(x, y); };
  for (int q = 0; q < 2; ++q)
  {
    const int mq = (m >> (4 * q)) & 15;
    if (mq == 0) continue;
    const V3* p = s.p;
    int at[4];
    for (int l = 0; l < 4; ++l) at[l] = std::min(4 * q + l, s.n - 1);
    const __m256d px = _mm256_setr_pd(p[at[0]].x, p[at[1]].x, p[at[2]].x, p[at[3]].x),
                  py = _mm256_setr_pd(p[at[0]].y, p[at[1]].y, p[at[2]].y, p[at[3]].y),
                  pz = _mm256_setr_pd(p[at[0]].z, p[at[1]].z, p[at[2]].z, p[at[3]].z);
    const __m256d apx = _mm256_sub_pd(px, ax), apy = _mm256_sub_pd(py, ay), apz = _mm256_sub_pd(pz, az);
    const __m256d d1 = dot4(abx, aby, abz, apx, apy, apz), d2 = dot4(acx, acy, acz, apx, apy, apz);
    const __m256d bpx = _mm256_sub_pd(px, bx), bpy = _mm256_sub_pd(py, by), bpz = _mm256_sub_pd(pz, bz);
    const __m256d d3 = dot4(abx, aby, abz, bpx, bpy, bpz), d4 = dot4(acx, acy, acz, bpx, bpy, bpz);
    const __m256d vc = _mm256_sub_pd(_mm256_mul_pd(d1, d4), _mm256_mul_pd(d3, d2));
    const __m256d cpx = _mm256_sub_pd(px, cx), cpy = _mm256_sub_pd(py, cy), cpz = _mm256_sub_pd(pz, cz);
    const __m256d d5 = dot4(abx, aby, abz, cpx, cpy, cpz), d6 = dot4(acx, acy, acz, cpx, cpy, cpz);
    const __m256d vb = _mm256_sub_pd(_mm256_mul_pd(d5, d2), _mm256_mul_pd(d1, d6));
    const __m256d va = _mm256_sub_pd(_mm256_mul_pd(d3, d6), _mm256_mul_pd(d5, d4));
    const __m256d e43 = _mm256_sub_pd(d4, d3), e56 = _mm256_sub_pd(d5, d6);
    // the regions in the routine's order; a lane takes the first that holds
    const __m256d inA = both(le(d1, zero), le(d2, zero));
    const __m256d inB = both(ge(d3, zero), le(d4, d3));
    const __m256d inAB = both(both(le(vc, zero), ge(d1, zero)), le(d3, zero));
    const __m256d inC = both(ge(d6, zero), le(d5, d6));
    const __m256d inCA = both(both(le(vb, zero), ge(d2, zero)), le(d6, zero));
    const __m256d inBC = both(both(le(va, zero), ge(e43, zero)), ge(e56, zero));
    const int mA = _mm256_movemask_pd(inA), mB = _mm256_movemask_pd(inB), mAB = _mm256_movemask_pd(inAB),
              mC = _mm256_movemask_pd(inC), mCA = _mm256_movemask_pd(inCA), mBC = _mm256_movemask_pd(inBC);
    int feat[4];
    int faceLanes = 0, bcLanes = 0, caLanes = 0, abLanes = 0;
    for (int l = 0; l < 4; ++l)
    {
      const int bit = 1 << l;
      Feature f = FeatFace;
      if (mA & bit) f = FeatVertA;
      else if (mB & bit) f = FeatVertB;
      else if (mAB & bit) f = FeatEdgeAB;
      else if (mC & bit) f = FeatVertC;
      else if (mCA & bit) f = FeatEdgeCA;
      else if (mBC & bit) f = FeatEdgeBC;
      feat[l] = f;
      if (!(mq & bit)) continue;
      faceLanes |= f == FeatFace ? bit : 0;
      bcLanes |= f == FeatEdgeBC ? bit : 0;
      caLanes |= f == FeatEdgeCA ? bit : 0;
      abLanes |= f == FeatEdgeAB ? bit : 0;
    }
    // the point and barycentrics of each lane, the face first, then each
    // region that takes precedence over it written on top
    __m256d x = zero, y = zero, z = zero, w1 = zero, w2 = zero;
    auto put = [&](__m256d sel, __m256d nx, __m256d ny, __m256d nz, __m256d n1, __m256d n2) {
      x = _mm256_blendv_pd(x, nx, sel);
      y = _mm256_blendv_pd(y, ny, sel);
      z = _mm256_blendv_pd(z, nz, sel);
      w1 = _mm256_blendv_pd(w1, n1, sel);
      w2 = _mm256_blendv_pd(w2, n2, sel);
    };
    const __m256d one = _mm256_set1_pd(1.0);
    if (faceLanes)
    {
      const __m256d denom = _mm256_div_pd(one, _mm256_add_pd(_mm256_add_pd(va, vb), vc));
      const __m256d v = _mm256_mul_pd(vb, denom), w = _mm256_mul_pd(vc, denom);
      x = _mm256_add_pd(_mm256_add_pd(ax, _mm256_mul_pd(v, abx)), _mm256_mul_pd(w, acx));
      y = _mm256_add_pd(_mm256_add_pd(ay, _mm256_mul_pd(v, aby)), _mm256_mul_pd(w, acy));
      z = _mm256_add_pd(_mm256_add_pd(az, _mm256_mul_pd(v, abz)), _mm256_mul_pd(w, acz));
      w1 = v;
      w2 = w;
    }
    auto laneMask = [](int bits) {
      return _mm256_castsi256_pd(_mm256_setr_epi64x(-(bits & 1), -(bits >> 1 & 1), -(bits >> 2 & 1), -(bits >> 3 & 1)));
    };
    if (bcLanes)
    {
      const __m256d w = _mm256_div_pd(e43, _mm256_add_pd(e43, e56));
      put(laneMask(bcLanes), _mm256_add_pd(bx, _mm256_mul_pd(w, cbx)), _mm256_add_pd(by, _mm256_mul_pd(w, cby)),
        _mm256_add_pd(bz, _mm256_mul_pd(w, cbz)), _mm256_sub_pd(one, w), w);
    }
    if (caLanes)
    {
      const __m256d w = _mm256_div_pd(d2, _mm256_sub_pd(d2, d6));
      put(laneMask(caLanes), _mm256_add_pd(ax, _mm256_mul_pd(w, acx)), _mm256_add_pd(ay, _mm256_mul_pd(w, acy)),
        _mm256_add_pd(az, _mm256_mul_pd(w, acz)), zero, w);
    }
    if (abLanes)
    {
      const __m256d v = _mm256_div_pd(d1, _mm256_sub_pd(d1, d3));
      put(laneMask(abLanes), _mm256_add_pd(ax, _mm256_mul_pd(v, abx)), _mm256_add_pd(ay, _mm256_mul_pd(v, aby)),
        _mm256_add_pd(az, _mm256_mul_pd(v, abz)), v, zero);
    }
    int cLanes = 0, bLanes = 0, aLanes = 0;
    for (int l = 0; l < 4; ++l)
    {
      cLanes |= feat[l] == FeatVertC ? 1 << l : 0;
      bLanes |= feat[l] == FeatVertB ? 1 << l : 0;
      aLanes |= feat[l] == FeatVertA ? 1 << l : 0;
    }
    if (cLanes) put(laneMask(cLanes), cx, cy, cz, zero, one);
    if (bLanes) put(laneMask(bLanes), bx, by, bz, one, zero);
    if (aLanes) put(laneMask(aLanes), ax, ay, az, zero, zero);
    const __m256d dx = _mm256_sub_pd(x, px), dy = _mm256_sub_pd(y, py), dz = _mm256_sub_pd(z, pz);
    alignas(32) double dd[4], X[4], Y[4], Z[4], B1[4], B2[4];
    _mm256_store_pd(dd, dot4(dx, dy, dz, dx, dy, dz));
    _mm256_store_pd(X, x);
    _mm256_store_pd(Y, y);
    _mm256_store_pd(Z, z);
    _mm256_store_pd(B1, w1);
    _mm256_store_pd(B2, w2);
    for (int l = 0; l < 4; ++l)
    {
      if (!(mq >> l & 1)) continue;
      NearestResult& best = s.out[4 * q + l];
      if (t.index == best.tri) continue;
      const double d2l = dd[l];
      // ties to the lowest index, like the brute force and the GPU
      if (d2l < best.dist2 || (d2l == best.dist2 && (best.tri < 0 || t.index < best.tri)))
      {
        best.dist2 = d2l;
        best.tri = t.index;
        best.closest.point = V3{ X[l], Y[l], Z[l] };
        best.closest.b1 = B1[l];
        best.closest.b2 = B2[l];
        best.closest.feature = static_cast<Feature>(feat[l]);
        s.setThreshold(4 * q + l);
      }
    }
  }
}
} // namespace
#pragma GCC diagnostic pop
#pragma GCC pop_options

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
        exactQuads(s, this->Tris[static_cast<std::size_t>(~ch)], mt);
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
