// PLY and OFF readers (see MeshReaders.h). PLY after Turk's format
// description (1994): a text header of elements with scalar and list
// properties, then the data in ascii or binary of either byte order.
#include "lvdif/MeshReaders.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace lvdif
{

namespace
{
[[noreturn]] void corrupt(const std::string& path, const std::string& what)
{
  throw Error(ErrorCode::CorruptData, path + ": " + what);
}

std::vector<char> slurp(const std::string& path)
{
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f)
  {
    throw Error(ErrorCode::IoFailure, "cannot open " + path);
  }
  const std::streamoff size = f.tellg();
  requireMemory(static_cast<std::uint64_t>(size), "reading " + path);
  std::vector<char> data(static_cast<std::size_t>(size));
  f.seekg(0);
  if (size > 0 && !f.read(data.data(), size))
  {
    throw Error(ErrorCode::IoFailure, "cannot read " + path);
  }
  return data;
}

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64, None };

Type parseType(const std::string& s)
{
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  return Type::None;
}

int typeSize(Type t)
{
  switch (t)
  {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    case Type::F64: return 8;
    default: return 0;
  }
}

struct Property
{
  std::string name;
  Type type = Type::None;
  Type countType = Type::None; // list properties only
  bool list() const { return this->countType != Type::None; }
};

struct Element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
};

/// Reads scalars from the body in ascii or binary.
class Body
{
public:
  Body(const std::string& path, const std::vector<char>& data, std::size_t pos, int format)
    : Path(path), Data(data), Pos(pos), Format(format)
  {
  }

  double read(Type t, const char* what)
  {
    if (this->Format == 0)
    {
      return this->readAscii(what);
    }
    const int n = typeSize(t);
    if (this->Pos + static_cast<std::size_t>(n) > this->Data.size())
    {
      corrupt(this->Path, std::string("unexpected end of file in ") + what);
    }
    unsigned char b[8];
    std::memcpy(b, this->Data.data() + this->Pos, static_cast<std::size_t>(n));
    this->Pos += static_cast<std::size_t>(n);
    if (this->Format == 2) std::reverse(b, b + n); // big endian (hosts are little endian)
    switch (t)
    {
      case Type::I8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case Type::U8: return b[0];
      case Type::I16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::U16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::I32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::U32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::F32: { float v; std::memcpy(&v, b, 4); return v; }
      case Type::F64: { double v; std::memcpy(&v, b, 8); return v; }
      default: corrupt(this->Path, "bad property type");
    }
  }

  std::size_t remaining() const { return this->Data.size() - this->Pos; }

private:
  double readAscii(const char* what)
  {
    while (this->Pos < this->Data.size() && std::isspace(static_cast<unsigned char>(this->Data[this->Pos])))
    {
      ++this->Pos;
    }
    std::size_t end = this->Pos;
    while (end < this->Data.size() && !std::isspace(static_cast<unsigned char>(this->Data[end])))
    {
      ++end;
    }
    if (end == this->Pos)
    {
      corrupt(this->Path, std::string("unexpected end of file in ") + what);
    }
    const std::string tok(this->Data.data() + this->Pos, end - this->Pos);
    this->Pos = end;
    char* stop = nullptr;
    const double v = std::strtod(tok.c_str(), &stop);
    if (stop == tok.c_str() || *stop != '\0')
    {
      corrupt(this->Path, std::string("not a number '") + tok + "' in " + what);
    }
    return v;
  }

  const std::string& Path;
  const std::vector<char>& Data;
  std::size_t Pos;
  int Format; // 0 ascii, 1 binary little endian, 2 binary big endian
};

std::uint32_t checkedIndex(const std::string& path, double v, std::size_t nv, std::uint64_t face)
{
  if (!(v >= 0) || v != std::floor(v) || v >= static_cast<double>(nv))
  {
    std::ostringstream m;
    m << "face " << face << " refers to vertex " << v << " but there are " << nv << " vertices";
    corrupt(path, m.str());
  }
  return static_cast<std::uint32_t>(v);
}

void addPolygon(const std::string& path, TriangleMesh& m, const std::vector<std::uint32_t>& poly, std::uint64_t face)
{
  if (poly.size() < 3)
  {
    corrupt(path, "face " + std::to_string(face) + " has fewer than 3 vertices");
  }
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
  {
    m.triangles.push_back({ poly[0], poly[k], poly[k + 1] });
  }
}

