// Incremental marching cubes: after random edits, re-meshing only the chunks
// the edits touched gives the same surface as a full extraction of the edited
// volume; the same through the background worker while another thread edits.
#include "GridTestUtil.h"
#include "MarchingCubesTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/MarchingCubesWorker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <thread>

using namespace lvdif;

namespace
{
using Store = std::map<std::int64_t, ChunkMesh>;

void apply(Store& store, std::vector<ChunkMesh> meshes)
{
  for (ChunkMesh& m : meshes)
  {
    if (m.empty())
      store.erase(m.chunkId);
    else
      store[m.chunkId] = std::move(m);
  }
}

std::vector<ChunkMesh> values(const Store& s)
{
  std::vector<ChunkMesh> v;
  for (const auto& kv : s) v.push_back(kv.second);
  return v;
}

/// CSG union with a sphere: d = min(d, sphere), the way a brush writes.
VoxelBox stampSphere(DictionaryVolume& vol, double cx, double cy, double cz, double r, ColorKey color)
{
  VoxelBox b;
  const double c[3] = { cx, cy, cz };
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(c[a] - r - 2)));
    b.hi[a] = std::min<std::int64_t>(vol.dims()[a] - 1, static_cast<std::int64_t>(std::ceil(c[a] + r + 2)));
  }
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
      for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
      {
        const float s = static_cast<float>(std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r);
        if (s < vol.sdf(x, y, z)) vol.set(x, y, z, Voxel{ vol.encode(s), color });
      }
  return b;
}
} // namespace

TEST(MarchingCubesIncremental, DirtyChunksRemeshedEqualFullExtraction)
{
  VolumeOptions vo;
  vo.dims = { 77, 70, 65 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(38, 35, 32, 18));
  vol.takeDirtyChunks();
  for (int edge : { 16, 24 })
  {
    MarchingCubesOptions o;
    o.chunkEdge = edge;
    ChunkedMarchingCubes mc(vol, o);
    Store store;
    apply(store, mc.extractAll());
    std::mt19937 rng(11 + edge);
    std::uniform_real_distribution<double> pos(10, 60), rad(1.5, 7); // inside: the surface stays closed
    const ColorKey blue = vol.colors().add(Rgba{ 0, 0, 255, 255 });
    for (int round = 0; round < 6; ++round)
    {
      for (int k = 0; k < 3; ++k) stampSphere(vol, pos(rng), pos(rng) * 0.9, pos(rng) * 0.84, rad(rng), blue);
      const auto dirty = vol.takeDirtyChunks();
      const auto ids = mc.chunksAffectedByStorageChunks(dirty);
      EXPECT_LT(ids.size(), static_cast<std::size_t>(mc.chunkCount())); // really incremental
      apply(store, mc.extractChunks(ids));
      const auto full = mc.extractAll();
      // every chunk mesh equal (points, normals, colours, triangles), not only the union
      ASSERT_EQ(full.size(), store.size()) << "round " << round;
      for (const ChunkMesh& f : full)
      {
        const ChunkMesh& s = store.at(f.chunkId);
        EXPECT_EQ(f.points, s.points) << "chunk " << f.chunkId;
        EXPECT_EQ(f.normals, s.normals) << "chunk " << f.chunkId;
        EXPECT_EQ(f.triangles, s.triangles) << "chunk " << f.chunkId;
        EXPECT_TRUE(f.colors == s.colors) << "chunk " << f.chunkId;
        EXPECT_EQ(f.cornerColors, s.cornerColors) << "chunk " << f.chunkId;
      }
      const auto topo = mctest::topology(mergeChunkMeshes(values(store)));
      EXPECT_EQ(topo.boundaryEdges, 0u);
      EXPECT_EQ(topo.nonManifoldEdges, 0u);
    }
  }
}

