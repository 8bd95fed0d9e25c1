// OBJ, OFF and STL readers and the format dispatch (PLY: MeshFilePly.cpp).
#include "lvdif/MeshFile.h"

#include "MeshFileDetail.h"

#include "lvdif/Memory.h"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cstring>
#include <unordered_map>

namespace lvdif
{

namespace
{
using namespace detail::volumefile::meshfile;

/// OBJ (Wavefront): v, f with i, i/t, i//n, i/t/n and negative (relative)
/// indices; other statements (vn, vt, g, o, s, usemtl, l, ...) are skipped.
// The format check that needs only the first bytes (and the size), made
// before the whole file is read: a garbage file of any size is refused after
// reading at most 4 KiB.
void checkMeshHead(ByteSource& source, MeshFormat format)
{
  const std::uint64_t size = source.size();
  std::vector<char> head(static_cast<std::size_t>(std::min<std::uint64_t>(size, 4096)));
  source.read(0, head.data(), head.size());
  std::string h(head.begin(), head.end());
  h.erase(0, byteOrderMark(h.data(), h.size())); // text after a byte order mark (binary STL: head, below)
  const auto text = [&]() {
    for (char c : h)
      if (c == '\0')
        return false;
    return true;
  };
  switch (format)
  {
    case MeshFormat::Ply:
      if (h.compare(0, 4, "ply\n") != 0 && h.compare(0, 5, "ply\r\n") != 0)
        fail(ErrorCode::ParseError, "PLY line 1", "missing the 'ply' magic line");
      return;
    case MeshFormat::Stl:
    {
      if (size >= 84)
      {
        std::uint32_t n = 0;
        std::memcpy(&n, head.data() + 80, 4); // little-endian hosts only, as the reader
        if (size == 84 + 50 * std::uint64_t(n))
          return; // a binary STL
      }
      const std::size_t b = h.find_first_not_of(" \t\r\n");
      const bool solid = b != std::string::npos && equalsAsciiNoCase(h.substr(b, 5), "solid");
      if (!solid || !text())
      {
        // a binary STL whose count disagrees with its size (a truncated copy, an
        // exporter writing 0): both numbers, so the user sees which
        std::string binary = "size is not 84 + 50 x triangle count";
        if (size >= 84)
        {
          std::uint32_t n = 0;
          std::memcpy(&n, head.data() + 80, 4);
          binary = "its header announces " + std::to_string(n) + " triangles, 84 + 50 x " + std::to_string(n) + " = " +
            std::to_string(84 + 50 * std::uint64_t(n)) + " bytes, but the file has " + std::to_string(size) + " bytes";
        }
        // a binary STL's header often starts with "solid" too: then the reason is the binary bytes
        fail(ErrorCode::CorruptData, "STL", "neither a binary STL (" + binary + ") nor an ASCII one (" +
            (solid ? "it starts with 'solid' but holds binary data: a NUL byte in its first 4 KiB" : "no 'solid'") + ")");
      }
      return;
    }
    case MeshFormat::Obj:
    case MeshFormat::Off:
      if (!text())
        fail(ErrorCode::ParseError, format == MeshFormat::Obj ? "OBJ" : "OFF", "not a text file (a NUL byte in its first 4 KiB)");
      return;
    default:
      return;
  }
}

/// A large OBJ file on OpenMP threads: a serial scan sorts the lines by
/// their first token (and counts the vertices, texture coordinates and
/// normals before each face); then the "v" lines (3 coordinates read whole,
/// the rest ignored as by the serial reader) and the "f" lines (corners v,
/// v/vt, v//vn or v/vt/vn with positive indices defined before the face;
/// polygons by triangulatePolygon) are read in parallel. False (mesh untouched) for
/// anything the serial reader may answer differently or with a message (a
/// negative index, a '+' sign, a hex float, a value out of range, a bad
/// corner): the serial reader then reads the file.
bool parallelObj(const char* p, std::size_t size, TriangleMesh& mesh)
{
  if (size < (std::size_t(1) << 22)) return false; // small files (< 4 MiB): not worth it
  const char* end = p + size;
  p += byteOrderMark(p, size);
  struct Face
  {
    const char* b;
    std::int64_t v, vt, vn; // counts defined before the face
  };
  std::vector<const char*> verts;
  std::vector<Face> faces;
  std::int64_t vt = 0, vn = 0;
  for (const char* q = p; q < end;)
  {
    const char* e = static_cast<const char*>(std::memchr(q, '\n', static_cast<std::size_t>(end - q)));
    if (!e) e = end;
    const char* b = q;
    const char* t = nullptr;
    // a line continued on the next (a backslash at its end): the serial reader joins them
    const char* last = e;
    while (last > b && TextScanner::blank(last[-1])) --last;
    if (last > b && last[-1] == '\\') return false;
    if (nextToken(b, e, t))
    {
      const std::size_t n = static_cast<std::size_t>(b - t);
      if (n == 1 && t[0] == 'v') verts.push_back(b);
      else if (n == 1 && t[0] == 'f') faces.push_back({ b, static_cast<std::int64_t>(verts.size()), vt, vn });
      else if (n == 2 && t[0] == 'v' && t[1] == 't') ++vt;
      else if (n == 2 && t[0] == 'v' && t[1] == 'n') ++vn;
    }
    q = e < end ? e + 1 : e;
  }
  const std::int64_t nv = static_cast<std::int64_t>(verts.size()), nf = static_cast<std::int64_t>(faces.size());
  if (nv > std::int64_t(UINT32_MAX)) return false;
  // one positive index read whole from [t, e), at most `count`
  auto index = [](const char* t, const char* e, std::int64_t count, std::int64_t& out) {
    long long v = 0;
    const auto r = std::from_chars(t, e, v);
    out = v - 1;
    return r.ec == std::errc() && r.ptr == e && v >= 1 && v <= count;
  };
  // the corners of face f: their vertex indices into ids (when given), their number
  auto corners = [&](const Face& f, std::int64_t* ids, int& count) {
    const char* b = f.b;
    const char* t = nullptr;
    count = 0;
    while (nextToken(b, end, t))
    {
      const char* a = static_cast<const char*>(std::memchr(t, '/', static_cast<std::size_t>(b - t)));
      std::int64_t v = 0;
      if (!index(t, a ? a : b, f.v, v)) return false;
      if (a)
      {
        const char* c = static_cast<const char*>(std::memchr(a + 1, '/', static_cast<std::size_t>(b - a - 1)));
        const char* texEnd = c ? c : b;
        std::int64_t unused = 0;
        if (texEnd > a + 1 && !index(a + 1, texEnd, f.vt, unused)) return false;
        if (c && !index(c + 1, b, f.vn, unused)) return false; // also refuses an empty normal or a third '/'
        if (!c && texEnd == a + 1) return false;               // "v/": the serial reader's message
      }
      if (ids) ids[count] = v;
      ++count;
    }
    return count >= 3;
  };
  // pass 1: triangles per face (n - 2), checked; then their offsets
  std::vector<std::int64_t> first(static_cast<std::size_t>(nf) + 1, 0);
  bool ok = true;
#pragma omp parallel for schedule(static) reduction(&& : ok)
  for (std::int64_t f = 0; f < nf; ++f)
  {
    int n = 0;
    // a face past MaxPolygonCorners: the serial reader's message
    const bool good = corners(faces[static_cast<std::size_t>(f)], nullptr, n) && n <= MaxPolygonCorners;
    first[static_cast<std::size_t>(f) + 1] = good ? n - 2 : 0;
    ok = ok && good;
  }
  if (!ok) return false;
  for (std::int64_t f = 0; f < nf; ++f) first[static_cast<std::size_t>(f) + 1] += first[static_cast<std::size_t>(f)];
  mesh.points.resize(static_cast<std::size_t>(nv));
  mesh.triangles.resize(static_cast<std::size_t>(first.back()));
  const double m = 3.4e38; // point()'s range
#pragma omp parallel for schedule(static) reduction(&& : ok)
  for (std::int64_t i = 0; i < nv + nf; ++i)
  {
    bool good = true;
    if (i < nv)
    {
      const char* b = verts[static_cast<std::size_t>(i)];
      const char* t = nullptr;
      double x[3];
      for (int k = 0; k < 3 && good; ++k)
      {
        good = nextToken(b, end, t);
        if (!good) break;
        const auto r = std::from_chars(t, b, x[k]);
        good = r.ec == std::errc() && r.ptr == b && std::fabs(x[k]) < m;
      }
      if (good)
        mesh.points[static_cast<std::size_t>(i)] = { static_cast<float>(x[0]), static_cast<float>(x[1]),
          static_cast<float>(x[2]) };
    }
    else
    {
      const std::size_t f = static_cast<std::size_t>(i - nv);
      const std::int64_t n = first[f + 1] - first[f] + 2;
      std::vector<std::int64_t> big;
      std::int64_t small[16];
      std::int64_t* ids = small;
      if (n > 16)
      {
        big.resize(static_cast<std::size_t>(n));
        ids = big.data();
      }
      int count = 0;
      good = corners(faces[f], ids, count) && count == n;
      if (good)
        triangulatePolygon(ids, static_cast<std::size_t>(n), mesh.triangles.data() + first[f]);
    }
    ok = ok && good;
  }
  if (!ok)
  {
    mesh.points.clear();
    mesh.triangles.clear();
  }
  return ok;
}

TriangleMesh readObj(const std::vector<char>& data)
{
  {
    TriangleMesh fast;
    if (parallelObj(data.data(), data.size(), fast))
    {
      finish(fast, "OBJ");
      return fast;
    }
  }
  TextScanner s(data.data(), data.size(), "OBJ");
  TriangleMesh mesh;
  std::vector<std::string> t;
  std::vector<std::int64_t> ids;
  std::int64_t texCoords = 0, normals = 0;
  // An index as written (1-based, or negative counting back from the newest
  // element) checked against the elements so far; messages quote it as written.
  auto resolve = [&](const std::string& text, std::int64_t count, const char* what, const char* plural) {
    const std::int64_t v = parseInt(text, s.where());
    if (v == 0)
      fail(ErrorCode::ParseError, s.where(), std::string(what) + " index 0 (OBJ indices start at 1)");
    if (v > count || v < -count)
      fail(ErrorCode::ParseError, s.where(),
        std::string(what) + " index " + text + " out of range: " + std::to_string(count) + " " +
          (count == 1 ? what : plural) + " defined so far (OBJ counts from 1; negative counts back)");
    return v > 0 ? v - 1 : count + v;
  };
  std::vector<std::string> more;
  while (s.next(t))
  {
    // a line that ends in a backslash continues on the next (the OBJ specification's line
    // continuation; "f 1 2 \" was "'\' is not an integer"); messages name the last line
    while (!t.empty() && t.back().back() == '\\')
    {
      t.back().pop_back();
      if (t.back().empty())
        t.pop_back();
      if (!s.next(more))
        break;
      t.insert(t.end(), more.begin(), more.end());
    }
    if (t.empty())
      continue;
    if (t[0] == "vt")
      ++texCoords;
    else if (t[0] == "vn")
      ++normals;
    else if (t[0] == "v")
    {
      if (t.size() < 4)
        fail(ErrorCode::ParseError, s.where(), "vertex with fewer than 3 coordinates");
      mesh.points.push_back(
        point(parseReal(t[1], s.where()), parseReal(t[2], s.where()), parseReal(t[3], s.where()), s.where()));
    }
    else if (t[0] == "f")
    {
      ids.clear();
      if (std::int64_t(t.size()) - 1 > MaxPolygonCorners)
        checkFaceCorners(std::int64_t(t.size()) - 1, s.where(), ErrorCode::ParseError); // before resolving them
      const std::int64_t n = static_cast<std::int64_t>(mesh.points.size());
      for (std::size_t i = 1; i < t.size(); ++i)
      {
        // v, v/vt, v//vn or v/vt/vn
        const std::string& f = t[i];
        const std::size_t a = f.find('/');
        ids.push_back(resolve(f.substr(0, a), n, "vertex", "vertices"));
        if (a == std::string::npos)
          continue;
        const std::size_t b = f.find('/', a + 1);
        const std::string tex = f.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
        if (!tex.empty())
          resolve(tex, texCoords, "texture coordinate", "texture coordinates");
        if (b != std::string::npos)
        {
          const std::string nor = f.substr(b + 1);
          if (nor.empty() || nor.find('/') != std::string::npos)
            fail(ErrorCode::ParseError, s.where(), "bad face corner " + quotedText(f) + " (expected v, v/vt, v//vn or v/vt/vn)" + binaryHint(f));
          resolve(nor, normals, "normal", "normals");
        }
        else if (tex.empty())
          fail(ErrorCode::ParseError, s.where(), "bad face corner " + quotedText(f) + " (expected v, v/vt, v//vn or v/vt/vn)" + binaryHint(f));
      }
      addPolygon(mesh, ids, n, s.where(), ErrorCode::ParseError);
    }
  }
  finish(mesh, "OBJ");
  return mesh;
}

/// OFF (Geomview): [C|N|CN]OFF header, counts, vertices, faces "n i1 .. in [colour]".
bool offSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// The body of a large plain OFF file on OpenMP threads: vertex lines of
/// numbers that std::from_chars reads whole, triangle lines ("3 a b c",
/// indices in range), extra values on a line ignored as by the serial
/// reader. False (mesh untouched) for anything else, a quad, a '+' sign, a
/// hex float, a bad index, too few lines, even '#' comments: the serial reader
/// then reads the body again with its checks and messages.
bool parallelOff(const char* p, std::size_t size, std::int64_t nv, std::int64_t nf, TriangleMesh& mesh, const char*& after)
{
  if (nv + nf < 100000) return false; // small files: not worth it
  const char* end = p + size;
  // where each of the nv + nf non-empty lines starts (a serial memchr scan)
  std::vector<const char*> line;
  line.reserve(static_cast<std::size_t>(nv + nf));
  for (const char* q = p; q < end && std::int64_t(line.size()) < nv + nf;)
  {
    const char* e = static_cast<const char*>(std::memchr(q, '\n', static_cast<std::size_t>(end - q)));
    if (!e) e = end;
    const char* b = q;
    while (b < e && offSpace(*b)) ++b;
    if (b < e && *b == '#') return false;
    if (b < e) line.push_back(b);
    q = e < end ? e + 1 : e;
  }
  if (std::int64_t(line.size()) < nv + nf) return false;
  after = line.empty() ? p : static_cast<const char*>(std::memchr(line.back(), '\n', static_cast<std::size_t>(end - line.back())));
  after = after ? after + 1 : end;
  // the numbers of one line: at most `want` tokens, false if one is not read whole
  auto tokens = [end](const char* b, auto* out, int want, int& got) {
    got = 0;
    while (got < want)
    {
      while (b < end && offSpace(*b)) ++b;
      if (b >= end || *b == '\n' || *b == '#') return true;
      const char* t = b;
      while (b < end && !offSpace(*b) && *b != '\n') ++b;
      const auto r = std::from_chars(t, b, out[got]);
      if (r.ec != std::errc() || r.ptr != b) return false;
      ++got;
    }
    return true;
  };
  mesh.points.resize(static_cast<std::size_t>(nv));
  mesh.triangles.resize(static_cast<std::size_t>(nf));
  bool ok = true;
  const double m = 3.4e38; // point()'s range
#pragma omp parallel for schedule(static) reduction(&& : ok)
  for (std::int64_t i = 0; i < nv + nf; ++i)
  {
    int got = 0;
    if (i < nv)
    {
      double x[3];
      const bool read = tokens(line[static_cast<std::size_t>(i)], x, 3, got);
      const bool good = read && got == 3 && std::fabs(x[0]) < m && std::fabs(x[1]) < m && std::fabs(x[2]) < m;
      if (good)
        mesh.points[static_cast<std::size_t>(i)] = { static_cast<float>(x[0]), static_cast<float>(x[1]),
          static_cast<float>(x[2]) };
      ok = ok && good;
    }
    else
    {
      long long v[4];
      const bool read = tokens(line[static_cast<std::size_t>(i)], v, 4, got);
      const bool good = read && got == 4 && v[0] == 3 && v[1] >= 0 && v[1] < nv && v[2] >= 0 && v[2] < nv &&
        v[3] >= 0 && v[3] < nv;
      if (good)
        mesh.triangles[static_cast<std::size_t>(i - nv)] = { static_cast<std::uint32_t>(v[1]),
          static_cast<std::uint32_t>(v[2]), static_cast<std::uint32_t>(v[3]) };
      ok = ok && good;
    }
  }
  if (!ok)
  {
    mesh.points.clear();
    mesh.triangles.clear();
  }
  return ok;
}

TriangleMesh readOff(const std::vector<char>& data)
{
  TextScanner s(data.data(), data.size(), "OFF");
  std::vector<std::string> t;
  if (!s.nextNonEmpty(t) || t[0].size() < 3 || t[0].compare(t[0].size() - 3, 3, "OFF") != 0)
    fail(ErrorCode::ParseError, "OFF line 1", "missing the OFF header");
  // the header is [ST][C][N][4][n]OFF: texture coordinates, colours and normals follow a vertex's
  // x y z and are skipped; 4 (homogeneous x y z w) and n (a dimension line) change what the
  // coordinates are, and were read as if absent: a 4OFF of w = 2 came out twice its size
  {
    const std::string& h = t[0];
    std::size_t i = h.compare(0, 2, "ST") == 0 ? 2 : 0;
    for (const char flag : { 'C', 'N' })
      if (i < h.size() && h[i] == flag)
        ++i;
    const std::string rest = h.substr(i, h.size() - 3 - i);
    if (rest == "4" || rest == "n" || rest == "4n")
      fail(ErrorCode::ParseError, "OFF line 1",
        "header " + quotedText(h) + ": " +
          (rest == "4" ? std::string("homogeneous vertices (x y z w) are not read; write the points x/w y/w z/w")
                       : std::string("vertices of the dimension given on the next line are not read; write 3-D points")) +
          " under an 'OFF' header");
    if (!rest.empty())
      fail(ErrorCode::ParseError, "OFF line 1",
        "header " + quotedText(h) + " is not an OFF header ([ST][C][N]OFF: OFF, COFF, NOFF, CNOFF, STOFF, ...)");
  }
  t.erase(t.begin()); // counts may follow on the same line
  if (t.empty() && !s.nextNonEmpty(t))
    fail(ErrorCode::ParseError, s.where(), "missing the vertex and face counts");
  if (t.size() < 2)
    fail(ErrorCode::ParseError, s.where(), "expected vertex, face (and edge) counts");
  const std::int64_t nv = parseInt(t[0], s.where()), nf = parseInt(t[1], s.where());
  if (nv < 0 || nf < 0) // ("-3 vertices and 1 faces cannot fit in the rest of the file")
    fail(ErrorCode::ParseError, s.where(),
      "negative " + std::string(nv < 0 ? "vertex" : "face") + " count " + std::to_string(nv < 0 ? nv : nf));
  // every vertex needs at least 6 bytes ("0 0 0\n"), every face 8 ("3 0 1 2\n")
  if (nv < 0 || nf < 0 || nv > std::int64_t(s.remaining() / 6) || nf > std::int64_t(s.remaining() / 8) ||
    nv > std::int64_t(UINT32_MAX))
    fail(ErrorCode::ParseError, s.where(),
      std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces cannot fit in the rest of the file");
  TriangleMesh mesh;
  // records past the counts are a damaged file or wrong counts: they were dropped without a word
  // (faces 1 of 4 made a mesh of one triangle)
  auto noMore = [&](TextScanner& rest) {
    if (rest.nextNonEmpty(t))
      fail(ErrorCode::ParseError, rest.where(),
        "more records than the header's " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
          " faces (wrong counts, or a damaged file)");
  };
  const char* after = nullptr;
  if (parallelOff(s.position(), s.remaining(), nv, nf, mesh, after))
  {
    TextScanner rest(after, static_cast<std::size_t>(s.end() - after), "OFF");
    rest.skipLines(s.line() + std::count(s.position(), after, '\n'));
    noMore(rest);
    finish(mesh, "OFF");
    return mesh;
  }
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
    if (k > MaxPolygonCorners)
      checkFaceCorners(k, s.where(), ErrorCode::ParseError); // before reading its corners
    ids.clear();
    for (std::int64_t i = 1; i <= k; ++i)
      ids.push_back(parseInt(t[static_cast<size_t>(i)], s.where()));
    addPolygon(mesh, ids, nv, s.where(), ErrorCode::ParseError);
  }
  noMore(s);
  finish(mesh, "OFF");
  return mesh;
}

/// Adds a corner to an STL mesh, sharing bit-identical points (ids in order
/// of first appearance). Open addressing over the points' 12 bytes in one
/// flat table, doubled at half load: no node or string per corner.
struct PointMerger
{
  std::vector<std::uint32_t> table = std::vector<std::uint32_t>(1024, Empty); // point id, or Empty
  static constexpr std::uint32_t Empty = 0xffffffffu;
  static std::size_t hash(const Vec3f& p)
  {
    std::uint32_t b[3];
    std::memcpy(b, p.data(), sizeof(b));
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t v : b) h = (h ^ v) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
  std::uint32_t add(TriangleMesh& mesh, const Vec3f& p)
  {
    const std::size_t mask = this->table.size() - 1;
    for (std::size_t slot = hash(p) & mask;; slot = (slot + 1) & mask)
    {
      const std::uint32_t e = this->table[slot];
      if (e == Empty)
      {
        const auto id = static_cast<std::uint32_t>(mesh.points.size());
        mesh.points.push_back(p);
        this->table[slot] = id;
        if (2 * mesh.points.size() > this->table.size()) this->grow(mesh);
        return id;
      }
      if (std::memcmp(mesh.points[e].data(), p.data(), sizeof(Vec3f)) == 0) return e;
    }
  }
  void grow(const TriangleMesh& mesh)
  {
    std::vector<std::uint32_t> bigger(2 * this->table.size(), Empty);
    const std::size_t mask = bigger.size() - 1;
    for (std::uint32_t id = 0; id < mesh.points.size(); ++id)
    {
      std::size_t slot = hash(mesh.points[id]) & mask;
      while (bigger[slot] != Empty) slot = (slot + 1) & mask;
      bigger[slot] = id;
    }
    this->table.swap(bigger);
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
          const float x = readLeFloat(r + 12 * c), y = readLeFloat(r + 12 * c + 4), z = readLeFloat(r + 12 * c + 8);
          const double m = 3.4e38; // point()'s range; the record's name is made only when it fails
          tri[c] = merge.add(mesh, std::fabs(double(x)) < m && std::fabs(double(y)) < m && std::fabs(double(z)) < m
              ? Vec3f{ x, y, z }
              : point(x, y, z, "STL triangle " + std::to_string(i)));
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
  if (!s.nextNonEmpty(t) || !equalsAsciiNoCase(t[0], "solid"))
    fail(ErrorCode::CorruptData, "STL", "neither a binary STL (size is not 84 + 50 x triangle count) nor an ASCII one (no 'solid')");
  // where each record may stand: a file cut off after 'facet normal' said "holds no triangles",
  // a facet without 'endloop' or 'endfacet' was taken or joined to the next one
  enum class In { Solid, Facet, Loop, LoopDone } in = In::Solid;
  std::int64_t facetLine = 0;
  auto facetText = [&] { return "the facet of line " + std::to_string(facetLine); };
  auto missing = [&] { return std::string(in == In::LoopDone ? "no 'endfacet'" : in == In::Loop ? "no 'endloop'" : "no 'outer loop'"); };
  std::vector<std::uint32_t> corners;
  while (s.nextNonEmpty(t))
  {
    std::string word = t[0]; // the keywords in any case (SOLID, FACET, VERTEX, ... were refused)
    lowerAscii(word);
    if (word == "vertex")
    {
      if (in != In::Loop)
        fail(ErrorCode::ParseError, s.where(), "'vertex' outside a facet's 'outer loop'");
      if (t.size() != 4)
        fail(ErrorCode::ParseError, s.where(), "vertex needs 3 coordinates");
      if (corners.size() == 3)
        fail(ErrorCode::ParseError, s.where(), facetText() + " has a 4th vertex (STL facets have 3)");
      corners.push_back(merge.add(mesh, point(parseReal(t[1], s.where()), parseReal(t[2], s.where()), parseReal(t[3], s.where()), s.where())));
    }
    else if (word == "facet")
    {
      if (in != In::Solid)
        fail(ErrorCode::ParseError, s.where(), "a facet starts before " + facetText() + " ends (" + missing() + ")");
      in = In::Facet;
      facetLine = s.line();
    }
    else if (word == "outer")
    {
      if (in != In::Facet)
        fail(ErrorCode::ParseError, s.where(), in == In::Solid ? "'outer loop' outside a facet" : "a second 'outer loop' in " + facetText());
      in = In::Loop;
    }
    else if (word == "endloop")
    {
      if (in != In::Loop)
        fail(ErrorCode::ParseError, s.where(), "'endloop' without its 'outer loop'");
      if (corners.size() != 3)
        fail(ErrorCode::ParseError, s.where(), facetText() + " has " + std::to_string(corners.size()) + " vertices (STL facets have 3)");
      mesh.triangles.push_back({ corners[0], corners[1], corners[2] });
      corners.clear();
      in = In::LoopDone;
    }
    else if (word == "endfacet")
    {
      if (in == In::Solid)
        fail(ErrorCode::ParseError, s.where(), "'endfacet' without its 'facet'");
      if (in != In::LoopDone)
        fail(ErrorCode::ParseError, s.where(), "'endfacet' inside " + facetText() + " (" + missing() + ")");
      in = In::Solid;
    }
    else if (word == "endsolid" || word == "solid")
    {
      if (in != In::Solid)
        fail(ErrorCode::ParseError, s.where(), "'" + word + "' inside " + facetText() + " (" + missing() + ")");
    }
    else
      fail(ErrorCode::ParseError, s.where(), "unexpected " + quotedText(t[0]) + binaryHint(t[0]));
  }
  if (in != In::Solid)
    fail(ErrorCode::ParseError, s.where(), "the file ends inside " + facetText() + " (" + missing() + ": is it cut off?)");
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
  checkMeshHead(source, format);
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
