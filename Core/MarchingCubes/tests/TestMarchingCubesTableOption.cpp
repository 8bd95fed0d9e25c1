// MarchingCubesOptions::triangleTable: a caller's triangulation of the same
// loops is accepted and used cell by cell (checked against a brute-force
// re-evaluation of every cell's case from the grid values), and tables that
// change the loops, the orientation or the format are refused with an error.
#include "ErrorTestUtil.h"
#include "MarchingCubesAltTable.h"

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Error.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <set>

using namespace lvdif;

namespace
{
using Table = MarchingCubesTriangleTable;

/// Oriented triangle of global edge ids, rotated so the smallest comes first.
using TriKey = std::array<std::uint64_t, 3>;
TriKey rotated(TriKey k)
{
  while (k[0] > k[1] || k[0] > k[2]) k = { k[1], k[2], k[0] };
  return k;
}

/// Every triangle of `meshes` is, in its cell, exactly what `table` says for
/// that cell's case (recomputed here from the values), and every triangle the
/// table asks for is there.
void expectCellsFollow(const Table& table, const std::vector<float>& v, const Index3& d, float iso,
  const std::vector<ChunkMesh>& meshes)
{
  std::multimap<std::int64_t, TriKey> got; // cell -> triangles
  for (const ChunkMesh& m : meshes)
  {
    ASSERT_EQ(m.triangleCells.size(), m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      got.emplace(m.triangleCells[t], rotated({ m.edgeIds[m.triangles[t][0]], m.edgeIds[m.triangles[t][1]],
                                         m.edgeIds[m.triangles[t][2]] }));
  }
  std::size_t expected = 0;
  for (std::int64_t z = 0; z + 1 < d[2]; ++z)
    for (std::int64_t y = 0; y + 1 < d[1]; ++y)
      for (std::int64_t x = 0; x + 1 < d[0]; ++x)
      {
        int cs = 0;
        for (int q = 0; q < 8; ++q)
          cs |= (v[(x + (q & 1)) + d[0] * ((y + ((q >> 1) & 1)) + d[1] * (z + ((q >> 2) & 1)))] >= iso) << q;
        const std::int64_t cell = x + d[0] * (y + d[1] * z);
        std::multiset<TriKey> want, have;
        for (int k = 0; k < 16 && table[cs][k] >= 0; k += 3)
        {
          TriKey key;
          for (int i = 0; i < 3; ++i)
          {
            const int e = table[cs][k + i], axis = e >> 2;
            std::int64_t p[3] = { x, y, z };
            p[(axis + 1) % 3] += (e >> 1) & 1;
            p[(axis + 2) % 3] += e & 1;
            key[i] = 3ull * static_cast<std::uint64_t>(p[0] + d[0] * (p[1] + d[1] * p[2])) + static_cast<std::uint64_t>(axis);
          }
          want.insert(rotated(key));
        }
        const auto r = got.equal_range(cell);
        for (auto it = r.first; it != r.second; ++it) have.insert(it->second);
        ASSERT_EQ(have, want) << "cell " << x << " " << y << " " << z << " case " << cs;
        expected += want.size();
      }
  EXPECT_EQ(got.size(), expected);
}

/// A noisy field: many cells of every kind, ambiguous faces included.
std::vector<float> noise(const Index3& d, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(static_cast<std::size_t>(d[0] * d[1] * d[2]));
  for (float& x : v) x = u(rng);
  return v;
}

void expectRefused(const Table& t, const char* what)
{
  SCOPED_TRACE(what);
  MarchingCubesOptions o;
  o.triangleTable = std::make_shared<const Table>(t);
  std::vector<float> v(8 * 8 * 8, 1.0f);
  FloatGridView g;
  g.data = v.data();
  g.geometry.dims = { 8, 8, 8 };
  const std::string refused =
    errortest::errorMessageOf([&] { ChunkedMarchingCubes mc(g, nullptr, o); }, ErrorCode::InvalidArgument);
  EXPECT_NE(refused.find("triangle table: case"), std::string::npos) << refused;
}
} // namespace

TEST(MarchingCubesTableOption, OwnTableRoundTripsAndAlternativeIsValid)
{
  const MarchingCubesTables& ours = marchingCubesTables();
  const MarchingCubesTables same = marchingCubesTablesWith(marchingCubesTriangleTable());
  EXPECT_EQ(std::memcmp(&same, &ours, sizeof ours), 0);
  const Table alt = mctest::fanFromLargestEdge();
  const MarchingCubesTables t = marchingCubesTablesWith(alt);
  int differ = 0;
  for (int cs = 0; cs < 256; ++cs)
  {
    EXPECT_EQ(t.triangleCount[cs], ours.triangleCount[cs]);
    differ += std::memcmp(t.triangles[cs], ours.triangles[cs], 16) != 0;
  }
  EXPECT_GT(differ, 50) << "the alternative table must actually differ";
}

TEST(MarchingCubesTableOption, EveryCellUsesTheGivenTable)
{
  const Index3 d{ 37, 29, 21 }; // chunk edges 16 and 23 do not divide the cells
  const std::vector<float> v = noise(d, 7);
  FloatGridView g;
  g.data = const_cast<float*>(v.data());
  g.geometry.dims = d;
  const Table alt = mctest::fanFromLargestEdge();
  for (int edge : { 16, 23 })
    for (bool custom : { false, true })
    {
      SCOPED_TRACE(std::to_string(edge) + (custom ? " custom table" : " own table"));
      MarchingCubesOptions o;
      o.chunkEdge = edge;
      o.cornerColors = true; // triangleCells
      if (custom) o.triangleTable = std::make_shared<const Table>(alt);
      ChunkedMarchingCubes mc(g, nullptr, o);
      const auto meshes = mc.extractAll();
      expectCellsFollow(custom ? alt : marchingCubesTriangleTable(), v, d, 0.0f, meshes);
    }
}

TEST(MarchingCubesTableOption, TablesChangingLoopsOrOrientationAreRefused)
{
  const Table own = marchingCubesTriangleTable();
  Table t = own;
  // reversed orientation of every triangle
  for (auto& row : t)
    for (int k = 0; k + 2 < 16 && row[k] >= 0; k += 3) std::swap(row[k], row[k + 1]);
  expectRefused(t, "reversed");
  // a case with one triangle too few (case 3: a quad of two triangles)
  t = own;
  t[3][3] = t[3][4] = t[3][5] = -1;
  expectRefused(t, "missing triangle");
  // an edge the case does not cut (case 1 cuts edges 0, 4, 8 around corner 0)
  t = own;
  t[1][0] = 11;
  expectRefused(t, "uncut edge");
  // out-of-range id, and garbage after the terminator
  t = own;
  t[1][1] = 12;
  expectRefused(t, "edge id 12");
  t = own;
  t[1][14] = 3;
  expectRefused(t, "entry after -1");
  // a case with two separate loops (corners 0 and 7): a triangle joining them
  t = own;
  ASSERT_EQ(marchingCubesTables().triangleCount[0x81], 2);
  std::swap(t[0x81][2], t[0x81][5]);
  expectRefused(t, "triangle across loops");
  // a quad's two triangles replaced by one triangle used twice (count right, not a disk)
  t = own;
  for (int k = 0; k < 3; ++k) t[3][3 + k] = t[3][k];
  expectRefused(t, "same triangle twice");
}
