// NearestIndex::nearestBrick: the bounded nearest triangle of many points of
// one small box (a brick of voxels within the band) from one short list of
// candidates. The list holds every triangle whose bounding box lies within U
// of the brick's box, U = min(d(c) + r, reach) with d(c) the exact nearest
// distance of the box's centre c and r the box's half-diagonal: a point p of
// the box has d(p) <= d(c) + |p - c| <= d(c) + r, and only points with
// d(p) <= reach want an answer, so the triangle that is nearest to p (and
// every triangle that ties with it) lies within U of p, hence of the box
// (the distance is 1-Lipschitz, the argument of the far blocks). A point then
// scans the list (a few dozen triangles near the surface; past BrickListMax,
// small triangles in a large brick, each point is one nearest() query) with the
// float plane bounds of nearestRow (the same margins) and runs the same
// closest-point routine with the same tie rule on the survivors: the answer
// is nearest(p, ., maxDist2), bit for bit.
#include "MeshToSdfNearestRow.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define LVDIF_BRICK_SSE 1
#endif
#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
/// One brick's candidate list as the per-point scans read it.
struct BrickScan
{
  const float* planes = nullptr;                        // groups of W candidates (see nearestBrick)
  const double* gaps = nullptr;                         // squared box gaps, ascending
  const std::int32_t* cand = nullptr;                   // positions in the packed triangles
  int count = 0;
  const NearestIndex::Packed* tris = nullptr;
  float eps = 0;
  std::uint64_t* exact = nullptr; // exact closest points, counted
};
void scanBrick4(const BrickScan& b, NearestRowState& s);
#if defined(__GNUC__) && defined(__x86_64__)
void scanBrickAvx2(const BrickScan& b, NearestRowState& s);
#endif
} // namespace

