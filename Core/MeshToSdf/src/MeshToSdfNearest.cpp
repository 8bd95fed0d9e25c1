// The CPU nearest-triangle index of mesh to SDF (MeshToSdfNearest.h).
// Build: binned SAH binary tree (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007) with one triangle per leaf, collapsed
// into 4-wide nodes (the largest child opened first). Query: branch and bound
// with conservative lower bounds (float boxes rounded outward, then the
// triangle's plane), the exact closestPointOnTriangle only for survivors.
#include "MeshToSdfNearest.h"

#include "lvdif/Memory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define LVDIF_NEAREST_SSE 1
#endif

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
constexpr int Bins = 16;
constexpr int SahDepthLimit = 48; // deeper: median splits (bounds the depth)
constexpr std::int32_t Grain = 4096; // subtrees of at most this many triangles are built in parallel

struct Ref
{
  double lo[3], hi[3], c[3];
};

struct BNode
{
  double lo[3], hi[3];
  std::int32_t left = -1, right = -1; // -1: leaf of one triangle
  std::int32_t tri = -1;
  std::int32_t first = 0, count = 0; // range in Builder::Order
};

double area(const double lo[3], const double hi[3])
{
  const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  return x * y + y * z + z * x;
}

void grow(double lo[3], double hi[3], const double blo[3], const double bhi[3])
{
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::min(lo[a], blo[a]);
    hi[a] = std::max(hi[a], bhi[a]);
  }
}

class Builder
{
public:
  Builder(const std::vector<Ref>& refs)
    : Refs(refs)
  {
    this->Order.resize(refs.size());
    for (std::size_t i = 0; i < refs.size(); ++i) this->Order[i] = static_cast<std::int32_t>(i);
    this->Nodes.reserve(2 * refs.size());
  }

  /// The whole tree. The top levels are split serially down to ranges of at
  /// most Grain triangles, which are then built in parallel into their own
  /// node arrays and appended in order: the same tree and the same layout
  /// for any number of threads (splits depend only on the range and depth).
  void buildAll()
  {
    const auto n = static_cast<std::int32_t>(this->Refs.size());
    struct Job
    {
      std::int32_t slot, first, count, depth;
    };
    std::vector<Job> jobs;
    std::vector<std::int32_t> top; // inner nodes of the top levels, parents first
    auto topLevels = [&](auto& self, std::int32_t first, std::int32_t count, int depth) -> std::int32_t {
      const auto id = static_cast<std::int32_t>(this->Nodes.size());
      this->Nodes.emplace_back();
      this->Nodes[id].first = first;
      this->Nodes[id].count = count;
      if (count <= Grain)
      {
        jobs.push_back({ id, first, count, depth });
        return id;
      }
      top.push_back(id);
      const std::int32_t mid = this->split(first, count, depth);
      const std::int32_t l = self(self, first, mid - first, depth + 1);
      const std::int32_t r = self(self, mid, first + count - mid, depth + 1);
      this->Nodes[id].left = l;
      this->Nodes[id].right = r;
      return id;
    };
    topLevels(topLevels, 0, n, 0);
    std::vector<std::vector<BNode>> local(jobs.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t j = 0; j < static_cast<std::int64_t>(jobs.size()); ++j)
    {
      const Job& d = jobs[static_cast<std::size_t>(j)];
      local[static_cast<std::size_t>(j)].reserve(2 * static_cast<std::size_t>(d.count));
      this->build(local[static_cast<std::size_t>(j)], d.first, d.count, d.depth);
    }
    for (std::size_t j = 0; j < jobs.size(); ++j)
    {
      // local node i > 0 goes to base + i - 1, the local root to its slot
      const auto base = static_cast<std::int32_t>(this->Nodes.size());
      auto map = [base](std::int32_t c) { return c < 0 ? c : base + c - 1; };
      for (std::size_t i = 1; i < local[j].size(); ++i)
      {
        BNode x = local[j][i];
        x.left = map(x.left);
        x.right = map(x.right);
        this->Nodes.push_back(x);
      }
      BNode root = local[j][0];
      root.left = map(root.left);
      root.right = map(root.right);
      this->Nodes[static_cast<std::size_t>(jobs[j].slot)] = root;
      std::vector<BNode>().swap(local[j]);
    }
    for (auto it = top.rbegin(); it != top.rend(); ++it)
    {
      BNode& x = this->Nodes[static_cast<std::size_t>(*it)];
      const BNode &l = this->Nodes[static_cast<std::size_t>(x.left)], &r = this->Nodes[static_cast<std::size_t>(x.right)];
      for (int a = 0; a < 3; ++a)
      {
        x.lo[a] = std::min(l.lo[a], r.lo[a]);
        x.hi[a] = std::max(l.hi[a], r.hi[a]);
      }
    }
  }

