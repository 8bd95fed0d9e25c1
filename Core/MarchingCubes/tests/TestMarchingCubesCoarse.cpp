// The coarse level of detail (ChunkedMarchingCubes::extractChunkCoarse, the
// editor's stroke frames) against an independent oracle: the full-resolution
// marching cubes of the volume subsampled by 2 into a dense float grid
// (points 0,2,4,..., spacing doubled, same origin) with half the chunk edge
// must give, chunk by chunk, the same vertices (bit for bit, in the same world
// coordinates), normals, colours and triangles. And the worker's levels: the
// last mesh of a chunk is the level of its last request.
#include "MarchingCubesTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/MarchingCubesWorker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace lvdif;

namespace
{
/// A sphere with a coloured bump: colours differ along the surface.
std::unique_ptr<DictionaryVolume> makeVolume()
{
  VolumeOptions vo;
  vo.dims = { 97, 90, 83 };
  vo.chunkEdge = 16;
  vo.origin = { 1.5, -2.0, 0.25 };
  vo.spacing = { 0.5, 0.5, 0.5 };
  auto vol = std::make_unique<DictionaryVolume>(vo);
  fillFromFunction(*vol, sphereSdf(48, 44, 40, 30), 0);
  const ColorKey red = vol->colors().add(Rgba{ 200, 30, 20, 255 });
  for (std::int64_t z = 20; z < 60; ++z)
    for (std::int64_t y = 20; y < 70; ++y)
      for (std::int64_t x = 60; x < 95; ++x)
      {
        const float s = static_cast<float>(std::sqrt((x - 78.0) * (x - 78.0) + (y - 44.0) * (y - 44.0) + (z - 40.0) * (z - 40.0)) - 12.0);
        if (s < vol->sdf(x, y, z)) vol->set(x, y, z, Voxel{ vol->encode(s), red });
      }
  return vol;
}
} // namespace

TEST(MarchingCubesCoarse, EqualsFullResolutionOfTheSubsampledGrid)
{
  const auto vol = makeVolume();
  MarchingCubesOptions o;
  o.chunkEdge = 32;
  ChunkedMarchingCubes mc(*vol, o);
  // the oracle: the subsampled grid, decoded, meshed at full resolution
  GridGeometry g;
  for (int a = 0; a < 3; ++a)
  {
    g.dims[a] = (vol->dims()[a] - 1) / 2 + 1;
    g.origin[a] = vol->options().origin[a];
    g.spacing[a] = 2 * vol->options().spacing[a];
  }
  std::vector<float> values(static_cast<std::size_t>(g.count()));
  std::vector<Rgba> colors(values.size());
  for (std::int64_t z = 0; z < g.dims[2]; ++z)
    for (std::int64_t y = 0; y < g.dims[1]; ++y)
      for (std::int64_t x = 0; x < g.dims[0]; ++x)
      {
        const Voxel v = vol->get(2 * x, 2 * y, 2 * z);
        values[g.index(x, y, z)] = vol->decode(v.sdf);
        colors[g.index(x, y, z)] = vol->colors().colors()[v.color];
      }
  FloatGridView view;
  view.data = values.data();
  view.geometry = g;
  MarchingCubesOptions oo = o;
  oo.chunkEdge = 16;
  oo.cornerColors = false;
  ChunkedMarchingCubes oracle(view, colors.data(), oo);
  ASSERT_EQ(oracle.chunkCount(), mc.chunkCount());
  std::size_t coarseTriangles = 0, fullTriangles = 0, colouredRed = 0;
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id)
  {
    const ChunkMesh c = mc.extractChunkCoarse(id);
    const ChunkMesh e = oracle.extractChunk(id);
    const ChunkMesh f = mc.extractChunk(id);
    EXPECT_EQ(c.level, 1);
    EXPECT_EQ(f.level, 0);
    EXPECT_EQ(c.chunkId, id);
    EXPECT_EQ(c.chunkCoord, mc.chunkCoord(id));
    EXPECT_EQ(c.cells.lo, mc.chunkCells(id).lo);
    EXPECT_EQ(c.cells.hi, mc.chunkCells(id).hi);
    ASSERT_EQ(c.points.size(), e.points.size()) << "chunk " << id;
    ASSERT_EQ(c.triangles.size(), e.triangles.size()) << "chunk " << id;
    EXPECT_TRUE(c.points == e.points) << "chunk " << id;
    EXPECT_TRUE(c.normals == e.normals) << "chunk " << id;
    ASSERT_EQ(c.colors.size(), e.colors.size());
    for (std::size_t i = 0; i < c.colors.size(); ++i)
    {
      EXPECT_TRUE(c.colors[i].r == e.colors[i].r && c.colors[i].g == e.colors[i].g && c.colors[i].b == e.colors[i].b &&
        c.colors[i].a == e.colors[i].a);
      colouredRed += c.colors[i].r > 100;
    }
    EXPECT_TRUE(c.triangles == e.triangles) << "chunk " << id;
    EXPECT_TRUE(c.cornerColors.empty());
    EXPECT_TRUE(c.triangleCells.empty());
    // edge ids: the oracle's coarse edge, named by its lower full-resolution point
    ASSERT_EQ(c.edgeIds.size(), e.edgeIds.size());
    for (std::size_t i = 0; i < c.edgeIds.size(); ++i)
    {
      const std::int64_t lin = static_cast<std::int64_t>(e.edgeIds[i] / 3);
      const std::int64_t x = lin % g.dims[0], y = (lin / g.dims[0]) % g.dims[1], z = lin / (g.dims[0] * g.dims[1]);
      const std::int64_t full = 2 * x + vol->dims()[0] * (2 * y + vol->dims()[1] * 2 * z);
      EXPECT_EQ(c.edgeIds[i], 3 * static_cast<std::uint64_t>(full) + e.edgeIds[i] % 3);
    }
    coarseTriangles += c.triangles.size();
    fullTriangles += f.triangles.size();
  }
  // not a trivial comparison: a surface, coloured in part, about 1/4 of the triangles
  EXPECT_GT(coarseTriangles, 1000u);
  EXPECT_GT(colouredRed, 10u);
  EXPECT_GT(coarseTriangles * 10, fullTriangles * 2);
  EXPECT_LT(coarseTriangles * 10, fullTriangles * 4);
  // merged, the coarse chunks are seamless: a closed surface of about the same volume
  std::vector<ChunkMesh> all;
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id) all.push_back(mc.extractChunkCoarse(id));
  const TriangleMesh merged = mergeChunkMeshes(all);
  const mctest::Topology t = mctest::topology(merged);
  EXPECT_EQ(t.boundaryEdges, 0u);
  EXPECT_EQ(t.nonManifoldEdges, 0u);
  const TriangleMesh fine = mergeChunkMeshes(mc.extractAll());
  EXPECT_NEAR(mctest::signedVolume(merged), mctest::signedVolume(fine), 0.03 * mctest::signedVolume(fine));
}

