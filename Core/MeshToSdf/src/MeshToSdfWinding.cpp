// Exact generalized winding numbers (Jacobson, Kavan, Sorkine-Hornung 2013)
// for every voxel, by crossings instead of summing solid angles.
//
// For ANY chain S with boundary dS = -dM, M + S is closed, so w_{M+S} is an
// integer (signed ray crossings) and w_M = w_{M+S} - w_S. S is chosen so
// that w_S is cheap to bound:
// * M+ = M with a set F of faces reversed and a set R of exact duplicates
//   removed (MeshToSdfOrientation.cpp: duplicates reduced to their net
//   multiplicity, then a BFS over manifold edges, F = the minority of each
//   component). As chains M = M+ - 2 F+ + R (F+ = F reversed).
// * C = a cone from one apex over the boundary chain of M+ (oriented edges
//   that do not cancel: only true holes and seams once F and R are out).
// So w_M = K - w_C - s, K the crossings of M+ + C, s = 2 w_{F+} + w_{-R}:
//   * u = K - w_C (= w_{M+}) is carried from voxel to voxel of a scan line
//     as an interval: across a triangle of M+ it jumps by exactly +-1;
//     elsewhere its gradient is the Biot-Savart field of dM+, |grad u| <=
//     sum_e len_e / (4 pi dist(x, e)^2), bounded per cluster of boundary
//     edges; w_C is evaluated again (sum over the cone) only when the sign
//     could change.
//   * s is bounded by a dipole tree with rigorous error bounds
//     (MeshToSdfDipoleTree.h, after Barill et al. 2018) over balls around
//     blocks of 16^3 and 4^3 voxels (computeBox, MeshToSdfEngine.cpp), the
//     voxels of a 4^3 block no ball decides one by one from a local
//     expansion about the block (boundCorrectionAt, MeshToSdfDipoleLocal.h),
//     else over balls around 16-voxel row segments; where that does not
//     decide, per voxel, refined (largest error first, starting from the
//     previous voxel's clusters) until decided.
//   The voxel's sign is decided once the interval of u - s lies on one side
//   of +-0.5.
// * A closed consistently oriented mesh has neither F, R nor C: w = K.
// * A ray that passes too close to an edge or vertex is ambiguous: that row
//   is evaluated voxel by voxel with an oblique ray, and a voxel whose
//   oblique ray is ambiguous too sums all solid angles of M.
// So every voxel gets the sign of the exact winding number of M as given (up
// to double rounding), flipped faces, duplicated and intersecting triangles,
// non-manifold and non-orientable parts included (any F, R give the same w_M).
#include "MeshToSdfDipoleLocal.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfOrientation.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <tuple>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
// voxels per bounded row segment; a segment whose ball cannot be bounded is
// not halved (measured: the halves mostly fail too, and the per-voxel
// refinement, warm-started from the previous voxel's cut, is cheaper)
constexpr std::int64_t Segment = 16, MinSegment = 16;
// work (node expansions x 2 + triangles x points) a block's local expansion
// may spend per voxel before it leaves the rest to the rows (measured on the
// damaged armadillos at 128^3, one thread: 200-300 left many of patch30's
// deep voxels to the rows, 1.3-1.7x its sign time; 1000 to 3000 within
// noise of each other)
constexpr std::int64_t LocalBudgetPerPoint = 1000;

bool insideOf(double w) { return std::fabs(w) >= 0.5; }

/// Sum of f(c), c in [0, n), in the order of the GPU's warp reduction
/// (MeshToSdfCuda.cu warpOrderedSum): 32 lane-strided partial sums, each in
/// index order, then an xor butterfly. Both sides then add the same terms in
/// the same order.
template <typename F>
double laneOrderedSum(std::size_t n, F&& f)
{
  double part[32] = {};
  for (std::size_t c = 0; c < n; ++c) part[c % 32] += f(c);
  for (int off = 16; off > 0; off >>= 1)
    for (int l = 0; l < off; ++l) part[l] = part[l] + part[l + off];
  return part[0];
}
bool decided(double lo, double hi) { return !(lo < 0.5 && hi >= 0.5) && !(lo <= -0.5 && hi > -0.5); }

