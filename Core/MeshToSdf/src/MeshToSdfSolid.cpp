// Whether a prepared mesh is the boundary of a solid (MeshToSdfSolid.h).
#include "MeshToSdfSolid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
using Face = std::array<std::uint32_t, 3>;

/// The first failure of the threads, kept once.
class FirstFailure
{
public:
  bool failed() const { return this->Failed.load(std::memory_order_relaxed); }
  void fail(const std::string& why)
  {
    std::lock_guard<std::mutex> lock(this->Lock);
    if (this->Failed.load(std::memory_order_relaxed)) return;
    this->Why = why;
    this->Failed.store(true, std::memory_order_relaxed);
  }
  const std::string& why() const { return this->Why; }

private:
  std::atomic<bool> Failed{ false };
  std::mutex Lock;
  std::string Why;
};

/// 1. Every vertex's corners: the faces after it (next) and before it (prev)
/// around each face. Closed and consistently oriented: the next vertices are
/// distinct, the prev vertices are distinct and the two sets are equal (each
/// edge v -> w has exactly one face running it back, w -> v). One fan: going
/// from face to face across those edges visits every face of the vertex.
void checkFans(const PreparedMesh& m, FirstFailure& result)
{
  const std::size_t nv = m.vertices, nt = m.welded.size();
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) ++start[m.welded[t][k] + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // per corner: (next, prev) of the face around its vertex
  std::vector<std::array<std::uint32_t, 2>> link(3 * nt);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
    {
      const Face& f = m.welded[t];
      for (int k = 0; k < 3; ++k) link[fill[f[k]]++] = { f[(k + 1) % 3], f[(k + 2) % 3] };
    }
  }
  const auto count = static_cast<std::int64_t>(nv);
#pragma omp parallel
  {
    std::vector<std::uint32_t> next, prev;
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t v = 0; v < count; ++v)
    {
      if (result.failed()) continue;
      const std::uint32_t b = start[static_cast<std::size_t>(v)], e = start[static_cast<std::size_t>(v) + 1];
      const std::uint32_t k = e - b;
      if (k == 0) continue; // a vertex of skipped triangles only
      if (k < 3)
      {
        result.fail("a vertex has fewer than 3 faces");
        continue;
      }
      next.clear();
      prev.clear();
      for (std::uint32_t i = b; i < e; ++i)
      {
        next.push_back(link[i][0]);
        prev.push_back(link[i][1]);
      }
      std::sort(next.begin(), next.end());
      std::sort(prev.begin(), prev.end());
      if (std::adjacent_find(next.begin(), next.end()) != next.end() || next != prev)
      {
        result.fail("an edge is not shared by exactly two faces of opposite orientation");
        continue;
      }
      // the fan: from face b, across the edge to its next vertex, to the face
      // whose prev vertex that is, until back at face b
      std::uint32_t steps = 1, at = b;
      for (;;)
      {
        const std::uint32_t w = link[at][0];
        std::uint32_t j = b;
        while (link[j][1] != w) ++j; // exists: the sets are equal
        if (j == b || steps > k) break;
        at = j;
        ++steps;
      }
      if (steps != k) result.fail("a vertex joins several fans of faces (not a manifold)");
    }
  }
}

