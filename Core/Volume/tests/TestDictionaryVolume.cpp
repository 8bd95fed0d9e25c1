#include "ErrorTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <atomic>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace lvdif;

static VolumeOptions opts(std::int64_t x, std::int64_t y, std::int64_t z, int edge = 32)
{
  VolumeOptions o;
  o.dims = { x, y, z };
  o.chunkEdge = edge;
  return o;
}

TEST(DictionaryVolume, StartsOutsideAndSparse)
{
  DictionaryVolume v(opts(100, 70, 33));
  EXPECT_EQ(v.chunkCounts()[0], 4);
  EXPECT_EQ(v.chunkCounts()[1], 3);
  EXPECT_EQ(v.chunkCounts()[2], 2);
  EXPECT_EQ(v.expandedChunkCount(), 0);
  EXPECT_FLOAT_EQ(v.sdf(99, 69, 32), 8.0f);
  EXPECT_EQ(v.get(0, 0, 0), v.outsideVoxel());
}

TEST(DictionaryVolume, RandomWritesReadBackAndCollapseKeepsEveryVoxel)
{
  DictionaryVolume v(opts(70, 45, 38, 16)); // not multiples of the chunk edge
  std::mt19937 rng(3);
  std::vector<Voxel> shadow(static_cast<size_t>(v.voxelCount()), v.outsideVoxel());
  auto idx = [&](std::int64_t x, std::int64_t y, std::int64_t z) { return x + 70 * (y + 45 * z); };
  for (int i = 0; i < 20000; ++i)
  {
    const std::int64_t x = rng() % 70, y = rng() % 45, z = rng() % 38;
    const Voxel val{ static_cast<SdfKey>(rng() % 65536), static_cast<ColorKey>(rng() % 7) };
    v.set(x, y, z, val);
    shadow[idx(x, y, z)] = val;
  }
  auto checkAll = [&] {
    for (std::int64_t z = 0; z < 38; ++z)
      for (std::int64_t y = 0; y < 45; ++y)
        for (std::int64_t x = 0; x < 70; ++x)
          ASSERT_EQ(v.get(x, y, z), shadow[idx(x, y, z)]) << x << " " << y << " " << z;
  };
  checkAll();
  // make a few chunks uniform again by writing one value across them
  for (std::int64_t id : { 0, 5, 17 })
  {
    const VoxelBox b = v.chunkBox(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          v.set(x, y, z, Voxel{ 1234, 2 });
          shadow[idx(x, y, z)] = Voxel{ 1234, 2 };
        }
  }
  const std::int64_t before = v.expandedChunkCount();
  const std::int64_t collapsed = v.collapseUniformChunks();
  EXPECT_EQ(collapsed, 3);
  EXPECT_EQ(v.expandedChunkCount(), before - 3);
  EXPECT_TRUE(v.isUniform(0));
  EXPECT_EQ(v.uniformValue(17), (Voxel{ 1234, 2 }));
  checkAll();
  // expanding a uniform chunk reproduces its value everywhere
  v.expandChunk(5);
  checkAll();
}

TEST(DictionaryVolume, PartialEdgeChunkCollapsesDespitePadding)
{
  DictionaryVolume v(opts(40, 40, 40));
  const std::int64_t last = v.chunkId(1, 1, 1); // owns voxels 32..39 only
  Voxel* d = v.expandChunk(last);
  (void)d;
  for (std::int64_t z = 32; z < 40; ++z)
    for (std::int64_t y = 32; y < 40; ++y)
      for (std::int64_t x = 32; x < 40; ++x) v.set(x, y, z, Voxel{ 5, 5 });
  EXPECT_TRUE(v.tryCollapseChunk(last));
  EXPECT_EQ(v.get(39, 39, 39), (Voxel{ 5, 5 }));
}

