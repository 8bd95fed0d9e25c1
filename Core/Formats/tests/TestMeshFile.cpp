// Mesh file readers: small files written out here by hand (the oracle is the
// mesh they describe) in every supported encoding, and a table of malformed
// inputs, each a clear error naming the problem.
#include "lvdif/Error.h"
#include "lvdif/MeshFile.h"

#include "CommaLocale.h"
#include "ErrorTestUtil.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace lvdif;

namespace
{
TriangleMesh readText(const std::string& text, MeshFormat f)
{
  MemorySource src(text.data(), text.size());
  return readMesh(src, f, "test");
}

/// The expected mesh of every "square" file: 4 points, the square split in 2 triangles.
void expectSquare(const TriangleMesh& m)
{
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.points[2], (Vec3f{ 1, 1, 0 }));
  EXPECT_EQ(m.points[3], (Vec3f{ 0, 1, 0.5f }));
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{ 0, 1, 2 }));
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{ 0, 2, 3 }));
}

void expectError(const std::string& text, MeshFormat f, const std::string& needle)
{
  try
  {
    readText(text, f);
    ADD_FAILURE() << "accepted: " << text.substr(0, 60);
  }
  catch (const Error& e)
  {
    EXPECT_TRUE(e.code() == ErrorCode::ParseError || e.code() == ErrorCode::CorruptData) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "'" << e.what() << "' lacks '" << needle << "'";
  }
}

template <typename T>
void put(std::string& s, T v, bool big = false)
{
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big)
    std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binaryPly(bool big)
{
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
    " 1.0\ncomment square\nelement vertex 4\nproperty double x\nproperty float y\nproperty float z\n"
    "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const double p[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0.5 } };
  for (auto& q : p)
  {
    put<double>(s, q[0], big);
    put<float>(s, float(q[1]), big);
    put<float>(s, float(q[2]), big);
    put<std::uint8_t>(s, 7);
  }
  put<std::uint8_t>(s, 4);
  for (int i : { 0, 1, 2, 3 })
    put<std::int32_t>(s, i, big);
  return s;
}
/// Vertex (i, j) of the large readers' tests' grid, as an OFF or ASCII PLY line ("x y z 255").
std::string gridVertex(int i, int j)
{
  char buf[96];
  return std::string(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g 255\n",
    0.1 * i + 1e-7 * j, 0.37 * j, std::sin(0.3 * i) * 1e-3)));
}

/// The k x k grid's two triangles a cell as "3 a b c" lines; the second one's
/// ids after `a` are joined by `gap` and it ends with `tail` (white space and
/// extra values the readers must take).
std::vector<std::string> gridFaces(int k, const std::string& gap, const std::string& tail)
{
  std::vector<std::string> faces;
  for (int j = 0; j + 1 < k; ++j)
    for (int i = 0; i + 1 < k; ++i)
    {
      const int a = j * k + i, b = a + 1, c = a + k + 1, d = a + k;
      faces.push_back("3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n");
      faces.push_back("3 " + std::to_string(a) + gap + std::to_string(c) + " " + std::to_string(d) + tail);
    }
  return faces;
}
} // namespace

TEST(MeshFile, EveryFormatReadsTheSquare)
{
  expectSquare(readText("# square\nv 0 0 0\nv 1 0 0\nvt 0 0\nv 1 1 0\nv 0 1 0.5\nvn 0 0 1\ng a\nf 1/1 2//1 3/1/1 -1\n",
    MeshFormat::Obj));
  expectSquare(readText("OFF\n# c\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3 255 0 0\n", MeshFormat::Off));
  // OFF's variants whose extra vertex columns (colour, normal, texture coordinates) follow x y z
  for (const std::string header : { "COFF", "NOFF", "CNOFF", "STOFF", "STCNOFF" })
    expectSquare(readText(header + "\n4 1 0\n0 0 0 9 9\n1 0 0 9 9\n1 1 0 9 9\n0 1 0.5 9 9\n4 0 1 2 3\n", MeshFormat::Off));
  expectSquare(readText("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n",
    MeshFormat::Ply));
  expectSquare(readText(binaryPly(false), MeshFormat::Ply));
  expectSquare(readText(binaryPly(true), MeshFormat::Ply));
  // a line end after the binary records (some writers add one) is no record
  expectSquare(readText(binaryPly(false) + "\r\n", MeshFormat::Ply));
}