TEST(MarchingCubesIncremental, BrushChangedBoxRemeshEqualsFullExtraction)
{
  // brushes (add, subtract, paint, smooth) report changedBox; re-meshing only
  // chunksAffectedBy(changedBox) must give every chunk mesh of a full extraction
  VolumeOptions vo;
  vo.dims = { 90, 84, 80 };
  vo.chunkEdge = 16;
  vo.bandWidth = 5;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(44, 41, 39, 24));
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  ChunkedMarchingCubes mc(vol, o);
  Store store;
  apply(store, mc.extractAll());
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> pos(12, 72), rad(2, 9), blend(0, 3);
  std::size_t fewer = 0;
  for (int round = 0; round < 12; ++round)
  {
    BrushSettings s;
    s.op = static_cast<BrushOp>(round % 3);
    s.blend = round % 2 ? blend(rng) : 0.0;
    s.color = Rgba{ 10, static_cast<std::uint8_t>(20 * round), 200, 255 };
    const EditResult r = applyDab(vol, Dab{ BrushShape::Sphere, { pos(rng), pos(rng), pos(rng) }, rad(rng), {} }, s);
    const auto ids = mc.chunksAffectedBy(r.changedBox);
    fewer += ids.size() < mc.chunksAffectedByStorageChunks(vol.takeDirtyChunks()).size();
    apply(store, mc.extractChunks(ids));
    const auto full = mc.extractAll();
    ASSERT_EQ(full.size(), store.size()) << "round " << round;
    for (const ChunkMesh& f : full)
    {
      const ChunkMesh& m = store.at(f.chunkId);
      EXPECT_EQ(f.points, m.points) << "round " << round << " chunk " << f.chunkId;
      EXPECT_EQ(f.triangles, m.triangles) << "round " << round << " chunk " << f.chunkId;
      EXPECT_TRUE(f.colors == m.colors) << "round " << round << " chunk " << f.chunkId;
      EXPECT_EQ(f.cornerColors, m.cornerColors) << "round " << round << " chunk " << f.chunkId;
    }
  }
  EXPECT_GT(fewer, 0u); // the box is tighter than the storage chunks
}

TEST(MarchingCubesIncremental, FloatGridInvalidateThenRemesh)
{
  gridtest::Grid grid(50, 50, 50, sphereSdf(24, 25, 23, 12));
  FloatGridView& g = grid.view;
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  ChunkedMarchingCubes mc(g, nullptr, o);
  Store store;
  apply(store, mc.extractAll());
  // a new blob far from the sphere, in a chunk that was empty
  VoxelBox b;
  b.lo = { 38, 38, 38 };
  b.hi = { 46, 46, 46 };
  const SdfFunction blob = sphereSdf(42, 42, 42, 3.3);
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
      for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x) g.at(x, y, z) = std::min(g.at(x, y, z), blob(x, y, z));
  mc.invalidate(b);
  apply(store, mc.extractChunks(mc.chunksAffectedBy(b)));
  ChunkedMarchingCubes fresh(g, nullptr, o);
  EXPECT_EQ(mctest::triangleSet(mergeChunkMeshes(values(store))),
    mctest::triangleSet(mergeChunkMeshes(fresh.extractAll())));
  EXPECT_EQ(mctest::topology(mergeChunkMeshes(values(store))).euler, 4); // two spheres
}

