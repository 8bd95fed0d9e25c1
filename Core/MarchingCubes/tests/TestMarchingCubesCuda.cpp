// CPU vs CUDA marching cubes: the same function. For every chunk, the vertex
// of every cut edge (position, normal, colour) is bit-identical and the
// triangles (as oriented edge-id triples, with their cell and corner colour
// keys) are the same set. Skipped without a CUDA device.
#include "GridTestUtil.h"
#include "MarchingCubesAltTable.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Cuda.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

using namespace lvdif;

namespace
{
/// Oriented triangle as edge ids, rotated so the smallest id comes first (keeps orientation).
using TriKey = std::array<std::uint64_t, 3>;

struct Canon
{
  std::map<std::uint64_t, std::tuple<Vec3f, Vec3f, std::uint32_t>> vertices; // position, normal, packed colour
  std::multimap<TriKey, std::pair<std::int64_t, std::array<ColorKey, 8>>> triangles;
};

Canon canon(const ChunkMesh& m)
{
  Canon c;
  for (std::size_t i = 0; i < m.points.size(); ++i)
  {
    const Vec3f n = m.normals.empty() ? Vec3f{ 0, 0, 0 } : m.normals[i];
    const std::uint32_t col = m.colors.empty() ? 0u : m.colors[i].packed();
    EXPECT_TRUE(c.vertices.emplace(m.edgeIds[i], std::make_tuple(m.points[i], n, col)).second) << "edge twice";
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    TriKey k{ m.edgeIds[m.triangles[t][0]], m.edgeIds[m.triangles[t][1]], m.edgeIds[m.triangles[t][2]] };
    while (k[0] > k[1] || k[0] > k[2]) k = { k[1], k[2], k[0] };
    const std::int64_t cell = m.triangleCells.empty() ? -1 : m.triangleCells[t];
    const std::array<ColorKey, 8> keys = m.cornerColors.empty() ? std::array<ColorKey, 8>{} : m.cornerColors[t];
    c.triangles.emplace(k, std::make_pair(cell, keys));
  }
  return c;
}

bool bitEqual(const Vec3f& a, const Vec3f& b) { return std::memcmp(a.data(), b.data(), sizeof(Vec3f)) == 0; }

void expectSame(const std::vector<ChunkMesh>& cpu, const std::vector<ChunkMesh>& gpu)
{
  ASSERT_EQ(cpu.size(), gpu.size());
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i)
  {
    ASSERT_EQ(cpu[i].chunkId, gpu[i].chunkId);
    const Canon a = canon(cpu[i]), b = canon(gpu[i]);
    ASSERT_EQ(a.vertices.size(), b.vertices.size()) << "chunk " << cpu[i].chunkId;
    for (const auto& v : a.vertices)
    {
      const auto it = b.vertices.find(v.first);
      ASSERT_NE(it, b.vertices.end()) << "edge " << v.first;
      EXPECT_TRUE(bitEqual(std::get<0>(v.second), std::get<0>(it->second))) << "position of edge " << v.first;
      EXPECT_TRUE(bitEqual(std::get<1>(v.second), std::get<1>(it->second))) << "normal of edge " << v.first;
      EXPECT_EQ(std::get<2>(v.second), std::get<2>(it->second)) << "colour of edge " << v.first;
    }
    EXPECT_TRUE(a.triangles == b.triangles) << "chunk " << cpu[i].chunkId;
    triangles += cpu[i].triangles.size();
  }
  if (cpu.size() > 1) EXPECT_GT(triangles, 1000u);
}

bool haveDevice()
{
  return cuda::available();
}
} // namespace

