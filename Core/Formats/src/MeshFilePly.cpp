// PLY reader (Turk's polygon file format): ASCII, binary_little_endian and
// binary_big_endian; any elements and properties (those not needed are
// skipped), vertex x/y/z of any numeric type, face lists named
// vertex_indices or vertex_index. Every count is checked against the bytes
// left before anything is allocated.
#include "MeshFileDetail.h"

#include <algorithm>

#include <charconv>
#include <system_error>

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

const char* const TypeNames = " (PLY's types: char, uchar, short, ushort, int, uint, float, double, or int8, uint8, "
                              "int16, uint16, int32, uint32, float32, float64)";

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

bool littleEndianHost()
{
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

template <typename T>
double load(const unsigned char* q)
{
  T v;
  std::memcpy(&v, q, sizeof(T));
  return static_cast<double>(v);
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
    if (!bigEndian && littleEndianHost())
    {
      // the common case straight from the bytes (one load, no byte loop)
      const unsigned char* q = p;
      p += size;
      switch (size * 4 + (kind == 'f' ? 0 : kind == 'u' ? 1 : 2))
      {
        case 16: return load<float>(q);
        case 32: return load<double>(q);
        case 5: return load<std::uint8_t>(q);
        case 6: return load<std::int8_t>(q);
        case 9: return load<std::uint16_t>(q);
        case 10: return load<std::int16_t>(q);
        case 17: return load<std::uint32_t>(q);
        case 18: return load<std::int32_t>(q);
        default: p = q; // other sizes: the general path below
      }
    }
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
/// Whether the binary record at `r`'s position reads as a valid face of `e`
/// (every list's count in range and its bytes there, the vertex list's corners
/// 3.. MaxPolygonCorners, each an index in [0, vertexCount)). Reads a copy, so
/// it changes nothing; used only to explain an error.
bool readsAsFace(BinaryReader r, const Element& e, int ilist, std::int64_t vertexCount)
{
  try
  {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
    {
      const Property& p = e.properties[i];
      if (!p.list)
      {
        r.value(p.type, p.kind);
        continue;
      }
      const double count = r.value(p.countType, p.countKind);
      if (count < 0 || count * p.type > double(r.end - r.p) || (int(i) == ilist && (count < 3 || count > double(MaxPolygonCorners))))
        return false;
      for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k)
      {
        const double v = r.value(p.type, p.kind);
        if (int(i) == ilist && !(v >= 0 && v < double(vertexCount) && v == std::floor(v)))
          return false;
      }
    }
  }
  catch (const Error&)
  {
    return false;
  }
  return true;
}
} // namespace

