// Chunked marching cubes on analytic shapes: area and enclosed volume against
// the analytic values, watertightness after merging, chunk-size independence,
// orientation, normals against the analytic gradient, corner colours against
// the voxels, and the case table's crack-freeness over all neighbour pairs.
#include "GridTestUtil.h"
#include "MarchingCubesTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Error.h"
#include "lvdif/MarchingCubesTables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace lvdif;

namespace
{
const double Pi = 3.14159265358979323846;

using gridtest::Grid;
using gridtest::torusSdf;

MarchingCubesOptions withEdge(int e)
{
  MarchingCubesOptions o;
  o.chunkEdge = e;
  return o;
}
} // namespace

TEST(MarchingCubesTables, NeighbouringCellsAgreeForEverySignPattern)
{
  // Two cells side by side along each axis, every one of the 4096 sign patterns of
  // their 12 points: every edge inside the domain must be shared by exactly two
  // triangles with opposite directions (closed, consistently oriented, no cracks).
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mag(0.1f, 1.0f);
  for (int axis = 0; axis < 3; ++axis)
  {
    std::int64_t dims[3] = { 2, 2, 2 };
    dims[axis] = 3;
    for (int pattern = 0; pattern < 4096; ++pattern)
    {
      std::vector<float> v(12);
      for (int i = 0; i < 12; ++i) v[i] = ((pattern >> i) & 1) ? mag(rng) : -mag(rng);
      FloatGridView g;
      g.data = v.data();
      g.geometry.dims = { dims[0], dims[1], dims[2] };
      ChunkedMarchingCubes mc(g, nullptr, withEdge(16));
      const TriangleMesh m = mergeChunkMeshes(mc.extractAll());
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
      for (const auto& t : m.triangles)
        for (int k = 0; k < 3; ++k) directed[{ t[k], t[(k + 1) % 3] }]++;
      for (const auto& d : directed)
      {
        ASSERT_EQ(d.second, 1) << "directed edge used twice, axis " << axis << " pattern " << pattern;
        if (directed.count({ d.first.second, d.first.first })) continue;
        // an unpaired edge must lie on the outer boundary of the two-cell domain
        const Vec3f& p = m.points[d.first.first];
        const Vec3f& q = m.points[d.first.second];
        bool onBoundary = false;
        for (int a = 0; a < 3; ++a)
          onBoundary |= (p[a] == 0 && q[a] == 0) || (p[a] == dims[a] - 1 && q[a] == dims[a] - 1);
        ASSERT_TRUE(onBoundary) << "crack inside the domain, axis " << axis << " pattern " << pattern;
      }
    }
  }
}

TEST(MarchingCubesTables, ComplementCasesHaveAtMostFiveTriangles)
{
  const MarchingCubesTables& t = marchingCubesTables();
  EXPECT_EQ(t.triangleCount[0], 0);
  EXPECT_EQ(t.triangleCount[255], 0);
  for (int c = 1; c < 255; ++c)
  {
    EXPECT_GE(t.triangleCount[c], 1);
    EXPECT_LE(t.triangleCount[c], 5);
  }
  // single corner below: one triangle; its 3 edges are the corner's edges
  EXPECT_EQ(t.triangleCount[0xFE], 1);
  EXPECT_EQ(t.triangleCount[0x01], 1);
}

TEST(MarchingCubes, SphereAreaVolumeWatertightForManyChunkSizes)
{
  const double r = 20.3;
  Grid g(61, 57, 53, sphereSdf(30.2, 28.1, 26.4, r), { -3.0, 1.5, 0.25 }, { 1.0, 1.0, 1.0 });
  std::vector<mctest::TriKey> reference;
  for (int edge : { 16, 17, 23, 32, 64, 256 })
  {
    ChunkedMarchingCubes mc(g.view, nullptr, withEdge(edge));
    const TriangleMesh m = mergeChunkMeshes(mc.extractAll());
    const auto topo = mctest::topology(m);
    EXPECT_EQ(topo.boundaryEdges, 0u) << "edge " << edge;
    EXPECT_EQ(topo.nonManifoldEdges, 0u) << "edge " << edge;
    EXPECT_EQ(topo.misorientedEdges, 0u) << "edge " << edge;
    EXPECT_EQ(topo.euler, 2) << "edge " << edge;
    EXPECT_NEAR(mctest::area(m), 4 * Pi * r * r, 0.01 * 4 * Pi * r * r);
    EXPECT_NEAR(mctest::signedVolume(m), 4.0 / 3.0 * Pi * r * r * r, 0.005 * 4.0 / 3.0 * Pi * r * r * r);
    const auto set = mctest::triangleSet(m);
    if (reference.empty())
      reference = set;
    else
      EXPECT_TRUE(set == reference) << "chunk edge " << edge << " changes the surface";
  }
}