TEST(MarchingCubesIncremental, WorkerKeepsUpWithEditsFromAnotherThread)
{
  VolumeOptions vo;
  vo.dims = { 96, 96, 96 };
  vo.chunkEdge = 32;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(48, 48, 48, 20));
  vol.takeDirtyChunks();
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  ChunkedMarchingCubes mc(vol, o);
  Store store;
  {
    MarchingCubesWorker worker(mc);
    worker.requestAll();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> pos(10, 86), rad(2, 6);
    for (int edit = 0; edit < 40; ++edit)
    {
      {
        std::lock_guard<std::mutex> lock(worker.sourceMutex());
        stampSphere(vol, pos(rng), pos(rng), pos(rng), rad(rng), 0);
        worker.request(mc.chunksAffectedByStorageChunks(vol.takeDirtyChunks()));
      }
      apply(store, worker.collect()); // never blocks
      if (edit % 8 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    worker.waitIdle();
    apply(store, worker.collect());
    EXPECT_TRUE(worker.idle());
  }
  const auto full = mc.extractAll();
  ASSERT_EQ(full.size(), store.size());
  EXPECT_EQ(mctest::triangleSet(mergeChunkMeshes(values(store))), mctest::triangleSet(mergeChunkMeshes(full)));
}

TEST(MarchingCubesIncremental, WorkerShutsDownWithWorkPending)
{
  VolumeOptions vo;
  vo.dims = { 128, 128, 128 };
  vo.chunkEdge = 32;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(64, 64, 64, 50));
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  ChunkedMarchingCubes mc(vol, o);
  auto worker = std::make_unique<MarchingCubesWorker>(mc);
  worker->requestAll();
  worker->cancelPending();
  worker->waitIdle();
  EXPECT_TRUE(worker->idle());
  worker->requestAll();
  worker->shutdown(); // returns without finishing the queue
  EXPECT_THROW(worker->request({ 0 }), Error);
  worker.reset();
}

TEST(MarchingCubesIncremental, WorkerSaysWhenEachMeshWasGathered)
{
  // Edits from this thread under the source mutex, each followed by a snapshot
  // (clone) of the volume. Every mesh collected with collect(&gatheredAt) must
  // equal the same chunk extracted from the snapshot of the last edit made
  // before its gather time (the oracle: a separate mesher on the snapshot).
  VolumeOptions vo;
  vo.dims = { 64, 64, 64 };
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  fillFromFunction(vol, sphereSdf(32, 32, 32, 16));
  vol.takeDirtyChunks();
  MarchingCubesOptions o;
  o.chunkEdge = 16;
  ChunkedMarchingCubes mc(vol, o);
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<Clock::time_point, std::unique_ptr<DictionaryVolume>>> snaps;
  snaps.emplace_back(Clock::now(), vol.clone());
  std::vector<ChunkMesh> got;
  std::vector<Clock::time_point> when;
  {
    MarchingCubesWorker worker(mc);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> pos(14, 50), rad(2, 5);
    for (int edit = 0; edit < 25; ++edit)
    {
      {
        std::lock_guard<std::mutex> lock(worker.sourceMutex());
        const VoxelBox b = stampSphere(vol, pos(rng), pos(rng), pos(rng), rad(rng), 0);
        vol.takeDirtyChunks();
        worker.request(mc.chunksAffectedBy(b));
        snaps.emplace_back(Clock::now(), vol.clone());
      }
      std::vector<Clock::time_point> w;
      auto m = worker.collect(&w);
      ASSERT_EQ(m.size(), w.size());
      for (auto& x : m) got.push_back(std::move(x));
      when.insert(when.end(), w.begin(), w.end());
      if (edit % 5 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    worker.waitIdle();
    std::vector<Clock::time_point> w;
    auto m = worker.collect(&w);
    ASSERT_EQ(m.size(), w.size());
    for (auto& x : m) got.push_back(std::move(x));
    when.insert(when.end(), w.begin(), w.end());
  }
  ASSERT_FALSE(got.empty());
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    // last snapshot taken (under the mutex) before the gather
    std::size_t s = 0;
    while (s + 1 < snaps.size() && snaps[s + 1].first < when[i]) ++s;
    ChunkedMarchingCubes oracle(*snaps[s].second, o);
    const ChunkMesh want = oracle.extractChunk(got[i].chunkId);
    EXPECT_EQ(mctest::triangleSet(mergeChunkMeshes({ got[i] })), mctest::triangleSet(mergeChunkMeshes({ want })))
      << "mesh " << i << " of chunk " << got[i].chunkId;
  }
}