void NearestIndex::nearestBrick(const V3* p, int n, double maxDist2, std::int32_t hint, NearestResult* out,
  BrickScratch& scratch) const
{
  for (int i = 0; i < n; ++i)
  {
    out[i] = NearestResult{};
    out[i].dist2 = maxDist2;
  }
  if (this->Nodes.empty() || n <= 0) return;
  V3 lo = p[0], hi = p[0];
  for (int i = 1; i < n; ++i)
  {
    lo = { std::min(lo.x, p[i].x), std::min(lo.y, p[i].y), std::min(lo.z, p[i].z) };
    hi = { std::max(hi.x, p[i].x), std::max(hi.y, p[i].y), std::max(hi.z, p[i].z) };
  }
  double big = this->Scale;
  for (const V3& q : { lo, hi }) big = std::max(big, std::max(std::fabs(q.x), std::max(std::fabs(q.y), std::fabs(q.z))));
  // every rounding below (the centre, the radius, the gaps, computed against
  // exact distances) is a few ulps of big; m is far above that, far below a voxel
  const double m = 1e-9 * big;
  const V3 c = 0.5 * (lo + hi);
  const double r = 0.5 * norm(hi - lo) * (1 + 1e-12) + m;
  const double reach = std::sqrt(maxDist2);
  // the centre's nearest within reach + r: none means every point is farther than reach
  const double cap = reach + r + m;
  const NearestResult centre = this->nearest(c, hint, cap * cap, &scratch.exact);
  if (centre.tri < 0) return;
  const double u = std::min(std::sqrt(centre.dist2) + r, reach) * (1 + 1e-12) + m;
  const double u2 = u * u;
  ++scratch.bricks;
  scratch.points += static_cast<std::uint64_t>(n);
  // A list longer than BrickListMax: the triangles are small against the
  // brick (a coarse grid on a dense mesh). The scan below visits every
  // candidate within d(p) of the box in the order of its gap to the box, not
  // to p, so the exact tests of a point grow with the list (about 0.035 K
  // per point: 5,400 per voxel on the 832k-triangle armadillo at 32^3, 230 at
  // 128^3), where the tree's nearest-first walk needs 16-85 (the walk stops at
  // the first list entry past the limit). Then each point is its own nearest(p, ., maxDist2): the
  // function the scan computes, so the same bits.
  auto pointByPoint = [&] {
    ++scratch.pointByPoint;
    std::int32_t prev = centre.tri;
    for (int i = 0; i < n; ++i)
    {
      out[i] = this->nearest(p[i], prev, maxDist2, &scratch.exact);
      if (out[i].tri >= 0) prev = out[i].tri;
    }
  };

  // the candidates: every triangle whose (float, outward) box is within u of [lo, hi]
  std::vector<std::int32_t>& cand = scratch.cand;
  cand.clear();
  scratch.near.clear();
  scratch.keys.clear();
  scratch.gaps.clear();
  std::int32_t stack[256];
  int top = 0;
  stack[top++] = 0;
#ifdef LVDIF_BRICK_SSE
  // four children at once in float, as nearest() tests its boxes: the brick's
  // box rounded outward, epsF covering the subtractions' rounding, the sum
  // shrunk; the gaps kept (a lower bound of the distance, the sort key)
  const float epsF = static_cast<float>(big * 1.2e-7 * 4.0);
  const __m128 veps = _mm_set1_ps(epsF), zero = _mm_setzero_ps(), shrink = _mm_set1_ps(0.999999f),
               limit = _mm_set1_ps(roundUpToFloat(u2));
  __m128 blo[3], bhi[3];
  for (int a = 0; a < 3; ++a)
  {
    blo[a] = _mm_set1_ps(roundDownToFloat(lo[a]));
    bhi[a] = _mm_set1_ps(roundUpToFloat(hi[a]));
  }
  while (top > 0)
  {
    if (scratch.keys.size() > BrickListMax) return pointByPoint();
    const Node& nd = this->Nodes[static_cast<std::size_t>(stack[--top])];
    __m128 sum = zero;
    for (int a = 0; a < 3; ++a)
    {
      const __m128 g = _mm_max_ps(_mm_sub_ps(_mm_load_ps(nd.lo[a]), bhi[a]), _mm_sub_ps(blo[a], _mm_load_ps(nd.hi[a])));
      const __m128 c = _mm_max_ps(_mm_sub_ps(g, veps), zero);
      sum = _mm_add_ps(sum, _mm_mul_ps(c, c));
    }
    const __m128 lb = _mm_mul_ps(sum, shrink);
    alignas(16) float g2[4];
    _mm_store_ps(g2, lb);
    int pass = _mm_movemask_ps(_mm_cmple_ps(lb, limit)) & ((1 << nd.count) - 1);
    for (; pass; pass &= pass - 1)
    {
      const int k = __builtin_ctz(static_cast<unsigned>(pass));
      if (nd.child[k] < 0)
      {
        // one 64-bit key: the gap's float bits (a gap is >= +0, so its bits
        // order as the float does), then the position (>= 0): the order of
        // the (gap, position) pairs, sorted as integers (the pairs' sort was
        // about 1.5 % of the banded call)
        std::uint32_t bits;
        std::memcpy(&bits, &g2[k], sizeof bits);
        scratch.keys.push_back((static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint32_t>(~nd.child[k]));
      }
      else
        stack[top++] = nd.child[k];
    }
  }
  if (scratch.keys.size() > BrickListMax) return pointByPoint();
  std::sort(scratch.keys.begin(), scratch.keys.end());
  for (const std::uint64_t key : scratch.keys)
  {
    const std::uint32_t bits = static_cast<std::uint32_t>(key >> 32);
    float g;
    std::memcpy(&g, &bits, sizeof g);
    scratch.gaps.push_back(static_cast<double>(g));
    cand.push_back(static_cast<std::int32_t>(key & 0xffffffffu));
  }
#else
  while (top > 0)
  {
    if (scratch.near.size() > BrickListMax) return pointByPoint();
    const Node& nd = this->Nodes[static_cast<std::size_t>(stack[--top])];
    for (int k = 0; k < nd.count; ++k)
    {
      double g2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double g = std::max(0.0, std::max(static_cast<double>(nd.lo[a][k]) - hi[a], lo[a] - static_cast<double>(nd.hi[a][k])));
        g2 += g * g;
      }
      if (g2 > u2) continue;
      if (nd.child[k] < 0)
        scratch.near.push_back({ g2, ~nd.child[k] });
      else
        stack[top++] = nd.child[k];
    }
  }
  if (scratch.near.size() > BrickListMax) return pointByPoint();
  std::sort(scratch.near.begin(), scratch.near.end());
  for (const auto& c2 : scratch.near)
  {
    scratch.gaps.push_back(c2.first);
    cand.push_back(c2.second);
  }
#endif
  // nearest to the box first (sorted above): a point stops at the first group whose gap
  // (a lower bound of the distance from any point of the box) exceeds its bound
  const int K = static_cast<int>(cand.size());
  // the candidates' float planes in groups of W (lanes = candidates, W = 8
  // with AVX2, else 4): group g holds coefficient c (x, y, z, w) of plane j at
  // 16 W g + W (4 j + c) + lane; padding lanes get zero planes (their bound
  // is 0: they pass, and are skipped)
  const bool avx2 = nearestRowUseAvx2;
  const int W = avx2 ? 8 : 4;
  const int groups = (K + W - 1) / W;
  std::vector<float>& f = scratch.planes;
  f.assign(static_cast<std::size_t>(16 * W * groups), 0.0f);
  for (int k = 0; k < K; ++k)
  {
    const PlanesF& pl = this->TriPlanes[static_cast<std::size_t>(cand[static_cast<std::size_t>(k)])];
    float* g = f.data() + 16 * W * (k >> (avx2 ? 3 : 2)) + (k & (W - 1));
    for (int j = 0; j < 4; ++j)
    {
      g[W * (4 * j + 0)] = pl.x[j];
      g[W * (4 * j + 1)] = pl.y[j];
      g[W * (4 * j + 2)] = pl.z[j];
      g[W * (4 * j + 3)] = pl.w[j];
    }
  }

  BrickScan scan;
  scan.planes = f.data();
  scan.gaps = scratch.gaps.data();
  scan.cand = cand.data();
  scan.count = K;
  scan.tris = this->Tris.data();
  scan.eps = static_cast<float>(4e-6 * big); // nearestRow's plane margin
  scan.exact = &scratch.exact;
  scratch.listed += static_cast<std::uint64_t>(K);
  const double tau = 1e-10 * big; // as nearest() with this (larger or equal) big
  // every point starts from out[i].dist2 = maxDist2: its threshold
  // (setThreshold's sqrt and rounding) computed once for the brick
  NearestRowState start;
  start.out = out;
  start.tau = tau;
  start.setThreshold(0);
  std::int32_t prev = centre.tri;
  for (int i = 0; i < n; ++i)
  {
    NearestRowState s; // its exact() and threshold, for this one point
    s.p = p + i;
    s.n = 1;
    s.out = out + i;
    s.tau = tau;
    s.thr2[0] = start.thr2[0]; // = s.setThreshold(0): out[i].dist2 == maxDist2 here
    s.thrF[0] = start.thrF[0];
    // seed: the previous point's triangle (the centre's for the first), taken
    // as nearest() takes its hint; seeding with both measured no fewer exact tests
    if (prev >= 0)
    {
      ++scratch.exact;
      s.exact(0, this->Tris[static_cast<std::size_t>(this->PosOf[static_cast<std::size_t>(prev)])]);
    }
#if defined(__GNUC__) && defined(__x86_64__)
    if (avx2)
      scanBrickAvx2(scan, s);
    else
#endif
      scanBrick4(scan, s);
    if (out[i].tri >= 0) prev = out[i].tri;
  }
}

