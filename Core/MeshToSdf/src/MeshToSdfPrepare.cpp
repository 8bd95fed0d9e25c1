// Mesh preparation for mesh to SDF: validation, degenerate triangles skipped
// and counted, face normals, angle-weighted pseudo-normals (Baerentzen &
// Aanaes, "Signed distance computation using the angle weighted
// pseudonormal", IEEE TVCG 2005) and the boundary chain used to bound the
// gradient of the winding number (MeshToSdf.cpp).
#include "MeshToSdfInternal.h"

#include "lvdif/Error.h"

#include <cmath>
#include <algorithm>
#include <cstring>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
/// Welds points of bitwise equal coordinates (as the hash map this replaced
/// did in effect: it hashed the bits; NaN is refused by validate()): ids in
/// order of first appearance. Open addressing in one flat table (no node per
/// point, no rehashing).
std::uint32_t weldPoints(const std::vector<Vec3f>& points, std::vector<std::uint32_t>& weld, std::vector<std::uint32_t>& firstOf)
{
  const std::size_t n = points.size();
  std::size_t cap = 16;
  while (cap < 2 * n) cap *= 2;
  std::vector<std::uint32_t> table(cap, 0xffffffffu); // point index of the first occurrence
  weld.resize(n);
  firstOf.clear();
  firstOf.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::uint32_t b[3];
    std::memcpy(b, points[i].data(), sizeof(b));
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t v : b) h = (h ^ v) * 1099511628211ull;
    std::size_t slot = static_cast<std::size_t>(h ^ (h >> 29)) & (cap - 1);
    for (;; slot = (slot + 1) & (cap - 1))
    {
      const std::uint32_t e = table[slot];
      if (e == 0xffffffffu)
      {
        table[slot] = static_cast<std::uint32_t>(i);
        weld[i] = static_cast<std::uint32_t>(firstOf.size());
        firstOf.push_back(static_cast<std::uint32_t>(i));
        break;
      }
      if (std::memcmp(points[e].data(), b, sizeof(b)) == 0)
      {
        weld[i] = weld[e];
        break;
      }
    }
  }
  return static_cast<std::uint32_t>(firstOf.size());
}

double angleAt(V3 p, V3 q, V3 r) // angle at p of triangle p q r
{
  const V3 u = normalized(q - p), v = normalized(r - p);
  double c = dot(u, v);
  c = c > 1 ? 1 : (c < -1 ? -1 : c);
  return std::acos(c);
}
} // namespace