/// An ASCII element on OpenMP threads: vertices whose records are all
/// scalars, or faces whose only property is the index list, every record
/// read as the serial loop reads it (std::from_chars reads a token whole as
/// strtod / strtoll do). False, nothing taken, for anything the serial loop
/// may answer differently or with a message (a '#', a '+' sign, a hex
/// float, a value out of range, a record of another length, a polygon, an
/// index out of range): that loop then reads the element.
bool parallelAscii(const Element& e, bool isVertex, int ix, int iy, int iz, std::int64_t vertexCount,
  TextScanner& body, TriangleMesh& mesh)
{
  if (e.count < 50000) return false; // small: not worth it
  const std::size_t np = e.properties.size();
  if (np > 64) return false;
  for (const Property& p : e.properties)
    if (p.list != !isVertex) return false;
  if (!isVertex && (np != 1 || e.properties[0].kind == 'f')) return false;
  TextScanner probe = body;
  std::vector<const char*> line;
  if (!probe.takeLines(e.count, line)) return false;
  const char* end = probe.end();
  const std::size_t base = isVertex ? mesh.points.size() : mesh.triangles.size();
  if (isVertex) mesh.points.resize(base + static_cast<std::size_t>(e.count));
  else mesh.triangles.resize(base + static_cast<std::size_t>(e.count));
  bool ok = true;
  const double m = 3.4e38; // point()'s range
#pragma omp parallel for schedule(static) reduction(&& : ok)
  for (std::int64_t r = 0; r < e.count; ++r)
  {
    const char* b = line[static_cast<std::size_t>(r)];
    const char* t = nullptr;
    bool good = true;
    if (isVertex)
    {
      double v[3] = { 0, 0, 0 };
      for (std::size_t i = 0; i < np && good; ++i)
      {
        good = nextToken(b, end, t);
        if (!good) break;
        double x = 0;
        if (e.properties[i].kind == 'f')
        {
          const auto res = std::from_chars(t, b, x);
          good = res.ec == std::errc() && res.ptr == b && std::isfinite(x);
        }
        else
        {
          long long k = 0;
          const auto res = std::from_chars(t, b, k);
          good = res.ec == std::errc() && res.ptr == b;
          x = static_cast<double>(k);
        }
        if (int(i) == ix) v[0] = x;
        if (int(i) == iy) v[1] = x;
        if (int(i) == iz) v[2] = x;
      }
      good = good && !nextToken(b, end, t) && std::fabs(v[0]) < m && std::fabs(v[1]) < m && std::fabs(v[2]) < m;
      if (good)
        mesh.points[base + static_cast<std::size_t>(r)] = { static_cast<float>(v[0]), static_cast<float>(v[1]),
          static_cast<float>(v[2]) };
    }
    else
    {
      long long v[4];
      for (int i = 0; i < 4 && good; ++i)
      {
        good = nextToken(b, end, t);
        if (!good) break;
        const auto res = std::from_chars(t, b, v[i]);
        good = res.ec == std::errc() && res.ptr == b;
      }
      good = good && !nextToken(b, end, t) && v[0] == 3 && v[1] >= 0 && v[1] < vertexCount && v[2] >= 0 &&
        v[2] < vertexCount && v[3] >= 0 && v[3] < vertexCount;
      if (good)
        mesh.triangles[base + static_cast<std::size_t>(r)] = { static_cast<std::uint32_t>(v[1]),
          static_cast<std::uint32_t>(v[2]), static_cast<std::uint32_t>(v[3]) };
    }
    ok = ok && good;
  }
  if (!ok)
  {
    if (isVertex) mesh.points.resize(base);
    else mesh.triangles.resize(base);
    return false;
  }
  body = probe;
  return true;
}

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
      else fail(ErrorCode::ParseError, s.where(), "unknown encoding " + quotedText(t[1]));
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
      // a name given twice is a broken header: the reader took the last one
      // (a second 'x' replaced the first; two vertex elements mixed their counts)
      for (const Element& o : elements)
        if (o.name == e.name)
          fail(ErrorCode::ParseError, s.where(), "element " + quotedText(e.name) + " given twice");
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
        // which type is wrong, and why (it was "bad list property types")
        if (!scalarType(t[2], p.countType, p.countKind))
          fail(ErrorCode::ParseError, s.where(), "unknown list count type " + quotedText(t[2]) + TypeNames);
        if (p.countKind == 'f')
          fail(ErrorCode::ParseError, s.where(), "list count type " + quotedText(t[2]) + " is not an integer type");
        if (!scalarType(t[3], p.type, p.kind))
          fail(ErrorCode::ParseError, s.where(), "unknown list item type " + quotedText(t[3]) + TypeNames);
        p.name = t[4];
      }
      else if (t.size() == 3 && scalarType(t[1], p.type, p.kind))
        p.name = t[2];
      else if (t.size() == 3 && t[1] != "list")
        fail(ErrorCode::ParseError, s.where(), "unknown property type " + quotedText(t[1]) + TypeNames);
      else
        fail(ErrorCode::ParseError, s.where(), "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      for (const Property& o : elements.back().properties)
        if (o.name == p.name)
          fail(ErrorCode::ParseError, s.where(),
            "property " + quotedText(p.name) + " of element " + quotedText(elements.back().name) + " given twice");
      elements.back().properties.push_back(p);
    }
    else if (t[0] == "end_header")
    {
      ended = true;
      break;
    }
    else
      fail(ErrorCode::ParseError, s.where(), "unknown header line " + quotedText(t[0]) + binaryHint(t[0]));
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
      fail(ErrorCode::CorruptData, "PLY element " + quotedText(e.name),
        std::to_string(e.count) + " records cannot fit in the " + std::to_string(left) + " bytes after the header");
    if (e.name == "vertex")
      vertexCount = e.count;
  }
  if (vertexCount < 0)
    fail(ErrorCode::ParseError, "PLY header", "no vertex element");

  TriangleMesh mesh;
  TextScanner body(s.position(), left, "PLY");
  body.skipLines(s.line()); // its lines are the file's
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
    const std::string prefix = "PLY " + e.name.substr(0, 40) + " ";
    scalars.assign(e.properties.size(), 0.0);
    const ErrorCode faceCode = enc == Encoding::Ascii ? ErrorCode::ParseError : ErrorCode::CorruptData;
    // Fast path for the common binary layouts (little-endian file and host):
    // vertices of 4-byte floats only, faces with only a uchar-counted list of
    // 4-byte indices. It takes records while they are plain (in range, 3
    // indices, bytes left) and leaves the first other one, with everything
    // after it, to the general loop below (its checks and messages).
    std::int64_t r0 = 0;
    if (enc == Encoding::LittleEndian && littleEndianHost())
    {
      bool floats = isVertex;
      for (const Property& p : e.properties) floats = floats && !p.list && p.kind == 'f' && p.type == 4;
      const bool triangleList = isFace && e.properties.size() == 1 && e.properties[0].list &&
        e.properties[0].countType == 1 && e.properties[0].type == 4 && e.properties[0].kind != 'f';
      if (floats)
      {
        const std::size_t rec = 4 * e.properties.size();
        const double m = 3.4e38; // point()'s range
        for (; r0 < e.count && static_cast<std::size_t>(bin.end - bin.p) >= rec; ++r0)
        {
          float v[3];
          std::memcpy(&v[0], bin.p + 4 * ix, 4);
          std::memcpy(&v[1], bin.p + 4 * iy, 4);
          std::memcpy(&v[2], bin.p + 4 * iz, 4);
          if (!(std::fabs(double(v[0])) < m && std::fabs(double(v[1])) < m && std::fabs(double(v[2])) < m)) break;
          mesh.points.push_back({ v[0], v[1], v[2] });
          bin.p += rec;
        }
      }
      else if (triangleList)
      {
        const bool isSigned = e.properties[0].kind == 'i';
        for (; r0 < e.count && bin.end - bin.p >= 13 && bin.p[0] == 3; ++r0)
        {
          std::int64_t id[3];
          for (int k = 0; k < 3; ++k)
          {
            std::uint32_t u;
            std::memcpy(&u, bin.p + 1 + 4 * k, 4);
            id[k] = isSigned ? static_cast<std::int64_t>(static_cast<std::int32_t>(u)) : static_cast<std::int64_t>(u);
          }
          if (!(id[0] >= 0 && id[0] < vertexCount && id[1] >= 0 && id[1] < vertexCount && id[2] >= 0 &&
                id[2] < vertexCount))
            break;
          mesh.triangles.push_back(
            { static_cast<std::uint32_t>(id[0]), static_cast<std::uint32_t>(id[1]), static_cast<std::uint32_t>(id[2]) });
          bin.p += 13;
        }
      }
    }
    if (enc == Encoding::Ascii && (isVertex || isFace) && parallelAscii(e, isVertex, ix, iy, iz, vertexCount, body, mesh))
      r0 = e.count;
    // binary faces: the corner count of the record before, so that a face
    // that fails because the count before it was one too high (its last corner read from
    // this record's bytes, this record read from the wrong place) is reported at that
    // face, not at this one
    double previousCorners = -1;
    for (std::int64_t r = r0; r < e.count; ++r)
    {
      // the record's name, made only for a message (not per record: binary
      // files then read at a fraction of the cost)
      std::string whereText;
      auto where = [&]() -> const std::string& {
        if (whereText.empty()) whereText = prefix + std::to_string(r);
        return whereText;
      };
      const unsigned char* start = bin.p;
      double corners = -1;
      try
      {
        ids.clear();
        std::size_t at = 0; // token position in ASCII
        if (enc == Encoding::Ascii && !body.nextNonEmpty(tok))
          fail(ErrorCode::ParseError, where(), "file ends before this record");
        auto next = [&](int size, char kind) -> double {
          if (enc != Encoding::Ascii)
            return bin.value(size, kind);
          if (at >= tok.size())
            fail(ErrorCode::ParseError, where(), "record has too few values");
          const std::string& v = tok[at++];
          return kind == 'f' ? parseReal(v, where()) : static_cast<double>(parseInt(v, where()));
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
          // the count and what the record or the file has room for ("PLY face 1: list of 300 items" said neither)
          const std::string announces = "list '" + p.name + "' announces " + std::to_string(static_cast<long long>(count)) + " items";
          if (count < 0)
            fail(ErrorCode::CorruptData, where(), announces + ", a negative count");
          if (enc == Encoding::Ascii && count > double(tok.size() - at))
            fail(ErrorCode::CorruptData, where(), announces + " but the record holds " + std::to_string(tok.size() - at) +
                " more values (a wrong count, or a damaged file)");
          if (count > double(left))
            fail(ErrorCode::CorruptData, where(), announces + ", more than the " + std::to_string(left) + " bytes after the header");
          // the record's own place (a count one too high in the last face was "PLY face: file ends inside the element data")
          if (enc != Encoding::Ascii && count * p.type > double(bin.end - bin.p))
            fail(ErrorCode::CorruptData, where(), announces + " of " + std::to_string(p.type) + " bytes, but the file ends inside them, " +
                std::to_string(bin.end - bin.p) + " bytes after the count (a wrong count, or a cut file)");
          if (int(i) == ilist)
            corners = count;
          if (isFace && int(i) == ilist && count > double(MaxPolygonCorners))
            checkFaceCorners(static_cast<std::int64_t>(count), where(), faceCode); // before reading its corners
          for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k)
          {
            const double v = next(p.type, p.kind);
            if (int(i) == ilist)
            {
              if (v != std::floor(v))
                fail(ErrorCode::CorruptData, where(), "vertex index is not an integer");
              ids.push_back(static_cast<std::int64_t>(std::max(-1.0, std::min(v, 1e18))));
            }
          }
        }
        if (enc == Encoding::Ascii && at != tok.size())
          fail(ErrorCode::ParseError, where(), "record has " + std::to_string(tok.size() - at) + " values too many");
        if (isVertex)
        {
          const double x = scalars[size_t(ix)], y = scalars[size_t(iy)], z = scalars[size_t(iz)];
          const double m = 3.4e38; // point()'s range: it names the record when it fails
          if (std::fabs(x) < m && std::fabs(y) < m && std::fabs(z) < m)
            mesh.points.push_back({ static_cast<float>(x), static_cast<float>(y), static_cast<float>(z) });
          else
            mesh.points.push_back(point(x, y, z, where()));
        }
        else if (isFace)
        {
          // a valid triangle straight in; anything else through addPolygon (fans, messages)
          if (ids.size() == 3 && ids[0] >= 0 && ids[0] < vertexCount && ids[1] >= 0 && ids[1] < vertexCount &&
            ids[2] >= 0 && ids[2] < vertexCount)
            mesh.triangles.push_back({ static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[1]),
              static_cast<std::uint32_t>(ids[2]) });
          else
            addPolygon(mesh, ids, vertexCount, where(), faceCode);
        }
      }
      catch (const Error& failed)
      {
        // the face before announced c >= 4 corners, and with c - 1 of them this record reads
        // as a valid face: its count is most likely one too high; said at that face
        const int itemBytes = ilist >= 0 ? e.properties[size_t(ilist)].type : 0;
        BinaryReader shifted = bin;
        shifted.p = start - itemBytes;
        if (enc == Encoding::Ascii || !isFace || previousCorners < 4 || !readsAsFace(shifted, e, ilist, vertexCount))
          throw;
        const std::string what = failed.what(), at = where() + ": ";
        const std::string name = e.properties[size_t(ilist)].name;
        const long long c = static_cast<long long>(previousCorners);
        fail(failed.code(), prefix + std::to_string(r - 1),
          "list '" + name + "' announces " + std::to_string(c) + " items, most likely one too many: its last item was read "
            "from the bytes of face " + std::to_string(r) + ", which then failed (" +
            (what.compare(0, at.size(), at) == 0 ? what.substr(at.size()) : what) + "); with " + std::to_string(c - 1) +
            " items, face " + std::to_string(r) + " reads as a valid face");
      }
      previousCorners = corners;
    }
  }
  // text past the last element's records: wrong counts or a damaged file (dropped without a word)
  if (enc == Encoding::Ascii && body.nextNonEmpty(tok))
    fail(ErrorCode::ParseError, body.where(), "more records than the header's element counts (wrong counts, or a damaged file)");
  // ... and bytes past them in a binary file, the same (a face count of 1 where 4 faces follow made a
  // mesh of one triangle without a word); white space alone (a line end some writers add) is no record
  if (enc != Encoding::Ascii &&
    std::any_of(bin.p, bin.end, [](unsigned char c) { return !(c == '\n' || c == '\r' || c == ' ' || c == '\t'); }))
    fail(ErrorCode::CorruptData, "PLY",
      "more data than the header's element counts: " + std::to_string(bin.end - bin.p) +
        " bytes after the last record (wrong counts, or a damaged file)");
  // triangle strips (element 'tristrips', as some scanners write) are not read: say so, not
  // only "the file holds no triangles"
  if (mesh.triangles.empty())
    for (const Element& e : elements)
      if (e.name != "vertex" && e.name != "face" && e.count > 0 &&
        std::any_of(e.properties.begin(), e.properties.end(), [](const Property& q) { return q.list; }))
        fail(ErrorCode::ParseError, "PLY", "the file holds no triangles: only the element 'face' is read, and its " +
            std::to_string(e.count) + " " + quotedText(e.name) + " records (triangle strips?) are not faces");
  finish(mesh, "PLY");
  return mesh;
}

} // namespace detail::volumefile::meshfile
} // namespace lvdif