TEST(DictionaryVolume, DirtyFlagsAndRanges)
{
  DictionaryVolume v(opts(64, 64, 64));
  EXPECT_TRUE(v.takeDirtyChunks().empty());
  v.setSdf(40, 1, 1, -2.5f);
  v.setSdf(1, 40, 40, 0.25f);
  const auto dirty = v.takeDirtyChunks();
  ASSERT_EQ(dirty.size(), 2u);
  EXPECT_EQ(dirty[0], v.chunkOf(40, 1, 1));
  EXPECT_EQ(dirty[1], v.chunkOf(1, 40, 40));
  EXPECT_TRUE(v.takeDirtyChunks().empty());
  auto r = v.chunkRange(v.chunkOf(40, 1, 1));
  EXPECT_FLOAT_EQ(v.decode(r.first), -2.5f);
  EXPECT_FLOAT_EQ(v.decode(r.second), 8.0f);
  v.setSdf(40, 1, 1, 1.0f); // the range shrinks after an overwrite
  r = v.chunkRange(v.chunkOf(40, 1, 1));
  EXPECT_FLOAT_EQ(v.decode(r.first), 1.0f);
  VoxelBox box;
  box.lo = { 30, 30, 30 };
  box.hi = { 33, 33, 33 };
  v.markDirty(box);
  EXPECT_EQ(v.takeDirtyChunks().size(), 8u);
  EXPECT_EQ(v.chunksInBox(box).size(), 8u);
}

TEST(DictionaryVolume, BandSaturatesDistances)
{
  DictionaryVolume v(opts(8, 8, 8, 8));
  v.setSdf(1, 1, 1, 100.0f);
  v.setSdf(2, 2, 2, -100.0f);
  v.setSdf(3, 3, 3, 3.25f);
  EXPECT_FLOAT_EQ(v.sdf(1, 1, 1), 8.0f);
  EXPECT_FLOAT_EQ(v.sdf(2, 2, 2), -8.0f);
  EXPECT_FLOAT_EQ(v.sdf(3, 3, 3), 3.25f);
  VolumeOptions full = opts(8, 8, 8, 8);
  full.bandWidth = std::numeric_limits<float>::infinity();
  DictionaryVolume f(full);
  f.setSdf(1, 1, 1, 100.04f);
  EXPECT_NEAR(f.sdf(1, 1, 1), 100.0f, 1e-3);
  f.setSdf(1, 1, 1, 1e9f);
  EXPECT_FLOAT_EQ(f.sdf(1, 1, 1), 2880.7f);
}

// A band narrower than the dictionary's finest step stored every distance as
// 0: all signs lost, no surface (vtkMeshToSDF BandWidth 1e-9 gave 0 triangles
// and the warning that the voxels are too large). Refused; the step itself keeps signs.
TEST(DictionaryVolume, BandBelowTheDictionaryStepIsRefused)
{
  for (float band : { 1e-9f, 0.0004f })
  {
    VolumeOptions o = opts(8, 8, 8, 8);
    o.bandWidth = band;
    const std::string narrow = errortest::errorMessageOf([&] { DictionaryVolume v(o); }, ErrorCode::InvalidArgument);
    EXPECT_NE(narrow.find("band width"), std::string::npos) << band << ": " << narrow;
  }
  VolumeOptions o = opts(8, 8, 8, 8);
  o.bandWidth = static_cast<float>(o.dictionary.stepA);
  DictionaryVolume v(o);
  v.setSdf(1, 1, 1, -5.0f);
  v.setSdf(2, 2, 2, 5.0f);
  EXPECT_LT(v.sdf(1, 1, 1), 0.0f);
  EXPECT_GT(v.sdf(2, 2, 2), 0.0f);
}

