// OBJ, OFF and STL readers and the format dispatch (PLY: MeshFilePly.cpp).
#include "lvdif/MeshFile.h"

#include "MeshFileDetail.h"

#include "lvdif/Memory.h"

#include <algorithm>
#include <cctype>
#include <unordered_map>

namespace lvdif
{

namespace
{
using namespace detail::volumefile::meshfile;

/// OBJ (Wavefront): v, f with i, i/t, i//n, i/t/n and negative (relative)
/// indices; other statements (vn, vt, g, o, s, usemtl, l, ...) are skipped.
TriangleMesh readObj(const std::vector<char>& data)
{
  TextScanner s(data.data(), data.size(), "OBJ");
  TriangleMesh mesh;
  std::vector<std::string> t;
  std::vector<std::int64_t> ids;
  while (s.next(t))
  {
    if (t.empty())
      continue;
    if (t[0] == "v")
    {
      if (t.size() < 4)
        fail(ErrorCode::ParseError, s.where(), "vertex with fewer than 3 coordinates");
      mesh.points.push_back(
        point(parseReal(t[1], s.where()), parseReal(t[2], s.where()), parseReal(t[3], s.where()), s.where()));
    }
    else if (t[0] == "f")
    {
      ids.clear();
      const std::int64_t n = static_cast<std::int64_t>(mesh.points.size());
      for (std::size_t i = 1; i < t.size(); ++i)
      {
        const std::int64_t v = parseInt(t[i].substr(0, t[i].find('/')), s.where());
        if (v == 0)
          fail(ErrorCode::ParseError, s.where(), "vertex index 0 (OBJ indices start at 1)");
        ids.push_back(v > 0 ? v - 1 : n + v); // negative: relative to the last vertex
      }
      addPolygon(mesh, ids, n, s.where(), ErrorCode::ParseError);
    }
  }
  finish(mesh, "OBJ");
  return mesh;
}

/// OFF (Geomview): [C|N|CN]OFF header, counts, vertices, faces "n i1 .. in [colour]".
TriangleMesh readOff(const std::vector<char>& data)
{
  TextScanner s(data.data(), data.size(), "OFF");
  std::vector<std::string> t;
  if (!s.nextNonEmpty(t) || t[0].size() < 3 || t[0].compare(t[0].size() - 3, 3, "OFF") != 0)
    fail(ErrorCode::ParseError, "OFF line 1", "missing the OFF header");
  t.erase(t.begin()); // counts may follow on the same line
  if (t.empty() && !s.nextNonEmpty(t))
    fail(ErrorCode::ParseError, s.where(), "missing the vertex and face counts");
  if (t.size() < 2)
    fail(ErrorCode::ParseError, s.where(), "expected vertex, face (and edge) counts");
  const std::int64_t nv = parseInt(t[0], s.where()), nf = parseInt(t[1], s.where());
  // every vertex needs at least 6 bytes ("0 0 0\n"), every face 8 ("3 0 1 2\n")
  if (nv < 0 || nf < 0 || nv > std::int64_t(s.remaining() / 6) || nf > std::int64_t(s.remaining() / 8) ||
    nv > std::int64_t(UINT32_MAX))
    fail(ErrorCode::ParseError, s.where(),
      std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces cannot fit in the rest of the file");
  TriangleMesh mesh;
  mesh.points.reserve(static_cast<size_t>(nv));
  for (std::int64_t i = 0; i < nv; ++i)
  {
    if (!s.nextNonEmpty(t))
      fail(ErrorCode::ParseError, s.where(), "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    if (t.size() < 3)
      fail(ErrorCode::ParseError, s.where(), "vertex with fewer than 3 coordinates");
    mesh.points.push_back(point(parseReal(t[0], s.where()), parseReal(t[1], s.where()), parseReal(t[2], s.where()), s.where()));
  }
  std::vector<std::int64_t> ids;
  for (std::int64_t f = 0; f < nf; ++f)
  {
    if (!s.nextNonEmpty(t))
      fail(ErrorCode::ParseError, s.where(), "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::int64_t k = parseInt(t[0], s.where());
    if (k < 0 || k > std::int64_t(t.size()) - 1)
      fail(ErrorCode::ParseError, s.where(), "face announces " + std::to_string(k) + " vertices but lists " + std::to_string(t.size() - 1));
    ids.clear();
    for (std::int64_t i = 1; i <= k; ++i)
      ids.push_back(parseInt(t[static_cast<size_t>(i)], s.where()));
    addPolygon(mesh, ids, nv, s.where(), ErrorCode::ParseError);
  }
  finish(mesh, "OFF");
  return mesh;
}

/// Adds a corner to an STL mesh, sharing bit-identical points.
struct PointMerger
{
  std::unordered_map<std::string, std::uint32_t> index;
  std::uint32_t add(TriangleMesh& mesh, const Vec3f& p)
  {
    const std::string key(reinterpret_cast<const char*>(p.data()), sizeof(Vec3f));
    auto it = index.emplace(key, static_cast<std::uint32_t>(mesh.points.size()));
    if (it.second)
      mesh.points.push_back(p);
    return it.first->second;
  }
};

float readLeFloat(const unsigned char* p)
{
  const std::uint32_t u = p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

TriangleMesh readStl(const std::vector<char>& data)
{
  TriangleMesh mesh;
  PointMerger merge;
  const auto* u = reinterpret_cast<const unsigned char*>(data.data());
  if (data.size() >= 84)
  {
    const std::uint64_t n = u[80] | (u[81] << 8) | (u[82] << 16) | (std::uint64_t(u[83]) << 24);
    if (84 + 50 * n == data.size())
    {
      mesh.triangles.reserve(static_cast<size_t>(n));
      for (std::uint64_t i = 0; i < n; ++i)
      {
        const unsigned char* r = u + 84 + 50 * i + 12; // skip the facet normal
        std::array<std::uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c)
        {
          const std::string where = "STL triangle " + std::to_string(i);
          tri[c] = merge.add(mesh, point(readLeFloat(r + 12 * c), readLeFloat(r + 12 * c + 4), readLeFloat(r + 12 * c + 8), where));
        }
        mesh.triangles.push_back(tri);
      }
      finish(mesh, "STL");
      return mesh;
    }
  }
  // ASCII: solid / facet normal / outer loop / vertex x3 / endloop / endfacet / endsolid
  TextScanner s(data.data(), data.size(), "STL");
  std::vector<std::string> t;
  if (!s.nextNonEmpty(t) || t[0] != "solid")
    fail(ErrorCode::CorruptData, "STL", "neither a binary STL (size is not 84 + 50 x triangle count) nor an ASCII one (no 'solid')");
  std::vector<std::uint32_t> corners;
  while (s.nextNonEmpty(t))
  {
    if (t[0] == "vertex")
    {
      if (t.size() != 4)
        fail(ErrorCode::ParseError, s.where(), "vertex needs 3 coordinates");
      corners.push_back(merge.add(mesh, point(parseReal(t[1], s.where()), parseReal(t[2], s.where()), parseReal(t[3], s.where()), s.where())));
    }
    else if (t[0] == "endloop")
    {
      if (corners.size() != 3)
        fail(ErrorCode::ParseError, s.where(), "facet with " + std::to_string(corners.size()) + " vertices (STL facets have 3)");
      mesh.triangles.push_back({ corners[0], corners[1], corners[2] });
      corners.clear();
    }
    else if (t[0] != "facet" && t[0] != "outer" && t[0] != "endfacet" && t[0] != "endsolid" && t[0] != "solid")
      fail(ErrorCode::ParseError, s.where(), "unexpected '" + t[0].substr(0, 40) + "'");
  }
  if (!corners.empty())
    fail(ErrorCode::ParseError, s.where(), "file ends inside a facet");
  finish(mesh, "STL");
  return mesh;
}
} // namespace

MeshFormat meshFormatFromName(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "off") return MeshFormat::Off;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "ply") return MeshFormat::Ply;
  throw Error(ErrorCode::InvalidArgument, "unknown mesh file type '" + path + "' (expected .obj, .off, .stl or .ply)");
}

TriangleMesh readMesh(ByteSource& source, MeshFormat format, const std::string& name)
{
  if (format == MeshFormat::Auto)
    format = meshFormatFromName(name);
  const std::uint64_t size = source.size();
  // the text and the mesh together take a few times the file size
  requireMemory(checkedMultiply(size, 4, "mesh file"), "reading the mesh file " + name);
  std::vector<char> data(static_cast<size_t>(size));
  source.read(0, data.data(), data.size());
  switch (format)
  {
    case MeshFormat::Obj: return readObj(data);
    case MeshFormat::Off: return readOff(data);
    case MeshFormat::Stl: return readStl(data);
    case MeshFormat::Ply: return detail::volumefile::meshfile::readPly(data);
    default: break;
  }
  throw Error(ErrorCode::InvalidArgument, "no mesh format given");
}

TriangleMesh loadMesh(const std::string& path, MeshFormat format)
{
  FileSource src(path);
  return readMesh(src, format, path);
}

} // namespace lvdif
