// Local expansions of the correction s over a block: see MeshToSdfDipoleLocal.h.
#include "MeshToSdfDipoleLocal.h"
#include "MeshToSdfTriangleLocal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
/// A triangle's exact Taylor polynomial (triangleTaylor) costs about this
/// many solid angles (its value, three edges' fields, the closest point), so
/// it is taken only where more voxels than that are open.
constexpr int TriangleTaylorWork = 4;
/// The running error is a sum of bounds added and subtracted as terms come
/// and go: one term far above the rest (a cluster whose ball nearly touches
/// the block's: A / d^2 with d tiny, finite) absorbs the others in floating
/// point, and when it is subtracted their errors are lost (the sum may even
/// turn negative). Such a sum's rounding is at most (operations, < 3 terms)
/// x eps x its largest value since it was last summed afresh. localInterval's
/// slack, 1e-12 x terms x (err + the terms' size bound mag), covers that
/// while the peak is at most 1024 x (err + mag): 3 x 1.2e-16 x 1024 < 1e-12.
/// Beyond (a term whose error bound far exceeds its size bound, which only
/// such a nearly touching cluster has) the sum is taken afresh from the
/// live terms: rarely, as mag keeps every term's size, closed ones too.
constexpr double ErrPeakRatio = 1024;
} // namespace

void LocalBoundsCounts::add(const LocalBoundsCounts& o)
{
  this->triangleTaylors += o.triangleTaylors;
  this->exactSolidAngles += o.exactSolidAngles;
}