TEST(DictionaryVolume, RefusesAbsurdSizesBeforeAllocating)
{
  const std::uint64_t rssBefore = residentMemoryBytes();
  const std::string huge =
    errortest::errorMessageOf([] { DictionaryVolume v(opts(1 << 20, 1 << 20, 1 << 20, 4)); }, ErrorCode::OutOfMemory);
  EXPECT_NE(huge.find("limit"), std::string::npos) << huge;
  EXPECT_THROW(DictionaryVolume(opts(0, 5, 5)), Error);
  EXPECT_THROW(DictionaryVolume(opts(-4, 5, 5)), Error);
  EXPECT_THROW(DictionaryVolume(opts((1 << 20) + 1, 5, 5)), Error);
  EXPECT_THROW(DictionaryVolume(opts(5, 5, 5, 24)), Error); // not a power of two
  // A 4096^3 dense request on a 24 GiB machine is refused by the estimate.
  VolumeOptions dense = opts(4096, 4096, 4096);
  const std::uint64_t need = DictionaryVolume::denseBytes(dense);
  EXPECT_GE(need, 256ull << 30);
  EXPECT_THROW(requireMemory(need, "dense 4096^3 volume", 24ull << 30), Error);
  // and the volume's own expansion honours a small limit
  VolumeOptions small = opts(256, 256, 256);
  small.memoryLimit = 1 << 20; // 1 MiB: the table fits, eight 128 KiB chunks do not
  DictionaryVolume v(small);
  EXPECT_THROW(
    {
      for (std::int64_t id = 0; id < v.chunkCount(); ++id) v.expandChunk(id);
    },
    Error);
  EXPECT_LT(residentMemoryBytes(), rssBefore + (64ull << 20));
}

// Threads expanding different chunks at once never pass the limit together:
// the limit leaves room for exactly `room` chunks, so exactly that many expand
// and the others are refused. (A check before counting let 16 threads on the
// GPU host overshoot; the mesh conversion's memory test caught it there.)
TEST(DictionaryVolume, ConcurrentExpansionsStayWithinTheLimit)
{
  VolumeOptions o = opts(256, 256, 256, 16);
  const std::uint64_t chunkBytes = 16 * 16 * 16 * sizeof(Voxel);
  const std::int64_t room = 5;
  o.memoryLimit = DictionaryVolume(opts(256, 256, 256, 16)).memoryBytes() + room * chunkBytes;
  for (int round = 0; round < 20; ++round)
  {
    DictionaryVolume v(o);
    const int threads = 16;
    std::atomic<int> ready{ 0 }, expanded{ 0 }, refused{ 0 };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
    {
      pool.emplace_back([&, t] {
        ready.fetch_add(1);
        while (ready.load() < threads) {}
        try
        {
          v.expandChunk(t * 7);
          expanded.fetch_add(1);
        }
        catch (const Error& e)
        {
          EXPECT_EQ(e.code(), ErrorCode::OutOfMemory);
          refused.fetch_add(1);
        }
      });
    }
    for (std::thread& th : pool) th.join();
    ASSERT_EQ(expanded.load(), room) << "round " << round;
    ASSERT_EQ(refused.load(), threads - room);
    ASSERT_EQ(v.expandedChunkCount(), room);
    ASSERT_LE(v.memoryBytes(), o.memoryLimit);
  }
}

TEST(DictionaryVolume, Sparse2048SphereWithinMemory)
{
  // 2048^3 = 8.6e9 voxels (34 GiB dense at 4 bytes). A sphere of radius 300
  // with band 8 touches only the chunks of its shell.
  VolumeOptions o = opts(2048, 2048, 2048);
  DictionaryVolume v(o);
  const double c = 1024.3, r = 300.0;
  fillFromFunction(v, sphereSdf(c, c, c, r));
  const std::uint64_t bytes = v.memoryBytes();
  EXPECT_LT(bytes, 512ull << 20) << formatBytes(bytes); // the bound stated in docs/DICTIONARY.md
  // far voxels saturate; near voxels keep their distance
  EXPECT_FLOAT_EQ(v.sdf(0, 0, 0), 8.0f);
  EXPECT_FLOAT_EQ(v.sdf(1024, 1024, 1024), -8.0f);
  const float d = v.sdf(1024 + 302, 1024, 1024);
  EXPECT_NEAR(d, std::sqrt((1326 - c) * (1326 - c) + 2 * 0.09) - r, 5e-4);
  // 64-bit indexing: the far corner
  EXPECT_FLOAT_EQ(v.sdf(2047, 2047, 2047), 8.0f);
  v.setSdf(2047, 2047, 2047, -1.5f);
  v.setSdf(5, 2000, 1000, 0.5f);
  EXPECT_FLOAT_EQ(v.sdf(2047, 2047, 2047), -1.5f);
  EXPECT_FLOAT_EQ(v.sdf(5, 2000, 1000), 0.5f);
  EXPECT_LT(v.memoryBytes(), bytes + (1u << 20));
}