  /// The subtree of Order[first, first + count) into `nodes` (its root first).
  /// Threads may build disjoint ranges at once (split touches only its range).
  std::int32_t build(std::vector<BNode>& nodes, std::int32_t first, std::int32_t count, int depth)
  {
    const std::int32_t id = static_cast<std::int32_t>(nodes.size());
    nodes.emplace_back();
    nodes[id].first = first;
    nodes[id].count = count;
    if (count == 1)
    {
      BNode& n = nodes[id];
      const Ref& r = this->Refs[this->Order[first]];
      n.tri = this->Order[first];
      std::copy(r.lo, r.lo + 3, n.lo);
      std::copy(r.hi, r.hi + 3, n.hi);
      return id;
    }
    const std::int32_t mid = this->split(first, count, depth);
    const std::int32_t l = this->build(nodes, first, mid - first, depth + 1);
    const std::int32_t r = this->build(nodes, mid, first + count - mid, depth + 1);
    BNode& n = nodes[id];
    n.left = l;
    n.right = r;
    for (int a = 0; a < 3; ++a)
    {
      n.lo[a] = std::min(nodes[l].lo[a], nodes[r].lo[a]);
      n.hi[a] = std::max(nodes[l].hi[a], nodes[r].hi[a]);
    }
    return id;
  }

  std::vector<std::int32_t> Order;
  std::vector<BNode> Nodes;

private:
  /// The first index of the right half: binned SAH on the longest centroid
  /// axis; the median when the centroids coincide, SAH finds no split or the
  /// tree is already deep.
  std::int32_t split(std::int32_t first, std::int32_t count, int depth)
  {
    double clo[3] = { 1e300, 1e300, 1e300 }, chi[3] = { -1e300, -1e300, -1e300 };
    for (std::int32_t i = first; i < first + count; ++i) grow(clo, chi, this->Refs[this->Order[i]].c, this->Refs[this->Order[i]].c);
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
    const double ext = chi[axis] - clo[axis];
    auto begin = this->Order.begin() + first, end = begin + count;
    if (ext > 0 && depth < SahDepthLimit)
    {
      const double k = Bins / ext;
      auto binOf = [&](std::int32_t t) { return std::min(Bins - 1, static_cast<int>((this->Refs[t].c[axis] - clo[axis]) * k)); };
      std::int32_t n[Bins] = {};
      double blo[Bins][3], bhi[Bins][3];
      for (int b = 0; b < Bins; ++b)
        for (int a = 0; a < 3; ++a) blo[b][a] = 1e300, bhi[b][a] = -1e300;
      for (auto it = begin; it != end; ++it)
      {
        const int b = binOf(*it);
        ++n[b];
        grow(blo[b], bhi[b], this->Refs[*it].lo, this->Refs[*it].hi);
      }
      double rightCost[Bins];
      double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
      std::int32_t m = 0;
      for (int b = Bins - 1; b > 0; --b)
      {
        grow(lo, hi, blo[b], bhi[b]);
        m += n[b];
        rightCost[b] = m ? area(lo, hi) * m : 0;
      }
      double best = std::numeric_limits<double>::infinity();
      int bestBin = -1;
      for (int a = 0; a < 3; ++a) lo[a] = 1e300, hi[a] = -1e300;
      m = 0;
      for (int b = 0; b < Bins - 1; ++b)
      {
        grow(lo, hi, blo[b], bhi[b]);
        m += n[b];
        if (m == 0 || m == count) continue;
        const double cost = area(lo, hi) * m + rightCost[b + 1];
        if (cost < best)
        {
          best = cost;
          bestBin = b;
        }
      }
      if (bestBin >= 0)
      {
        auto midIt = std::partition(begin, end, [&](std::int32_t t) { return binOf(t) <= bestBin; });
        return static_cast<std::int32_t>(midIt - this->Order.begin());
      }
    }
    const std::int32_t half = count / 2;
    std::nth_element(begin, begin + half, end, [&](std::int32_t x, std::int32_t y) {
      const double cx = this->Refs[x].c[axis], cy = this->Refs[y].c[axis];
      return cx < cy || (cx == cy && x < y);
    });
    return first + half;
  }