PreparedMesh prepareMesh(const TriangleMesh& mesh)
{
  mesh.validate();
  PreparedMesh out;
  const std::size_t nt = mesh.triangles.size();

  // Weld by exact position so pseudo-normals and the boundary chain see the
  // surface's topology even in a soup with duplicated points.
  std::vector<std::uint32_t> weld, firstOf;
  const std::size_t nv = weldPoints(mesh.points, weld, firstOf);
  auto toV3 = [](const Vec3f& p) { return V3{ p[0], p[1], p[2] }; };
  std::vector<V3> weldPos(nv);
  for (std::size_t v = 0; v < nv; ++v) weldPos[v] = toV3(mesh.points[firstOf[v]]);

  // triangle records and corner angles, in parallel, written straight to
  // their final (compacted) place: which triangles are kept is known first
  const std::int64_t ntI = static_cast<std::int64_t>(nt);
  auto faceCross = [&](std::int64_t t, V3* v) {
    const auto& ix = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) v[k] = toV3(mesh.points[ix[k]]);
    return cross(v[1] - v[0], v[2] - v[0]);
  };
  std::vector<std::uint32_t> slot(nt + 1, 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < ntI; ++t)
  {
    V3 v[3];
    slot[t + 1] = norm(faceCross(t, v)) > 0 ? 1 : 0;
  }
  for (std::size_t t = 0; t < nt; ++t) slot[t + 1] += slot[t];
  const std::size_t n = slot[nt];
  out.degenerate = nt - n;
  require(n > 0, "mesh has no triangle of non-zero area (" + std::to_string(out.degenerate) +
      " degenerate triangles)");
  out.tris.resize(n);
  std::vector<std::array<std::uint32_t, 3>> welded(n);
  std::vector<std::array<double, 3>> keptAngles(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < ntI; ++t)
  {
    if (slot[t + 1] == slot[t]) continue; // degenerate
    const std::size_t o = slot[t];
    const auto& ix = mesh.triangles[static_cast<std::size_t>(t)];
    Tri& tri = out.tris[o];
    const V3 c = faceCross(t, tri.v);
    const double len = norm(c);
    tri.n = (1.0 / len) * c;
    tri.area = 0.5 * len;
    tri.source = static_cast<std::uint32_t>(t);
    if (!mesh.normals.empty())
    {
      for (int k = 0; k < 3; ++k)
      {
        tri.nv[k] = normalized(toV3(mesh.normals[ix[k]]));
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      keptAngles[o][k] = angleAt(tri.v[k], tri.v[(k + 1) % 3], tri.v[(k + 2) % 3]);
    }
    welded[o] = { weld[ix[0]], weld[ix[1]], weld[ix[2]] };
  }

  // vertex pseudo-normals: summed in triangle order (deterministic)
  std::vector<V3> vertexNormal(nv);
  for (std::size_t t = 0; t < n; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      vertexNormal[welded[t][k]] = vertexNormal[welded[t][k]] + keptAngles[t][k] * out.tris[t].n;
    }
  }

  // Edges grouped by their smaller welded vertex (counting sort, no hashing):
  // entry = corner (t, k) whose edge goes w[k] -> w[k+1].
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) ++start[std::min(welded[t][k], welded[t][(k + 1) % 3]) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> corners(3 * n), fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      corners[fill[std::min(welded[t][k], welded[t][(k + 1) % 3])]++] = static_cast<std::uint32_t>(3 * t + k);

  // per vertex: the distinct edges, their summed normals (triangle order) and
  // oriented multiplicities; boundary edges collected per vertex, then in
  // vertex order so the chain does not depend on the threads
  std::vector<std::vector<std::array<V3, 2>>> boundaryOf(nv);
  std::vector<double> lengthOf(nv, 0);
  std::vector<std::uint32_t> edgesOf(nv, 0);
  const std::int64_t nvI = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t v = 0; v < nvI; ++v)
  {
    const std::uint32_t b0 = start[v], b1 = start[v + 1];
    auto hiOf = [&](std::uint32_t c) {
      const auto& w = welded[c / 3];
      return std::max(w[c % 3], w[(c % 3 + 1) % 3]);
    };
    // group the corners by edge; within an edge, triangle order (c = 3t + k)
    std::sort(corners.begin() + b0, corners.begin() + b1, [&](std::uint32_t x, std::uint32_t y) {
      const std::uint32_t hx = hiOf(x), hy = hiOf(y);
      return hx != hy ? hx < hy : x < y;
    });
    for (std::uint32_t e = b0; e < b1;)
    {
      const std::uint32_t hiE = hiOf(corners[e]);
      std::uint32_t e1 = e;
      V3 en;
      int mult = 0;
      for (; e1 < b1 && hiOf(corners[e1]) == hiE; ++e1)
      {
        const std::uint32_t cf = corners[e1];
        en = en + out.tris[cf / 3].n;
        mult += welded[cf / 3][cf % 3] < hiE ? 1 : -1; // a -> b with a < b counts +1
      }
      const V3 enu = normalized(en);
      for (std::uint32_t f = e; f < e1; ++f)
      {
        out.tris[corners[f] / 3].en[corners[f] % 3] = enu; // each corner is in exactly one list
      }
      e = e1;
      if (mult != 0)
      {
        const V3 a = weldPos[v], b = weldPos[hiE];
        lengthOf[v] += std::abs(mult) * norm(b - a);
        ++edgesOf[v];
        for (int k = 0; k < std::abs(mult); ++k)
        {
          // key (lo, hi) with positive multiplicity means lo -> hi
          boundaryOf[v].push_back(mult > 0 ? std::array<V3, 2>{ a, b } : std::array<V3, 2>{ b, a });
        }
      }
    }
  }
  for (std::size_t v = 0; v < nv; ++v)
  {
    out.boundaryLength += lengthOf[v];
    out.boundaryEdges += edgesOf[v];
    out.boundary.insert(out.boundary.end(), boundaryOf[v].begin(), boundaryOf[v].end());
  }

  const std::int64_t nI = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nI; ++t)
  {
    Tri& tri = out.tris[t];
    for (int k = 0; k < 3; ++k)
    {
      tri.vn[k] = normalized(vertexNormal[welded[t][k]]);
      // a pseudo-normal that cancels (e.g. a face and its flipped duplicate)
      // falls back to the face normal: the sign there is ambiguous anyway
      if (dot(tri.vn[k], tri.vn[k]) == 0) tri.vn[k] = tri.n;
      if (dot(tri.en[k], tri.en[k]) == 0) tri.en[k] = tri.n;
    }
  }

  // bounds: min/max are exact, so the parallel reduction gives the same values
  double lx = out.tris[0].v[0].x, ly = out.tris[0].v[0].y, lz = out.tris[0].v[0].z;
  double hx = lx, hy = ly, hz = lz;
#pragma omp parallel for schedule(static) reduction(min : lx, ly, lz) reduction(max : hx, hy, hz)
  for (std::int64_t t = 0; t < nI; ++t)
  {
    for (const V3& v : out.tris[t].v)
    {
      lx = std::min(lx, v.x), ly = std::min(ly, v.y), lz = std::min(lz, v.z);
      hx = std::max(hx, v.x), hy = std::max(hy, v.y), hz = std::max(hz, v.z);
    }
  }
  out.lo[0] = lx, out.lo[1] = ly, out.lo[2] = lz;
  out.hi[0] = hx, out.hi[1] = hy, out.hi[2] = hz;
  out.welded = std::move(welded);
  return out;
}

} // namespace detail::meshtosdf
} // namespace lvdif