TEST(MarchingCubes, TorusInDictionaryVolumeMatchesAnalytic)
{
  VolumeOptions vo;
  vo.dims = { 90, 84, 40 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  const double R = 28, r = 9.5;
  fillFromFunction(vol, torusSdf(45, 42, 19.5, R, r));
  for (int edge : { 16, 20, 64 })
  {
    ChunkedMarchingCubes mc(vol, withEdge(edge));
    const TriangleMesh m = mergeChunkMeshes(mc.extractAll());
    const auto topo = mctest::topology(m);
    EXPECT_EQ(topo.boundaryEdges, 0u);
    EXPECT_EQ(topo.nonManifoldEdges, 0u);
    EXPECT_EQ(topo.misorientedEdges, 0u);
    EXPECT_EQ(topo.euler, 0); // genus 1
    EXPECT_NEAR(mctest::area(m), 4 * Pi * Pi * R * r, 0.01 * 4 * Pi * Pi * R * r);
    EXPECT_NEAR(mctest::signedVolume(m), 2 * Pi * Pi * R * r * r, 0.01 * 2 * Pi * Pi * R * r * r);
  }
}

TEST(MarchingCubes, NormalsFollowTheAnalyticGradientAndTrianglesFaceOutward)
{
  const double c[3] = { 20.5, 21.25, 19.75 }, r = 13.0;
  Grid g(42, 43, 41, sphereSdf(c[0], c[1], c[2], r), { 0, 0, 0 }, { 0.5, 0.5, 0.5 });
  ChunkedMarchingCubes mc(g.view, nullptr, withEdge(16));
  const auto meshes = mc.extractAll();
  ASSERT_FALSE(meshes.empty());
  double worst = 1;
  std::size_t outward = 0, total = 0;
  for (const ChunkMesh& m : meshes)
  {
    ASSERT_EQ(m.normals.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
      // analytic outward direction at the vertex (world = 0.5 * index)
      double d[3], l = 0;
      for (int a = 0; a < 3; ++a)
      {
        d[a] = m.points[i][a] / 0.5 - c[a];
        l += d[a] * d[a];
      }
      l = std::sqrt(l);
      double dot = 0;
      for (int a = 0; a < 3; ++a) dot += d[a] / l * m.normals[i][a];
      worst = std::min(worst, dot);
    }
    for (const auto& t : m.triangles)
    {
      const Vec3f &p = m.points[t[0]], &q = m.points[t[1]], &s = m.points[t[2]];
      const double u[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] }, w[3] = { s[0] - p[0], s[1] - p[1], s[2] - p[2] };
      const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
      double dot = 0;
      for (int a = 0; a < 3; ++a) dot += n[a] * (p[a] / 0.5 - c[a]);
      outward += dot > 0;
      ++total;
    }
  }
  EXPECT_GT(worst, 0.99); // within ~8 degrees everywhere
  EXPECT_EQ(outward, total);
  // signed volume in world units (spacing 0.5)
  const TriangleMesh merged = mergeChunkMeshes(meshes);
  const double vol = 4.0 / 3.0 * Pi * std::pow(r * 0.5, 3);
  EXPECT_NEAR(mctest::signedVolume(merged), vol, 0.01 * vol);
}