Tri makeTri(V3 a, V3 b, V3 c, bool& ok)
{
  Tri t;
  t.v[0] = a;
  t.v[1] = b;
  t.v[2] = c;
  const V3 n = faceCross(t.v);
  const double len = norm(n);
  ok = len > 0;
  if (ok)
  {
    t.n = unitFaceNormal(n, len);
    t.area = 0.5 * len;
  }
  return t;
}

/// Clusters of boundary edges (median splits, at most 16 edges each).
std::vector<WindingSigner::Cluster> clusterEdges(std::vector<std::array<V3, 2>> edges)
{
  std::vector<WindingSigner::Cluster> out;
  struct Range
  {
    std::size_t first, count;
  };
  std::vector<Range> todo{ { 0, edges.size() } };
  while (!todo.empty())
  {
    const Range r = todo.back();
    todo.pop_back();
    V3 lo{ 1e300, 1e300, 1e300 }, hi{ -1e300, -1e300, -1e300 };
    for (std::size_t i = r.first; i < r.first + r.count; ++i)
    {
      for (const V3& v : edges[i])
      {
        lo = { std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z) };
        hi = { std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z) };
      }
    }
    if (r.count > 16)
    {
      const V3 ext = hi - lo;
      const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
      const std::size_t half = r.count / 2;
      std::nth_element(edges.begin() + r.first, edges.begin() + r.first + half, edges.begin() + r.first + r.count,
        [axis](const std::array<V3, 2>& x, const std::array<V3, 2>& y) {
          return x[0][axis] + x[1][axis] < y[0][axis] + y[1][axis];
        });
      todo.push_back({ r.first, half });
      todo.push_back({ r.first + half, r.count - half });
      continue;
    }
    WindingSigner::Cluster c;
    c.centre = 0.5 * (lo + hi);
    for (std::size_t i = r.first; i < r.first + r.count; ++i)
    {
      c.length += norm(edges[i][1] - edges[i][0]);
      c.radius = std::max(c.radius, std::max(norm(edges[i][0] - c.centre), norm(edges[i][1] - c.centre)));
    }
    out.push_back(c);
  }
  return out;
}

/// Fills c (in place: its BVH refers to c.closed) with the mesh, the faces
/// reversed or removed as `state` says (OrientedMesh::State), closed by a
/// cone over `boundary`.
void buildClosure(WindingSigner::Closure& c, const TriList& tris, const std::vector<std::uint8_t>* state,
  const std::vector<std::array<V3, 2>>& boundary, const std::vector<WeightedTri>* caps = nullptr)
{
  c.own.reserve(tris.size() + boundary.size() + (caps ? caps->size() : 0));
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    const std::uint8_t st = state ? (*state)[t] : static_cast<std::uint8_t>(OrientedMesh::Keep);
    if (st == OrientedMesh::Remove) continue;
    c.own.push_back(tris[t]);
    if (st == OrientedMesh::Reverse)
    {
      Tri& x = c.own.back();
      std::swap(x.v[1], x.v[2]);
      x.n = -1.0 * x.n;
    }
  }
  c.meshTris = c.own.size();
  if (caps)
  {
    for (const WeightedTri& w : *caps)
    {
      bool ok = false;
      const Tri t = makeTri(w.v[0], w.v[1], w.v[2], ok);
      if (ok) c.own.push_back(t);
    }
  }
  else if (!boundary.empty())
  {
    V3 apex;
    for (const auto& e : boundary) apex = apex + e[0] + e[1];
    apex = (0.5 / static_cast<double>(boundary.size())) * apex;
    for (const auto& e : boundary)
    {
      bool ok = false;
      // boundary edge a -> b is closed by the cone triangle (apex, b, a)
      const Tri t = makeTri(apex, e[1], e[0], ok);
      if (ok)
      {
        c.cone.push_back(t);
        c.own.push_back(t);
      }
    }
    c.clusters = clusterEdges(boundary);
  }
  c.bvh = std::make_shared<const Bvh>(c.own);
}

