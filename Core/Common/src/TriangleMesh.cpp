#include "lvdif/TriangleMesh.h"

#include "lvdif/Error.h"

#include <cmath>
#include <locale>
#include <sstream>

namespace lvdif
{

void TriangleMesh::validate() const
{
  if (this->triangles.empty())
  {
    throw Error(ErrorCode::InvalidArgument, "mesh has no triangles");
  }
  bool tooFar = false;
  for (std::size_t i = 0; i < this->points.size(); ++i)
  {
    for (float c : this->points[i])
    {
      if (!std::isfinite(c))
      {
        std::ostringstream msg;
        msg << "mesh point " << i << " has a NaN or infinite coordinate";
        throw Error(ErrorCode::InvalidArgument, msg.str());
      }
      tooFar = tooFar || !isWorldCoordinate(c);
    }
  }
  if (tooFar)
  {
    // the bounds, not one point: the user sees the mesh's scale (and which axis)
    const auto b = this->bounds();
    std::ostringstream msg;
    msg.imbue(std::locale::classic()); // "1e+30", whatever a host set
    msg << "mesh coordinates span";
    for (int a = 0; a < 3; ++a) msg << (a ? ", " : " ") << "xyz"[a] << " [" << b[0][a] << ", " << b[1][a] << "]";
    msg << ": every coordinate must lie within +-" << MaxWorldCoordinate
        << " (volume positions are floats; scale the mesh down)";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
  for (std::size_t t = 0; t < this->triangles.size(); ++t)
  {
    for (std::uint32_t v : this->triangles[t])
    {
      if (v >= this->points.size())
      {
        std::ostringstream msg;
        msg << "triangle " << t << " refers to point " << v << " but the mesh has " << this->points.size()
            << " points";
        throw Error(ErrorCode::InvalidArgument, msg.str());
      }
    }
  }
  if (!this->normals.empty() && this->normals.size() != this->points.size())
  {
    std::ostringstream msg;
    msg << "mesh has " << this->normals.size() << " normals for " << this->points.size() << " points";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
}

std::array<Vec3f, 2> TriangleMesh::bounds() const
{
  require(!this->points.empty(), "mesh has no points");
  std::array<Vec3f, 2> b{ this->points[0], this->points[0] };
  for (const Vec3f& p : this->points)
  {
    for (int a = 0; a < 3; ++a)
    {
      b[0][a] = std::fmin(b[0][a], p[a]);
      b[1][a] = std::fmax(b[1][a], p[a]);
    }
  }
  return b;
}

std::size_t TriangleMesh::degenerateCount() const
{
  std::size_t n = 0;
  for (const auto& t : this->triangles)
  {
    const Vec3f &a = this->points[t[0]], &b = this->points[t[1]], &c = this->points[t[2]];
    const double u[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
    const double v[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    if (x * x + y * y + z * z == 0.0)
    {
      ++n;
    }
  }
  return n;
}

TriangleMesh makeSphereMesh(float cx, float cy, float cz, float radius, int rings, int segments)
{
  require(rings >= 2 && segments >= 3 && radius > 0, "sphere mesh: rings >= 2, segments >= 3, radius > 0");
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  m.points.push_back({ cx, cy, cz + radius }); // north pole
  for (int i = 1; i < rings; ++i)
  {
    const double th = pi * i / rings;
    for (int j = 0; j < segments; ++j)
    {
      const double ph = 2 * pi * j / segments;
      m.points.push_back({ static_cast<float>(cx + radius * std::sin(th) * std::cos(ph)),
        static_cast<float>(cy + radius * std::sin(th) * std::sin(ph)),
        static_cast<float>(cz + radius * std::cos(th)) });
    }
  }
  m.points.push_back({ cx, cy, cz - radius }); // south pole
  const std::uint32_t south = static_cast<std::uint32_t>(m.points.size() - 1);
  auto ring = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j)
  {
    m.triangles.push_back({ 0, ring(1, j), ring(1, j + 1) });
  }
  for (int i = 1; i < rings - 1; ++i)
  {
    for (int j = 0; j < segments; ++j)
    {
      m.triangles.push_back({ ring(i, j), ring(i + 1, j), ring(i + 1, j + 1) });
      m.triangles.push_back({ ring(i, j), ring(i + 1, j + 1), ring(i, j + 1) });
    }
  }
  for (int j = 0; j < segments; ++j)
  {
    m.triangles.push_back({ ring(rings - 1, j), south, ring(rings - 1, j + 1) });
  }
  return m;
}

TriangleMesh makeBoxMesh(Vec3f lo, Vec3f hi)
{
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
  {
    m.points.push_back({ (i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2] });
  }
  // outward, counter-clockwise seen from outside
  const std::uint32_t f[12][3] = { { 0, 2, 1 }, { 1, 2, 3 }, { 4, 5, 6 }, { 5, 7, 6 }, { 0, 1, 4 }, { 1, 5, 4 },
    { 2, 6, 3 }, { 3, 6, 7 }, { 0, 4, 2 }, { 2, 4, 6 }, { 1, 3, 5 }, { 3, 7, 5 } };
  for (auto& t : f)
  {
    m.triangles.push_back({ t[0], t[1], t[2] });
  }
  return m;
}

} // namespace lvdif