struct P2
{
  double x, y;
};
P2 operator-(P2 a, P2 b) { return { a.x - b.x, a.y - b.y }; }
double cross2(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
double length2d(P2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }

/// The axis a plane of normal n is projected along (its largest component).
int dropAxis(V3 n)
{
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}
P2 project(V3 p, int drop)
{
  return drop == 0 ? P2{ p.y, p.z } : (drop == 1 ? P2{ p.z, p.x } : P2{ p.x, p.y });
}

/// Whether convex point sets a (na points) and b (nb) in the plane come
/// within tol of each other: no edge line of either (separating axis
/// theorem) leaves them more than tol apart. Projection along an axis only
/// shrinks distances, so a gap found here is a gap in space.
bool convexWithin(const P2* a, int na, const P2* b, int nb, double tol)
{
  auto separates = [&](P2 p, P2 q) {
    const P2 d = q - p;
    const P2 axis{ -d.y, d.x };
    const double len = length2d(axis);
    if (!(len > 0)) return false;
    double loA = 1e300, hiA = -1e300, loB = 1e300, hiB = -1e300;
    for (int i = 0; i < na; ++i)
    {
      const double s = axis.x * a[i].x + axis.y * a[i].y;
      loA = std::min(loA, s);
      hiA = std::max(hiA, s);
    }
    for (int i = 0; i < nb; ++i)
    {
      const double s = axis.x * b[i].x + axis.y * b[i].y;
      loB = std::min(loB, s);
      hiB = std::max(hiB, s);
    }
    return loB > hiA + tol * len || loA > hiB + tol * len;
  };
  for (int i = 0; i < na && na > 1; ++i)
    if (separates(a[i], a[(i + 1) % na])) return false;
  for (int i = 0; i < nb && nb > 1; ++i)
    if (separates(b[i], b[(i + 1) % nb])) return false;
  return true;
}

/// Whether direction u lies in (or within angle tol of) the wedge between
/// e1 and e2 (a triangle's corner, less than a half-turn).
bool inWedge(P2 u, P2 e1, P2 e2, double tol)
{
  if (cross2(e1, e2) < 0) std::swap(e1, e2);
  const double nu = length2d(u);
  return cross2(e1, u) >= -tol * length2d(e1) * nu && cross2(u, e2) >= -tol * nu * length2d(e2);
}

/// Whether two corners (wedges e1-e2 and f1-f2 at one apex) overlap beyond
/// the apex or come within angle tol: no edge line through the apex keeps
/// the other wedge strictly on its far side.
bool wedgesOverlap(P2 e1, P2 e2, P2 f1, P2 f2, double tol)
{
  // the other wedge's edge o is clear of the line along `edge` when it lies
  // strictly on the far side, or on the line's opposite ray (outside the wedge)
  auto separates = [tol](P2 edge, P2 own, P2 o1, P2 o2) {
    const double side = cross2(edge, own) >= 0 ? 1.0 : -1.0;
    const double ne = length2d(edge);
    auto clear = [&](P2 o) {
      const double c = side * cross2(edge, o), allowance = tol * ne * length2d(o);
      return c < -allowance ||
        (c <= allowance && edge.x * o.x + edge.y * o.y < 0 && !inWedge(o, edge, own, tol));
    };
    return clear(o1) && clear(o2);
  };
  return !(separates(e1, e2, f1, f2) || separates(e2, e1, f1, f2) || separates(f1, f2, e1, e2) ||
    separates(f2, f1, e1, e2));
}

/// Whether triangles a and b (welded corners fa, fb) meet anywhere but at
/// the vertices and the edge they share, or come within tol (lengths) / atol
/// (angles) of it.
bool trianglesMeet(const Tri& a, const Face& fa, const Tri& b, const Face& fb, double tol, double atol)
{
  int sharedA[3] = { -1, -1, -1 }; // per corner of a: the corner of b at the same vertex
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (fa[i] == fb[j])
      {
        sharedA[i] = j;
        ++shared;
      }
  if (shared == 3) return true; // the same face twice
  // each case computes only the plane distances it reads (most pairs share
  // a vertex or an edge and are decided by two or one of them)
  const int drop = dropAxis(a.n);
  double db[3];
  if (shared == 2)
  {
    // across their edge they meet only when folded flat onto each other
    const int aFree = sharedA[0] < 0 ? 0 : (sharedA[1] < 0 ? 1 : 2);
    int bFree = 0;
    while (bFree == sharedA[0] || bFree == sharedA[1] || bFree == sharedA[2]) ++bFree;
    db[bFree] = dot(b.v[bFree] - a.v[0], a.n);
    if (std::fabs(db[bFree]) > tol) return false;
    const P2 p = project(a.v[(aFree + 1) % 3], drop), q = project(a.v[(aFree + 2) % 3], drop);
    const P2 e = q - p, ta = project(a.v[aFree], drop) - p, tb = project(b.v[bFree], drop) - p;
    const double sa = cross2(e, ta), sb = cross2(e, tb);
    return sa * sb > 0 || std::fabs(sb) <= atol * length2d(e) * length2d(tb);
  }
  auto oneSide = [tol](const double d[3], int skip) {
    bool pos = true, neg = true;
    for (int k = 0; k < 3; ++k)
    {
      if (k == skip) continue;
      pos = pos && d[k] > tol;
      neg = neg && d[k] < -tol;
    }
    return pos || neg;
  };
  double da[3];
  if (shared == 1)
  {
    const int va = sharedA[0] >= 0 ? 0 : (sharedA[1] >= 0 ? 1 : 2), vb = sharedA[va];
    // planes through the shared vertex: the others' signed distances
    for (int j = 0; j < 3; ++j) db[j] = dot(b.v[j] - a.v[va], a.n);
    if (oneSide(db, vb)) return false;
    for (int i = 0; i < 3; ++i) da[i] = dot(a.v[i] - b.v[vb], b.n);
    if (oneSide(da, va)) return false;
    const P2 v = project(a.v[va], drop);
    const P2 e1 = project(a.v[(va + 1) % 3], drop) - v, e2 = project(a.v[(va + 2) % 3], drop) - v;
    const int b1 = (vb + 1) % 3, b2 = (vb + 2) % 3;
    if (std::fabs(db[b1]) <= tol && std::fabs(db[b2]) <= tol)
      return wedgesOverlap(e1, e2, project(b.v[b1], drop) - v, project(b.v[b2], drop) - v, atol);
    // b meets a's plane in a segment from the shared vertex to q
    V3 q;
    if (std::fabs(db[b1]) <= tol)
      q = b.v[b1];
    else if (std::fabs(db[b2]) <= tol)
      q = b.v[b2];
    else
      q = b.v[b1] + (db[b1] / (db[b1] - db[b2])) * (b.v[b2] - b.v[b1]);
    return inWedge(project(q, drop) - v, e1, e2, atol);
  }
  for (int j = 0; j < 3; ++j) db[j] = dot(b.v[j] - a.v[0], a.n);
  if (oneSide(db, -1)) return false;
  for (int i = 0; i < 3; ++i) da[i] = dot(a.v[i] - b.v[0], b.n);
  if (oneSide(da, -1)) return false;
  // b's part in a's plane (its vertices within tol of it and its edges'
  // crossings; convex), against a in that plane
  P2 part[3];
  int n = 0;
  for (int j = 0; j < 3; ++j)
    if (std::fabs(db[j]) <= tol) part[n++] = project(b.v[j], drop);
  for (int j = 0; j < 3 && n < 3; ++j)
  {
    const int k = (j + 1) % 3;
    if ((db[j] > tol && db[k] < -tol) || (db[j] < -tol && db[k] > tol))
      part[n++] = project(b.v[j] + (db[j] / (db[j] - db[k])) * (b.v[k] - b.v[j]), drop);
  }
  const P2 ta[3] = { project(a.v[0], drop), project(a.v[1], drop), project(a.v[2], drop) };
  return convexWithin(ta, 3, part, n, tol);
}

/// 2. No two triangles meet but as neighbours: every pair of the tree's
/// nodes whose boxes come within tol of each other, once (a node with
/// itself, and the two children of a node), down to the leaves' triangles
/// whose own boxes do.
class EmbeddedCheck
{
public:
  EmbeddedCheck(const PreparedMesh& m, const Bvh& bvh, double tol, FirstFailure& result)
    : M(m)
    , Nodes(bvh.nodes())
    , Order(bvh.order())
    , Tol(tol)
    , Result(result)
  {
  }

  void run()
  {
    // the triangles' boxes side by side in the leaves' order: most pairs of
    // two near leaves are refused by their boxes (sub2: 13.5M pairs tested,
    // 5.2M kept), each of which read its box from its triangle's record
    // (112 bytes, in input order) before
    const auto slots = static_cast<std::int64_t>(this->Order.size());
    this->SlotBoxes.resize(static_cast<std::size_t>(slots));
#pragma omp parallel for schedule(static)
    for (std::int64_t x = 0; x < slots; ++x)
    {
      const Tri& t = this->M.tris[static_cast<std::size_t>(this->Order[static_cast<std::size_t>(x)])];
      SlotBox& b = this->SlotBoxes[static_cast<std::size_t>(x)];
      for (int k = 0; k < 3; ++k)
      {
        // the corners are the input's floats (PreparedMesh::points): exact
        b.lo[k] = static_cast<float>(std::min({ t.v[0][k], t.v[1][k], t.v[2][k] }));
        b.hi[k] = static_cast<float>(std::max({ t.v[0][k], t.v[1][k], t.v[2][k] }));
      }
    }
    // the recursion's top levels on one thread, listing the node pairs it
    // reaches at SplitDepth; those (a few per thread and more) on all threads
    std::vector<Work> work;
    this->expand({ 0, 0, true }, 0, work);
    const auto n = static_cast<std::int64_t>(work.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t w = 0; w < n; ++w)
    {
      const Work& x = work[static_cast<std::size_t>(w)];
      if (x.same)
        this->self(x.a);
      else
        this->pair(x.a, x.b);
    }
  }

private:
  static constexpr double AngleTol = 1e-9;
  static constexpr int SplitDepth = 9; // about 2^9 node pairs and their neighbours to share out

  struct Work
  {
    std::int32_t a, b;
    bool same; // the pairs within node a (b == a)
  };

  void expand(Work w, int depth, std::vector<Work>& out) const
  {
    const Bvh::Node& na = this->Nodes[static_cast<std::size_t>(w.a)];
    const Bvh::Node& nb = this->Nodes[static_cast<std::size_t>(w.b)];
    if (!w.same && !this->near(na.lo, na.hi, nb.lo, nb.hi)) return;
    if (depth >= SplitDepth || (na.left < 0 && nb.left < 0))
    {
      out.push_back(w);
      return;
    }
    if (w.same)
    {
      this->expand({ na.left, na.left, true }, depth + 1, out);
      this->expand({ na.right, na.right, true }, depth + 1, out);
      this->expand({ na.left, na.right, false }, depth + 1, out);
      return;
    }
    const bool splitA = nb.left < 0 || (na.left >= 0 && na.count >= nb.count);
    const Bvh::Node& split = splitA ? na : nb;
    const std::int32_t other = splitA ? w.b : w.a;
    this->expand({ split.left, other, false }, depth + 1, out);
    this->expand({ split.right, other, false }, depth + 1, out);
  }

  /// A triangle's bounding box (its corners are floats: exact).
  struct SlotBox
  {
    float lo[3], hi[3];
  };

  template <typename T>
  bool near(const T alo[3], const T ahi[3], const T blo[3], const T bhi[3]) const
  {
    for (int k = 0; k < 3; ++k)
      if (alo[k] > bhi[k] + this->Tol || blo[k] > ahi[k] + this->Tol) return false;
    return true;
  }

  /// The triangles of leaf slots x and y, whose boxes come within Tol.
  void testPair(std::int32_t x, std::int32_t y)
  {
    const std::int32_t i = this->Order[static_cast<std::size_t>(x)], j = this->Order[static_cast<std::size_t>(y)];
    const Tri& a = this->M.tris[static_cast<std::size_t>(i)];
    const Tri& b = this->M.tris[static_cast<std::size_t>(j)];
    if (!trianglesMeet(a, this->M.welded[static_cast<std::size_t>(i)], b, this->M.welded[static_cast<std::size_t>(j)],
          this->Tol, AngleTol))
      return;
    std::ostringstream why;
    why << "triangles " << std::min(a.source, b.source) << " and " << std::max(a.source, b.source)
        << " meet (or come within the rounding allowance) away from a shared edge or vertex";
    this->Result.fail(why.str());
  }

  void leaves(const Bvh::Node& a, const Bvh::Node& b, bool same)
  {
    for (std::int32_t x = a.first; x < a.first + a.count; ++x)
    {
      const SlotBox& bx = this->SlotBoxes[static_cast<std::size_t>(x)];
      for (std::int32_t y = same ? x + 1 : b.first; y < b.first + b.count; ++y)
      {
        const SlotBox& by = this->SlotBoxes[static_cast<std::size_t>(y)];
        if (this->near(bx.lo, bx.hi, by.lo, by.hi)) this->testPair(x, y);
      }
    }
  }

  /// The pairs within node a.
  void self(std::int32_t a)
  {
    if (this->Result.failed()) return;
    const Bvh::Node& n = this->Nodes[static_cast<std::size_t>(a)];
    if (n.left < 0)
    {
      this->leaves(n, n, true);
      return;
    }
    this->self(n.left);
    this->self(n.right);
    this->pair(n.left, n.right);
  }

  /// The pairs between nodes a and b (disjoint sets of triangles).
  void pair(std::int32_t a, std::int32_t b)
  {
    if (this->Result.failed()) return;
    const Bvh::Node& na = this->Nodes[static_cast<std::size_t>(a)];
    const Bvh::Node& nb = this->Nodes[static_cast<std::size_t>(b)];
    if (!this->near(na.lo, na.hi, nb.lo, nb.hi)) return;
    if (na.left < 0 && nb.left < 0)
    {
      this->leaves(na, nb, false);
      return;
    }
    // split the node with more triangles (a leaf is never split)
    const bool splitA = nb.left < 0 || (na.left >= 0 && na.count >= nb.count);
    const Bvh::Node& split = splitA ? na : nb;
    const std::int32_t other = splitA ? b : a;
    this->pair(split.left, other);
    this->pair(split.right, other);
  }

  const PreparedMesh& M;
  const LargeVector<Bvh::Node>& Nodes;
  const LargeVector<std::int32_t>& Order;
  double Tol;
  FirstFailure& Result;
  std::vector<SlotBox> SlotBoxes; // per leaf slot (Order's index)
};

/// 3. The winding number just in front of each part (and just behind it)
/// by the signed crossings of a ray: 0 in front, 1 behind. The point is
/// off the part's largest triangle by a tenth of its smallest height along
/// its normal; that triangle must be the point's nearest, so no other face
/// lies between the point and the part.
std::size_t checkFronts(const PreparedMesh& m, const Bvh& bvh, const MeshParts& parts, FirstFailure& result)
{
  std::atomic<std::size_t> inward{ 0 };
  std::vector<std::int64_t> largest(parts.count, -1);
  for (std::size_t t = 0; t < m.tris.size(); ++t)
  {
    const std::uint32_t p = parts.partOfVertex[m.welded[t][0]];
    if (largest[p] < 0 || m.tris[t].area > m.tris[static_cast<std::size_t>(largest[p])].area)
      largest[p] = static_cast<std::int64_t>(t);
  }
  static const V3 directions[] = { normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 }),
    normalized(V3{ -0.31, 0.83, 0.46 }), normalized(V3{ 0.71, -0.22, -0.67 }), normalized(V3{ -0.52, -0.61, 0.6 }),
    normalized(V3{ 0.13, 0.27, -0.95 }), normalized(V3{ -0.88, 0.35, -0.32 }) };
  const auto count = static_cast<std::int64_t>(parts.count);