namespace
{
void scanBrick4(const BrickScan& b, NearestRowState& s)
{
  const float px = static_cast<float>(s.p[0].x), py = static_cast<float>(s.p[0].y), pz = static_cast<float>(s.p[0].z);
  const int groups = (b.count + 3) / 4;
  for (int g = 0; g < groups; ++g)
  {
    if (b.gaps[4 * g] > s.thr2[0]) break;
    // the plane and edge bounds of four candidates, as nearestRow computes them
    const float* q = b.planes + 64 * g;
    int pass = 0;
#ifdef LVDIF_BRICK_SSE
    const __m128 vx = _mm_set1_ps(px), vy = _mm_set1_ps(py), vz = _mm_set1_ps(pz), eps = _mm_set1_ps(b.eps),
                 zero = _mm_setzero_ps();
    auto val = [&](int j) {
      const float* c = q + 16 * j;
      return _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(c), vx),
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_loadu_ps(c + 4), vy), _mm_mul_ps(_mm_loadu_ps(c + 8), vz)), _mm_loadu_ps(c + 12)));
    };
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 pd = _mm_max_ps(_mm_sub_ps(_mm_and_ps(val(0), absMask), eps), zero);
    const __m128 ed = _mm_max_ps(_mm_sub_ps(_mm_max_ps(val(1), _mm_max_ps(val(2), val(3))), eps), zero);
    const __m128 lt = _mm_mul_ps(_mm_add_ps(_mm_mul_ps(pd, pd), _mm_mul_ps(ed, ed)), _mm_set1_ps(0.999999f));
    pass = _mm_movemask_ps(_mm_cmple_ps(lt, _mm_set1_ps(s.thrF[0])));
    alignas(16) float lts[4];
    _mm_store_ps(lts, lt);