TEST(MeshFile, ByteOrderMarkBeforeTheTextIsSkipped)
{
  // Windows editors start UTF-8 text with EF BB BF: it was read as part of the
  // first token, so an OBJ lost its first vertex ("v" unknown, skipped) and the
  // faces pointed one vertex off; PLY and ASCII STL were refused.
  const std::string bom = "\xEF\xBB\xBF";
  expectSquare(readText(bom + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 3 4\n", MeshFormat::Obj));
  expectSquare(readText(bom + "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n", MeshFormat::Off));
  expectSquare(readText(bom + "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                              "0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n",
    MeshFormat::Ply));
  expectSquare(readText(bom + binaryPly(false), MeshFormat::Ply));
  const TriangleMesh stl = readText(bom + "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                          "vertex 1 1 0\nendloop\nendfacet\nendsolid s\n",
    MeshFormat::Stl);
  EXPECT_EQ(stl.points.size(), 3u);
  EXPECT_EQ(stl.triangles.size(), 1u);
  // only at the start: elsewhere it is still not a number
  expectError("v 0 0 0\n" + bom + "v 1 0 0\nv 1 1 0\nf 1 2 3\n", MeshFormat::Obj, "OBJ line 4: vertex index 3 out of range");
}

// The OBJ specification joins a line that ends in a backslash with the next
// one ("f 1 2 \" then "3 4"); such files were refused with "'\' is not an integer".
TEST(MeshFile, ObjLinesEndingInABackslashContinue)
{
  expectSquare(readText("v 0 0 0\nv 1 0 \\\n 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 \\\n3 4\n", MeshFormat::Obj));
  // CRLF, a backslash against the last token, a statement over three lines, a comment before the backslash
  expectSquare(readText("v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0.5\r\nf 1 2\\\r\n  3 \\ # corner 4 next\r\n 4\r\n",
    MeshFormat::Obj));
  // on the last line: nothing follows, the statement is the line
  expectSquare(readText("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 3 4 \\", MeshFormat::Obj));
  // a message names the line where the statement ends
  expectError("v 0 0 0\nv 1 0 0\nf 1 2 \\\n 9\n", MeshFormat::Obj, "OBJ line 4: vertex index 9 out of range");
  // a file large enough for the parallel reader (4 MiB or more) gives the serial reader's mesh: a
  // group name continued onto a 'v' line takes it (it is no vertex), and the faces count without it
  std::string big = "g part \\\nv 5 5 5\n";
  for (int i = 0; i < 120000; ++i) big += "v " + std::to_string(i) + " 0.25 0.125\nv 0 1 0\nv 0 0 1\n";
  for (int i = 0; i < 120000; ++i) big += "f " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
  ASSERT_GT(big.size(), std::size_t(1) << 22);
  const TriangleMesh m = readText(big, MeshFormat::Obj);
  ASSERT_EQ(m.points.size(), 360000u);
  EXPECT_EQ(m.points[0], (Vec3f{ 0, 0.25f, 0.125f }));
  EXPECT_EQ(m.triangles.back(), (std::array<std::uint32_t, 3>{ 359997, 359998, 359999 }));
}

TEST(MeshFile, StlAsciiAndBinaryShareCorners)
{
  const std::string ascii = "solid sq\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n"
                            " endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
                            "vertex 0 1 0.5\nendloop\nendfacet\nendsolid sq\n";
  expectSquare(readText(ascii, MeshFormat::Stl));
  // the keywords in any case, as some exporters write them ("SOLID" was "no 'solid'",
  // "FACET" "unexpected 'FACET'"); the name after solid keeps its case
  std::string upper = ascii;
  for (const char* w : { "solid", "facet", "normal", "outer", "loop", "vertex", "endloop", "endfacet", "endsolid" })
    for (std::size_t at = upper.find(w); at != std::string::npos; at = upper.find(w, at + 1))
      for (std::size_t i = at; i < at + std::strlen(w); ++i)
        upper[i] = static_cast<char>(upper[i] - 'a' + 'A');
  ASSERT_EQ(upper.rfind("SOLID sq\nFACET NORMAL 0 0 1\n OUTER LOOP\n  VERTEX 0 0 0\n", 0), 0u) << upper;
  expectSquare(readText(upper, MeshFormat::Stl));
  expectSquare(readText("Solid x\nFacet normal 0 0 1\nOuter Loop\nVertex 0 0 0\nVertex 1 0 0\nVertex 1 1 0\nEndLoop\n"
                        "EndFacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0.5\nENDLOOP\n"
                        "endfacet\nEndSolid x\n",
    MeshFormat::Stl));
  expectError("SOLID x\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTICES 0 0 0\n", MeshFormat::Stl, "unexpected 'VERTICES'");
  std::string bin(80, ' ');
  put<std::uint32_t>(bin, 2);
  const float tris[2][9] = { { 0, 0, 0, 1, 0, 0, 1, 1, 0 }, { 0, 0, 0, 1, 1, 0, 0, 1, 0.5f } };
  for (auto& t : tris)
  {
    for (int i = 0; i < 3; ++i) put<float>(bin, 0);
    for (float f : t) put<float>(bin, f);
    put<std::uint16_t>(bin, 0);
  }
  expectSquare(readText(bin, MeshFormat::Stl));
  EXPECT_EQ(meshFormatFromName("/a/b.STL"), MeshFormat::Stl);
  EXPECT_THROW(meshFormatFromName("x.3ds"), Error);
}

TEST(MeshFile, MalformedInputsAreClearErrors)
{
  const std::string plyHead = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  struct Case { const char* label; std::string text; MeshFormat f; const char* needle; };
  const std::vector<Case> cases = {
    { "OBJ index out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", MeshFormat::Obj, "out of range" },
    { "OBJ relative index before the start", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", MeshFormat::Obj, "out of range" },
    { "OBJ index 0", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", MeshFormat::Obj, "index 0" },
    { "OBJ NaN", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj, "NaN" },
    { "OBJ inf", "v 0 1e999 0\n", MeshFormat::Obj, "NaN or infinite" },
    { "OBJ two-vertex face", "v 0 0 0\nv 1 0 0\nf 1 2\n", MeshFormat::Obj, "OBJ line 3: a face needs at least 3 vertices, this one has 2" },
    { "OBJ one-vertex face", "v 0 0 0\nf 1\n", MeshFormat::Obj, "OBJ line 2: a face needs at least 3 vertices, this one has 1" },
    { "OBJ empty face", "v 0 0 0\nf\n", MeshFormat::Obj, "this one has 0" },
    // near float's limit: the mesh's bounds, at reading (it was a message about the volume's origin)
    { "OBJ at 3e38", "v 3e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj,
      "OBJ: mesh coordinates span x [0, 3e+38], y [0, 1], z [0, 0]: every coordinate must lie within +-1e+30" },
    { "OFF at -2e30", "OFF\n3 1 0\n0 0 -2e30\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off, "OFF: mesh coordinates span" },
    { "PLY at 1e35", plyHead + "0 1e35 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Ply, "PLY: mesh coordinates span x [0, 1], y [0, 1e+35]" },
    { "STL at 3e38", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 3e38 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n", MeshFormat::Stl, "STL: mesh coordinates span" },
    { "OBJ garbage index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", MeshFormat::Obj, "not an integer" },
    { "OBJ short vertex", "v 0 0\n", MeshFormat::Obj, "fewer than 3" },
    { "OBJ no faces", "v 0 0 0\n", MeshFormat::Obj, "no triangles" },
    { "OFF negative index", "OFF\n3 1 0\n" + tri + "3 0 -1 2\n", MeshFormat::Off, "out of range" },
    { "OFF huge counts", "OFF\n2000000000 1 0\n0 0 0\n", MeshFormat::Off, "cannot fit" },
    // a negative count is named as one (it was "-3 vertices and 1 faces cannot fit in the rest of the file")
    { "OFF negative vertex count", "OFF\n-3 1 0\n" + tri + "3 0 1 2\n", MeshFormat::Off, "OFF line 2: negative vertex count -3" },
    { "OFF negative face count", "OFF\n3 -1 0\n" + tri, MeshFormat::Off, "OFF line 2: negative face count -1" },
    { "OFF truncated", "OFF\n3 1 0\n0 0 0\n1 0 0\n# a comment long enough to pass the size bound\n", MeshFormat::Off, "file ends" },
    { "OFF counts past the size", "OFF\n3 1 0\n0 0 0\n1 0 0\n", MeshFormat::Off, "cannot fit" },
    { "OFF face shorter than announced", "OFF\n3 1 0\n" + tri + "4 0 1 2\n", MeshFormat::Off, "announces 4" },
    { "OFF no header", "3 1 0\n" + tri, MeshFormat::Off, "header" },
    // OFF's header variants that change what the coordinates are were read as plain OFF (a 4OFF whose
    // w is 2 came out twice its size, an nOFF's dimension line "expected vertex, face (and edge) counts")
    { "4OFF", "4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n", MeshFormat::Off,
      "OFF line 1: header '4OFF': homogeneous vertices (x y z w) are not read; write the points x/w y/w z/w under an 'OFF' header" },
    { "nOFF", "nOFF\n3\n3 1 0\n" + tri + "3 0 1 2\n", MeshFormat::Off,
      "OFF line 1: header 'nOFF': vertices of the dimension given on the next line are not read" },
    { "C4OFF", "C4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n", MeshFormat::Off, "header 'C4OFF': homogeneous" },
    { "OFF unknown prefix", "HELLOOFF\n3 1 0\n" + tri + "3 0 1 2\n", MeshFormat::Off,
      "OFF line 1: header 'HELLOOFF' is not an OFF header ([ST][C][N]OFF" },
    { "PLY index out of range", plyHead + tri + "3 0 1 3\n", MeshFormat::Ply, "out of range" },
    { "PLY negative index", plyHead + tri + "3 0 -1 2\n", MeshFormat::Ply, "out of range" },
    { "PLY empty face", plyHead + tri + "0\n", MeshFormat::Ply, "PLY face 0: a face needs at least 3 vertices, this one has 0" },
    { "PLY NaN", plyHead + "nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Ply, "NaN" },
    { "PLY too few values", plyHead + "0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Ply, "too few" },
    { "PLY huge count", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n" + std::string(12, '\0'), MeshFormat::Ply, "cannot fit" },
    { "PLY truncated binary", binaryPly(false).substr(0, binaryPly(false).size() - 3), MeshFormat::Ply, "ends inside" },
    // a list's count that the record or the file cannot hold names the list, its count and the room
    // (it was "PLY face 0: list of 300 items", and a count one too many "record has too few values")
    // a type the header cannot have is named (it was "bad list property types", or for a scalar
    // "expected 'property <type> <name>' or ...")
    { "PLY float list count", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list float int vertex_indices\nend_header\n" + tri + "3 0 1 2\n", MeshFormat::Ply,
      "PLY header line 8: list count type 'float' is not an integer type" },
    { "PLY unknown list item type", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int64 vertex_indices\nend_header\n" + tri + "3 0 1 2\n", MeshFormat::Ply,
      "PLY header line 8: unknown list item type 'int64' (PLY's types: char, uchar, short, ushort, int, uint, float, double, or int8, " },
    { "PLY unknown list count type", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list byte int vertex_indices\nend_header\n" + tri + "3 0 1 2\n", MeshFormat::Ply,
      "PLY header line 8: unknown list count type 'byte' (PLY's types:" },
    { "PLY unknown scalar type", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty real z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n" + tri + "3 0 1 2\n", MeshFormat::Ply,
      "PLY header line 6: unknown property type 'real' (PLY's types:" },
    { "PLY list count past the record", plyHead + tri + "300 0 1 2\n", MeshFormat::Ply,
      "PLY face 0: list 'vertex_indices' announces 300 items but the record holds 3 more values (a wrong count, or a damaged file)" },
    { "PLY list count one too many", plyHead + tri + "4 0 1 2\n", MeshFormat::Ply,
      "PLY face 0: list 'vertex_indices' announces 4 items but the record holds 3 more values" },
    { "PLY negative list count", plyHead + tri + "-1 0 1 2\n", MeshFormat::Ply,
      "PLY face 0: list 'vertex_indices' announces -1 items, a negative count" },
    { "PLY binary list count past the file", [] {
        std::string b = binaryPly(false);
        const std::size_t body = b.find("end_header\n") + 11;
        b[body + 4 * 17] = char(200); // the face's uchar count, after 4 vertices of 8 + 4 + 4 + 1 bytes
        return b;
      }(), MeshFormat::Ply, "PLY face 0: list 'vertex_indices' announces 200 items, more than the 85 bytes after the header" },
    // triangle strips are not read: named (it said only "the file holds no triangles")
    { "PLY tristrips", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 2 3\n",
      MeshFormat::Ply, "PLY: the file holds no triangles: only the element 'face' is read, and its 1 'tristrips' records "
      "(triangle strips?) are not faces" },
    { "PLY no format", "ply\nelement vertex 0\nend_header\n", MeshFormat::Ply, "no format" },
    { "PLY no end_header", "ply\nformat ascii 1.0\nelement vertex 0\n", MeshFormat::Ply, "no end_header" },
    { "PLY missing z", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", MeshFormat::Ply, "without x, y and z" },
    { "PLY not ply", "plx\n", MeshFormat::Ply, "magic" },
    // records past the header's counts: dropped without a word (a mesh with holes), now refused
    { "PLY more faces than counted", plyHead + tri + "3 0 1 2\n3 0 2 1\n", MeshFormat::Ply,
      "PLY line 14: more records than the header's element counts" },
    // ... and in a binary file: the faces past the count were dropped without a word, as a last face
    // whose count was one too low lost its last corner (the bytes left were never looked at)
    { "PLY binary more faces than counted", [] {
        std::string b = binaryPly(false);
        put<std::uint8_t>(b, 3);
        for (int i : { 0, 2, 1 })
          put<std::int32_t>(b, i);
        return b;
      }(), MeshFormat::Ply,
      "PLY: more data than the header's element counts: 13 bytes after the last record (wrong counts, or a damaged file)" },
    { "PLY binary list count one too low", [] {
        std::string b = binaryPly(false);
        b[b.find("end_header\n") + 11 + 4 * 17] = 3; // the face's uchar count: 3 of its 4 corners read
        return b;
      }(), MeshFormat::Ply, "PLY: more data than the header's element counts: 4 bytes after the last record" },
    { "OFF more faces than counted", "OFF\n3 1 0\n" + tri + "3 0 1 2\n\n# a comment\n3 0 2 1\n", MeshFormat::Off,
      "OFF line 9: more records than the header's 3 vertices and 1 faces" },
    // a name given twice is a broken header: the last one was taken (a second x made
    // every vertex's x 5, and the error blamed the triangles' area)
    { "PLY property twice", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 5\n1 0 0 5\n0 1 0 5\n3 0 1 2\n", MeshFormat::Ply,
      "PLY header line 7: property 'x' of element 'vertex' given twice" },
    { "PLY element twice", plyHead.substr(0, plyHead.size() - 11) + "element vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n" + tri + "3 0 1 2\n" + tri, MeshFormat::Ply,
      "PLY header line 9: element 'vertex' given twice" },
    { "STL neither", "hello", MeshFormat::Stl, "neither a binary STL (size is not 84 + 50 x triangle count) nor an ASCII one" },
    // a binary STL whose count disagrees with its size names both (it said only "size is not 84 + 50 x triangle count")
    { "STL wrong count", std::string(80, ' ') + std::string("\x05\0\0\0", 4) + std::string(150, '\0'), MeshFormat::Stl,
      "STL: neither a binary STL (its header announces 5 triangles, 84 + 50 x 5 = 334 bytes, but the file has 234 bytes) nor an ASCII one (no 'solid')" },
    // a binary STL whose header starts with "solid" (many exporters write one) and whose size is off: it was
    // "nor an ASCII one (no 'solid')" about a file that starts with 'solid'
    { "STL solid header, wrong count", "solid part" + std::string(70, ' ') + std::string("\x05\0\0\0", 4) +
      std::string(151, '\0'), MeshFormat::Stl,
      "STL: neither a binary STL (its header announces 5 triangles, 84 + 50 x 5 = 334 bytes, but the file has 235 bytes) "
      "nor an ASCII one (it starts with 'solid' but holds binary data: a NUL byte in its first 4 KiB)" },
    // a facet of the wrong shape names its line (a file cut off after 'facet normal' said
    // "holds no triangles"; a facet without 'endloop' or 'endfacet' was taken)
    { "STL 4-vertex facet", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n", MeshFormat::Stl,
      "STL line 7: the facet of line 2 has a 4th vertex (STL facets have 3)" },
    { "STL 2-vertex facet", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n", MeshFormat::Stl,
      "STL line 6: the facet of line 2 has 2 vertices (STL facets have 3)" },
    { "STL cut after facet normal", "solid a\nfacet normal 0 0 1\n", MeshFormat::Stl,
      "STL line 2: the file ends inside the facet of line 2 (no 'outer loop': is it cut off?)" },
    { "STL cut inside a loop", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n", MeshFormat::Stl,
      "STL line 6: the file ends inside the facet of line 2 (no 'endloop': is it cut off?)" },
    { "STL cut before endfacet", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n", MeshFormat::Stl,
      "STL line 7: the file ends inside the facet of line 2 (no 'endfacet': is it cut off?)" },
    { "STL no endloop", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid\n", MeshFormat::Stl,
      "STL line 7: 'endfacet' inside the facet of line 2 (no 'endloop')" },
    { "STL no endfacet", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n", MeshFormat::Stl,
      "STL line 8: a facet starts before the facet of line 2 ends (no 'endfacet')" },
    { "STL endsolid in a facet", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendsolid\n", MeshFormat::Stl,
      "STL line 5: 'endsolid' inside the facet of line 2 (no 'endloop')" },
    { "STL vertex outside a loop", "solid a\nvertex 0 0 0\n", MeshFormat::Stl, "STL line 2: 'vertex' outside a facet's 'outer loop'" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.label);
    expectError(c.text, c.f, c.needle);
  }
}

// Text from the file is quoted printable and short: a binary body under an ASCII
// PLY header ended the message at its first NUL byte ("PLY vertex 0: '"), and an
// OBJ face corner of 100,000 characters was quoted whole.
TEST(MeshFile, MessagesQuoteFileTextPrintableAndShort)
{
  auto messageOf = [](const std::string& text, MeshFormat f) {
    try
    {
      readText(text, f);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // the binary square under a header that says ascii: its first double, 0, is eight NUL bytes
  std::string mixed = binaryPly(false);
  mixed.replace(mixed.find("binary_little_endian"), 20, "ascii");
  const std::string m = messageOf(mixed, MeshFormat::Ply);
  EXPECT_EQ(m.find('\0'), std::string::npos);
  EXPECT_EQ(m.rfind("PLY vertex 0: '\\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00", 0), 0u) << m;
  EXPECT_NE(m.find("...' is not a number (binary data where text was expected: is the file's format right?)"),
    std::string::npos) << m;
  // a NUL after the first 4 KiB of an OBJ (the head check reads 4 KiB)
  const std::string nul = messageOf("v 0 0 0\n# " + std::string(5000, 'c') + "\nv 1 " + std::string(1, '\0') + " 2\n", MeshFormat::Obj);
  EXPECT_EQ(nul, "OBJ line 3: '\\x00' is not a number (binary data where text was expected: is the file's format right?)");
  // long tokens: 40 bytes, then "..."
  const std::string corner = messageOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3//" + std::string(100000, '1') + "/\n", MeshFormat::Obj);
  EXPECT_EQ(corner, "OBJ line 4: bad face corner '3//" + std::string(37, '1') + "...' (expected v, v/vt, v//vn or v/vt/vn)");
  const std::string stl = messageOf("solid a\n" + std::string(1000, 'z') + "\n", MeshFormat::Stl);
  EXPECT_EQ(stl, "STL line 2: unexpected '" + std::string(40, 'z') + "...'");
}

// A polygon of n corners becomes n - 2 triangles that tile it (each of its
// edges once, each inner edge twice in opposite directions, the polygon's
// area, its winding), and no corner collects more than a few of them: a fan
// from corner 0 put all n - 2 slivers on one corner and mesh to SDF of a
// 100,000-corner OBJ face took minutes. Every format and the parallel OBJ
// reader (a file of 4 MiB or more) give the same triangles.
TEST(MeshFile, PolygonsBecomeLocalTriangles)
{
  const double pi = 3.14159265358979323846;
  for (int n : { 3, 4, 5, 6, 7, 8, 9, 17, 100, 1000, 65536 }) // up to MaxPolygonCorners
  {
    SCOPED_TRACE(n);
    std::string obj, off = "OFF\n" + std::to_string(n) + " 1 0\n", face = "f", offFace = std::to_string(n);
    for (int i = 0; i < n; ++i)
    {
      char v[96];
      std::snprintf(v, sizeof v, "%.9f %.9f 0", std::cos(2 * pi * i / n), std::sin(2 * pi * i / n));
      obj += std::string("v ") + v + "\n";
      off += std::string(v) + "\n";
      face += " " + std::to_string(i + 1);
      offFace += " " + std::to_string(i);
    }
    obj += face + "\n";
    off += offFace + "\n";
    const TriangleMesh m = readText(obj, MeshFormat::Obj);
    ASSERT_EQ(m.triangles.size(), std::size_t(n - 2));
    EXPECT_EQ(readText(off, MeshFormat::Off).triangles, m.triangles);
    if (obj.size() < (std::size_t(4) << 20)) // the parallel reader too: the same face in a file past 4 MiB
    {
      std::string big = obj + "# " + std::string((std::size_t(4) << 20) - obj.size(), 'x') + "\n";
      EXPECT_EQ(readText(big, MeshFormat::Obj).triangles, m.triangles);
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    std::vector<int> perCorner(static_cast<std::size_t>(n), 0);
    double area = 0;
    for (const auto& t : m.triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        ++edges[{ t[k], t[(k + 1) % 3] }];
        ++perCorner[t[k]];
      }
      const Vec3f &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
      const double twice = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
      if (n <= 1000) // (beyond, neighbours on the circle are collinear in float)
        EXPECT_GT(twice, 0) << "winding"; // counter-clockwise as the polygon
      area += twice / 2;
    }
    for (const auto& e : edges)
    {
      ASSERT_EQ(e.second, 1);
      const bool boundary = (e.first.second == (e.first.first + 1) % std::uint32_t(n));
      EXPECT_EQ(edges.count({ e.first.second, e.first.first }), boundary ? 0u : 1u);
    }
    // the regular n-gon's area, n/2 sin(2 pi / n), computed independently
    EXPECT_NEAR(area, n / 2.0 * std::sin(2 * pi / n), 1e-6 * n / 2.0 * std::sin(2 * pi / n) + 1e-9);
    const int most = *std::max_element(perCorner.begin(), perCorner.end());
    EXPECT_LE(most, 2 * int(std::ceil(std::log2(n))) + 1);
  }
}

// A face of more than 65,536 corners (MaxPolygonCorners) is refused by every
// reader with its place and corner count (a face of 10^6 corners took 204 s and
// 1.37 GB through mesh to SDF); 65,536 corners are read (the test above).
TEST(MeshFile, FacesOfMoreThanTheCornerLimitAreRefused)
{
  ASSERT_EQ(MaxPolygonCorners, 65536);
  const int n = 65537, v = 70000;
  std::string points, objFace = "f", offFace = std::to_string(n), plyFace = std::to_string(n);
  std::string plyBinary;
  for (int i = 0; i < v; ++i) points += std::to_string(i) + " " + std::to_string(i % 7) + " 0\n";
  for (int i = 0; i < n; ++i)
  {
    objFace += " " + std::to_string(i + 1);
    offFace += " " + std::to_string(i);
    plyFace += " " + std::to_string(i);
  }
  std::string obj;
  for (int i = 0; i < v; ++i) obj += "v " + std::to_string(i) + " " + std::to_string(i % 7) + " 0\n";
  obj += "f 1 2 3\n" + objFace + "\n";
  const std::string message = "a face of 65537 corners: at most 65536 corners a face";
  expectError(obj, MeshFormat::Obj, "OBJ line " + std::to_string(v + 2) + ": " + message);
  // the parallel OBJ reader (4 MiB or more) leaves it to the serial one
  expectError(obj + "# " + std::string(std::size_t(4) << 20, 'x') + "\n", MeshFormat::Obj,
    "OBJ line " + std::to_string(v + 2) + ": " + message);
  expectError("OFF\n" + std::to_string(v) + " 2 0\n" + points + "3 0 1 2\n" + offFace + "\n", MeshFormat::Off, message);
  const std::string plyHead = "element vertex " + std::to_string(v) +
    "\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list int int vertex_indices\nend_header\n";
  expectError("ply\nformat ascii 1.0\n" + plyHead + points + "3 0 1 2\n" + plyFace + "\n", MeshFormat::Ply,
    "PLY face 1: " + message);
  std::string bin = "ply\nformat binary_little_endian 1.0\n" + plyHead;
  for (int i = 0; i < v; ++i)
    for (float c : { float(i), float(i % 7), 0.0f }) put<float>(bin, c);
  put<std::int32_t>(bin, 3);
  for (int i = 0; i < 3; ++i) put<std::int32_t>(bin, i);
  put<std::int32_t>(bin, n);
  for (int i = 0; i < n; ++i) put<std::int32_t>(bin, i);
  expectError(bin, MeshFormat::Ply, "PLY face 1: " + message);
  // one corner fewer is read (the same file otherwise)
  std::string fits = obj.substr(0, obj.rfind(' ')) + "\n";
  EXPECT_EQ(readText(fits, MeshFormat::Obj).triangles.size(), std::size_t(1 + 65536 - 2));
}

TEST(MeshFile, BinaryPlyFastPathMatchesTheGeneralReader)
{
  // float-only vertices and uchar/int triangle lists take the fast path of
  // little-endian files; the same records as ASCII (and big-endian) go
  // through the general reader: the meshes must be equal, and a record the
  // fast path leaves (a quad, a bad index, a NaN, a truncation) must give
  // the general reader's result or message
  const float v[5][4] = { { 0, 0, 0, 1 }, { 1, 0, 0, 1 }, { 1, 1, 0, 1 }, { 0, 1, 0.5f, 1 }, { 2, 2, 2, 1 } };
  const std::vector<std::vector<int>> faces = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 1, 2, 3 }, { 1, 2, 4 } };
  auto head = [&](const std::string& format, std::size_t nv, std::size_t nf, const char* index) {
    return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(nv) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nelement face " + std::to_string(nf) +
      "\nproperty list uchar " + index + " vertex_indices\nend_header\n";
  };
  auto binary = [&](bool big, const char* index, int badFace, float nanAt) {
    std::string s = head(big ? "binary_big_endian" : "binary_little_endian", 5, faces.size(), index);
    for (int i = 0; i < 5; ++i)
      for (int k = 0; k < 4; ++k) put<float>(s, i == 2 && k == 1 ? nanAt : v[i][k], big);
    for (std::size_t f = 0; f < faces.size(); ++f)
    {
      put<std::uint8_t>(s, static_cast<std::uint8_t>(faces[f].size()));
      for (int id : faces[f]) put<std::int32_t>(s, int(f) == badFace && id == faces[f].back() ? 99 : id, big);
    }
    return s;
  };
  std::string ascii = head("ascii", 5, faces.size(), "int");
  for (auto& p : v) ascii += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 1\n";
  for (auto& f : faces)
  {
    ascii += std::to_string(f.size());
    for (int id : f) ascii += " " + std::to_string(id);
    ascii += "\n";
  }
  const TriangleMesh want = readText(ascii, MeshFormat::Ply);
  ASSERT_EQ(want.triangles.size(), 5u);
  for (const char* index : { "int", "uint" })
    for (bool big : { false, true })
    {
      const TriangleMesh got = readText(binary(big, index, -1, v[2][1]), MeshFormat::Ply);
      EXPECT_EQ(got.points, want.points) << index << big;
      EXPECT_EQ(got.triangles, want.triangles) << index << big;
    }
  expectError(binary(false, "int", 1, v[2][1]), MeshFormat::Ply, "PLY face 1: vertex index 99 out of range [0, 5)");
  expectError(binary(false, "int", 3, v[2][1]), MeshFormat::Ply, "PLY face 3: vertex index 99 out of range");
  expectError(binary(false, "int", -1, std::numeric_limits<float>::quiet_NaN()), MeshFormat::Ply, "PLY vertex 2");
  const std::string whole = binary(false, "int", -1, v[2][1]);
  const std::size_t vertexBytes = whole.find("end_header\n") + 11;
  expectError(whole.substr(0, vertexBytes + 16 * 3 + 5), MeshFormat::Ply, "ends inside");
}

// A binary PLY face whose corner count is one too high takes its last corner from the
// next face's bytes, and the next face is read from the wrong place: it was reported
// ("PLY face 2: a face needs at least 3 vertices, this one has 0"), the wrong face; now
// the face whose count is wrong, with what was found. A count one too high in the last
// face was "PLY face: file ends inside the element data", naming no face.
TEST(MeshFile, BinaryPlyCountOneTooHighIsReportedAtItsFace)
{
  auto ply = [](std::vector<std::vector<int>> faces, int wrong) {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nelement face " + std::to_string(faces.size()) +
      "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 4; ++i)
      for (float c : { float(i & 1), float(i >> 1), 0.f }) put<float>(s, c);
    for (std::size_t f = 0; f < faces.size(); ++f)
    {
      put<std::uint8_t>(s, static_cast<std::uint8_t>(faces[f].size() + (int(f) == wrong)));
      for (int id : faces[f]) put<std::int32_t>(s, id);
    }
    return s;
  };
  const std::vector<std::vector<int>> faces = { { 0, 1, 2 }, { 1, 3, 2 }, { 0, 1, 3 } };
  EXPECT_EQ(readText(ply(faces, -1), MeshFormat::Ply).triangles.size(), 3u); // the oracle: the file is right with its counts
  auto message = [](const std::string& text) {
    return errortest::errorMessageOf([&] { readText(text, MeshFormat::Ply); }, ErrorCode::CorruptData);
  };
  // face 1 announces 4: its fourth corner is face 2's count byte (3) and the first bytes of its 0, a valid
  // index 3, and face 2's count is the last byte of that 0
  EXPECT_EQ(message(ply(faces, 1)),
    "PLY face 1: list 'vertex_indices' announces 4 items, most likely one too many: its last item was read from the "
    "bytes of face 2, which then failed (a face needs at least 3 vertices, this one has 0); with 3 items, face 2 reads "
    "as a valid face");
  EXPECT_EQ(message(ply(faces, 2)), "PLY face 2: list 'vertex_indices' announces 4 items of 4 bytes, but the file ends "
                                    "inside them, 12 bytes after the count (a wrong count, or a cut file)");
  // a face that is wrong itself stays reported where it is
  EXPECT_EQ(message(ply({ { 0, 1, 2 }, { 1, 3, 2, 2 }, { 0, 1, 9 } }, -1)), "PLY face 2: vertex index 9 out of range [0, 4)");
}

TEST(MeshFile, BinaryStlSharesCornersOfLargeMeshes)
{
  // a 40 x 40 grid as 3,200 separate STL triangles: the 1,681 distinct
  // corners are shared again (the point table grows past its first size),
  // ids in order of first appearance, every corner at its own position
  const int k = 40;
  std::string bin(80, ' ');
  put<std::uint32_t>(bin, 2 * k * k);
  std::vector<std::array<float, 9>> tris;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i)
    {
      const float x0 = i * 0.25f, x1 = (i + 1) * 0.25f, y0 = j * 0.5f, y1 = (j + 1) * 0.5f;
      tris.push_back({ x0, y0, 1, x1, y0, 1, x1, y1, 1 });
      tris.push_back({ x0, y0, 1, x1, y1, 1, x0, y1, 1 });
    }
  for (const auto& t : tris)
  {
    for (int i = 0; i < 3; ++i) put<float>(bin, 0);
    for (float f : t) put<float>(bin, f);
    put<std::uint16_t>(bin, 0);
  }
  const TriangleMesh m = readText(bin, MeshFormat::Stl);
  EXPECT_EQ(m.points.size(), std::size_t((k + 1) * (k + 1)));
  ASSERT_EQ(m.triangles.size(), tris.size());
  std::uint32_t next = 0; // first appearances number the points 0, 1, 2, ...
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c)
    {
      const std::uint32_t id = m.triangles[t][c];
      EXPECT_EQ(m.points[id], (Vec3f{ tris[t][3 * c], tris[t][3 * c + 1], tris[t][3 * c + 2] }));
      if (id == next) ++next;
      EXPECT_LT(id, next);
    }
  // a NaN corner still names its triangle
  std::string bad = bin;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bad[84 + 50 * 7 + 12 + 4], &nan, 4);
  expectError(bad, MeshFormat::Stl, "STL triangle 7");
}

TEST(MeshFile, LargeOffOnThreadsMatchesTheSerialReader)
{
  // 250 x 250 grid: 62,500 vertices and 124,002 faces (above the parallel
  // path's threshold). The same text with a comment line (which the parallel
  // path leaves to the serial reader) must give the same mesh; a bad index,
  // a quad and a '+' sign give the serial reader's result or message.
  const int k = 250;
  std::string body;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) body += gridVertex(i, j);
  const std::size_t verticesEnd = body.size();
  std::vector<std::string> faces = gridFaces(k, " ", " 1 2 3\n");
  faces.push_back("3 0 1 2\n");
  faces.push_back("3 2 1 0\n");
  faces.push_back("3 0 1 251\n");
  faces.push_back("3 0 251 250\n");
  auto file = [&](const std::string& verts, const std::vector<std::string>& fs) {
    std::string s = "OFF\n" + std::to_string(k * k) + " " + std::to_string(fs.size()) + " 0\n" + verts;
    for (const auto& f : fs) s += f;
    return s;
  };
  const TriangleMesh fast = readText(file(body, faces), MeshFormat::Off);
  const TriangleMesh serial = readText(file(body.substr(0, verticesEnd) + "# serial\n", faces), MeshFormat::Off);
  ASSERT_EQ(fast.points.size(), std::size_t(k * k));
  EXPECT_EQ(fast.points, serial.points);
  EXPECT_EQ(fast.triangles, serial.triangles);
  auto bad = faces;
  bad[70000] = "3 0 1 62500\n";
  expectError(file(body, bad), MeshFormat::Off, "OFF line " + std::to_string(2 + k * k + 70000 + 1) + ": vertex index 62500");
  auto quad = faces;
  quad[5] = "4 0 1 251 250\n"; // a fan of two triangles
  const TriangleMesh q = readText(file(body, quad), MeshFormat::Off);
  EXPECT_EQ(q.triangles.size(), faces.size() + 1);
  const std::string plus = "+" + body; // "+0 ...": strtod reads it, from_chars does not
  EXPECT_EQ(readText(file(plus, faces), MeshFormat::Off).points, fast.points);
  // a face past the count is refused on the threaded path too, at its line (it was dropped)
  std::string more = file(body, faces) + "\n3 0 1 2\n";
  expectError(more, MeshFormat::Off,
    "OFF line " + std::to_string(2 + k * k + faces.size() + 2) + ": more records than the header's");
  expectError(file(body.substr(0, verticesEnd) + "# serial\n", faces) + "3 0 1 2\n", MeshFormat::Off,
    "OFF line " + std::to_string(2 + k * k + 1 + faces.size() + 1) + ": more records than the header's");
}

TEST(MeshFile, LargeAsciiPlyOnThreadsMatchesTheSerialReader)
{
  // 250 x 250 grid (62,500 vertices, 124,002 faces: above the parallel
  // path's threshold). The same records with a comment line in each element
  // (which the parallel path leaves to the serial loop) must give the same
  // mesh; a '+' sign, a quad, an index out of range and a value too many
  // give the serial loop's result or message.
  const int k = 250;
  std::vector<std::string> verts, faces = gridFaces(k, "\t", " \r\n");
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) verts.push_back(gridVertex(i, j));
  faces.push_back("3 0 1 2\n");
  faces.push_back("\n3 2 1 0\n");
  auto file = [&](const std::vector<std::string>& vs, const std::vector<std::string>& fs, const std::string& extra) {
    std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vs.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face " +
      std::to_string(fs.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < vs.size(); ++i) s += (i == 7 ? extra : "") + vs[i];
    for (std::size_t i = 0; i < fs.size(); ++i) s += (i == 9 ? extra : "") + fs[i];
    return s;
  };
  const TriangleMesh fast = readText(file(verts, faces, ""), MeshFormat::Ply);
  const TriangleMesh serial = readText(file(verts, faces, "# serial\n"), MeshFormat::Ply);
  ASSERT_EQ(fast.points.size(), std::size_t(k * k));
  ASSERT_EQ(fast.triangles.size(), faces.size());
  EXPECT_EQ(fast.points, serial.points);
  EXPECT_EQ(fast.triangles, serial.triangles);
  auto plus = verts;
  plus[100] = "+" + plus[100]; // strtod reads it, from_chars does not
  EXPECT_EQ(readText(file(plus, faces, ""), MeshFormat::Ply).points, fast.points);
  auto quad = faces;
  quad[5] = "4 0 1 251 250\n"; // a fan of two triangles
  EXPECT_EQ(readText(file(verts, quad, ""), MeshFormat::Ply).triangles.size(), faces.size() + 1);
  auto bad = faces;
  bad[70000] = "3 0 1 62500\n";
  expectError(file(verts, bad, ""), MeshFormat::Ply, "PLY face 70000: vertex index 62500 out of range");
  // a face past the count is refused after the threaded path too (it was dropped)
  expectError(file(verts, faces, "") + "3 0 1 2\n", MeshFormat::Ply,
    "PLY line " + std::to_string(10 + k * k + faces.size() + 2) + ": more records than the header's element counts");
  auto extra = verts;
  extra[3] = "1 2 3 4 5\n";
  expectError(file(extra, faces, ""), MeshFormat::Ply, "PLY vertex 3: record has 1 values too many");
}

TEST(MeshFile, LargeObjOnThreadsMatchesTheSerialReader)
{
  // 300 x 300 grid: 90,000 vertices, texture coordinates and normals,
  // faces in every corner form, quads, comments (above the parallel path's
  // 4 MiB). A negative index (which the parallel path leaves to the serial
  // reader) in one more face gives the same mesh plus that face; a '+' sign
  // and an index not yet defined give the serial reader's result or message.
  const int k = 300;
  std::string body;
  char buf[128];
  for (int j = 0; j < k; ++j)
  {
    for (int i = 0; i < k; ++i)
      body += std::string(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g%s\n",
        0.1 * i + 1e-7 * j, 0.37 * j, std::sin(0.3 * i) * 1e-3, i % 7 == 0 ? " 1.0 # w" : "")));
    body += "vt 0.5 0.5\nvn 0 0 1\n";
    if (j == 0) continue;
    for (int i = 0; i + 1 < k; ++i)
    {
      const int d = j * k + i + 1, a = d - k, b = a + 1, c = d + 1; // 1-based
      const std::string t = std::to_string(j), n = std::to_string(j + 1);
      if (i % 3 == 0)
        body += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
      else if (i % 3 == 1)
        body += "f " + std::to_string(a) + "/" + t + "/" + n + " " + std::to_string(b) + "//" + n + " " +
          std::to_string(c) + "/" + t + "\nf " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + " # tri\n";
      else
        body += "g part\nf\t" + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\r\nf " +
          std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
  }
  ASSERT_GT(body.size(), std::size_t(1) << 22);
  const TriangleMesh fast = readText(body, MeshFormat::Obj);
  const TriangleMesh serial = readText(body + "f 1 2 -1\n", MeshFormat::Obj);
  ASSERT_EQ(fast.points.size(), std::size_t(k * k));
  EXPECT_EQ(readText("\xEF\xBB\xBF" + body, MeshFormat::Obj).points, fast.points); // a byte order mark: no vertex lost
  EXPECT_EQ(fast.points, serial.points);
  ASSERT_EQ(serial.triangles.size(), fast.triangles.size() + 1);
  EXPECT_TRUE(std::equal(fast.triangles.begin(), fast.triangles.end(), serial.triangles.begin()));
  EXPECT_EQ(serial.triangles.back(), (std::array<std::uint32_t, 3>{ 0, 1, std::uint32_t(k * k - 1) }));
  std::string plus = body;
  plus.replace(plus.find("v ") + 2, 0, "+");
  EXPECT_EQ(readText(plus, MeshFormat::Obj).points, fast.points);
  std::string early = "f 1 2 3\n" + body;
  expectError(early, MeshFormat::Obj, "OBJ line 1: vertex index 1 out of range: 0 vertices defined so far");
}

TEST(MeshFile, TextNumbersAreCTextUnderACommaLocale)
{
  // a host (the Qt editor, ParaView, Python) may set LC_NUMERIC to a comma
  // locale: "0.5" was then refused ("'0.5' is not a number") by strtod
  lvdif::test::CommaLocale comma;
  if (!comma.made) GTEST_SKIP() << "no comma-decimal locale could be made (localedef)";
  expectSquare(readText("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 3 4\n", MeshFormat::Obj));
  expectSquare(readText("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n", MeshFormat::Off));
  expectSquare(readText("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n",
    MeshFormat::Ply));
}