void checkFinite(const std::string& path, const Vec3f& p, std::size_t i)
{
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
  {
    corrupt(path, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
}
} // namespace

TriangleMesh readPly(const std::string& path)
{
  const std::vector<char> data = slurp(path);
  // header: lines up to "end_header"
  std::size_t pos = 0;
  auto nextLine = [&]() -> std::string {
    const std::size_t start = pos;
    while (pos < data.size() && data[pos] != '\n') ++pos;
    if (pos >= data.size()) corrupt(path, "PLY header has no end_header");
    std::string line(data.data() + start, pos - start);
    ++pos;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  };
  if (nextLine() != "ply") corrupt(path, "not a PLY file (first line is not 'ply')");
  int format = -1;
  std::vector<Element> elements;
  for (int lines = 0;; ++lines)
  {
    if (lines > 10000) corrupt(path, "PLY header too long");
    std::istringstream ls(nextLine());
    std::string word;
    ls >> word;
    if (word == "end_header") break;
    if (word == "comment" || word == "obj_info" || word.empty()) continue;
    if (word == "format")
    {
      std::string f, version;
      ls >> f >> version;
      format = f == "ascii" ? 0 : f == "binary_little_endian" ? 1 : f == "binary_big_endian" ? 2 : -1;
      if (format < 0) corrupt(path, "unknown PLY format '" + f + "'");
    }
    else if (word == "element")
    {
      Element e;
      std::string count;
      ls >> e.name >> count;
      char* stop = nullptr;
      const unsigned long long c = std::strtoull(count.c_str(), &stop, 10);
      if (count.empty() || *stop != '\0' || count[0] == '-') corrupt(path, "bad count for element " + e.name);
      e.count = c;
      elements.push_back(e);
    }
    else if (word == "property")
    {
      if (elements.empty()) corrupt(path, "PLY property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list")
      {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.countType = parseType(ct);
        p.type = parseType(it);
        if (p.countType == Type::None || p.type == Type::None) corrupt(path, "bad list property types");
      }
      else
      {
        p.type = parseType(t);
        ls >> p.name;
        if (p.type == Type::None) corrupt(path, "unknown property type '" + t + "'");
      }
      elements.back().props.push_back(p);
    }
    else
    {
      corrupt(path, "unknown PLY header line starting with '" + word + "'");
    }
  }
  if (format < 0) corrupt(path, "PLY header has no format line");

  Body body(path, data, pos, format);
  TriangleMesh mesh;
  bool haveVertices = false, haveFaces = false;
  for (const Element& e : elements)
  {
    // every item takes at least one byte in any format: refuse counts the file cannot hold
    if (e.count > body.remaining())
    {
      corrupt(path, "element " + e.name + " claims " + std::to_string(e.count) + " items, more than the file holds");
    }
    if (e.name == "vertex")
    {
      int ix[3] = { -1, -1, -1 }, in[3] = { -1, -1, -1 };
      for (std::size_t k = 0; k < e.props.size(); ++k)
      {
        const std::string& n = e.props[k].name;
        for (int a = 0; a < 3; ++a)
        {
          if (n == std::string(1, "xyz"[a])) ix[a] = static_cast<int>(k);
          if (n == std::string("n") + "xyz"[a]) in[a] = static_cast<int>(k);
        }
      }
      if (ix[0] < 0 || ix[1] < 0 || ix[2] < 0) corrupt(path, "vertex element lacks x, y or z");
      const bool normals = in[0] >= 0 && in[1] >= 0 && in[2] >= 0;
      mesh.points.resize(static_cast<std::size_t>(e.count));
      if (normals) mesh.normals.resize(static_cast<std::size_t>(e.count));
      std::vector<double> vals(e.props.size());
      for (std::uint64_t i = 0; i < e.count; ++i)
      {
        for (std::size_t k = 0; k < e.props.size(); ++k)
        {
          const Property& p = e.props[k];
          if (p.list())
          {
            const double n = body.read(p.countType, "vertex list");
            for (double c = 0; c < n; ++c) body.read(p.type, "vertex list");
            continue;
          }
          vals[k] = body.read(p.type, "vertex");
        }
        for (int a = 0; a < 3; ++a)
        {
          mesh.points[i][a] = static_cast<float>(vals[ix[a]]);
          if (normals) mesh.normals[i][a] = static_cast<float>(vals[in[a]]);
        }
        checkFinite(path, mesh.points[i], static_cast<std::size_t>(i));
      }
      haveVertices = true;
    }
    else if (e.name == "face")
    {
      if (!haveVertices) corrupt(path, "face element before the vertex element");
      mesh.triangles.reserve(static_cast<std::size_t>(e.count));
      std::vector<std::uint32_t> poly;
      for (std::uint64_t f = 0; f < e.count; ++f)
      {
        for (const Property& p : e.props)
        {
          if (!p.list())
          {
            body.read(p.type, "face");
            continue;
          }
          const double n = body.read(p.countType, "face");
          if (!(n >= 0) || n > 1e6) corrupt(path, "face " + std::to_string(f) + " has a bad vertex count");
          const bool indices = p.name == "vertex_indices" || p.name == "vertex_index";
          poly.clear();
          for (int c = 0; c < static_cast<int>(n); ++c)
          {
            const double v = body.read(p.type, "face");
            if (indices) poly.push_back(checkedIndex(path, v, mesh.points.size(), f));
          }
          if (indices) addPolygon(path, mesh, poly, f);
        }
      }
      haveFaces = true;
    }
    else
    {
      for (std::uint64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props)
        {
          if (p.list())
          {
            const double n = body.read(p.countType, e.name.c_str());
            if (!(n >= 0) || n > 1e6) corrupt(path, "bad list count in element " + e.name);
            for (int c = 0; c < static_cast<int>(n); ++c) body.read(p.type, e.name.c_str());
          }
          else
          {
            body.read(p.type, e.name.c_str());
          }
        }
    }
  }
  if (!haveVertices || !haveFaces || mesh.triangles.empty()) corrupt(path, "PLY file has no vertices or no faces");
  return mesh;
}

TriangleMesh readOff(const std::string& path)
{
  const std::vector<char> data = slurp(path);
  std::string text(data.begin(), data.end());
  // strip comments
  std::string clean;
  clean.reserve(text.size());
  bool comment = false;
  for (char c : text)
  {
    if (c == '#') comment = true;
    if (c == '\n') comment = false;
    clean.push_back(comment ? ' ' : c);
  }
  std::vector<char> cleanData(clean.begin(), clean.end());
  std::size_t pos = 0;
  while (pos < cleanData.size() && std::isspace(static_cast<unsigned char>(cleanData[pos]))) ++pos;
  if (clean.compare(pos, 3, "OFF") != 0) corrupt(path, "not an OFF file (no OFF keyword)");
  pos += 3;
  Body body(path, cleanData, pos, 0);
  const double nv = body.read(Type::F64, "OFF counts"), nf = body.read(Type::F64, "OFF counts");
  body.read(Type::F64, "OFF counts");
  if (!(nv >= 0) || !(nf >= 0) || nv != std::floor(nv) || nf != std::floor(nf) ||
    nv * 3 > static_cast<double>(body.remaining()) || nf > static_cast<double>(body.remaining()))
  {
    corrupt(path, "OFF vertex or face count is invalid or larger than the file");
  }
  TriangleMesh mesh;
  mesh.points.resize(static_cast<std::size_t>(nv));
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    for (int a = 0; a < 3; ++a) mesh.points[i][a] = static_cast<float>(body.read(Type::F64, "OFF vertex"));
    checkFinite(path, mesh.points[i], i);
  }
  std::vector<std::uint32_t> poly;
  for (std::uint64_t f = 0; f < static_cast<std::uint64_t>(nf); ++f)
  {
    const double n = body.read(Type::F64, "OFF face");
    if (!(n >= 0) || n > 1e6 || n != std::floor(n)) corrupt(path, "face " + std::to_string(f) + " has a bad vertex count");
    poly.clear();
    for (int c = 0; c < static_cast<int>(n); ++c)
    {
      poly.push_back(checkedIndex(path, body.read(Type::F64, "OFF face"), mesh.points.size(), f));
    }
    addPolygon(path, mesh, poly, f);
  }
  if (mesh.triangles.empty()) corrupt(path, "OFF file has no faces");
  return mesh;
}

TriangleMesh readMesh(const std::string& path)
{
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".ply") return readPly(path);
  if (ext == ".off") return readOff(path);
  throw Error(ErrorCode::Unsupported, "unknown mesh file type: " + path + " (supported: .ply, .off)");
}

} // namespace lvdif