TEST(DictionaryVolume, CloneIsDeep)
{
  DictionaryVolume v(opts(50, 50, 50));
  fillFromFunction(v, sphereSdf(25, 25, 25, 15));
  v.colors().add(Rgba{ 1, 2, 3, 4 });
  auto c = v.clone();
  for (std::int64_t z = 0; z < 50; z += 3)
    for (std::int64_t y = 0; y < 50; y += 2)
      for (std::int64_t x = 0; x < 50; ++x) ASSERT_EQ(c->get(x, y, z), v.get(x, y, z));
  EXPECT_EQ(c->colors().size(), 2u);
  c->setSdf(25, 25, 25, 3.0f);
  EXPECT_FLOAT_EQ(v.sdf(25, 25, 25), -8.0f);
}

namespace
{
/// Every voxel of a volume, as an independent record to compare with later.
std::vector<Voxel> snapshot(const DictionaryVolume& v)
{
  std::vector<Voxel> all;
  all.reserve(static_cast<std::size_t>(v.voxelCount()));
  for (std::int64_t z = 0; z < v.dims()[2]; ++z)
    for (std::int64_t y = 0; y < v.dims()[1]; ++y)
      for (std::int64_t x = 0; x < v.dims()[0]; ++x) all.push_back(v.get(x, y, z));
  return all;
}
} // namespace

TEST(DictionaryVolume, CloneIsCopyOnWrite)
{
  DictionaryVolume v(opts(50, 50, 50, 8));
  fillFromFunction(v, sphereSdf(25, 25, 25, 15));
  const std::int64_t expanded = v.expandedChunkCount();
  ASSERT_GT(expanded, 20);
  const std::vector<Voxel> original = snapshot(v);
  auto c = v.clone();
  // nothing copied yet: every expanded chunk is shared by both
  EXPECT_EQ(v.sharedChunkCount(), expanded);
  EXPECT_EQ(c->sharedChunkCount(), expanded);
  EXPECT_EQ(c->expandedChunkCount(), expanded);
  EXPECT_EQ(c->chunkData(v.chunkOf(25, 25, 10)), v.chunkData(v.chunkOf(25, 25, 10)));

  // every way of writing the clone leaves the original alone and copies only that chunk
  c->setSdf(25, 25, 10, 3.0f);                                    // set
  EXPECT_EQ(c->sharedChunkCount(), expanded - 1);
  EXPECT_NE(c->chunkData(v.chunkOf(25, 25, 10)), v.chunkData(v.chunkOf(25, 25, 10)));
  Voxel* d = c->expandChunk(c->chunkOf(10, 25, 25));               // expandChunk
  d[c->localIndex(10, 25, 25)] = Voxel{ 7, 1 };
  c->fillChunk(c->chunkOf(25, 40, 25), c->insideVoxel());         // fillChunk
  for (std::int64_t id = 0; id < c->chunkCount(); ++id) c->tryCollapseChunk(id);
  EXPECT_EQ(snapshot(v), original);
  EXPECT_FLOAT_EQ(c->sdf(25, 25, 10), 3.0f);
  EXPECT_EQ(c->get(10, 25, 25), (Voxel{ 7, 1 }));
  EXPECT_EQ(c->get(25, 40, 25), c->insideVoxel());
  EXPECT_EQ(v.sharedChunkCount(), expanded - 3);

  // and writing the original leaves the clone alone
  const std::vector<Voxel> cloned = snapshot(*c);
  v.setSdf(25, 10, 25, -2.0f);
  v.fillChunk(v.chunkOf(40, 25, 25), v.outsideVoxel());
  EXPECT_EQ(snapshot(*c), cloned);
  EXPECT_FLOAT_EQ(v.sdf(25, 10, 25), -2.0f);

  // a clone outlives its source; clones of clones share too
  auto cc = c->clone();
  auto ccc = cc->clone();
  c.reset();
  EXPECT_EQ(snapshot(*cc), cloned);
  ccc->setSdf(25, 25, 12, -1.0f);
  EXPECT_EQ(snapshot(*cc), cloned);
  cc.reset();
  EXPECT_FLOAT_EQ(ccc->sdf(25, 25, 12), -1.0f);
  EXPECT_EQ(ccc->sharedChunkCount(), v.sharedChunkCount()); // what neither wrote is still v's buffer
}