TEST(MarchingCubesCuda, FloatGridEqualsCpu)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  gridtest::Grid grid(83, 71, 66, gridtest::torusSdf(41.3, 35.2, 32.6, 22.1, 8.3), { -1.5, 0.25, 3.0 }, { 0.3, 0.7, 1.1 });
  grid.paint([](std::int64_t x, std::int64_t y, std::int64_t z) {
    return Rgba{ static_cast<std::uint8_t>(3 * x), static_cast<std::uint8_t>(y), static_cast<std::uint8_t>(z), 77 };
  });
  const FloatGridView& g = grid.view;
  const Rgba* colors = grid.colorData();
  for (int edge : { 16, 23, 64 })
    for (float iso : { 0.0f, 1.37f })
    {
      SCOPED_TRACE("edge " + std::to_string(edge) + " iso " + std::to_string(iso));
      MarchingCubesOptions o;
      o.chunkEdge = edge;
      o.isoValue = iso;
      o.device = Device::Cpu;
      ChunkedMarchingCubes cpu(g, colors, o);
      o.device = Device::Cuda;
      ChunkedMarchingCubes gpu(g, colors, o);
      ASSERT_EQ(gpu.options().device, Device::Cuda);
      expectSame(cpu.extractAll(), gpu.extractAll());
    }
  // a piece with an offset and a cell region (the VTK filter's use)
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  o.gridOffset = { 5, 0, 7 };
  o.cellRegion.lo = { 3, 2, 1 };
  o.cellRegion.hi = { 60, 50, 40 };
  o.device = Device::Cpu;
  ChunkedMarchingCubes cpu(g, colors, o);
  o.device = Device::Cuda;
  ChunkedMarchingCubes gpu(g, colors, o);
  expectSame(cpu.extractAll(), gpu.extractAll());
}

TEST(MarchingCubesCuda, DictionaryVolumeWithCornerColoursEqualsCpu)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  VolumeOptions vo;
  vo.dims = { 96, 80, 72 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(47.3, 39.8, 35.1, 30.2));
  const ColorKey red = vol.colors().add(Rgba{ 255, 0, 0, 255 });
  for (std::int64_t z = 30; z < 50; ++z)
    for (std::int64_t y = 0; y < 80; ++y)
      for (std::int64_t x = 60; x < 96; ++x) vol.set(x, y, z, Voxel{ vol.get(x, y, z).sdf, red });
  for (int edge : { 32, 64 })
  {
    MarchingCubesOptions o;
    o.chunkEdge = edge;
    o.device = Device::Cpu;
    ChunkedMarchingCubes cpu(vol, o);
    o.device = Device::Cuda;
    ChunkedMarchingCubes gpu(vol, o);
    const auto a = cpu.extractAll(), b = gpu.extractAll();
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(a[0].cornerColors.empty());
    expectSame(a, b);
  }
}

TEST(MarchingCubesCuda, FloatGridChangeIsSeenAfterInvalidate)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  const std::int64_t n = 48;
  gridtest::Grid grid(n, n, n, sphereSdf(23.4, 24.1, 22.8, 15.3));
  const FloatGridView& g = grid.view;
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  o.device = Device::Cuda;
  ChunkedMarchingCubes gpu(g, nullptr, o);
  gpu.extractAll(); // uploads the grid
  grid.fill(sphereSdf(23.4, 24.1, 22.8, 11.7));
  VoxelBox all;
  all.lo = { 0, 0, 0 };
  all.hi = { n - 1, n - 1, n - 1 };
  gpu.invalidate(all);
  o.device = Device::Cpu;
  ChunkedMarchingCubes cpu(g, nullptr, o);
  expectSame(cpu.extractAll(), gpu.extractAll());
}

TEST(MarchingCubesCuda, BatchOfChunksInAnyOrderWithEmptyOnesEqualsCpu)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  gridtest::Grid grid(70, 70, 70, sphereSdf(30.4, 33.1, 28.8, 19.6));
  const FloatGridView& g = grid.view;
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  o.device = Device::Cpu;
  ChunkedMarchingCubes cpu(g, nullptr, o);
  o.device = Device::Cuda;
  ChunkedMarchingCubes gpu(g, nullptr, o);
  std::vector<std::int64_t> ids;
  for (std::int64_t id = cpu.chunkCount() - 1; id >= 0; --id) ids.push_back(id); // every chunk, reversed
  const auto a = cpu.extractChunks(ids), b = gpu.extractChunks(ids);
  std::size_t empty = 0;
  for (const auto& m : a) empty += m.empty();
  EXPECT_GT(empty, 0u);
  expectSame(a, b);
  // the one-chunk path (a batch of one) too
  for (std::int64_t id : ids)
  {
    const auto c = cpu.extractChunk(id), d = gpu.extractChunk(id);
    expectSame({ c }, { d });
    if (!c.empty()) break;
  }
}