  const std::vector<Ref>& Refs;
};

} // namespace

namespace
{
float roundDown(double x) { return roundDownToFloat(x); }
float roundUp(double x) { return roundUpToFloat(x); }
} // namespace

NearestIndex::NearestIndex(const TriList& tris)
{
  const std::size_t n = tris.size();
  // peak: the index (~350 bytes a triangle: packed records, float planes,
  // nodes, positions) plus the build data (~220 bytes a triangle, ~400 while
  // the parallel subtrees are appended; 40 for the slabs)
  requireMemory(static_cast<std::uint64_t>(n) * NearestIndexBytesPerTriangle, "mesh to SDF: nearest-triangle index");
  std::vector<Ref> refs(n);
  double scale = 0;
#pragma omp parallel for schedule(static) reduction(max : scale)
  for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k)
  {
    const auto i = static_cast<std::size_t>(k);
    const Tri& t = tris[i];
    for (int a = 0; a < 3; ++a)
    {
      refs[i].lo[a] = std::min(t.v[0][a], std::min(t.v[1][a], t.v[2][a]));
      refs[i].hi[a] = std::max(t.v[0][a], std::max(t.v[1][a], t.v[2][a]));
      refs[i].c[a] = t.v[0][a] + t.v[1][a] + t.v[2][a];
      scale = std::max(scale, std::max(std::fabs(refs[i].lo[a]), std::fabs(refs[i].hi[a])));
    }
  }
  this->Scale = scale;
  if (n == 0) return;
  double t0 = now();
  Builder b(refs);
  b.buildAll();
  trace("nearest index: binary tree", now() - t0);
  checkBuildInterrupt();
  t0 = now();
  this->PosOf.assign(n, -1);
  this->Nodes.reserve(n / 2 + 1);

  // a leaf's record is written after the layout (below, on the threads):
  // the layout only assigns its position
  std::vector<std::int32_t> triAt; // position -> triangle
  triAt.reserve(n);
  auto addTri = [&](std::int32_t t) {
    triAt.push_back(t);
    return ~static_cast<std::int32_t>(triAt.size() - 1);
  };
  auto packTri = [&](std::int32_t t, Packed& p, PlanesF& f) {
    const Tri& src = tris[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) p.v[k] = src.v[k];
    // plane bound only where the normal's direction is accurate: the cross
    // product's rounding tilts it by about 2^-50 |e1||e2| / |e1 x e2|; slivers
    // whose tilt could exceed 1e-13 get a zero normal (no plane test)
    const V3 e1 = src.v[1] - src.v[0], e2 = src.v[2] - src.v[0];
    const V3 c = cross(e1, e2);
    const double len = norm(c);
    const double tilt = 8.0 * 1.1102230246251565e-16 * norm(e1) * norm(e2) / len;
    for (auto& pl : p.plane) pl[0] = pl[1] = pl[2] = pl[3] = 0;
    if (len > 0 && tilt < 1e-13)
    {
      const V3 n = (1.0 / len) * c;
      auto setPlane = [&](int k, V3 m, V3 on) {
        p.plane[k][0] = m.x;
        p.plane[k][1] = m.y;
        p.plane[k][2] = m.z;
        p.plane[k][3] = -dot(m, on);
      };
      setPlane(0, n, src.v[0]);
      for (int e = 0; e < 3; ++e)
      {
        const V3 a = src.v[e], b = src.v[(e + 1) % 3];
        setPlane(1 + e, normalized(cross(b - a, n)), a); // outward for a counter-clockwise (about n) triangle
      }
    }
    p.index = t;
    for (int k = 0; k < 4; ++k)
    {
      f.x[k] = static_cast<float>(p.plane[k][0]);
      f.y[k] = static_cast<float>(p.plane[k][1]);
      f.z[k] = static_cast<float>(p.plane[k][2]);
      f.w[k] = static_cast<float>(p.plane[k][3]);
    }
  };

  // a child's slab: its area-weighted mean normal rounded to float, and the
  // range of that float normal's dot with every vertex, rounded outward
  auto childSlab = [&](const BNode& c, float out[5]) {
    V3 sum;
    for (std::int32_t i = c.first; i < c.first + c.count; ++i)
    {
      const Tri& t = tris[static_cast<std::size_t>(b.Order[static_cast<std::size_t>(i)])];
      sum = sum + cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    }
    const V3 n = normalized(sum);
    const V3 nf{ static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z) };
    double lo = 1e300, hi = -1e300;
    for (std::int32_t i = c.first; i < c.first + c.count; ++i)
    {
      const Tri& t = tris[static_cast<std::size_t>(b.Order[static_cast<std::size_t>(i)])];
      for (int k = 0; k < 3; ++k)
      {
        lo = std::min(lo, dot(nf, t.v[k]));
        hi = std::max(hi, dot(nf, t.v[k]));
      }
    }
    // the double dots round too: widen by a relative 1e-15 of the magnitudes
    const double pad = 1e-15 * (std::fabs(lo) + std::fabs(hi) + this->Scale);
    out[0] = static_cast<float>(nf.x);
    out[1] = static_cast<float>(nf.y);
    out[2] = static_cast<float>(nf.z);
    out[3] = roundDown(lo - pad);
    out[4] = roundUp(hi + pad);
  };

  // every node's slab up front, in parallel (each reads its own triangles)
  std::vector<std::array<float, 5>> slabOf(b.Nodes.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(b.Nodes.size()); ++i)
    childSlab(b.Nodes[static_cast<std::size_t>(i)], slabOf[static_cast<std::size_t>(i)].data());
  trace("nearest index: slabs", now() - t0);
  checkBuildInterrupt();
  t0 = now();

  // collapse: open the child of largest surface area until four, then emit
  // in preorder (children's triangles and nodes laid out as they are visited)
  std::size_t maxDepth = 0;
  auto emit = [&](auto&& self, std::int32_t bn, std::size_t depth) -> std::int32_t {
    maxDepth = std::max(maxDepth, depth);
    const std::int32_t id = static_cast<std::int32_t>(this->Nodes.size());
    this->Nodes.emplace_back();
    std::int32_t kids[4];
    int k = 0;
    if (b.Nodes[bn].left < 0)
    {
      kids[k++] = bn; // a one-triangle mesh
    }
    else
    {
      kids[k++] = b.Nodes[bn].left;
      kids[k++] = b.Nodes[bn].right;
      while (k < 4)
      {
        int open = -1;
        double bestArea = -1;
        for (int i = 0; i < k; ++i)
        {
          const BNode& c = b.Nodes[kids[i]];
          if (c.left >= 0 && area(c.lo, c.hi) > bestArea)
          {
            bestArea = area(c.lo, c.hi);
            open = i;
          }
        }
        if (open < 0) break;
        const BNode& c = b.Nodes[kids[open]];
        kids[open] = c.left;
        kids[k++] = c.right;
      }
    }
    std::int32_t child[4];
    for (int i = 0; i < k; ++i)
    {
      const BNode& c = b.Nodes[kids[i]];
      child[i] = c.left < 0 ? addTri(c.tri) : self(self, kids[i], depth + 1);
    }
    float slab[4][5];
    for (int i = 0; i < k; ++i) std::copy_n(slabOf[static_cast<std::size_t>(kids[i])].data(), 5, slab[i]);
    Node& node = this->Nodes[id];
    node.count = k;
    for (int i = 0; i < 4; ++i)
    {
      const bool used = i < k;
      node.child[i] = used ? child[i] : 0;
      for (int a = 0; a < 3; ++a)
      {
        node.lo[a][i] = used ? roundDown(b.Nodes[kids[i]].lo[a]) : std::numeric_limits<float>::infinity();
        node.hi[a][i] = used ? roundUp(b.Nodes[kids[i]].hi[a]) : -std::numeric_limits<float>::infinity();
        node.sn[a][i] = used ? slab[i][a] : 0.0f;
      }
      node.smin[i] = used ? slab[i][3] : 0.0f;
      node.smax[i] = used ? slab[i][4] : 0.0f;
    }
    return id;
  };
  emit(emit, 0, 1);
  trace("nearest index: 4-wide layout", now() - t0);
  checkBuildInterrupt();
  t0 = now();
  const auto placed = static_cast<std::int64_t>(triAt.size());
  resizeLargeForOverwrite(this->Tris, triAt.size());
  resizeLargeForOverwrite(this->TriPlanes, triAt.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t pos = 0; pos < placed; ++pos)
  {
    const std::int32_t t = triAt[static_cast<std::size_t>(pos)];
    packTri(t, this->Tris[static_cast<std::size_t>(pos)], this->TriPlanes[static_cast<std::size_t>(pos)]);
    this->PosOf[static_cast<std::size_t>(t)] = static_cast<std::int32_t>(pos);
  }
  trace("nearest index: leaf records", now() - t0);
  this->Depth = maxDepth;
  require(this->Depth <= 80, "mesh to SDF: nearest-triangle tree too deep");
}