TEST(MarchingCubesCoarse, OddGridOffsetRefused)
{
  const auto vol = makeVolume();
  MarchingCubesOptions o;
  o.chunkEdge = 32;
  o.gridOffset = { 1, 0, 0 };
  ChunkedMarchingCubes mc(*vol, o);
  EXPECT_THROW(mc.extractChunkCoarse(0), Error);
}

TEST(MarchingCubesCoarse, WorkerMeshesAtTheLevelOfTheLastRequest)
{
  const auto vol = makeVolume();
  MarchingCubesOptions o;
  o.chunkEdge = 32;
  ChunkedMarchingCubes mc(*vol, o);
  MarchingCubesWorker worker(mc);
  std::vector<std::int64_t> ids;
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id) ids.push_back(id);
  auto check = [&](int level) {
    std::map<std::int64_t, ChunkMesh> last;
    for (ChunkMesh& m : worker.collect()) last[m.chunkId] = std::move(m);
    ASSERT_EQ(last.size(), ids.size());
    std::size_t nonEmpty = 0;
    for (const auto& kv : last)
    {
      const ChunkMesh want = level ? mc.extractChunkCoarse(kv.first) : mc.extractChunk(kv.first);
      EXPECT_EQ(kv.second.level, level);
      EXPECT_TRUE(kv.second.points == want.points);
      EXPECT_TRUE(kv.second.triangles == want.triangles);
      nonEmpty += !want.empty();
    }
    EXPECT_GT(nonEmpty, 4u);
  };
  worker.request(ids, 1);
  worker.waitIdle();
  check(1);
  // coarse first, then full resolution: the full one is the last of each chunk
  worker.request(ids, 1);
  worker.request(ids, 0);
  worker.waitIdle();
  std::map<std::int64_t, ChunkMesh> last;
  for (ChunkMesh& m : worker.collect()) last[m.chunkId] = std::move(m);
  ASSERT_EQ(last.size(), ids.size());
  for (const auto& kv : last)
  {
    EXPECT_EQ(kv.second.level, 0);
    const ChunkMesh want = mc.extractChunk(kv.first);
    EXPECT_TRUE(kv.second.points == want.points);
    EXPECT_TRUE(kv.second.triangles == want.triangles);
  }
  EXPECT_THROW(worker.request(ids, 2), Error);
}
