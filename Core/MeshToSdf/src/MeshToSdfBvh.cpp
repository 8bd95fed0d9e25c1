// BVH for mesh to SDF: exact nearest-triangle queries (branch and bound on
// box distances) and ray crossings for the winding-number signs.
#include "MeshToSdfInternal.h"

#include "lvdif/Memory.h"
#include "lvdif/Error.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
constexpr int LeafSize = 4;
/// The split's total order: centroid coordinate on the axis, then triangle
/// index (the left child gets the count / 2 smallest: a function of the
/// triangles, not of the order std::nth_element leaves equal keys in).
template <typename R>
bool refLess(const R& x, const R& y, int axis)
{
  return x.c[axis] < y.c[axis] || (x.c[axis] == y.c[axis] && x.tri < y.tri);
}

int longestAxis(const double clo[3], const double chi[3])
{
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
  }
  return axis;
}

/// Parts of [0, n) for the parallel passes: part p is [n p / P, n (p+1) / P).
/// P is fixed before the region (a loop over parts, not over the team), so
/// per-part counts stay valid whatever team runs them.
struct Parts
{
  explicit Parts(std::size_t n_)
    : n(n_)
    , count(omp_get_max_threads())
  {
  }
  std::size_t lo(int p) const { return n * static_cast<std::size_t>(p) / static_cast<std::size_t>(count); }
  std::size_t hi(int p) const { return lo(p + 1); }
  std::size_t n;
  int count;
};

/// Bounds of the centroids, [0] the left side, [1] the right.
struct SideBounds
{
  double lo[2][3], hi[2][3];
  SideBounds()
  {
    for (int s = 0; s < 2; ++s)
      for (int a = 0; a < 3; ++a) lo[s][a] = std::numeric_limits<double>::infinity(), hi[s][a] = -lo[s][a];
  }
  template <typename R>
  void add(int s, const R& x)
  {
    for (int a = 0; a < 3; ++a) lo[s][a] = std::min<double>(lo[s][a], x.c[a]), hi[s][a] = std::max<double>(hi[s][a], x.c[a]);
  }
  void add(const SideBounds& o)
  {
    for (int s = 0; s < 2; ++s)
      for (int a = 0; a < 3; ++a) lo[s][a] = std::min(lo[s][a], o.lo[s][a]), hi[s][a] = std::max(hi[s][a], o.hi[s][a]);
  }
};

