// Internal helpers of the mesh readers: the line scanner, strict number
// parsing and the checks every reader shares.
#pragma once

#include "lvdif/Error.h"
#include "lvdif/CNumbers.h"
#include "lvdif/MeshFile.h"
#include "lvdif/QuotedText.h"
#include "lvdif/TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::volumefile::meshfile
{

[[noreturn]] inline void fail(ErrorCode code, const std::string& where, const std::string& what)
{
  throw Error(code, where + ": " + what);
}

/// Bytes of a UTF-8 byte order mark at p (3 or 0). Windows editors start text
/// with one; none of the formats has it, and read as text it became part of the
/// first token (an OBJ's first vertex "\xEF\xBB\xBFv" was silently skipped).
inline std::size_t byteOrderMark(const char* p, std::size_t size)
{
  return size >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
}

/// ASCII letters to lower case in place (keywords of formats that take any case).
inline void lowerAscii(std::string& s)
{
  for (char& c : s)
    if (c >= 'A' && c <= 'Z')
      c = static_cast<char>(c - 'A' + 'a');
}

/// a == lower (a lower-case ASCII keyword) ignoring the case of a's ASCII letters.
inline bool equalsAsciiNoCase(std::string a, const char* lower)
{
  lowerAscii(a);
  return a == lower;
}

/// Splits text into lines and lines into whitespace-separated tokens; a
/// byte order mark before the text is skipped.
class TextScanner
{
public:
  TextScanner(const char* data, std::size_t size, std::string format)
    : P(data + byteOrderMark(data, size))
    , End(data + size)
    , Format(std::move(format))
  {
  }
  /// Next line's tokens (comments from '#' removed); false at the end.
  bool next(std::vector<std::string>& tokens, bool stripComments = true)
  {
    tokens.clear();
    if (this->P >= this->End)
      return false;
    ++this->Line;
    const char* e = static_cast<const char*>(std::memchr(this->P, '\n', static_cast<size_t>(this->End - this->P)));
    if (!e)
      e = this->End;
    const char* q = this->P;
    while (q < e)
    {
      while (q < e && (*q == ' ' || *q == '\t' || *q == '\r' || *q == '\f' || *q == '\v'))
        ++q;
      if (q >= e || (stripComments && *q == '#'))
        break;
      const char* s = q;
      while (q < e && !(*q == ' ' || *q == '\t' || *q == '\r' || *q == '\f' || *q == '\v'))
        ++q;
      tokens.emplace_back(s, q);
    }
    this->P = e < this->End ? e + 1 : e;
    return true;
  }
  /// The next line with at least one token; false at the end.
  bool nextNonEmpty(std::vector<std::string>& tokens)
  {
    while (this->next(tokens))
      if (!tokens.empty())
        return true;
    return false;
  }
  /// Where each of the next `count` non-empty lines starts (its first
  /// non-blank character), for the parallel readers; false, nothing taken,
  /// when one of them starts with a '#' comment or fewer are left. On
  /// success the scanner stands after the last of them.
  bool takeLines(std::int64_t count, std::vector<const char*>& starts)
  {
    starts.clear();
    starts.reserve(static_cast<std::size_t>(count));
    const char* q = this->P;
    std::int64_t lines = 0;
    while (q < this->End && static_cast<std::int64_t>(starts.size()) < count)
    {
      const char* e = static_cast<const char*>(std::memchr(q, '\n', static_cast<size_t>(this->End - q)));
      if (!e)
        e = this->End;
      const char* b = q;
      while (b < e && blank(*b))
        ++b;
      if (b < e && *b == '#')
        return false;
      if (b < e)
        starts.push_back(b);
      ++lines;
      q = e < this->End ? e + 1 : e;
    }
    if (static_cast<std::int64_t>(starts.size()) < count)
      return false;
    this->P = q;
    this->Line += lines;
    return true;
  }
  static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  const char* end() const { return this->End; }
  std::string where() const { return this->Format + " line " + std::to_string(this->Line); }
  /// The number of the line read last (0 before the first).
  std::int64_t line() const { return this->Line; }
  /// Counts `n` lines as read before this scanner's text (a scanner over the rest of a file).
  void skipLines(std::int64_t n) { this->Line += n; }
  const char* position() const { return this->P; }
  std::size_t remaining() const { return static_cast<std::size_t>(this->End - this->P); }

private:
  const char* P;
  const char* End;
  std::string Format;
  std::int64_t Line = 0;
};

/// The next whitespace-separated token of a line from b (up to '\n' or
/// end): [t, b) on return; false at the end of the line or at a '#' (the
/// parallel readers then leave the line to the serial ones).
inline bool nextToken(const char*& b, const char* end, const char*& t)
{
  while (b < end && TextScanner::blank(*b))
    ++b;
  if (b >= end || *b == '\n' || *b == '#')
    return false;
  t = b;
  while (b < end && !TextScanner::blank(*b) && *b != '\n')
    ++b;
  return true;
}

/// What bytes that no text holds (a NUL, other control bytes but tab and
/// CR) in a quoted token suggest, for the end of its message; "" for text.
inline std::string binaryHint(const std::string& t)
{
  for (char c : t)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
      return " (binary data where text was expected: is the file's format right?)";
  return "";
}

inline double parseReal(const std::string& t, const std::string& where)
{
  char* end = nullptr;
  const double v = strtodC(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size())
    fail(ErrorCode::ParseError, where, quotedText(t) + " is not a number" + binaryHint(t));
  if (!std::isfinite(v))
    fail(ErrorCode::ParseError, where, "coordinate " + quotedText(t) + " is NaN or infinite" + binaryHint(t));
  return v;
}

inline std::int64_t parseInt(const std::string& t, const std::string& where)
{
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE)
    fail(ErrorCode::ParseError, where, quotedText(t) + " is not an integer" + binaryHint(t));
  return v;
}