NearestResult NearestIndex::nearest(V3 p, std::int32_t hint, double maxDist2, std::uint64_t* exactCount) const
{
  NearestResult best;
  best.dist2 = maxDist2;
  if (this->Nodes.empty()) return best;
  // Tau: slack on every bound, far above the rounding of the closest point
  // (a few ulps of the largest coordinate), far below a voxel
  const double big = std::max(this->Scale, std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z))));
  const double tau = 1e-10 * big;
  double thr2 = 0;
  float thrF = 0;
  auto setThreshold = [&]() {
    const double s = std::sqrt(best.dist2) + tau;
    thr2 = s * s;
    thrF = roundUp(thr2);
  };
  auto consider = [&](const Packed& t) {
    if (t.index == best.tri) return;
    auto eval = [&](int k) { return t.plane[k][0] * p.x + t.plane[k][1] * p.y + t.plane[k][2] * p.z + t.plane[k][3]; };
    const double pd = eval(0);
    const double ed = std::max(0.0, std::max(eval(1), std::max(eval(2), eval(3))));
    if (pd * pd + ed * ed > thr2) return;
    if (exactCount) ++*exactCount;
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    // ties to the lowest index, like the brute force and the GPU
    if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || t.index < best.tri)))
    {
      best.dist2 = d2;
      best.tri = t.index;
      best.closest = c;
      setThreshold();
    }
  };
  if (hint >= 0)
  {
    if (exactCount) ++*exactCount;
    const Packed& t = this->Tris[static_cast<std::size_t>(this->PosOf[static_cast<std::size_t>(hint)])];
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 <= best.dist2)
    {
      best.dist2 = d2;
      best.tri = hint;
      best.closest = c;
    }
  }
  setThreshold();
  // float query point; epsF covers its rounding and that of the subtraction
  const float px = static_cast<float>(p.x), py = static_cast<float>(p.y), pz = static_cast<float>(p.z);
  const float epsF = static_cast<float>(big * 1.2e-7 * 4.0);
  struct Item
  {
    std::int32_t node;
    float lb;
  };
  Item stack[256];
  int top = 0;
  stack[top++] = { 0, 0.0f };