TEST(MarchingCubes, CornerColoursAndCellsMatchTheVoxels)
{
  VolumeOptions vo;
  vo.dims = { 40, 40, 40 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(19.5, 20.5, 18.7, 12));
  const ColorKey red = vol.colors().add(Rgba{ 255, 0, 0, 255 });
  for (std::int64_t z = 0; z < 40; ++z)
    for (std::int64_t y = 0; y < 40; ++y)
      for (std::int64_t x = 0; x < 20; ++x) vol.set(x, y, z, Voxel{ vol.get(x, y, z).sdf, red });
  ChunkedMarchingCubes mc(vol, withEdge(17));
  std::size_t seenRed = 0, seenGrey = 0, mixed = 0;
  for (const ChunkMesh& m : mc.extractAll())
  {
    ASSERT_EQ(m.cornerColors.size(), m.triangles.size());
    ASSERT_EQ(m.triangleCells.size(), m.triangles.size());
    ASSERT_EQ(m.colors.size(), m.points.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
    {
      const std::int64_t cell = m.triangleCells[t];
      const std::int64_t x = cell % 40, y = (cell / 40) % 40, z = cell / 1600;
      EXPECT_TRUE(m.cells.contains(x, y, z));
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
        {
          const double p = m.points[m.triangles[t][k]][a], lo = (a == 0 ? x : a == 1 ? y : z);
          EXPECT_GE(p, lo);
          EXPECT_LE(p, lo + 1);
        }
      for (int q = 0; q < 8; ++q)
        EXPECT_EQ(m.cornerColors[t][q], vol.get(x + (q & 1), y + ((q >> 1) & 1), z + ((q >> 2) & 1)).color);
    }
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
      const Rgba c = m.colors[i];
      if (m.points[i][0] < 19) { EXPECT_EQ(c, (Rgba{ 255, 0, 0, 255 })); ++seenRed; }
      else if (m.points[i][0] > 20) { EXPECT_EQ(c, (Rgba{ 200, 200, 200, 255 })); ++seenGrey; }
      else ++mixed; // on an edge from x=19 to x=20: interpolated between the two
    }
  }
  EXPECT_GT(seenRed, 100u);
  EXPECT_GT(seenGrey, 100u);
  EXPECT_GT(mixed, 10u);
}

TEST(MarchingCubes, EmptyChunksAreSkippedAndReallyEmpty)
{
  VolumeOptions vo;
  vo.dims = { 100, 100, 100 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(50, 50, 50, 20));
  ChunkedMarchingCubes mc(vol, withEdge(16));
  std::int64_t skipped = 0;
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id)
  {
    // brute force: does any cell of the chunk straddle the iso value?
    const VoxelBox cb = mc.chunkCells(id);
    bool lo = false, hi = false;
    for (std::int64_t z = cb.lo[2]; z <= cb.hi[2] + 1; ++z)
      for (std::int64_t y = cb.lo[1]; y <= cb.hi[1] + 1; ++y)
        for (std::int64_t x = cb.lo[0]; x <= cb.hi[0] + 1; ++x) (vol.sdf(x, y, z) >= 0 ? hi : lo) = true;
    if (mc.chunkIsEmpty(id))
    {
      ++skipped;
      EXPECT_FALSE(lo && hi) << "chunk " << id << " skipped but crossed by the surface";
    }
    EXPECT_EQ(mc.extractChunk(id).empty(), !(lo && hi)) << "chunk " << id;
  }
  EXPECT_GT(skipped, mc.chunkCount() / 2);
}

