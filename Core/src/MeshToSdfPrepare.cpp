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
#include <unordered_map>

namespace lvdif
{
namespace sdfdetail
{

namespace
{
struct PosHash
{
  std::size_t operator()(const Vec3f& p) const
  {
    std::uint32_t b[3];
    std::memcpy(b, p.data(), sizeof(b));
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t v : b)
    {
      h = (h ^ v) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

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
  std::unordered_map<Vec3f, std::uint32_t, PosHash> weldMap;
  weldMap.reserve(mesh.points.size());
  std::vector<std::uint32_t> weld(mesh.points.size());
  std::vector<V3> weldPos;
  weldPos.reserve(mesh.points.size());
  auto toV3 = [](const Vec3f& p) { return V3{ p[0], p[1], p[2] }; };
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    const auto ins = weldMap.emplace(mesh.points[i], static_cast<std::uint32_t>(weldMap.size()));
    if (ins.second) weldPos.push_back(toV3(mesh.points[i]));
    weld[i] = ins.first->second;
  }
  const std::size_t nv = weldPos.size();

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

  for (int a = 0; a < 3; ++a)
  {
    out.lo[a] = out.hi[a] = out.tris[0].v[0][a];
  }
  for (const Tri& tri : out.tris)
  {
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        out.lo[a] = std::fmin(out.lo[a], tri.v[k][a]);
        out.hi[a] = std::fmax(out.hi[a], tri.v[k][a]);
      }
    }
  }
  return out;
}

} // namespace sdfdetail
} // namespace lvdif