inline Vec3f point(double x, double y, double z, const std::string& where)
{
  const double m = 3.4e38;
  if (!(std::fabs(x) < m && std::fabs(y) < m && std::fabs(z) < m))
    fail(ErrorCode::ParseError, where, "coordinate is NaN, infinite or beyond float range");
  return { static_cast<float>(x), static_cast<float>(y), static_cast<float>(z) };
}

/// The n - 2 triangles of a polygon of n >= 3 corners ids[0, n) into out:
/// the ears of every other corner ((0,1,2), (2,3,4), ...), then the same on
/// the corners left (0, 2, 4, ..., n-1), and so on: O(n) work and each
/// triangle spans neighbouring corners (a fan from corner 0 made n - 2 slivers
/// across the whole polygon, all meeting at that corner, and mesh to SDF of a
/// 100,000-corner OBJ face took minutes). Quads give the fan's two triangles;
/// like a fan it assumes a convex (planar) polygon, and keeps its winding.
template <class Id>
void triangulatePolygon(const Id* ids, std::size_t n, std::array<std::uint32_t, 3>* out)
{
  std::size_t k = 0;
  for (std::size_t stride = 1;; stride *= 2)
  {
    // the corners left: every multiple of stride below n - 1, and n - 1
    const std::size_t left = (n - 1 + stride - 1) / stride + 1;
    if (left < 3)
      break;
    const auto at = [&](std::size_t j) { return static_cast<std::uint32_t>(ids[std::min(j * stride, n - 1)]); };
    for (std::size_t j = 0; j + 2 < left; j += 2)
      out[k++] = { at(j), at(j + 1), at(j + 2) };
  }
}

/// The readers' one rule on a face's corner count (at least 3, at most
/// MaxPolygonCorners): checked where the count is known, before the corners are read.
inline void checkFaceCorners(std::int64_t corners, const std::string& where, ErrorCode code)
{
  if (corners < 3)
    fail(code, where, "a face needs at least 3 vertices, this one has " + std::to_string(corners));
  if (corners > MaxPolygonCorners)
    fail(code, where,
      "a face of " + std::to_string(corners) + " corners: at most " + std::to_string(MaxPolygonCorners) +
        " corners a face (lvdif::MaxPolygonCorners; split or triangulate it first)");
}

/// Appends a polygon's triangles (triangulatePolygon) after checking its indices.
inline void addPolygon(TriangleMesh& mesh, const std::vector<std::int64_t>& ids, std::int64_t pointCount,
  const std::string& where, ErrorCode code)
{
  checkFaceCorners(static_cast<std::int64_t>(ids.size()), where, code);
  for (std::int64_t id : ids)
    if (id < 0 || id >= pointCount)
      fail(code, where, "vertex index " + std::to_string(id) + " out of range [0, " + std::to_string(pointCount) + ")");
  const std::size_t first = mesh.triangles.size();
  mesh.triangles.resize(first + ids.size() - 2);
  triangulatePolygon(ids.data(), ids.size(), mesh.triangles.data() + first);
}

/// Final checks: at least one triangle, point count within 32-bit indices.
inline void finish(TriangleMesh& mesh, const std::string& format)
{
  if (mesh.triangles.empty())
    fail(ErrorCode::ParseError, format, "the file holds no triangles");
  try
  {
    mesh.validate();
  }
  catch (const Error& e)
  {
    fail(ErrorCode::ParseError, format, e.what());
  }
}

TriangleMesh readPly(const std::vector<char>& data);

} // namespace detail::volumefile::meshfile
} // namespace lvdif