/// Moves src[0, n) to dst[0, n) so that dst[0, k) holds the k smallest in
/// refLess order and dst[k, n) the others, each side in no particular order
/// (the tree depends on the sets alone: every split selects by the total
/// order, every leaf sorts its triangles), on the threads; adds the
/// centroid bounds of both sides to `bounds`. A bucket partition
/// (selection by distribution counting, e.g. Alabi et al., "Fast
/// k-Selection Algorithms for Graphics Processing Units", JEA 2012): per-part
/// histograms of the key over Bins equal bins of [lo, hi]; one scatter puts
/// the bins below the bin that holds rank k to the left, those above to the
/// right and that bin between them, which is then split by std::nth_element,
/// or, when it is large, by this function again (src as its buffer). The
/// bin of a key is monotone in it (a subtraction, a product and a
/// truncation, each monotone in IEEE arithmetic), so the bins follow the
/// order. The key is the coordinate, or the triangle index once every
/// coordinate is equal (byTri). lo, hi: the keys' bounds over src; small:
/// what this thread splits alone.
template <typename R>
void splitAtRank(R* src, R* dst, std::size_t n, std::size_t k, int axis, bool byTri, double lo, double hi,
  std::size_t small, SideBounds& bounds)
{
  constexpr int Bins = 4096;
  const auto key = [axis, byTri](const R& r) { return byTri ? static_cast<double>(r.tri) : r.c[axis]; };
  const std::int64_t nI = static_cast<std::int64_t>(n);
  if (!(lo < hi) && !byTri && n > small)
  {
    // every coordinate equal: by index
    double l = std::numeric_limits<double>::infinity(), h = -l;
#pragma omp parallel for schedule(static) reduction(min : l) reduction(max : h)
    for (std::int64_t i = 0; i < nI; ++i) l = std::min(l, static_cast<double>(src[i].tri)), h = std::max(h, static_cast<double>(src[i].tri));
    splitAtRank(src, dst, n, k, axis, true, l, h, small, bounds);
    return;
  }
  const double scale = Bins / (hi - lo);
  if (n <= small || !(lo < hi) || !(scale <= std::numeric_limits<double>::max()))
  {
    // small (or too narrow to bin): on this thread
    std::copy(src, src + n, dst);
    std::nth_element(dst, dst + k, dst + n, [axis](const R& x, const R& y) { return refLess(x, y, axis); });
    for (std::size_t i = 0; i < n; ++i) bounds.add(i < k ? 0 : 1, dst[i]);
    return;
  }
  const auto binOf = [&](const R& r) { return std::min(Bins - 1, static_cast<int>((key(r) - lo) * scale)); };
  const Parts parts(n);
  const std::size_t P = static_cast<std::size_t>(parts.count);
  std::vector<std::uint32_t> hist(P * Bins, 0);
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts.count; ++p)
  {
    std::uint32_t* h = hist.data() + static_cast<std::size_t>(p) * Bins;
    for (std::size_t i = parts.lo(p); i < parts.hi(p); ++i) ++h[binOf(src[i])];
  }
  // the bin b holding rank k; per part, where its elements below b, in b
  // and above b go (bin-major, part-minor)
  std::vector<std::size_t> inBins(Bins, 0);
  for (std::size_t p = 0; p < P; ++p)
    for (int i = 0; i < Bins; ++i) inBins[i] += hist[p * Bins + i];
  std::size_t below = 0;
  int b = 0;
  while (k >= below + inBins[b]) below += inBins[b++];
  const std::size_t inBin = inBins[b];
  std::vector<std::array<std::size_t, 3>> at(P);
  std::array<std::size_t, 3> next = { 0, below, below + inBin };
  for (std::size_t p = 0; p < P; ++p)
  {
    at[p] = next;
    const std::uint32_t* h = hist.data() + p * Bins;
    for (int i = 0; i < Bins; ++i) next[i < b ? 0 : (i == b ? 1 : 2)] += h[i];
  }
  std::vector<SideBounds> partBounds(P);
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts.count; ++p)
  {
    std::array<std::size_t, 3> o = at[static_cast<std::size_t>(p)];
    SideBounds& pb = partBounds[static_cast<std::size_t>(p)];
    for (std::size_t i = parts.lo(p); i < parts.hi(p); ++i)
    {
      const int bin = binOf(src[i]);
      const int where = bin < b ? 0 : (bin == b ? 1 : 2);
      dst[o[where]++] = src[i];
      if (where != 1) pb.add(where / 2, src[i]);
    }
  }
  for (const SideBounds& pb : partBounds) bounds.add(pb);
  // the bin of rank k, dst[below, below + inBin): rank k - below in it
  R* mid = dst + below;
  if (inBin > small)
  {
    double l = std::numeric_limits<double>::infinity(), h = -l;
    const std::int64_t mI = static_cast<std::int64_t>(inBin);
#pragma omp parallel for schedule(static) reduction(min : l) reduction(max : h)
    for (std::int64_t i = 0; i < mI; ++i) l = std::min(l, key(mid[i])), h = std::max(h, key(mid[i]));
    splitAtRank(mid, src + below, inBin, k - below, axis, byTri, l, h, small, bounds);
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < mI; ++i) mid[i] = src[below + static_cast<std::size_t>(i)];
  }
  else
  {
    std::nth_element(mid, dst + k, mid + inBin, [axis](const R& x, const R& y) { return refLess(x, y, axis); });
    for (std::size_t i = below; i < below + inBin; ++i) bounds.add(i < k ? 0 : 1, dst[i]);
  }
}
} // namespace