/// Local caps S with dS = -(boundary): the boundary chain (a 1-cycle: every
/// vertex has as many edges in as out) is split into closed walks, and each
/// walk v0 .. v(n-1) is spanned by a balanced triangulation (triangle
/// (v_i, v_m, v_j), m = (i + j) / 2, then both halves), reversed. Unlike one
/// cone over the whole boundary, a hole's cap stays inside the hole and a
/// long rim gets few large and many small triangles, so the dipole tree can
/// bound the caps hierarchically. Zero-area caps are dropped (solid angle 0).
/// False if some walk does not close (not a cycle: cannot happen for the
/// boundary of a chain; the caller then keeps the cone).
bool capLoops(const std::vector<std::array<V3, 2>>& boundary, std::vector<WeightedTri>& caps)
{
  const std::size_t m = boundary.size();
  std::vector<V3> pos;
  pos.reserve(2 * m);
  for (const auto& e : boundary)
  {
    pos.push_back(e[0]);
    pos.push_back(e[1]);
  }
  auto less = [](const V3& a, const V3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::sort(pos.begin(), pos.end(), less);
  pos.erase(std::unique(pos.begin(), pos.end(), [](const V3& a, const V3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }),
    pos.end());
  auto idOf = [&](const V3& v) { return static_cast<std::size_t>(std::lower_bound(pos.begin(), pos.end(), v, less) - pos.begin()); };
  std::vector<std::size_t> src(m), dst(m), first(pos.size() + 1, 0), out(m);
  for (std::size_t e = 0; e < m; ++e)
  {
    src[e] = idOf(boundary[e][0]);
    dst[e] = idOf(boundary[e][1]);
    ++first[src[e] + 1];
  }
  for (std::size_t v = 0; v < pos.size(); ++v) first[v + 1] += first[v];
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t e = 0; e < m; ++e) out[fill[src[e]]++] = e;
  std::vector<std::size_t> nextOut(first.begin(), first.end() - 1); // first unused out-edge per vertex
  std::vector<char> used(m, 0);
  std::vector<std::size_t> loop;
  auto tri = [&](std::size_t a, std::size_t b, std::size_t c) {
    WeightedTri w;
    w.v[0] = pos[loop[a]];
    w.v[1] = pos[loop[c]]; // reversed: dS = -loop
    w.v[2] = pos[loop[b]];
    w.w = 1;
    if (norm(cross(w.v[1] - w.v[0], w.v[2] - w.v[0])) > 0) caps.push_back(w);
  };
  auto span = [&](auto& self, std::size_t i, std::size_t j) -> void {
    if (j - i < 2) return;
    const std::size_t mid = i + (j - i) / 2;
    tri(i, mid, j);
    self(self, i, mid);
    self(self, mid, j);
  };
  for (std::size_t e0 = 0; e0 < m; ++e0)
  {
    if (used[e0]) continue;
    used[e0] = 1;
    loop.assign(1, src[e0]);
    std::size_t cur = dst[e0];
    while (cur != src[e0])
    {
      while (nextOut[cur] < first[cur + 1] && used[out[nextOut[cur]]]) ++nextOut[cur];
      if (nextOut[cur] == first[cur + 1]) return false;
      const std::size_t e = out[nextOut[cur]++];
      used[e] = 1;
      loop.push_back(cur);
      cur = dst[e];
    }
    span(span, 0, loop.size() - 1);
  }
  return true;
}