#ifdef LVDIF_NEAREST_SSE
  const __m128 vx = _mm_set1_ps(px), vy = _mm_set1_ps(py), vz = _mm_set1_ps(pz);
  const __m128 vsepsv = _mm_set1_ps(2.5f * epsF);
  const __m128 veps = _mm_set1_ps(epsF), zero = _mm_setzero_ps(), shrink = _mm_set1_ps(0.999999f);
#endif
  while (top > 0)
  {
    const Item it = stack[--top];
    if (it.lb > thrF) continue;
    const Node& n = this->Nodes[static_cast<std::size_t>(it.node)];
    alignas(16) float lb[4];
#ifdef LVDIF_NEAREST_SSE
    {
      auto gap = [&](int a, __m128 v) {
        const __m128 g = _mm_max_ps(_mm_sub_ps(_mm_load_ps(n.lo[a]), v), _mm_sub_ps(v, _mm_load_ps(n.hi[a])));
        const __m128 c = _mm_max_ps(_mm_sub_ps(g, veps), zero);
        return _mm_mul_ps(c, c);
      };
      const __m128 box = _mm_add_ps(_mm_add_ps(gap(0, vx), gap(1, vy)), gap(2, vz));
      const __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(n.sn[0]), vx), _mm_mul_ps(_mm_load_ps(n.sn[1]), vy)),
        _mm_mul_ps(_mm_load_ps(n.sn[2]), vz));
      const __m128 sg = _mm_max_ps(_mm_sub_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(n.smin), d), _mm_sub_ps(d, _mm_load_ps(n.smax))), vsepsv), zero);
      _mm_store_ps(lb, _mm_mul_ps(_mm_max_ps(box, _mm_mul_ps(sg, sg)), shrink));
    }