TEST(MarchingCubes, RejectsBadOptions)
{
  VolumeOptions vo;
  vo.dims = { 20, 20, 20 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  EXPECT_THROW(ChunkedMarchingCubes(vol, withEdge(8)), Error);
  EXPECT_THROW(ChunkedMarchingCubes(vol, withEdge(300)), Error);
  FloatGridView g;
  EXPECT_THROW(ChunkedMarchingCubes(g, nullptr, withEdge(16)), Error);
  std::vector<float> one(4, 1.0f);
  g.data = one.data();
  g.geometry.dims = { 4, 1, 1 };
  EXPECT_THROW(ChunkedMarchingCubes(g, nullptr, withEdge(16)), Error);
}

TEST(MarchingCubes, PackedEqualsChunkMeshes)
{
  VolumeOptions vo;
  vo.dims = { 61, 57, 66 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(30.2, 28.7, 33.1, 21.4));
  MarchingCubesOptions o;
  o.chunkEdge = 24;
  ChunkedMarchingCubes mc(vol, o);
  const auto meshes = mc.extractAll();
  PackedChunkMeshes p;
  mc.extractAllPacked(p);
  ASSERT_EQ(p.chunkCount(), meshes.size());
  ASSERT_GT(meshes.size(), 4u);
  EXPECT_FALSE(p.pageLocked());
  const PackedChunkMeshes copy = p; // shares the block; the next extraction must not overwrite it
  mc.extractAllPacked(p);
  for (const PackedChunkMeshes* q : { static_cast<const PackedChunkMeshes*>(&p), &copy })
    for (std::size_t i = 0; i < meshes.size(); ++i)
    {
      const ChunkMesh c = q->chunk(i);
      const ChunkMesh& m = meshes[i];
      EXPECT_EQ(c.chunkId, m.chunkId);
      EXPECT_EQ(c.chunkCoord, m.chunkCoord);
      EXPECT_EQ(c.points, m.points);
      EXPECT_EQ(c.edgeIds, m.edgeIds);
      EXPECT_EQ(c.normals, m.normals);
      EXPECT_TRUE(c.colors == m.colors);
      EXPECT_EQ(c.triangles, m.triangles);
      EXPECT_EQ(c.triangleCells, m.triangleCells);
      EXPECT_EQ(c.cornerColors, m.cornerColors);
    }
  EXPECT_NE(p.points(), copy.points());
}

TEST(MarchingCubes, DictionaryVolumeEqualsItsDecodedFloatGrid)
{
  // the dictionary path skips decoding storage chunks whose neighbourhood is on
  // one side of iso; the float grid path reads every value: same meshes
  VolumeOptions vo;
  vo.dims = { 100, 90, 84 };
  vo.chunkEdge = 16;
  vo.bandWidth = 6;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(49.5, 44.2, 41.7, 33.3));
  const ColorKey green = vol.colors().add(Rgba{ 0, 250, 10, 255 });
  for (std::int64_t z = 20; z < 60; ++z)
    for (std::int64_t y = 0; y < 90; ++y)
      for (std::int64_t x = 50; x < 100; ++x) vol.set(x, y, z, Voxel{ vol.get(x, y, z).sdf, green });
  std::vector<float> values(static_cast<std::size_t>(100 * 90 * 84));
  std::vector<Rgba> colors(values.size());
  for (std::int64_t z = 0; z < 84; ++z)
    for (std::int64_t y = 0; y < 90; ++y)
      for (std::int64_t x = 0; x < 100; ++x)
      {
        const Voxel v = vol.get(x, y, z);
        values[x + 100 * (y + 90 * z)] = vol.decode(v.sdf);
        colors[x + 100 * (y + 90 * z)] = vol.colors().colors()[v.color];
      }
  FloatGridView g;
  g.data = values.data();
  g.geometry.dims = vol.dims();
  for (float iso : { 0.0f, -2.5f, 3.25f })
  {
    MarchingCubesOptions o;
    o.chunkEdge = 24;
    o.isoValue = iso;
    ChunkedMarchingCubes a(vol, o), b(g, colors.data(), o);
    const auto ma = a.extractAll(), mb = b.extractAll();
    ASSERT_EQ(ma.size(), mb.size());
    ASSERT_GT(ma.size(), 10u);
    for (std::size_t i = 0; i < ma.size(); ++i)
    {
      EXPECT_EQ(ma[i].chunkId, mb[i].chunkId);
      EXPECT_EQ(ma[i].points, mb[i].points);
      EXPECT_EQ(ma[i].normals, mb[i].normals);
      EXPECT_TRUE(ma[i].colors == mb[i].colors);
      EXPECT_EQ(ma[i].triangles, mb[i].triangles);
      EXPECT_EQ(ma[i].triangleCells, mb[i].triangleCells);
    }
  }
}
