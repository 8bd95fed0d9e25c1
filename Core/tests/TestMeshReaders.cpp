// PLY / OFF readers: ascii and both binary byte orders give the same mesh;
// broken files are refused with CorruptData (never a crash or a huge allocation).
#include "lvdif/Error.h"
#include "lvdif/MeshReaders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
std::string tempPath(const std::string& name)
{
  return (::testing::TempDir().empty() ? std::string("/tmp/") : ::testing::TempDir()) + "lvdif_reader_" + name;
}

std::string write(const std::string& name, const std::string& content)
{
  const std::string p = tempPath(name);
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

template <typename T>
void put(std::string& s, T v, bool big)
{
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

// a unit square as one quad plus a triangle, with an extra element to skip
std::string binaryPly(bool big)
{
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
    " 1.0\ncomment test\nelement vertex 5\nproperty float x\nproperty float y\nproperty double z\n"
    "element face 2\nproperty uchar intensity\nproperty list uchar int vertex_indices\n"
    "element extra 1\nproperty list uchar float junk\nend_header\n";
  const float xy[5][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 2, 2 } };
  for (auto& p : xy)
  {
    put(s, p[0], big);
    put(s, p[1], big);
    put(s, 0.5, big);
  }
  s.push_back(7);
  s.push_back(4);
  for (int i : { 0, 1, 2, 3 }) put(s, std::int32_t(i), big);
  s.push_back(7);
  s.push_back(3);
  for (int i : { 1, 4, 2 }) put(s, std::int32_t(i), big);
  s.push_back(2);
  put(s, 1.0f, big);
  put(s, 2.0f, big);
  return s;
}

const char* AsciiPly = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                       "property float nx\nproperty float ny\nproperty float nz\n"
                       "element face 2\nproperty list uchar int vertex_index\nend_header\n"
                       "0 0 0.5 0 0 1\n1 0 0.5 0 0 1\n1 1 0.5 0 0 1\n0 1 0.5 0 0 1\n2 2 0.5 0 0 1\n4 0 1 2 3\n3 1 4 2\n";

void expectSquare(const TriangleMesh& m)
{
  ASSERT_EQ(m.points.size(), 5u);
  ASSERT_EQ(m.triangles.size(), 3u); // quad fan-triangulated + one triangle
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{ 0, 1, 2 }));
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{ 0, 2, 3 }));
  EXPECT_EQ(m.triangles[2], (std::array<std::uint32_t, 3>{ 1, 4, 2 }));
  EXPECT_FLOAT_EQ(m.points[4][0], 2);
  EXPECT_FLOAT_EQ(m.points[2][2], 0.5f);
  m.validate();
}

ErrorCode codeOf(const std::string& path)
{
  try
  {
    readMesh(path);
  }
  catch (const Error& e)
  {
    return e.code();
  }
  return ErrorCode::Unsupported; // "no error" marker, distinct from CorruptData
}
} // namespace

TEST(MeshReaders, PlyAllFormatsAgree)
{
  expectSquare(readMesh(write("le.ply", binaryPly(false))));
  expectSquare(readMesh(write("be.ply", binaryPly(true))));
  const TriangleMesh a = readMesh(write("a.PLY", AsciiPly));
  expectSquare(a);
  ASSERT_EQ(a.normals.size(), 5u);
  EXPECT_FLOAT_EQ(a.normals[3][2], 1);
}

TEST(MeshReaders, Off)
{
  const TriangleMesh m = readMesh(write("m.off", "OFF # comment\n5 2 0\n0 0 0.5\n1 0 0.5\n1 1 0.5\n0 1 0.5\n2 2 0.5\n"
                                                 "4 0 1 2 3\n3 1 4 2\n"));
  expectSquare(m);
}

TEST(MeshReaders, BrokenFilesAreRefused)
{
  std::string s = AsciiPly;
  EXPECT_EQ(codeOf(write("idx.ply", std::string(AsciiPly).replace(s.find("3 1 4 2"), 7, "3 1 5 2"))),
    ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("neg.ply", std::string(AsciiPly).replace(s.find("3 1 4 2"), 7, "3 1 -1 2"))),
    ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("nan.ply", std::string(AsciiPly).replace(s.find("2 2 0.5"), 7, "2 nan 0.5"))),
    ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("two.ply", std::string(AsciiPly).replace(s.find("3 1 4 2"), 7, "2 1 4  "))),
    ErrorCode::CorruptData);
  const std::string bin = binaryPly(false);
  EXPECT_EQ(codeOf(write("trunc.ply", bin.substr(0, bin.size() - 12))), ErrorCode::CorruptData);
  std::string huge = bin;
  huge.replace(huge.find("vertex 5"), 8, "vertex 4000000000");
  EXPECT_EQ(codeOf(write("huge.ply", huge)), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("nohdr.ply", "ply\nformat ascii 1.0\nelement vertex 1\n")), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("notply.ply", "solid x\n")), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("fmt.ply", "ply\nformat weird 1.0\nend_header\n")), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                       "property float z\nend_header\n0 0 0\n")),
    ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("offbig.off", "OFF\n99999999 1 0\n0 0 0\n")), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(write("offidx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")), ErrorCode::CorruptData);
  EXPECT_EQ(codeOf(tempPath("does-not-exist.ply")), ErrorCode::IoFailure);
  EXPECT_EQ(codeOf(write("x.stl", "solid")), ErrorCode::Unsupported);
}

TEST(MeshReaders, MutatedFilesNeverCrash)
{
  // deterministic fuzzing: every mutated file either reads into a mesh that
  // validates, or is refused with an lvdif::Error (never a crash or a hang)
  std::mt19937 rng(1234);
  const std::string seeds[3] = { binaryPly(false), binaryPly(true), AsciiPly };
  int refused = 0, read = 0;
  for (int n = 0; n < 600; ++n)
  {
    std::string s = seeds[n % 3];
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e)
    {
      const std::size_t at = rng() % s.size();
      switch (rng() % 3)
      {
        case 0: s[at] = static_cast<char>(rng() & 0xff); break;
        case 1: s.erase(at, 1 + rng() % 8); break;
        default: s.insert(at, 1, static_cast<char>('0' + rng() % 10)); break;
      }
      if (s.empty()) s = "p";
    }
    const std::string p = write("fuzz.ply", s);
    try
    {
      const TriangleMesh m = readMesh(p);
      m.validate();
      ++read;
    }
    catch (const Error&)
    {
      ++refused;
    }
  }
  EXPECT_GT(refused, 50);
  EXPECT_EQ(read + refused, 600);
}