TEST(DictionaryVolume, CloneCopiesOnConcurrentWrites)
{
  // threads write distinct chunks of a clone (the documented concurrency), each chunk copied once
  DictionaryVolume v(opts(64, 64, 64, 8));
  fillFromFunction(v, sphereSdf(32, 32, 32, 20));
  const std::vector<Voxel> original = snapshot(v);
  auto c = v.clone();
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t id = 0; id < c->chunkCount(); ++id)
  {
    const VoxelBox b = c->chunkBox(id);
    if (c->isUniform(id)) continue;
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x) c->setSdf(x, y, z, -c->sdf(x, y, z));
  }
  EXPECT_EQ(snapshot(v), original);
  EXPECT_EQ(c->sharedChunkCount(), 0);
  EXPECT_EQ(v.sharedChunkCount(), 0);
  for (std::int64_t z = 0; z < 64; z += 5)
    for (std::int64_t y = 0; y < 64; y += 3)
      for (std::int64_t x = 0; x < 64; ++x)
        if (!v.isUniform(v.chunkOf(x, y, z))) ASSERT_EQ(c->sdf(x, y, z), v.decode(v.encode(-v.sdf(x, y, z))));
}

TEST(DictionaryVolume, BoundsCheckedAccess)
{
  DictionaryVolume v(opts(10, 10, 10, 8));
  EXPECT_THROW(v.at(10, 0, 0), Error);
  EXPECT_THROW(v.at(-1, 0, 0), Error);
  EXPECT_NO_THROW(v.at(9, 9, 9));
}

// The editors' one canvas rule (2..MaxDimension voxels per axis), thrown with
// checkCanvasDimensions' words; newCanvas applies it before the volume's own
// (wider) range check and before allocating: a 1 x 2^20 x 2^20 canvas is
// refused as too thin, not as a chunk table over the memory limit.
TEST(DictionaryVolume, NewCanvasRefusesWithTheCanvasRuleBeforeAllocating)
{
  using lvdif::DictionaryVolume;
  const std::int64_t M = DictionaryVolume::MaxDimension;
  for (const lvdif::Index3& d : { lvdif::Index3{ 1, 8, 8 }, lvdif::Index3{ 8, 0, 8 }, lvdif::Index3{ M + 1, 2, 2 },
         lvdif::Index3{ 1, M, M } })
  {
    const std::string rule = DictionaryVolume::checkCanvasDimensions(d);
    EXPECT_NE(rule.find("cannot be edited: each axis needs 2..1048576 voxels"), std::string::npos) << rule;
    EXPECT_EQ(errortest::errorMessageOf([&] { DictionaryVolume::requireCanvasDimensions(d); },
                lvdif::ErrorCode::InvalidArgument),
      rule);
    lvdif::VolumeOptions o;
    o.dims = d;
    EXPECT_EQ(errortest::errorMessageOf([&] { DictionaryVolume::newCanvas(o); }, lvdif::ErrorCode::InvalidArgument), rule);
  }
  lvdif::VolumeOptions o;
  o.dims = { 2, 3, 2 };
  o.chunkEdge = 4;
  EXPECT_NO_THROW(DictionaryVolume::requireCanvasDimensions(o.dims));
  const std::shared_ptr<DictionaryVolume> v = DictionaryVolume::newCanvas(o);
  EXPECT_EQ(v->dims(), o.dims);
  EXPECT_EQ(v->get(1, 2, 1), v->outsideVoxel());
}
