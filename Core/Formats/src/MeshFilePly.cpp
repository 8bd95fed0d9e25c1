// PLY reader (Turk's polygon file format): ASCII, binary_little_endian and
// binary_big_endian; any elements and properties (those not needed are
// skipped), vertex x/y/z of any numeric type, face lists named
// vertex_indices or vertex_index. Every count is checked against the bytes
// left before anything is allocated.
#include "MeshFileDetail.h"

namespace lvdif
{
namespace detail::volumefile::meshfile
{

namespace
{
enum class Encoding
{
  Ascii,
  LittleEndian,
  BigEndian
};

struct Property
{
  std::string name;
  int type = 0;      // size in bytes of the value (or the list's items); sign/float in kind
  char kind = 'i';   // 'i' signed, 'u' unsigned, 'f' float
  bool list = false;
  int countType = 0; // size of a list's count
  char countKind = 'u';
};

struct Element
{
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
};

bool scalarType(const std::string& t, int& size, char& kind)
{
  static const struct { const char* name; int size; char kind; } types[] = { { "char", 1, 'i' }, { "int8", 1, 'i' },
    { "uchar", 1, 'u' }, { "uint8", 1, 'u' }, { "short", 2, 'i' }, { "int16", 2, 'i' }, { "ushort", 2, 'u' },
    { "uint16", 2, 'u' }, { "int", 4, 'i' }, { "int32", 4, 'i' }, { "uint", 4, 'u' }, { "uint32", 4, 'u' },
    { "float", 4, 'f' }, { "float32", 4, 'f' }, { "double", 8, 'f' }, { "float64", 8, 'f' } };
  for (const auto& ty : types)
    if (t == ty.name)
    {
      size = ty.size;
      kind = ty.kind;
      return true;
    }
  return false;
}

/// Reads values from the binary body, bounds-checked.
struct BinaryReader
{
  const unsigned char* p;
  const unsigned char* end;
  bool bigEndian;
  std::string element;
  double value(int size, char kind)
  {
    if (end - p < size)
      fail(ErrorCode::CorruptData, "PLY " + element, "file ends inside the element data");
    unsigned char b[8];
    for (int i = 0; i < size; ++i)
      b[i] = bigEndian ? p[size - 1 - i] : p[i];
    p += size;
    std::uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i)
      u = (u << 8) | b[i];
    if (kind == 'f')
    {
      if (size == 4)
      {
        float f;
        const std::uint32_t w = static_cast<std::uint32_t>(u);
        std::memcpy(&f, &w, 4);
        return f;
      }
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
    if (kind == 'u')
      return static_cast<double>(u);
    const int shift = 64 - 8 * size; // sign-extend
    return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
  }
};
} // namespace

TriangleMesh readPly(const std::vector<char>& data)
{
  TextScanner s(data.data(), data.size(), "PLY header");
  std::vector<std::string> t;
  if (!s.next(t, false) || t.size() != 1 || t[0] != "ply")
    fail(ErrorCode::ParseError, "PLY line 1", "missing the 'ply' magic line");
  Encoding enc = Encoding::Ascii;
  std::vector<Element> elements;
  bool haveFormat = false, ended = false;
  while (s.next(t, false))
  {
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info")
      continue;
    if (t[0] == "format")
    {
      if (t.size() != 3 || t[2] != "1.0")
        fail(ErrorCode::ParseError, s.where(), "expected 'format <encoding> 1.0'");
      if (t[1] == "ascii") enc = Encoding::Ascii;
      else if (t[1] == "binary_little_endian") enc = Encoding::LittleEndian;
      else if (t[1] == "binary_big_endian") enc = Encoding::BigEndian;
      else fail(ErrorCode::ParseError, s.where(), "unknown encoding '" + t[1].substr(0, 40) + "'");
      haveFormat = true;
    }
    else if (t[0] == "element")
    {
      if (t.size() != 3)
        fail(ErrorCode::ParseError, s.where(), "expected 'element <name> <count>'");
      Element e;
      e.name = t[1];
      e.count = parseInt(t[2], s.where());
      if (e.count < 0)
        fail(ErrorCode::ParseError, s.where(), "negative element count");
      elements.push_back(e);
    }
    else if (t[0] == "property")
    {
      if (elements.empty())
        fail(ErrorCode::ParseError, s.where(), "property before any element");
      Property p;
      if (t.size() == 5 && t[1] == "list")
      {
        p.list = true;
        if (!scalarType(t[2], p.countType, p.countKind) || p.countKind == 'f' || !scalarType(t[3], p.type, p.kind))
          fail(ErrorCode::ParseError, s.where(), "bad list property types");
        p.name = t[4];
      }
      else if (t.size() == 3 && scalarType(t[1], p.type, p.kind))
        p.name = t[2];
      else
        fail(ErrorCode::ParseError, s.where(), "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      elements.back().properties.push_back(p);
    }
    else if (t[0] == "end_header")
    {
      ended = true;
      break;
    }
    else
      fail(ErrorCode::ParseError, s.where(), "unknown header line '" + t[0].substr(0, 40) + "'");
  }
  if (!haveFormat || !ended)
    fail(ErrorCode::ParseError, "PLY header", !haveFormat ? "no format line" : "no end_header");

  // every element record takes at least one byte per property (binary) or two characters (ASCII)
  const std::size_t left = s.remaining();
  std::int64_t vertexCount = -1;
  for (const Element& e : elements)
  {
    const std::int64_t minBytes = std::max<std::int64_t>(1, static_cast<std::int64_t>(e.properties.size()));
    if (e.count > std::int64_t(left) / minBytes)
      fail(ErrorCode::CorruptData, "PLY element '" + e.name.substr(0, 40) + "'",
        std::to_string(e.count) + " records cannot fit in the " + std::to_string(left) + " bytes after the header");
    if (e.name == "vertex")
      vertexCount = e.count;
  }
  if (vertexCount < 0)
    fail(ErrorCode::ParseError, "PLY header", "no vertex element");

  TriangleMesh mesh;
  TextScanner body(s.position(), left, "PLY");
  BinaryReader bin{ reinterpret_cast<const unsigned char*>(s.position()),
    reinterpret_cast<const unsigned char*>(s.position()) + left, enc == Encoding::BigEndian, "" };
  std::vector<std::string> tok;
  std::vector<double> scalars;
  std::vector<std::int64_t> ids;
  for (const Element& e : elements)
  {
    const bool isVertex = e.name == "vertex", isFace = e.name == "face";
    int ix = -1, iy = -1, iz = -1, ilist = -1;
    for (std::size_t i = 0; i < e.properties.size(); ++i)
    {
      const std::string& n = e.properties[i].name;
      if (isVertex && !e.properties[i].list)
      {
        if (n == "x") ix = int(i);
        if (n == "y") iy = int(i);
        if (n == "z") iz = int(i);
      }
      if (isFace && e.properties[i].list && (n == "vertex_indices" || n == "vertex_index"))
        ilist = int(i);
    }
    if (isVertex && (ix < 0 || iy < 0 || iz < 0))
      fail(ErrorCode::ParseError, "PLY header", "vertex element without x, y and z");
    if (isFace && ilist < 0)
      fail(ErrorCode::ParseError, "PLY header", "face element without a vertex_indices list");
    if (isVertex)
      mesh.points.reserve(static_cast<size_t>(e.count));
    bin.element = e.name.substr(0, 40);
    for (std::int64_t r = 0; r < e.count; ++r)
    {
      const std::string where = "PLY " + e.name.substr(0, 40) + " " + std::to_string(r);
      scalars.assign(e.properties.size(), 0.0);
      ids.clear();
      std::size_t at = 0; // token position in ASCII
      if (enc == Encoding::Ascii && !body.nextNonEmpty(tok))
        fail(ErrorCode::ParseError, where, "file ends before this record");
      auto next = [&](int size, char kind) -> double {
        if (enc != Encoding::Ascii)
          return bin.value(size, kind);
        if (at >= tok.size())
          fail(ErrorCode::ParseError, where, "record has too few values");
        const std::string& v = tok[at++];
        return kind == 'f' ? parseReal(v, where) : static_cast<double>(parseInt(v, where));
      };
      for (std::size_t i = 0; i < e.properties.size(); ++i)
      {
        const Property& p = e.properties[i];
        if (!p.list)
        {
          scalars[i] = next(p.type, p.kind);
          continue;
        }
        const double count = next(p.countType, p.countKind);
        if (count < 0 || count > double(left))
          fail(ErrorCode::CorruptData, where, "list of " + std::to_string(static_cast<long long>(count)) + " items");
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k)
        {
          const double v = next(p.type, p.kind);
          if (int(i) == ilist)
          {
            if (v != std::floor(v))
              fail(ErrorCode::CorruptData, where, "vertex index is not an integer");
            ids.push_back(static_cast<std::int64_t>(std::max(-1.0, std::min(v, 1e18))));
          }
        }
      }
      if (enc == Encoding::Ascii && at != tok.size())
        fail(ErrorCode::ParseError, where, "record has " + std::to_string(tok.size() - at) + " values too many");
      if (isVertex)
        mesh.points.push_back(point(scalars[size_t(ix)], scalars[size_t(iy)], scalars[size_t(iz)], where));
      else if (isFace)
        addPolygon(mesh, ids, vertexCount, where, enc == Encoding::Ascii ? ErrorCode::ParseError : ErrorCode::CorruptData);
    }
  }
  finish(mesh, "PLY");
  return mesh;
}

} // namespace detail::volumefile::meshfile
} // namespace lvdif