/// Nodes of a subtree over `count` triangles (median splits, leaves of at
/// most LeafSize): lets parallel tasks place their nodes deterministically.
/// The counts of one depth differ by at most one, so the recursion meets
/// O(log n) distinct counts: they are computed once (memo) and looked up
/// read-only by the build's tasks (recomputing them per node visited every
/// node of the left subtree again: O(n log n)). (Depth never reaches 60: 31
/// halvings bring any int32 count to LeafSize.)
class BvhSubtreeNodes
{
public:
  explicit BvhSubtreeNodes(std::int32_t n) { this->of(n); }
  std::int32_t operator()(std::int32_t count) const
  {
    for (const auto& e : this->Memo)
      if (e.first == count) return e.second;
    return 1; // count <= LeafSize (never stored)
  }

private:
  std::int32_t of(std::int32_t count)
  {
    if (count <= LeafSize) return 1;
    for (const auto& e : this->Memo)
      if (e.first == count) return e.second;
    const std::int32_t half = count / 2;
    const std::int32_t nodes = 1 + this->of(half) + this->of(count - half);
    this->Memo.push_back({ count, nodes });
    return nodes;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> Memo;
};

/// Centroids computed once in parallel; the build then touches only this
/// compact array (the triangle records are 112 bytes each). The top nodes
/// (parallelSplitMin triangles or more: 2^19 by default) split one after the
/// other, each with all threads (splitAtRank: centroid bounds from the
/// parent's split, into the other buffer, ref <-> spare); no step runs on
/// one thread over more than a small part of the triangles (the root's
/// nth_element over all of them did: the serial head of the build).
/// The subtrees below are OpenMP tasks that split with std::nth_element by
/// the same total order; their leaves write their entries of Order and
/// their boxes, their inner nodes the union of their children's boxes once those
/// are done; the top nodes' boxes come last. The node layout (preorder) does
/// not depend on the threads.
Bvh::Bvh(const TriList& tris, std::int32_t parallelSplitMin)
  : Tris(tris)
{
  const std::int32_t n = static_cast<std::int32_t>(tris.size());
  double tp = now(); // sub-phase times on the trace (tracePhases)
  const auto lap = [&tp](const char* what) {
    const double t = now();
    trace(what, t - tp);
    tp = t;
    checkBuildInterrupt();
  };
  // every element of these arrays is written by the build, on the threads:
  // their pages are first touched there (Memory.h)
  resizeLargeForOverwrite(this->Order, tris.size());
  BuildData d;
  d.parallelSplitMin = std::max(parallelSplitMin, 2 * LeafSize + 2);
  resizeLargeForOverwrite(d.ref, tris.size());
  if (n >= d.parallelSplitMin) resizeLargeForOverwrite(d.spare, tris.size());
  double lx = std::numeric_limits<double>::infinity(), ly = lx, lz = lx, hx = -lx, hy = -lx, hz = -lx;
  // The key: the vertices' sum less 3x an origin inside the mesh (the first
  // vertex), rounded to float. Both steps are monotone, so the key orders
  // the centroids (ties by index); relative to the mesh, not to the
  // coordinates' magnitude, its 24 bits resolve 1e-7 of the mesh's extent.
  const V3 origin = n > 0 ? 3.0 * tris[0].v[0] : V3{};
#pragma omp parallel for schedule(static) reduction(min : lx, ly, lz) reduction(max : hx, hy, hz)
  for (std::int32_t i = 0; i < n; ++i)
  {
    const Tri& t = tris[i];
    auto& r = d.ref[i];
    for (int a = 0; a < 3; ++a) r.c[a] = static_cast<float>((t.v[0][a] + t.v[1][a] + t.v[2][a]) - origin[a]);
    r.tri = i;
    lx = std::min<double>(lx, r.c[0]), ly = std::min<double>(ly, r.c[1]), lz = std::min<double>(lz, r.c[2]);
    hx = std::max<double>(hx, r.c[0]), hy = std::max<double>(hy, r.c[1]), hz = std::max<double>(hz, r.c[2]);
  }
  const BvhSubtreeNodes nodesOf(n);
  d.subtreeNodes = &nodesOf;
  resizeLargeForOverwrite(this->Nodes, static_cast<std::size_t>(nodesOf(n)));
  const double clo[3] = { lx, ly, lz }, chi[3] = { hx, hy, hz };
  lap("mesh BVH: centroids");
  this->splitTop(d, 0, 0, n, 0, false, clo, chi);
  lap("mesh BVH: top splits");
  const std::int64_t subtrees = static_cast<std::int64_t>(d.subtrees.size());
#pragma omp parallel
#pragma omp single
  for (std::int64_t s = 0; s < subtrees; ++s)
  {
    const BuildData::Subtree st = d.subtrees[static_cast<std::size_t>(s)];
#pragma omp task shared(d) firstprivate(st)
    {
      if (st.inSpare)
        std::copy(d.spare.begin() + st.first, d.spare.begin() + st.first + st.count, d.ref.begin() + st.first);
      this->build(d, st.id, st.first, st.count, st.depth);
    }
  }
  lap("mesh BVH: subtrees, leaves and their boxes");
  // the top nodes' boxes from their children, last first (preorder:
  // children come after their parent)
  for (auto id = d.topNodes.rbegin(); id != d.topNodes.rend(); ++id) this->innerBox(*id);
}

void Bvh::splitTop(BuildData& d, std::int32_t id, std::int32_t first, std::int32_t count, int depth, bool inSpare,
  const double clo[3], const double chi[3])
{
  if (count < d.parallelSplitMin)
  {
    d.subtrees.push_back({ id, first, count, depth, inSpare });
    return;
  }
  d.topNodes.push_back(id);
  Node& node = this->Nodes[id];
  node.first = first;
  node.count = count;
  const int axis = longestAxis(clo, chi);
  const std::int32_t half = count / 2;
  BuildData::Ref* src = (inSpare ? d.spare : d.ref).data() + first;
  BuildData::Ref* dst = (inSpare ? d.ref : d.spare).data() + first;
  SideBounds sides;
  splitAtRank(src, dst, static_cast<std::size_t>(count), static_cast<std::size_t>(half), axis, false, clo[axis], chi[axis],
    std::min<std::size_t>(std::size_t(1) << 12, static_cast<std::size_t>(d.parallelSplitMin) / 8), sides);
  node.left = id + 1;
  node.right = id + 1 + (*d.subtreeNodes)(half);
  this->splitTop(d, node.left, first, half, depth + 1, !inSpare, sides.lo[0], sides.hi[0]);
  this->splitTop(d, node.right, first + half, count - half, depth + 1, !inSpare, sides.lo[1], sides.hi[1]);
}

void Bvh::build(BuildData& d, std::int32_t id, std::int32_t first, std::int32_t count, int depth)
{
  Node& node = this->Nodes[id];
  node.first = first;
  node.count = count;
  if (count > LeafSize && depth < 60)
  {
    double clo[3] = { 1e300, 1e300, 1e300 }, chi[3] = { -1e300, -1e300, -1e300 };
    for (std::int32_t i = first; i < first + count; ++i)
    {
      const float* c = d.ref[i].c;
      for (int a = 0; a < 3; ++a)
      {
        clo[a] = std::min<double>(clo[a], c[a]);
        chi[a] = std::max<double>(chi[a], c[a]);
      }
    }
    const int axis = longestAxis(clo, chi);
    const std::int32_t half = count / 2;
    std::nth_element(d.ref.begin() + first, d.ref.begin() + first + half, d.ref.begin() + first + count,
      [axis](const BuildData::Ref& x, const BuildData::Ref& y) { return refLess(x, y, axis); });
    node.left = id + 1;
    node.right = id + 1 + (*d.subtreeNodes)(half);
    if (count > 2048)
    {
      // shared(d): by default a task takes a firstprivate COPY of the object
      // a reference refers to (the centroids, per task)
#pragma omp task shared(d)
      this->build(d, node.left, first, half, depth + 1);
#pragma omp task shared(d)
      this->build(d, node.right, first + half, count - half, depth + 1);
#pragma omp taskwait
    }
    else
    {
      this->build(d, node.left, first, half, depth + 1);
      this->build(d, node.right, first + half, count - half, depth + 1);
    }
    this->innerBox(id);
    return;
  }
  node.left = node.right = -1;
  // a leaf's triangles by index: Order is a function of the triangles too
  std::sort(d.ref.begin() + first, d.ref.begin() + first + count,
    [](const BuildData::Ref& x, const BuildData::Ref& y) { return x.tri < y.tri; });
  // its entries of Order and its box (exact min/max: the bits of boxes taken
  // during the build; the triangle's box first, the order of a build that
  // kept per-triangle boxes: min/max of +0 and -0 depend on it)
  for (int a = 0; a < 3; ++a)
  {
    node.lo[a] = 1e300;
    node.hi[a] = -1e300;
  }
  for (std::int32_t i = first; i < first + count; ++i)
  {
    this->Order[i] = d.ref[i].tri;
    const Tri& t = this->Tris[this->Order[i]];
    for (int a = 0; a < 3; ++a)
    {
      node.lo[a] = std::min(node.lo[a], std::min(t.v[0][a], std::min(t.v[1][a], t.v[2][a])));
      node.hi[a] = std::max(node.hi[a], std::max(t.v[0][a], std::max(t.v[1][a], t.v[2][a])));
    }
  }
}

void Bvh::innerBox(std::int32_t id)
{
  Node& node = this->Nodes[id];
  const Node &l = this->Nodes[node.left], &r = this->Nodes[node.right];
  for (int a = 0; a < 3; ++a)
  {
    node.lo[a] = std::min(l.lo[a], r.lo[a]);
    node.hi[a] = std::max(l.hi[a], r.hi[a]);
  }
}

LargeVector<LeafTri> leafCopies(const Bvh& b)
{
  LargeVector<LeafTri> out;
  resizeLargeForOverwrite(out, b.order().size());
  const std::int64_t n = static_cast<std::int64_t>(out.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
  {
    const Tri& t = b.tris()[static_cast<std::size_t>(b.order()[static_cast<std::size_t>(i)])];
    LeafTri& l = out[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) l.v[k] = t.v[k];
    l.n = t.n;
  }
  return out;
}

NearestResult Bvh::nearest(V3 p, std::int32_t hint, double maxDist2, const std::int32_t* skip, int skipCount) const
{
  NearestResult best;
  best.dist2 = maxDist2;
  auto skipped = [&](std::int32_t t) { return std::find(skip, skip + skipCount, t) != skip + skipCount; };
  if (hint >= 0 && skipped(hint)) hint = -1;
  if (hint >= 0)
  {
    const Tri& t = this->Tris[hint];
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
  struct Item
  {
    std::int32_t node;
    double d2;
  };
  Item stack[128];
  int top = 0;
  stack[top++] = { 0, pointBoxDist2(p, this->Nodes[0].lo, this->Nodes[0].hi) };
  while (top > 0)
  {
    const Item it = stack[--top];
    if (it.d2 > best.dist2)
    {
      continue;
    }
    const Node& n = this->Nodes[it.node];
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
      {
        const std::int32_t ti = this->Order[i];
        if (ti == best.tri || (skipCount > 0 && skipped(ti))) continue;
        const Tri& t = this->Tris[ti];
        const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
        const V3 d = c.point - p;
        const double d2 = dot(d, d);
        // ties go to the lowest index, so every accelerator (and the GPU) picks
        // the same triangle, whose normal Normal mode uses
        if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || ti < best.tri)))
        {
          best.dist2 = d2;
          best.tri = ti;
          best.closest = c;
        }
      }
      continue;
    }
    const Node &l = this->Nodes[n.left], &r = this->Nodes[n.right];
    const double dl = pointBoxDist2(p, l.lo, l.hi), dr = pointBoxDist2(p, r.lo, r.hi);
    // push the farther child first so the nearer one is searched first
    if (dl <= dr)
    {
      if (dr <= best.dist2) stack[top++] = { n.right, dr };
      if (dl <= best.dist2) stack[top++] = { n.left, dl };
    }
    else
    {
      if (dl <= best.dist2) stack[top++] = { n.left, dl };
      if (dr <= best.dist2) stack[top++] = { n.right, dr };
    }
  }
  return best;
}