int localBounds(const DipoleTree& tree, V3 centre, double rho, const V3* pts, int n, double* lo, double* hi,
  std::int64_t budget, const std::vector<std::int32_t>* start, double remainderScale, LocalBoundsCounts* counts)
{
  for (int i = 0; i < n; ++i)
  {
    lo[i] = -std::numeric_limits<double>::infinity();
    hi[i] = std::numeric_limits<double>::infinity();
  }
  if (tree.empty())
  {
    std::fill(lo, lo + n, 0.0);
    std::fill(hi, hi + n, 0.0);
    return n;
  }
  const auto& nodes = tree.nodes();
  const auto& tris = tree.tris();
  // what an entry of the heap is: a cluster's expansion (a node, or a
  // triangle about its centroid); a triangle whose own Taylor polynomial
  // was tried and is no tighter (summed exactly when it is opened); a
  // triangle's exact Taylor polynomial (summed exactly when it is opened)
  enum Kind : int
  {
    Cluster,
    NoTaylor,
    Taylor
  };
  struct Open
  {
    double err;
    std::int32_t node;
    int order; // Taylor: 3
    LocalPoly poly; // the cluster's expansion, subtracted again when it is opened
    int kind = Cluster;
  };
  // the heap holds (error, slot in the pool): the sift moves 16 bytes, not
  // the 104 of an Open (the same comparisons, so the same order of opening)
  struct Key
  {
    double err;
    std::int32_t slot;
    bool operator<(const Key& o) const { return this->err < o.err; }
  };
  thread_local std::vector<Key> heapTL;
  thread_local std::vector<Open> poolTL;
  thread_local std::vector<double> directTL, directMagTL; // per point: exact sums of the near triangles
  thread_local std::vector<int> openTL; // the points not decided yet
  thread_local std::vector<V3> offTL; // per point: its offset from the centre
  // bound once: each use of a thread_local in the loops would look its address up again
  std::vector<Key>& heap = heapTL;
  std::vector<Open>& pool = poolTL;
  std::vector<double>& direct = directTL;
  std::vector<double>& directMag = directMagTL;
  std::vector<int>& open = openTL;
  std::vector<V3>& off = offTL;
  heap.clear();
  pool.clear();
  off.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) off[static_cast<std::size_t>(i)] = pts[i] - centre;
  direct.assign(static_cast<std::size_t>(n), 0.0);
  directMag.assign(static_cast<std::size_t>(n), 0.0);
  open.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) open[static_cast<std::size_t>(i)] = i;
  LocalBoundsCounts count;
  LocalPoly poly;            // the far clusters' expansions summed
  double err = 0, mag = 0;   // their error over the ball; a bound of their terms (rounding slack)
  double errPeak = 0;        // err's largest value since it was last summed afresh
  int unbounded = 0, decided = 0;
  std::int64_t work = 0, terms = 0;
  auto addErr = [&](double e) {
    err += e;
    errPeak = std::max(errPeak, err);
  };
  // id >= 0: a node of the tree; id = -(t + 1): triangle t of a leaf on its
  // own, a cluster about its centroid (second-order term 0, radius its
  // farthest vertex), so a leaf too near for its own expansion is first
  // split into its triangles, and only those still too near are summed
  DipoleTree::Node triNode;
  auto nodeOf = [&](std::int32_t id) -> const DipoleTree::Node& {
    if (id >= 0) return nodes[static_cast<std::size_t>(id)];
    triNode = triangleCluster(tris[static_cast<std::size_t>(-id - 1)], -id - 1);
    return triNode;
  };
  auto visit = [&](std::int32_t id) {
    const DipoleTree::Node& nd = nodeOf(id);
    const V3 y = nd.c - centre;
    const double r0 = norm(y);
    Open o{ 0, id, 0, {}, Cluster };
    o.err = clusterLocalError(nd, r0, rho, o.order, remainderScale);
    if (std::isfinite(o.err))
    {
      addErr(o.err);
      mag += clusterLocalMag(nd, r0 - rho, rho);
      if (o.order > 0)
      {
        o.poly = clusterLocal(nd, y, o.order);
        poly.add(o.poly, 1);
      }
    }
    else
    {
      ++unbounded;
    }
    work += 2;
    ++terms;
    heap.push_back(Key{ o.err, static_cast<std::int32_t>(pool.size()) });
    pool.push_back(o);
    std::push_heap(heap.begin(), heap.end());
  };
  auto close = [&](const Open& o) {
    if (!std::isfinite(o.err))
    {
      --unbounded;
      return;
    }
    err -= o.err; // mag keeps the closed terms: their rounding stays in the sums
    if (o.order > 0) poly.add(o.poly, -1);
  };
  // the running error summed afresh from the live terms (the heap's) where
  // its peak passed ErrPeakRatio x what the slack scales with (see there)
  auto resum = [&] {
    if (errPeak <= ErrPeakRatio * (err + std::fabs(mag))) return;
    err = 0;
    for (const Key& key : heap)
    {
      const Open& o = pool[static_cast<std::size_t>(key.slot)];
      if (std::isfinite(o.err)) err += o.err;
    }
    errPeak = err;
  };
  if (start && !start->empty())
    for (const std::int32_t id : *start) visit(id);
  else
    visit(0);
  // intervals of every point not yet decided; checked again each time the
  // error has halved (a check costs a quadratic per point)
  double checkAt = std::numeric_limits<double>::infinity(), checkedErr = checkAt;
  auto check = [&] {
    resum();
    std::size_t kept = 0;
    for (const int i : open)
    {
      const auto k = static_cast<std::size_t>(i);
      double l = 0, u = 0;
      localInterval(poly.at(off[k]) + direct[k], err, std::fabs(mag), directMag[k], terms, l, u);
      lo[i] = l;
      hi[i] = u;
      if (avoidsHalfIntegers(l, u))
        ++decided;
      else
        open[kept++] = i;
    }
    work += static_cast<std::int64_t>(open.size()) / 8;
    open.resize(kept);
    checkAt = 0.5 * err;
    checkedErr = err;
  };
  while (decided < n)
  {
    // a triangle at the top would be summed exactly at every open point next:
    // its exact solid angle's Taylor polynomial about the centre instead, where
    // the remainder over the ball is smaller than the triangle's bound as a
    // cluster (which keeps the dipole's truncation however far it is)
    if (!heap.empty() && pool[static_cast<std::size_t>(heap.front().slot)].node < 0 &&
      pool[static_cast<std::size_t>(heap.front().slot)].kind == Cluster)
    {
      Open& top = pool[static_cast<std::size_t>(heap.front().slot)];
      const WeightedTri& tri = tris[static_cast<std::size_t>(-top.node - 1)];
      double dist = 0;
      const double e = open.size() > TriangleTaylorWork ? triangleTaylorError(centre, rho, tri, dist, remainderScale) : HUGE_VAL;
      ++work;
      // and only a bound below 4 pi: a wider one cannot decide a point (its
      // interval is wider than 1), and it would only delay the exact sum
      if (!(e < top.err && e < FourPi))
      {
        top.kind = NoTaylor;
      }
      else
      {
        const std::int32_t slot = heap.front().slot;
        close(pool[static_cast<std::size_t>(slot)]);
        double tmag = 0;
        Open t{ e, top.node, 3, triangleTaylor(centre, rho, tri.v[0], tri.v[1], tri.v[2], tri.w, tmag), Taylor };
        addErr(e);
        mag += tmag;
        poly.add(t.poly, 1);
        work += TriangleTaylorWork;
        ++terms;
        ++count.triangleTaylors;
        pool[static_cast<std::size_t>(slot)] = t; // the same slot, its key lowered:
        // sifted down from the root in place (a pop and a push cost twice that:
        // 11 % of patch30's samples at 256^3)
        const Key key{ e, slot };
        std::size_t at = 0;
        while (true)
        {
          std::size_t child = 2 * at + 1;
          if (child >= heap.size()) break;
          if (child + 1 < heap.size() && heap[child] < heap[child + 1]) ++child;
          if (!(key < heap[child])) break;
          heap[at] = heap[child];
          at = child;
        }
        heap[at] = key;
        continue;
      }
    }
    // checked when the error has halved, and before a leaf is summed at
    // every open point if the error fell since (a check costs a quadratic
    // per point, a leaf a few solid angles per point)
    const bool leafNext = !heap.empty() && pool[static_cast<std::size_t>(heap.front().slot)].node < 0;
    if (unbounded == 0 && (err <= checkAt || heap.empty() || (leafNext && err < checkedErr)))
    {
      check();
      if (decided == n || heap.empty()) break;
    }
    if (work > budget) break;
    std::pop_heap(heap.begin(), heap.end());
    const Open o = pool[static_cast<std::size_t>(heap.back().slot)];
    heap.pop_back();
    close(o);
    const DipoleTree::Node& nd = nodeOf(o.node);
    if (nd.left >= 0)
    {
      visit(nd.left);
      visit(nd.right);
      continue;
    }
    if (o.node >= 0 && nd.count > 1)
    {
      for (std::int32_t t = nd.first; t < nd.first + nd.count; ++t) visit(-t - 1);
      continue;
    }
    // a near triangle (or a leaf of one): summed exactly at every open point
    for (std::int32_t t = nd.first; t < nd.first + nd.count; ++t)
    {
      const WeightedTri& tri = tris[static_cast<std::size_t>(t)];
      for (const int i : open)
      {
        const double a = tri.w * nearSolidAngle(pts[i], tri.v[0], tri.v[1], tri.v[2]);
        direct[static_cast<std::size_t>(i)] += a;
        directMag[static_cast<std::size_t>(i)] += std::fabs(a);
      }
      ++terms;
    }
    const std::int64_t summed = static_cast<std::int64_t>(nd.count) * static_cast<std::int64_t>(open.size());
    work += summed;
    count.exactSolidAngles += summed;
    if (heap.empty()) err = 0; // nothing bounded left: drop the rounding of the running error
  }
  if (counts) counts->add(count);
  return decided;
}

} // namespace detail::meshtosdf
} // namespace lvdif