#else
    float lts[4];
    for (int l = 0; l < 4; ++l)
    {
      auto val = [&](int j) { return q[16 * j + l] * px + ((q[16 * j + 4 + l] * py + q[16 * j + 8 + l] * pz) + q[16 * j + 12 + l]); };
      const float pd = std::max(std::fabs(val(0)) - b.eps, 0.0f);
      const float ed = std::max(std::max(val(1), std::max(val(2), val(3))) - b.eps, 0.0f);
      lts[l] = (pd * pd + ed * ed) * 0.999999f;
      pass |= lts[l] <= s.thrF[0] ? 1 << l : 0;
    }
#endif
    for (; pass; pass &= pass - 1)
    {
      const int l = __builtin_ctz(static_cast<unsigned>(pass));
      const int k = 4 * g + l;
      // the same test again against the threshold as the exact tests of this
      // group left it (see scanBrickAvx2)
      if (k < b.count && lts[l] <= s.thrF[0])
      {
        ++*b.exact;
        s.exact(0, b.tris[static_cast<std::size_t>(b.cand[k])]);
      }
    }
  }
}

#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("avx2"))) void scanBrickAvx2(const BrickScan& b, NearestRowState& s)
{
  const __m256 vx = _mm256_set1_ps(static_cast<float>(s.p[0].x)), vy = _mm256_set1_ps(static_cast<float>(s.p[0].y)),
               vz = _mm256_set1_ps(static_cast<float>(s.p[0].z)), eps = _mm256_set1_ps(b.eps),
               zero = _mm256_setzero_ps(), shrink = _mm256_set1_ps(0.999999f),
               absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const int groups = (b.count + 7) / 8;
  for (int g = 0; g < groups; ++g)
  {
    if (b.gaps[8 * g] > s.thr2[0]) break;
    // the same bounds for eight candidates (the same operations per lane)
    const float* q = b.planes + 128 * g;
    __m256 v[4];
    for (int j = 0; j < 4; ++j)
    {
      const float* c = q + 32 * j;
      v[j] = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(c), vx),
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(c + 8), vy), _mm256_mul_ps(_mm256_loadu_ps(c + 16), vz)),
          _mm256_loadu_ps(c + 24)));
    }
    const __m256 pd = _mm256_max_ps(_mm256_sub_ps(_mm256_and_ps(v[0], absMask), eps), zero);
    const __m256 ed = _mm256_max_ps(_mm256_sub_ps(_mm256_max_ps(v[1], _mm256_max_ps(v[2], v[3])), eps), zero);
    const __m256 lt = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(pd, pd), _mm256_mul_ps(ed, ed)), shrink);
    int pass = _mm256_movemask_ps(_mm256_cmp_ps(lt, _mm256_set1_ps(s.thrF[0]), _CMP_LE_OQ));
    alignas(32) float lts[8];
    _mm256_store_ps(lts, lt);
    for (; pass; pass &= pass - 1)
    {
      const int l = __builtin_ctz(static_cast<unsigned>(pass));
      const int k = 8 * g + l;
      // a lane that passed against the group's starting threshold is tested
      // again (the same <= on the same float) against the threshold as the
      // exact tests before it in this group left it: a bound above it cannot
      // beat or tie the best, which is what the next group's test would say
      // too, so the answer is the same; it spares the exact closest point of
      // the lanes after the one that tightened it
      if (k < b.count && lts[l] <= s.thrF[0])
      {
        ++*b.exact;
        s.exact(0, b.tris[static_cast<std::size_t>(b.cand[k])]);
      }
    }
  }
}
#endif
} // namespace

} // namespace detail::meshtosdf
} // namespace lvdif