#pragma omp parallel
  {
    std::vector<Bvh::RayHit> hits;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t p = 0; p < count; ++p)
    {
      // every part, also after a failure: the parts that face inwards are counted
      const std::int64_t t = largest[static_cast<std::size_t>(p)];
      const Tri& tri = m.tris[static_cast<std::size_t>(t)];
      double longest = 0;
      for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(tri.v[(k + 1) % 3] - tri.v[k]));
      const double delta = 0.1 * (2 * tri.area / longest);
      const V3 centre = (1.0 / 3.0) * (tri.v[0] + tri.v[1] + tri.v[2]);
      int w[2] = { 0, 0 }; // in front, behind
      bool decided = true;
      for (int side = 0; side < 2 && decided; ++side)
      {
        const V3 at = centre + (side == 0 ? delta : -delta) * tri.n;
        if (bvh.nearest(at, static_cast<std::int32_t>(t), 1e300).tri != t)
        {
          result.fail("a face lies too close in front of or behind a part's largest face to test its winding number");
          decided = false;
          break;
        }
        decided = false;
        for (const V3& dir : directions)
        {
          hits.clear();
          if (!bvh.rayHits(at, dir, 0, hits)) continue;
          for (const Bvh::RayHit& h : hits) w[side] += h.sign;
          decided = true;
          break;
        }
        if (!decided) result.fail("every test ray of a part's winding number was ambiguous");
      }
      if (!decided || (w[0] == 0 && w[1] == 1)) continue;
      if (w[0] == -1 && w[1] == 0) inward.fetch_add(1, std::memory_order_relaxed);
      std::ostringstream why;
      why << "the winding number in front of part " << p << " is " << w[0] << " and behind it " << w[1]
          << " (not 0 and 1): " << (w[0] == -1 && w[1] == 0 ? "the part faces inwards" : "parts are nested");
      result.fail(why.str());
    }
  }
  return inward.load();
}
} // namespace

SolidBoundary checkSolidBoundary(const PreparedMesh& mesh, const Bvh& bvh, const MeshParts& parts)
{
  SolidBoundary r;
  if (mesh.tris.empty())
  {
    r.why = "no triangles";
    return r;
  }
  FirstFailure result;
  double t0 = now();
  checkFans(mesh, result);
  trace("solid check: edges and fans", now() - t0);
  checkBuildInterrupt();
  if (!result.failed())
  {
    t0 = now();
    // lengths within this of meeting count as meeting: far above the rounding
    // of the planes' distances, far below any triangle a mesh resolves
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, mesh.hi[a] - mesh.lo[a]);
    EmbeddedCheck(mesh, bvh, 1e-9 * extent, result).run();
    trace("solid check: no triangles meet", now() - t0);
    checkBuildInterrupt();
  }
  if (!result.failed())
  {
    t0 = now();
    r.inwardParts = checkFronts(mesh, bvh, parts, result);
    trace("solid check: winding numbers in front of the parts", now() - t0);
  }
  r.solid = !result.failed();
  r.why = result.why();
  r.parts = parts.count;
  return r;
}

} // namespace detail::meshtosdf
} // namespace lvdif