#else
    {
      const float q[3] = { px, py, pz };
      for (int i = 0; i < 4; ++i)
      {
        float s = 0;
        for (int a = 0; a < 3; ++a)
        {
          const float g = std::max(std::max(n.lo[a][i] - q[a], q[a] - n.hi[a][i]) - epsF, 0.0f);
          s += g * g;
        }
        const float d = n.sn[0][i] * px + n.sn[1][i] * py + n.sn[2][i] * pz;
        const float g = std::max(std::max(n.smin[i] - d, d - n.smax[i]) - 2.5f * epsF, 0.0f);
        lb[i] = std::max(s, g * g) * 0.999999f;
      }
    }
#endif
    // triangles now; nodes pushed farthest first so the nearest pops next
    Item kids[4];
    int nk = 0;
    for (int i = 0; i < n.count; ++i)
    {
      if (!(lb[i] <= thrF)) continue;
      const std::int32_t c = n.child[i];
      if (c < 0)
      {
        consider(this->Tris[static_cast<std::size_t>(~c)]);
        continue;
      }
      int j = nk++;
      while (j > 0 && kids[j - 1].lb < lb[i])
      {
        kids[j] = kids[j - 1];
        --j;
      }
      kids[j] = { c, lb[i] };
    }
    for (int i = 0; i < nk; ++i)
      if (kids[i].lb <= thrF) stack[top++] = kids[i];
  }
  return best;
}

} // namespace detail::meshtosdf
} // namespace lvdif
