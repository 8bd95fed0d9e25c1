// Exact generalized winding numbers (Jacobson, Kavan, Sorkine-Hornung 2013)
// for every voxel, by crossings instead of summing solid angles:
//
// * The mesh M is closed into a chain M' = M + C by a cone C from one apex
//   over the boundary chain (the oriented edges of M that do not cancel).
//   w_M' is an integer: the signed count of crossings along any ray, and
//   w_M = w_M' - w_C, where w_C is the (exact) solid angle of the small cone
//   (one triangle per boundary edge). Closed meshes have no cone.
// * One ray per scan line (+x) gives the crossings of every voxel of the row.
// * Open meshes: w_M is carried from voxel to voxel as an interval: across
//   a triangle of M it jumps by exactly +-1; elsewhere its gradient is the
//   Biot-Savart field of the boundary, |grad w| <= sum_e len_e / (4 pi
//   dist(x, e)^2), bounded per cluster of boundary edges. w_C is evaluated
//   again only when the interval could straddle +-0.5.
// * A ray that passes too close to an edge or vertex is ambiguous: that row
//   is evaluated voxel by voxel with an oblique ray, and a voxel whose
//   oblique ray is ambiguous too sums all solid angles.
// So every voxel gets the sign of the exact winding number (up to double
// rounding), flipped faces, duplicated and intersecting triangles included.
#include "MeshToSdfInternal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lvdif
{
namespace sdfdetail
{

namespace
{
constexpr double FourPi = 12.566370614359172;

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
  const V3 n = cross(b - a, c - a);
  const double len = norm(n);
  ok = len > 0;
  if (ok)
  {
    t.n = (1.0 / len) * n;
    t.area = 0.5 * len;
  }
  return t;
}
} // namespace

WindingSigner::WindingSigner(const PreparedMesh& mesh)
  : Mesh(mesh)
{
  this->Closed.reserve(mesh.tris.size() + mesh.boundary.size());
  this->Closed.assign(mesh.tris.begin(), mesh.tris.end());
  this->MeshTris = mesh.tris.size();
  if (!mesh.boundary.empty())
  {
    V3 apex;
    for (const auto& e : mesh.boundary) apex = apex + e[0] + e[1];
    apex = (0.5 / static_cast<double>(mesh.boundary.size())) * apex;
    for (const auto& e : mesh.boundary)
    {
      bool ok = false;
      // boundary edge a -> b is closed by the cone triangle (apex, b, a)
      const Tri t = makeTri(apex, e[1], e[0], ok);
      if (ok)
      {
        this->Cone.push_back(t);
        this->Closed.push_back(t);
      }
    }
    // clusters of boundary edges (median splits, at most 16 edges each)
    std::vector<std::array<V3, 2>> edges = mesh.boundary;
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
      Cluster c;
      c.centre = 0.5 * (lo + hi);
      for (std::size_t i = r.first; i < r.first + r.count; ++i)
      {
        c.length += norm(edges[i][1] - edges[i][0]);
        c.radius = std::max(c.radius, std::max(norm(edges[i][0] - c.centre), norm(edges[i][1] - c.centre)));
      }
      this->Clusters.push_back(c);
    }
  }
  this->ClosedBvh = std::make_unique<Bvh>(this->Closed);
}

double WindingSigner::coneWinding(V3 p) const
{
  return laneOrderedSum(this->Cone.size(), [&](std::size_t c) {
    const Tri& t = this->Cone[c];
    return solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

double WindingSigner::driftPerLength(V3 p, V3 q, double h) const
{
  // every point x of segment pq has |x - c| >= (|p - c| + |q - c| - h) / 2
  double sum = 0;
  for (const Cluster& c : this->Clusters)
  {
    const double m = 0.5 * (norm(p - c.centre) + norm(q - c.centre) - h) - c.radius;
    if (!(m > 0)) return std::numeric_limits<double>::infinity();
    sum += c.length / (m * m);
  }
  return h * sum / FourPi;
}

double WindingSigner::evaluate(V3 p) const
{
  const V3 dir = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
  std::vector<Bvh::RayHit> hits;
  if (this->ClosedBvh->rayHits(p, dir, 0.0, hits))
  {
    double k = 0;
    for (const auto& h : hits) k += h.sign;
    return k - this->coneWinding(p);
  }
  return laneOrderedSum(this->Mesh.tris.size(), [&](std::size_t i) {
    const Tri& t = this->Mesh.tris[i];
    return solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

void WindingSigner::signRow(V3 rowStart, double h, std::int64_t n, float* out, std::int64_t& evaluations,
  std::int64_t& fallbacks) const
{
  std::vector<Bvh::RayHit> hits;
  const V3 origin = rowStart - V3{ 0.5 * h, 0, 0 };
  auto pos = [&](std::int64_t i) { return rowStart + V3{ static_cast<double>(i) * h, 0, 0 }; };
  if (!this->ClosedBvh->rayHits(origin, V3{ 1, 0, 0 }, 0.0, hits))
  {
    for (std::int64_t i = 0; i < n; ++i)
    {
      if (insideOf(this->evaluate(pos(i)))) out[i] = -out[i];
    }
    fallbacks += n;
    evaluations += n;
    return;
  }
  std::sort(hits.begin(), hits.end(), [](const Bvh::RayHit& a, const Bvh::RayHit& b) { return a.t < b.t; });
  // k of voxel i = signed crossings ahead of it (t > t_i)
  int ahead = 0;
  for (const auto& x : hits) ahead += x.sign;
  std::size_t next = 0; // first hit not yet passed
  const bool open = !this->Cone.empty();
  bool have = false;
  double lo = 0, hi = 0;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const double ti = 0.5 * h + static_cast<double>(i) * h;
    int jumpMesh = 0; // signed crossings of mesh triangles passed since the previous voxel
    while (next < hits.size() && hits[next].t <= ti)
    {
      ahead -= hits[next].sign;
      if (static_cast<std::size_t>(hits[next].tri) < this->MeshTris) jumpMesh += hits[next].sign;
      ++next;
    }
    double w;
    if (!open)
    {
      w = ahead; // closed chain: the crossing count is the winding number
    }
    else
    {
      if (have)
      {
        const double drift = this->driftPerLength(pos(i - 1), pos(i), h);
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
      if (!have || !decided(lo, hi))
      {
        const double exact = ahead - this->coneWinding(pos(i));
        lo = exact - 1e-9;
        hi = exact + 1e-9;
        have = true;
        ++evaluations;
      }
      w = 0.5 * (lo + hi);
    }
    if (insideOf(w)) out[i] = -out[i];
  }
}

} // namespace sdfdetail
} // namespace lvdif
