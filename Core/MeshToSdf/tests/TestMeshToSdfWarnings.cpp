// Warnings when the field cannot be what the user expects: a signed field over
// the whole grid with no voxel inside (an open sheet that encloses no volume,
// or voxels larger than the mesh's parts). Checked against the output itself:
// a warning exactly when no voxel is deeper than 1 voxel inside, naming the
// cause and the option that helps (and the option is shown to help).
#include "lvdif/DictionaryVolume.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace lvdif;

namespace
{
/// A flat tilted open sheet of n x n quads over [-1, 1]^2 (no volume enclosed).
TriangleMesh sheet(int n)
{
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
    {
      const float x = -1.0f + 2.0f * i / n, y = -1.0f + 2.0f * j / n;
      m.points.push_back({ x, y, 0.02f * x - 0.05f * y + 0.013f });
    }
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return m;
}

/// Two small closed boxes far apart.
TriangleMesh twoSmallBoxes()
{
  TriangleMesh a = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 0.5f, 0.5f, 0.5f });
  const TriangleMesh b = makeBoxMesh({ 10.0f, 10.0f, 10.0f }, { 10.5f, 10.5f, 10.5f });
  const auto n = static_cast<std::uint32_t>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.triangles) a.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  return a;
}

/// Voxels deeper than 1 voxel inside (voxel units): what the warnings are about.
std::int64_t deepInside(const std::vector<float>& v)
{
  std::int64_t n = 0;
  for (float x : v) n += x < -1.0f;
  return n;
}

struct Result
{
  MeshToSdfStats stats;
  std::int64_t inside = 0;
};

Result runFloat(const TriangleMesh& m, std::int64_t res, SignMode sign)
{
  const GridGeometry g = fitGridToMesh(m, res, 2.0);
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  o.sign = sign;
  o.device = Device::Cpu;
  Result r;
  r.stats = meshToSdf(m, FloatGridView{ out.data(), g }, o);
  r.inside = deepInside(out);
  return r;
}

bool mentions(const MeshToSdfStats& s, const std::string& what)
{
  return s.warnings.size() == 1 && s.warnings[0].find(what) != std::string::npos;
}
} // namespace

TEST(MeshToSdfWarnings, OpenSheetEnclosesNoVolume)
{
  const TriangleMesh m = sheet(12);
  const Result w = runFloat(m, 40, SignMode::WindingNumber);
  EXPECT_EQ(w.inside, 0); // the premise: |w| < 1/2 except in a film near the sheet
  ASSERT_EQ(w.stats.warnings.size(), 1u);
  EXPECT_TRUE(mentions(w.stats, "encloses no volume")) << w.stats.warnings[0];
  EXPECT_TRUE(mentions(w.stats, "pseudo-normal"));
  // the option it names helps: each side of the sheet gets its own sign
  const Result pn = runFloat(m, 40, SignMode::PseudoNormal);
  EXPECT_GT(pn.inside, 0);
  EXPECT_TRUE(pn.stats.warnings.empty());
  // unsigned fields are never "inside"
  EXPECT_TRUE(runFloat(m, 40, SignMode::Unsigned).stats.warnings.empty());
  // into a dictionary volume too
  const GridGeometry g = fitGridToMesh(m, 40, 2.0);
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(mentions(meshToSdf(m, vol, o), "encloses no volume"));
}

TEST(MeshToSdfWarnings, VoxelsLargerThanTheParts)
{
  const TriangleMesh m = twoSmallBoxes();
  const Result coarse = runFloat(m, 8, SignMode::WindingNumber);
  EXPECT_EQ(coarse.inside, 0);
  EXPECT_TRUE(mentions(coarse.stats, "more voxels")) << (coarse.stats.warnings.empty() ? "" : coarse.stats.warnings[0]);
  // the option it names helps
  const Result fine = runFloat(m, 128, SignMode::WindingNumber);
  EXPECT_GT(fine.inside, 0);
  EXPECT_TRUE(fine.stats.warnings.empty());
}

TEST(MeshToSdfWarnings, NoneForAClosedMeshOrAPiece)
{
  const TriangleMesh sphere = makeSphereMesh(0, 0, 0, 1, 10, 20);
  for (SignMode s : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Normal })
  {
    const Result r = runFloat(sphere, 24, s);
    EXPECT_GT(r.inside, 0);
    EXPECT_TRUE(r.stats.warnings.empty()) << toString(s);
  }
  // a piece of a grid that has nothing inside is not the user's whole field
  const TriangleMesh m = sheet(6);
  const GridGeometry g = fitGridToMesh(m, 24, 2.0);
  VoxelBox piece;
  piece.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] / 2 };
  std::vector<float> out(static_cast<std::size_t>(piece.voxelCount()));
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(meshToSdf(m, g, piece, out.data(), o).warnings.empty());
}