double coneWinding(const WindingSigner::Closure& c, V3 p)
{
  return laneOrderedSum(c.cone.size(), [&](std::size_t i) {
    const Tri& t = c.cone[i];
    return solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

double driftPerLength(const WindingSigner::Closure& c, V3 p, V3 q, double h)
{
  // every point x of segment pq has |x - c| >= (|p - c| + |q - c| - h) / 2
  double sum = 0;
  for (const WindingSigner::Cluster& k : c.clusters)
  {
    const double m = 0.5 * (norm(p - k.centre) + norm(q - k.centre) - h) - k.radius;
    if (!(m > 0)) return std::numeric_limits<double>::infinity();
    sum += k.length / (m * m);
  }
  return h * sum / FourPi;
}

const V3 Oblique = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
} // namespace

WindingSigner::WindingSigner(const PreparedMesh& mesh, std::shared_ptr<const Bvh> meshBvh)
  : Mesh(mesh)
{
  if (mesh.boundary.empty())
  {
    // M is already a closed chain (every oriented edge cancels): w = K, no
    // orientation pass needed; the closure is M itself, its tree the mesh's
    // (the build is deterministic: Bvh(mesh.tris) is that same tree)
    this->Plus.shared = &mesh.tris;
    this->Plus.meshTris = mesh.tris.size();
    const double t0 = now();
    this->Plus.bvh = meshBvh ? std::move(meshBvh) : std::make_shared<const Bvh>(mesh.tris);
    trace("winding: closure BVH (the mesh's)", now() - t0);
    // Closed parts whose faces all have copies (a face and its reversed copy
    // cancel: w = 0 there) leave every edge cancelled; only edges of more
    // than two faces betray them. M as given needs nothing more, but the
    // re-oriented mesh M+ keeps each duplicate once (reorientFaces: before,
    // with no orientation pass, it was M and such parts stayed empty). A
    // clean closed mesh has no such edge and pays nothing.
    if (mesh.crowdedEdges > 0)
    {
      const double t1 = now();
      OrientedMesh om = orientMesh(mesh.tris, mesh.welded);
      trace("winding: orientation pass (a closed mesh with edges of more than two faces)", now() - t1);
      checkBuildInterrupt();
      if (om.removedCount != 0)
      {
        // (the faces as given are a closed chain: nothing is reversed in M
        // itself, so ReversedFaces, the warning's count, stays 0)
        this->CorrectedFaces = om.flippedCount + om.removedCount;
        this->OpposedDuplicates = om.opposedDuplicates;
        this->OrientState = std::move(om.state); // for reorientFaces, built on first use
        this->OrientBoundary = std::move(om.boundary);
      }
    }
    return;
  }
  // The orientation pass (a sort of every edge) only pays when the boundary
  // is large or doubled: a few hundred true boundary edges of single
  // multiplicity (holes) are cheap to cap, and every construction is exact,
  // so this is a speed choice only (the open bunny: 182 edges).
  OrientedMesh om;
  const std::vector<std::uint8_t>* state = nullptr;
  const std::vector<std::array<V3, 2>>* boundary = &mesh.boundary;
  if (WindingSigner::mayHaveReversedFaces(mesh))
  {
    const double t0 = now();
    om = orientMesh(mesh.tris, mesh.welded);
    trace("winding: orientation pass", now() - t0);
    checkBuildInterrupt();
    this->CorrectedFaces = om.flippedCount + om.removedCount;
    this->ReversedFaces = om.flippedCount;
    this->OpposedDuplicates = om.opposedDuplicates;
    // M+ pays when F, R and the boundary of M+ are fewer than the boundary
    // edges of M (scattered reversed faces, duplicates); reversed patches
    // have far more faces than rim edges, and caps over dM span a patch
    // with few large triangles (measured on the armadillo, 10 % reversed in
    // patches: 1.2x faster, 30 %: 2x). Either closure is exact.
    if (this->CorrectedFaces != 0 && this->CorrectedFaces + om.boundary.size() <= mesh.boundary.size())
    {
      state = &om.state;
      boundary = &om.boundary;
    }
    else if (this->CorrectedFaces != 0)
    {
      this->OrientState = std::move(om.state); // for reorientFaces, built on first use
      this->OrientBoundary = std::move(om.boundary);
    }
  }
  // the correction s with w_M = w_{M+} + w_S... written w_M = K - s: each
  // reversed face t counts 2 w_{-t} (M+ = M - 2t), each removed duplicate
  // w_{-t} (M+ = M - t), each cap triangle w_cap (K counts M+ + S)
  std::vector<WeightedTri> f;
  if (state)
  {
    f.reserve(om.flippedCount + om.removedCount);
    for (std::size_t t = 0; t < mesh.tris.size(); ++t)
    {
      if (om.state[t] == OrientedMesh::Keep) continue;
      const Tri& x = mesh.tris[t];
      WeightedTri w;
      w.v[0] = x.v[0];
      w.v[1] = x.v[2]; // -t: the face reversed
      w.v[2] = x.v[1];
      w.w = om.state[t] == OrientedMesh::Reverse ? 2 : 1;
      f.push_back(w);
    }
  }
  std::vector<WeightedTri> caps;
  double t0 = now();
  if (!boundary->empty() && capLoops(*boundary, caps))
  {
    trace("winding: caps", now() - t0);
    checkBuildInterrupt();
    t0 = now();
    buildClosure(this->Plus, mesh.tris, state, *boundary, &caps);
    trace("winding: closure BVH", now() - t0);
    checkBuildInterrupt();
    this->PlusIsCone = false;
    if (state && !caps.empty()) this->CapsOnly = std::make_unique<DipoleTree>(caps);
    f.insert(f.end(), caps.begin(), caps.end());
  }
  else
  {
    buildClosure(this->Plus, mesh.tris, state, *boundary);
    trace("winding: closure BVH", now() - t0);
    checkBuildInterrupt();
    this->PlusIsCone = state == nullptr; // M+ = M: exactly the cone over dM (shared with the CUDA path)
  }
  t0 = now();
  if (!f.empty()) this->Flipped = std::make_unique<DipoleTree>(std::move(f));
  trace("winding: dipole tree", now() - t0);
}

WindingSigner::~WindingSigner() = default;

bool WindingSigner::mayHaveReversedFaces(const PreparedMesh& mesh)
{
  return !mesh.boundary.empty() &&
    !(mesh.boundary.size() == mesh.boundaryEdges &&
      mesh.boundary.size() <= std::max<std::size_t>(512, mesh.tris.size() / 64));
}

const WindingSigner::Closure& WindingSigner::coneOverMesh() const
{
  if (this->PlusIsCone) return this->Plus;
  std::call_once(this->LegacyOnce, [this] {
    this->Legacy = std::make_unique<Closure>();
    buildClosure(*this->Legacy, this->Mesh.tris, nullptr, this->Mesh.boundary);
  });
  return *this->Legacy;
}

const WindingSigner::Closure& WindingSigner::closure(bool reoriented) const
{
  if (!reoriented || this->OrientState.empty()) return this->Plus;
  std::call_once(this->ReorientedOnce, [this] {
    // M+ closed by caps over its boundary, as the constructor would build it
    this->Reoriented = std::make_unique<Closure>();
    std::vector<WeightedTri> caps;
    if (!this->OrientBoundary.empty() && capLoops(this->OrientBoundary, caps))
    {
      buildClosure(*this->Reoriented, this->Mesh.tris, &this->OrientState, this->OrientBoundary, &caps);
      if (!caps.empty()) this->ReorientedCaps = std::make_unique<DipoleTree>(std::move(caps));
    }
    else
    {
      buildClosure(*this->Reoriented, this->Mesh.tris, &this->OrientState, this->OrientBoundary);
    }
  });
  return *this->Reoriented;
}

const DipoleTree* WindingSigner::correction(bool reoriented) const
{
  if (!reoriented || this->CorrectedFaces == 0) return this->Flipped.get();
  if (!this->OrientState.empty())
  {
    this->closure(true);
    return this->ReorientedCaps.get();
  }
  return this->CapsOnly.get();
}

double WindingSigner::evaluate(V3 p, bool reoriented) const
{
  std::vector<Bvh::RayHit> hits;
  const DipoleTree* s = this->correction(reoriented);
  const Closure& c = this->closure(reoriented);
  if (c.bvh->rayHits(p, Oblique, 0.0, hits))
  {
    double k = 0;
    for (const auto& h : hits) k += h.sign;
    return k - coneWinding(c, p) - (s ? s->exact(p) : 0.0);
  }
  if (reoriented)
  {
    // w of M+ (the re-oriented faces, duplicates once): its triangles lead Plus.closed
    return laneOrderedSum(c.meshTris, [&](std::size_t i) {
      const Tri& t = c.closed()[i];
      return solidAngleCanonical(p, t.v[0], t.v[1], t.v[2]);
    }) / FourPi;
  }
  // canonical solid angles: the GPU's evaluateWarp adds the same bits in the same order
  return laneOrderedSum(this->Mesh.tris.size(), [&](std::size_t i) {
    const Tri& t = this->Mesh.tris[i];
    return solidAngleCanonical(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

bool WindingSigner::insideAt(V3 p, std::int64_t& fullSums, bool reoriented) const
{
  std::vector<Bvh::RayHit> hits;
  const Closure& c = this->closure(reoriented);
  if (!c.bvh->rayHits(p, Oblique, 0.0, hits))
  {
    ++fullSums;
    return insideOf(this->evaluate(p, reoriented)); // sums all solid angles of M (M+)
  }
  double k = 0;
  for (const auto& h : hits) k += h.sign;
  const double u = k - coneWinding(c, p);
  const DipoleTree* s = this->correction(reoriented);
  if (!s) return insideOf(u);
  double sLo = 0, sHi = 0;
  std::int64_t leafTris = 0;
  const auto r = s->refine(p, 0,
    [&](double lo, double hi) { return decided(u - 1e-9 - hi, u + 1e-9 - lo) ? 1 : 0; }, sLo, sHi, leafTris);
  if (r == DipoleTree::Refined::Exact) ++fullSums;
  // within rounding of +-1/2 with everything summed: decided by the canonical
  // sum (u = K exactly without a cone), as the GPU decides it
  if (!decided(u - 1e-9 - sHi, u + 1e-9 - sLo) && c.cone.empty()) return insideOf(u - s->exactCanonical(p));
  return insideOf(u - 0.5 * (sLo + sHi));
}

bool WindingSigner::boundCorrection(V3 q, double rho, double& lo, double& hi, std::int64_t& leafTris, bool reoriented,
  std::vector<std::int32_t>* cut) const
{
  const DipoleTree* s = this->correction(reoriented);
  if (!s) return false;
  // inside (n - 1/2, n + 1/2) for an integer n, as on the GPU (dipoleBlockBound):
  // K - s then avoids +-1/2 whatever K (s near 1 inside caps over reversed patches)
  return s->refine(q, rho,
           [](double l, double u) {
             const double n = std::floor(0.5 * (l + u) + 0.5);
             return l > n - 0.5 && u < n + 0.5 ? 1 : 0;
           },
           lo, hi, leafTris, cut) == DipoleTree::Refined::Done;
}

int WindingSigner::boundCorrectionAt(V3 centre, double rho, const V3* pts, int n, double* lo, double* hi,
  bool reoriented, const std::vector<std::int32_t>* start, LocalBoundsCounts* counts) const
{
  const DipoleTree* s = this->correction(reoriented);
  if (!s) return 0;
  return localBounds(*s, centre, rho, pts, n, lo, hi, LocalBudgetPerPoint * n, start, 1, counts);
}

void WindingSigner::signRow(V3 rowStart, double h, std::int64_t n, float* out, std::int64_t& evaluations,
  std::int64_t& fallbacks, std::int64_t* fullSums, bool reoriented, const double* priorLo, const double* priorHi) const
{
  std::int64_t fullLocal = 0;
  std::int64_t& full = fullSums ? *fullSums : fullLocal;
  const Closure& c = this->closure(reoriented);
  std::vector<Bvh::RayHit> hits;
  const V3 origin = rowStart - V3{ 0.5 * h, 0, 0 };
  auto pos = [&](std::int64_t i) { return rowStart + V3{ static_cast<double>(i) * h, 0, 0 }; };
  if (!c.bvh->rayHits(origin, V3{ 1, 0, 0 }, 0.0, hits))
  {
    for (std::int64_t i = 0; i < n; ++i)
    {
      if (this->insideAt(pos(i), full, reoriented)) out[i] = -out[i];
    }
    fallbacks += n;
    evaluations += n;
    return;
  }
  std::sort(hits.begin(), hits.end(), [](const Bvh::RayHit& a, const Bvh::RayHit& b) { return a.t < b.t; });
  // K of voxel i = signed crossings ahead of it (t > t_i)
  int ahead = 0;
  for (const auto& x : hits) ahead += x.sign;
  std::size_t next = 0; // first hit not yet passed
  const bool open = !c.cone.empty();
  const DipoleTree* flips = this->correction(reoriented);
  if (!open && !flips)
  {
    // Closed M+ and no correction (a clean closed mesh: the common case): w is
    // the crossing count K, an integer that only changes where the ray crosses
    // a triangle, so the row is a few runs of constant sign. The general loop
    // below spent ~10 instructions on every voxel of the grid (9 % of the
    // banded armadillo's CPU time at 512) for a sign that is constant between
    // hits. Here each run's end is found with the same voxel positions
    // t_i = h/2 + i h and the same test (hit.t <= t_i) as the general loop,
    // so each voxel passes the same hits and gets the same K: the same signs,
    // bit for bit; inside runs are negated as one loop (vectorized).
    auto tAt = [h](std::int64_t i) { return 0.5 * h + static_cast<double>(i) * h; };
    std::int64_t i = 0;
    while (i < n)
    {
      const double ti = tAt(i);
      while (next < hits.size() && hits[next].t <= ti)
      {
        ahead -= hits[next].sign;
        ++next;
      }
      // the run [i, e): every voxel j in it has t_j < the next hit's t (t_j is
      // monotone in j), so it passes no further hit
      std::int64_t e = n;
      if (next < hits.size())
      {
        const double t = hits[next].t;
        e = i + 1;
        const double guess = (t - 0.5 * h) / h - 1; // a voxel just before the hit: few steps below
        if (guess > static_cast<double>(e)) e = guess >= static_cast<double>(n) ? n : static_cast<std::int64_t>(guess);
        while (e > i + 1 && !(tAt(e - 1) < t)) --e;
        while (e < n && tAt(e) < t) ++e;
      }
      if (ahead != 0) // |K| >= 1/2: inside
        for (std::int64_t j = i; j < e; ++j) out[j] = -out[j];
      i = e;
    }
    return;
  }
  bool have = false;
  double lo = 0, hi = 0;                 // interval of u = w_{M+}
  std::int64_t segEnd = 0;               // the bounded segment covers voxels < segEnd
  std::int64_t segStart = 0;
  double segLo[Segment], segHi[Segment]; // s over the voxels of the segment
  int segK[Segment];                     // their crossing counts (closed M+ + C only)
  std::vector<std::int32_t> cut;         // the last per-voxel refinement's clusters
  std::int64_t leafTris = 0;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const double ti = 0.5 * h + static_cast<double>(i) * h;
    int jumpMesh = 0; // signed crossings of M+ triangles passed since the previous voxel
    while (next < hits.size() && hits[next].t <= ti)
    {
      ahead -= hits[next].sign;
      if (static_cast<std::size_t>(hits[next].tri) < c.meshTris) jumpMesh += hits[next].sign;
      ++next;
    }
    bool uExact = !open, evaluated = false;
    if (!open)
    {
      lo = hi = ahead; // closed chain: the crossing count is w_{M+}
    }
    else if (have)
    {
      const double drift = driftPerLength(c, pos(i - 1), pos(i), h);
      if (std::isfinite(drift))
      {
        lo = lo - jumpMesh - drift;
        hi = hi - jumpMesh + drift;
      }
      else
      {
        have = false;
      }
    }
    auto exactU = [&] {
      const double exact = ahead - coneWinding(c, pos(i));
      lo = exact - 1e-9;
      hi = exact + 1e-9;
      have = uExact = evaluated = true;
    };
    if (!have && open) exactU();
    double sLo = 0, sHi = 0;
    int level = 2; // 1: s can still be refined at this voxel
    if (flips)
    {
      if (i >= segEnd)
      {
        // s over balls around row segments: 16 voxels, halved down to
        // MinSegment where a leaf is too close. Goal, when u = K exactly
        // (no cone): the interval of K - s decided for every crossing count
        // K of the segment's voxels; with a cone: s inside (-0.5, 0.5),
        // which decides every voxel whose u is an integer.
        const std::int64_t len = std::min(Segment, n - i);
        std::fill(segLo, segLo + len, -std::numeric_limits<double>::infinity());
        std::fill(segHi, segHi + len, std::numeric_limits<double>::infinity());
        if (!open)
        {
          std::size_t nx = next;
          int k = ahead;
          for (std::int64_t a = 0; a < len; ++a)
          {
            const double ta = 0.5 * h + static_cast<double>(i + a) * h;
            for (; nx < hits.size() && hits[nx].t <= ta; ++nx) k -= hits[nx].sign;
            segK[a] = k;
          }
        }
        // blocks of voxels bounded already (priors) may decide the whole segment
        bool priorsDecide = priorLo != nullptr;
        for (std::int64_t a = 0; a < len && priorsDecide; ++a)
        {
          const double pl = priorLo[i + a], ph = priorHi[i + a];
          priorsDecide = pl <= ph && (open ? pl > -0.5 && ph < 0.5 : decided(segK[a] - ph, segK[a] - pl));
        }
        auto tryBall = [&](auto& self, std::int64_t a, std::int64_t m) -> void {
          const double half = 0.5 * static_cast<double>(m - 1) * h;
          const V3 centre = pos(i + a) + V3{ half, 0, 0 };
          // rho covers the rounding of the voxel positions too
          const double slack = 1e-12 * (half + std::fabs(centre.x) + std::fabs(centre.y) + std::fabs(centre.z));
          int kLo = 0, kHi = 0;
          if (!open)
          {
            kLo = *std::min_element(segK + a, segK + a + m);
            kHi = *std::max_element(segK + a, segK + a + m);
          }
          auto goal = [&](double l, double u) {
            if (open) return l > -0.5 && u < 0.5 ? 1 : (l >= 0.5 || u <= -0.5 ? -1 : 0);
            for (int k = kLo; k <= kHi; ++k)
              if (!decided(k - u, k - l)) return 0;
            return 1;
          };
          double x = 0, y = 0;
          const auto r = flips->refine(centre, half + slack, goal, x, y, leafTris);
          if (r == DipoleTree::Refined::Done)
          {
            std::fill(segLo + a, segLo + a + m, x);
            std::fill(segHi + a, segHi + a + m, y);
          }
          else if (m >= 2 * MinSegment)
          {
            self(self, a, m / 2);
            self(self, a + m / 2, m - m / 2);
          }
        };
        // with block bounds the segment's ball (radius 7.5 voxels) decides
        // nothing they left: skipped (measured: the same voxels, 3 % slower)
        if (!priorsDecide && !priorLo) tryBall(tryBall, 0, len);
        cut.clear();
        segStart = i;
        segEnd = i + len;
      }
      level = 1;
      sLo = segLo[i - segStart];
      sHi = segHi[i - segStart];
      if (priorLo && priorLo[i] <= priorHi[i])
      {
        sLo = std::max(sLo, priorLo[i]);
        sHi = std::min(sHi, priorHi[i]);
      }
    }
    while (!decided(lo - sHi, hi - sLo))
    {
      if (!uExact)
      {
        exactU();
        continue;
      }
      if (level == 1)
      {
        // s at this voxel, refined until the sign is decided (or all exact),
        // starting from the cut the previous voxel ended with (cleared at
        // every segment). A fixed-opening-angle bound tried first cost more
        // than it saved (measured on damaged armadillos: 15-60 % more time)
        double a = 0, b = 0;
        const double ulo = lo, uhi = hi;
        evaluated = true;
        const auto r = flips->refine(pos(i), 0, [&](double x, double y) { return decided(ulo - y, uhi - x) ? 1 : 0; },
          a, b, leafTris, &cut);
        sLo = std::max(sLo, a);
        sHi = std::min(sHi, b);
        if (r == DipoleTree::Refined::Exact) ++full;
        level = 2;
        evaluated = true;
        continue;
      }
      break; // within rounding of +-0.5 with everything exact
    }
    if (evaluated) ++evaluations;
    // undecided only within rounding of +-1/2 with every face of s summed
    // exactly: then the canonical sum decides (u = K here without a cone),
    // bit for bit as on the GPU (MeshToSdfCudaDipole.cuh)
    const bool inside = !open && flips && !decided(lo - sHi, hi - sLo) ? insideOf(lo - flips->exactCanonical(pos(i)))
                                                                      : insideOf(0.5 * ((lo - sHi) + (hi - sLo)));
    if (inside) out[i] = -out[i];
  }
}

} // namespace detail::meshtosdf
} // namespace lvdif