TEST(MarchingCubesCuda, PackedPipelineEqualsCpuOverManyBatches)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  gridtest::Grid grid(90, 90, 90, sphereSdf(44.4, 41.1, 46.8, 31.6));
  grid.paint([](std::int64_t x, std::int64_t y, std::int64_t) {
    return Rgba{ static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(2 * y), 9, 255 };
  });
  const FloatGridView& g = grid.view;
  const Rgba* colors = grid.colorData();
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  o.device = Device::Cpu;
  ChunkedMarchingCubes cpu(g, colors, o);
  o.device = Device::Cuda;
  // batches of ~4 chunks: many batches, both output sets, the block grows on the way
  o.cudaBatchPoints = 20000;
  ChunkedMarchingCubes gpu(g, colors, o);
  const auto a = cpu.extractAll();
  PackedChunkMeshes packed;
  gpu.extractAllPacked(packed);
  EXPECT_TRUE(packed.pageLocked());
  const Vec3f* block = packed.points();
  for (int pass = 0; pass < 2; ++pass)
  {
    ASSERT_EQ(packed.chunkCount(), a.size());
    std::vector<ChunkMesh> b;
    std::uint64_t tris = 0;
    for (std::size_t i = 0; i < packed.chunkCount(); ++i)
    {
      b.push_back(packed.chunk(i));
      tris += b.back().triangles.size();
    }
    EXPECT_EQ(tris, packed.triangleCount());
    expectSame(a, b);
    gpu.extractAllPacked(packed); // second pass: the same block, reused
    EXPECT_EQ(packed.points(), block);
  }
  // the split path (extractAll) over many batches too
  expectSame(a, gpu.extractAll());
}

TEST(MarchingCubesCuda, CustomTriangleTableEqualsCpu)
{
  if (!haveDevice()) GTEST_SKIP() << "no CUDA device";
  // a noisy field (every case, ambiguous faces) and another triangulation of the loops
  const std::int64_t nx = 45, ny = 38, nz = 29;
  std::vector<float> values(static_cast<std::size_t>(nx * ny * nz));
  std::uint32_t r = 12345;
  for (float& v : values)
  {
    r = r * 1664525u + 1013904223u;
    v = static_cast<float>(r >> 8) / static_cast<float>(1u << 24) - 0.5f;
  }
  FloatGridView g;
  g.data = values.data();
  g.geometry.dims = { nx, ny, nz };
  auto alt = std::make_shared<const MarchingCubesTriangleTable>(mctest::fanFromLargestEdge());
  for (int edge : { 16, 23 })
  {
    SCOPED_TRACE("edge " + std::to_string(edge));
    MarchingCubesOptions o;
    o.chunkEdge = edge;
    o.device = Device::Cpu;
    ChunkedMarchingCubes cpuOwn(g, nullptr, o);
    o.triangleTable = alt;
    ChunkedMarchingCubes cpu(g, nullptr, o);
    o.device = Device::Cuda;
    ChunkedMarchingCubes gpu(g, nullptr, o);
    ASSERT_EQ(gpu.options().device, Device::Cuda);
    const auto c = cpu.extractAll();
    expectSame(c, gpu.extractAll());
    // the packed pipeline uses the table too
    PackedChunkMeshes packed;
    gpu.extractAllPacked(packed);
    std::vector<ChunkMesh> split;
    for (std::size_t i = 0; i < packed.chunkCount(); ++i) split.push_back(packed.chunk(i));
    expectSame(c, split);
    // and the table really changed the triangles
    const auto own = cpuOwn.extractAll();
    ASSERT_EQ(own.size(), c.size());
    bool differs = false;
    for (std::size_t i = 0; i < c.size() && !differs; ++i) differs = !(canon(own[i]).triangles == canon(c[i]).triangles);
    EXPECT_TRUE(differs);
  }
}