double Bvh::maxAlongAbove(V3 o, V3 dir, double limit) const
{
  const double d[3] = { dir.x, dir.y, dir.z }, at[3] = { o.x, o.y, o.z };
  auto boxBound = [&](const Node& n) {
    double s = 0;
    for (int a = 0; a < 3; ++a) s += std::max(d[a] * (n.lo[a] - at[a]), d[a] * (n.hi[a] - at[a]));
    return s;
  };
  std::int32_t stack[128];
  int top = 0;
  if (!this->Nodes.empty()) stack[top++] = 0;
  while (top > 0)
  {
    const Node& n = this->Nodes[stack[--top]];
    if (boxBound(n) <= limit) continue;
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
        for (const V3& x : this->Tris[this->Order[i]].v)
        {
          const double s = ((d[0] * (x.x - at[0]) + 0.0) + d[1] * (x.y - at[1])) + d[2] * (x.z - at[2]);
          if (s > limit) return s;
        }
      continue;
    }
    stack[top++] = n.left;
    stack[top++] = n.right;
  }
  return limit;
}

double Bvh::windingExact(V3 p) const
{
  double omega = 0;
  for (const Tri& t : this->Tris)
  {
    omega += solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }
  return omega / FourPi;
}

bool Bvh::rayHits(V3 o, V3 dir, double tmin, std::vector<RayHit>& hits) const
{
  // slab test per node; Moeller-Trumbore per triangle, with a relative
  // tolerance that reports near-edge / near-vertex crossings as ambiguous
  constexpr double Eps = 1e-9;
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  std::int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const Node& n = this->Nodes[stack[--top]];
    double t0 = tmin, t1 = 1e300;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a)
    {
      const double da = dir[a];
      if (da == 0)
      {
        miss = o[a] < n.lo[a] || o[a] > n.hi[a];
        continue;
      }
      double ta = (n.lo[a] - o[a]) * inv[a], tb = (n.hi[a] - o[a]) * inv[a];
      if (ta > tb) std::swap(ta, tb);
      const double pad = 1e-9 * (std::fabs(ta) + std::fabs(tb)) + 1e-300;
      t0 = std::max(t0, ta - pad);
      t1 = std::min(t1, tb + pad);
      miss = t0 > t1;
    }
    if (miss) continue;
    if (n.left >= 0)
    {
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (std::int32_t i = n.first; i < n.first + n.count; ++i)
    {
      const std::int32_t ti = this->Order[i];
      const Tri& t = this->Tris[ti];
      const V3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
      const V3 pv = cross(dir, e2);
      const double det = dot(e1, pv);
      const double scale = norm(e1) * norm(e2) * norm(dir);
      const V3 tv = o - t.v[0];
      if (std::fabs(det) <= Eps * scale)
      {
        // parallel: ambiguous only if the ray lies in the triangle's plane
        if (std::fabs(dot(tv, t.n)) <= Eps * (norm(tv) + norm(e1))) return false;
        continue;
      }
      const double invDet = 1.0 / det;
      const double u = dot(tv, pv) * invDet;
      const V3 qv = cross(tv, e1);
      const double v = dot(dir, qv) * invDet;
      const double tt = dot(e2, qv) * invDet;
      const double w = 1 - u - v;
      if (u < -Eps || v < -Eps || w < -Eps) continue; // clear miss
      const double tScale = 1e-9 * (std::fabs(tt) + std::fabs(tmin) + norm(e1) / norm(dir));
      if (tt < tmin - tScale) continue;
      if (u <= Eps || v <= Eps || w <= Eps || std::fabs(tt - tmin) <= tScale) return false;
      hits.push_back({ tt, ti, static_cast<std::int8_t>(dot(dir, t.n) > 0 ? 1 : -1) });
    }
  }
  return true;
}

} // namespace detail::meshtosdf
} // namespace lvdif
