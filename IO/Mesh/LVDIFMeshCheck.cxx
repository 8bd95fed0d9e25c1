#include "LVDIFMeshCheck.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace lvdif_mesh_check
{
namespace
{
using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

std::int64_t findRoot(std::vector<std::int64_t>& parent, std::int64_t i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

/// Representative of every vertex after welding (union of pairs within tol).
std::vector<std::int64_t> weldMap(const lvdif::TriangleMesh& mesh, double tol)
{
  const std::int64_t n = static_cast<std::int64_t>(mesh.points.size());
  std::vector<std::int64_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  if (tol <= 0)
    return parent;
  auto cell = [tol](double v) { return static_cast<std::int64_t>(std::floor(v / tol)); };
  std::map<std::array<std::int64_t, 3>, std::vector<std::int64_t>> grid;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const auto& p = mesh.points[i];
    grid[{ cell(p[0]), cell(p[1]), cell(p[2]) }].push_back(i);
  }
  const double tol2 = tol * tol;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const auto& p = mesh.points[i];
    const std::array<std::int64_t, 3> c{ cell(p[0]), cell(p[1]), cell(p[2]) };
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          auto it = grid.find({ c[0] + dx, c[1] + dy, c[2] + dz });
          if (it == grid.end())
            continue;
          for (std::int64_t j : it->second)
          {
            if (j <= i)
              continue;
            const auto& q = mesh.points[j];
            const double ex = double(p[0]) - q[0], ey = double(p[1]) - q[1], ez = double(p[2]) - q[2];
            if (ex * ex + ey * ey + ez * ez <= tol2)
            {
              const std::int64_t a = findRoot(parent, i), b = findRoot(parent, j);
              if (a != b)
                parent[std::max(a, b)] = std::min(a, b);
            }
          }
        }
  }
  for (std::int64_t i = 0; i < n; ++i)
    parent[i] = findRoot(parent, i);
  return parent;
}

bool zeroArea(const lvdif::TriangleMesh& m, const std::array<std::uint32_t, 3>& t)
{
  const auto &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
  const double u[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
  const double v[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return x == 0 && y == 0 && z == 0;
}
} // namespace

std::string Report::summary() const
{
  std::ostringstream s;
  s << vertices << " vertices (" << weldedVertices << " welded), " << inputFaces << " faces: " << boundaryEdges
    << " boundary edges, " << nonManifoldEdges << " non-manifold edges, " << nonManifoldVertices
    << " non-manifold vertices, " << refusedFaces << " faces refused by OpenMesh, " << duplicatedFaces
    << " duplicated faces, " << degenerateFaces << " degenerate faces, " << components << " connected components";
  return s.str();
}

Report check(lvdif::TriangleMesh& mesh, double weldTolerance)
{
  Report r;
  r.inputVertices = static_cast<std::int64_t>(mesh.points.size());
  r.inputFaces = static_cast<std::int64_t>(mesh.triangles.size());

  // 1. weld: renumber representatives densely, in input order
  if (weldTolerance > 0)
  {
    const std::vector<std::int64_t> rep = weldMap(mesh, weldTolerance);
    std::vector<std::int64_t> newIndex(rep.size(), -1);
    std::vector<lvdif::Vec3f> points;
    for (std::size_t i = 0; i < rep.size(); ++i)
      if (rep[i] == static_cast<std::int64_t>(i))
      {
        newIndex[i] = static_cast<std::int64_t>(points.size());
        points.push_back(mesh.points[i]);
      }
    for (auto& t : mesh.triangles)
      for (auto& c : t)
        c = static_cast<std::uint32_t>(newIndex[rep[c]]);
    mesh.points = std::move(points);
    mesh.normals.clear();
  }
  r.vertices = static_cast<std::int64_t>(mesh.points.size());
  r.weldedVertices = r.inputVertices - r.vertices;

  // 2. degenerate and duplicated faces; undirected edge uses of the kept faces
  std::vector<std::array<std::uint32_t, 3>> kept;
  std::set<std::array<std::uint32_t, 3>> seen;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUses;
  for (const auto& t : mesh.triangles)
  {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || zeroArea(mesh, t))
    {
      ++r.degenerateFaces;
      continue;
    }
    std::array<std::uint32_t, 3> key = t;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second)
    {
      ++r.duplicatedFaces;
      continue;
    }
    kept.push_back(t);
    for (int e = 0; e < 3; ++e)
    {
      const std::uint32_t a = t[e], b = t[(e + 1) % 3];
      ++edgeUses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  for (const auto& eu : edgeUses)
  {
    r.boundaryEdges += eu.second == 1;
    r.nonManifoldEdges += eu.second > 2;
  }

  // 3. OpenMesh: add_face refusals, non-manifold vertices, components
  OMesh om;
  std::vector<OMesh::VertexHandle> vh(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    vh[i] = om.add_vertex(OMesh::Point(mesh.points[i][0], mesh.points[i][1], mesh.points[i][2]));
  const bool wasEnabled = omerr().is_enabled();
  omerr().disable(); // add_face prints "complex edge" for each refusal
  for (const auto& t : kept)
  {
    if (!om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid())
      ++r.refusedFaces;
  }
  if (wasEnabled)
    omerr().enable();
  for (auto v : om.vertices())
  {
    if (!om.is_isolated(v) && !om.is_manifold(v))
      ++r.nonManifoldVertices;
  }
  std::vector<std::int64_t> parent(om.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  for (auto f : om.faces())
  {
    std::vector<int> ids;
    for (auto v : om.fv_range(f))
      ids.push_back(v.idx());
    for (std::size_t k = 1; k < ids.size(); ++k)
    {
      const std::int64_t a = findRoot(parent, ids[0]), b = findRoot(parent, ids[k]);
      if (a != b)
        parent[std::max(a, b)] = std::min(a, b);
    }
  }
  for (auto v : om.vertices())
    r.components += !om.is_isolated(v) && findRoot(parent, v.idx()) == v.idx();
  return r;
}
} // namespace lvdif_mesh_check
