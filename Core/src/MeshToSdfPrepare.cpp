// Mesh preparation for mesh to SDF: validation, degenerate triangles skipped
// and counted, face normals, angle-weighted pseudo-normals (Baerentzen &
// Aanaes, "Signed distance computation using the angle weighted
// pseudonormal", IEEE TVCG 2005) and the boundary chain used to bound the
// gradient of the winding number (MeshToSdf.cpp).
#include "MeshToSdfInternal.h"

#include "lvdif/Error.h"

#include <cmath>
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

  // Weld by exact position so pseudo-normals and the boundary chain see the
  // surface's topology even in a soup with duplicated points.
  std::unordered_map<Vec3f, std::uint32_t, PosHash> weldMap;
  std::vector<std::uint32_t> weld(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    weld[i] = weldMap.emplace(mesh.points[i], static_cast<std::uint32_t>(weldMap.size())).first->second;
  }

  auto toV3 = [](const Vec3f& p) { return V3{ p[0], p[1], p[2] }; };
  std::vector<V3> vertexNormal(weldMap.size());
  std::unordered_map<std::uint64_t, V3> edgeNormal;
  std::unordered_map<std::uint64_t, int> edgeMultiplicity;
  auto edgeKey = [](std::uint32_t a, std::uint32_t b) {
    return a < b ? (static_cast<std::uint64_t>(a) << 32) | b : (static_cast<std::uint64_t>(b) << 32) | a;
  };

  std::vector<std::array<std::uint32_t, 3>> welded;
  out.tris.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& ix = mesh.triangles[t];
    Tri tri;
    for (int k = 0; k < 3; ++k)
    {
      tri.v[k] = toV3(mesh.points[ix[k]]);
    }
    const V3 c = cross(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]);
    const double len = norm(c);
    if (!(len > 0))
    {
      ++out.degenerate;
      continue;
    }
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
    const std::array<std::uint32_t, 3> w{ weld[ix[0]], weld[ix[1]], weld[ix[2]] };
    for (int k = 0; k < 3; ++k)
    {
      const double ang = angleAt(tri.v[k], tri.v[(k + 1) % 3], tri.v[(k + 2) % 3]);
      vertexNormal[w[k]] = vertexNormal[w[k]] + ang * tri.n;
      const std::uint32_t a = w[k], b = w[(k + 1) % 3];
      V3& en = edgeNormal[edgeKey(a, b)];
      en = en + tri.n;
      edgeMultiplicity[edgeKey(a, b)] += a < b ? 1 : -1;
    }
    welded.push_back(w);
    out.tris.push_back(tri);
  }
  require(!out.tris.empty(), "mesh has no triangle of non-zero area (" + std::to_string(out.degenerate) +
      " degenerate triangles)");

  for (std::size_t t = 0; t < out.tris.size(); ++t)
  {
    Tri& tri = out.tris[t];
    const auto& w = welded[t];
    for (int k = 0; k < 3; ++k)
    {
      tri.vn[k] = normalized(vertexNormal[w[k]]);
      tri.en[k] = normalized(edgeNormal[edgeKey(w[k], w[(k + 1) % 3])]);
      // a pseudo-normal that cancels (e.g. a face and its flipped duplicate)
      // falls back to the face normal: the sign there is ambiguous anyway
      if (dot(tri.vn[k], tri.vn[k]) == 0) tri.vn[k] = tri.n;
      if (dot(tri.en[k], tri.en[k]) == 0) tri.en[k] = tri.n;
    }
  }

  // boundary chain: edges whose oriented multiplicities do not cancel
  std::unordered_map<std::uint32_t, V3> pos;
  for (std::size_t t = 0; t < out.tris.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      pos[welded[t][k]] = out.tris[t].v[k];
    }
  }
  for (const auto& e : edgeMultiplicity)
  {
    if (e.second != 0)
    {
      const V3 a = pos[static_cast<std::uint32_t>(e.first >> 32)];
      const V3 b = pos[static_cast<std::uint32_t>(e.first & 0xffffffffu)];
      out.boundaryLength += std::abs(e.second) * norm(b - a);
      ++out.boundaryEdges;
      for (int k = 0; k < std::abs(e.second); ++k)
      {
        // key (lo, hi) with positive multiplicity means lo -> hi
        out.boundary.push_back(e.second > 0 ? std::array<V3, 2>{ a, b } : std::array<V3, 2>{ b, a });
      }
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
