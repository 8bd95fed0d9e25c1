// The GPU edit session against the CPU one: after seeded random strokes with
// undo/redo interleaved, the device-resident volume (synced) equals the CPU
// session's volume bit for bit, and the chunk meshes handed out (meshed on the
// device from the device volume) equal a full CPU re-mesh. Skipped without a GPU.
#include "SessionTestUtil.h"

#include <gtest/gtest.h>

using namespace sessiontest;

namespace
{
bool haveGpu()
{
  return lvdif::resolveDevice(lvdif::Device::Cuda) == lvdif::Device::Cuda;
}

// The session under test on the device and its CPU peer, each over its own clone of one start
// volume, with the same options but the device.
struct SessionPair
{
  std::unique_ptr<lvdif::EditSession> gpu;
  std::unique_ptr<lvdif::EditSession> cpu;
};

SessionPair makePair(const lvdif::DictionaryVolume& start, lvdif::EditSessionOptions options)
{
  SessionPair pair;
  options.device = lvdif::Device::Cuda;
  pair.gpu = std::make_unique<lvdif::EditSession>(start.clone(), options);
  options.device = lvdif::Device::Cpu;
  pair.cpu = std::make_unique<lvdif::EditSession>(start.clone(), options);
  return pair;
}

// The meshes the device session handed out, frame after frame, against one CPU re-mesh of the
// CPU session's volume.
void expectMeshesEqualFullRemesh(const MeshStore& store, const SessionPair& pair)
{
  std::string problem;
  EXPECT_EQ(compareWithFullRemesh(store, pair.cpu->volume(), pair.gpu->mesher().options(), &problem), 0)
    << problem;
}


void runAgainstCpu(std::int64_t n, int edge, std::uint32_t seed, int count, std::uint64_t historyBytes,
  int meshChunkEdge = 0)
{
  auto start = sphereVolume(n, edge);
  lvdif::EditSessionOptions o;
  o.undo.maxBytes = historyBytes;
  o.meshChunkEdge = meshChunkEdge;
  const SessionPair pair = makePair(*start, o);
  lvdif::EditSession& gpu = *pair.gpu;
  lvdif::EditSession& cpu = *pair.cpu;
  ASSERT_TRUE(gpu.onDevice()) << gpu.notice();
  MeshStore store;
  gpu.requestAllMeshes();
  store.take(gpu.collectMeshes());
  const std::vector<Op> ops = randomOps(seed, count, static_cast<double>(n));
  for (std::size_t i = 0; i < ops.size(); ++i)
  {
    apply(gpu, ops[i]);
    apply(cpu, ops[i]);
    EXPECT_EQ(gpu.canUndo(), cpu.canUndo()) << "op " << i;
    EXPECT_EQ(gpu.canRedo(), cpu.canRedo()) << "op " << i;
    store.take(gpu.collectMeshes()); // one frame per operation
    if (i % 10 == 9)
    {
      // a sync in the middle (a save): later edits and undos continue from it
      EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0) << "seed " << seed << " after op " << i;
    }
  }
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0) << "seed " << seed;
  const auto oracle = replay(*start, ops);
  EXPECT_EQ(decodedDifferences(gpu.volume(), *oracle), 0) << "seed " << seed;
  SCOPED_TRACE("seed " + std::to_string(seed));
  expectMeshesEqualFullRemesh(store, pair);
}
} // namespace

TEST(EditSessionCuda, DeviceVolumeEqualsCpuBitForBitAndMeshesEqualFullRemesh)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  for (std::uint32_t seed : { 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u })
    runAgainstCpu(64, 16, seed, 40, 256ull << 20);
}

TEST(EditSessionCuda, MeshChunksOfAnotherEdgeThanTheStorageChunks)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  runAgainstCpu(80, 16, 21, 40, 256ull << 20, 24); // mesh chunks of 24 cells over storage chunks of 16
  runAgainstCpu(96, 32, 22, 30, 256ull << 20, 16);
}

TEST(EditSessionCuda, LargerChunksAndAClippedVolume)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  runAgainstCpu(100, 32, 5, 30, 256ull << 20); // 100 is not a multiple of 32: border chunks are clipped
  runAgainstCpu(128, 32, 6, 60, 256ull << 20);
}

TEST(EditSessionCuda, SmallHistoryDropsOldStepsLikeTheCpu)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  // a tiny history: both keep only the newest step(s); equality must hold whatever survives
  lvdif::EditSessionOptions o;
  o.undo.maxBytes = 1; // below one snapshot: only minSteps (1) survive
  const SessionPair pair = makePair(*sphereVolume(64, 16), o);
  lvdif::EditSession& gpu = *pair.gpu;
  lvdif::EditSession& cpu = *pair.cpu;
  ASSERT_TRUE(gpu.onDevice()) << gpu.notice();
  const std::vector<Op> ops = randomOps(9, 25, 64);
  for (const Op& op : ops)
  {
    apply(gpu, op);
    apply(cpu, op);
    EXPECT_EQ(gpu.undoCount(), cpu.undoCount());
  }
  while (gpu.undo())
    cpu.undo();
  EXPECT_FALSE(cpu.canUndo());
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0);
}

TEST(EditSessionCuda, ScriptsAndCanvasFillOnTheDevice)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  const SessionPair pair = makePair(*sphereVolume(64, 16), {});
  lvdif::EditSession& gpu = *pair.gpu;
  lvdif::EditSession& cpu = *pair.cpu;
  ASSERT_TRUE(gpu.onDevice()) << gpu.notice();
  const std::string script = "op subtract\nfor i in 0..3 { sphere 16 + 10*i, 32, 50, 6 }\nundo\nop paint\ncolor 10 200 30\n"
                             "sphere 32 32 50 12";
  gpu.runScript(script);
  cpu.runScript(script);
  EXPECT_EQ(gpu.undoCount(), cpu.undoCount());
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0);
  gpu.undo();
  cpu.undo();
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0);
  gpu.runScript("canvas fill\nop subtract\nsphere 32 32 32 10");
  cpu.runScript("canvas fill\nop subtract\nsphere 32 32 32 10");
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0);
  MeshStore store;
  gpu.requestAllMeshes();
  store.take(gpu.collectMeshes());
  expectMeshesEqualFullRemesh(store, pair);
}

TEST(EditSessionCuda, SculptingBrushesOnTheDeviceEqualTheCpu)
{
  if (!haveGpu())
    GTEST_SKIP() << "no CUDA device";
  // every op (Smooth, Grab and Pinch run on the synced host copy and hand their chunks to
  // the device step), soft falloffs and strengths (soft paint's mix tables on the device)
  const SessionPair pair = makePair(*sphereVolume(64, 16), {});
  lvdif::EditSession& gpu = *pair.gpu;
  lvdif::EditSession& cpu = *pair.cpu;
  ASSERT_TRUE(gpu.onDevice()) << gpu.notice();
  MeshStore store;
  gpu.requestAllMeshes();
  store.take(gpu.collectMeshes());
  for (int op = 0; op <= static_cast<int>(lvdif::BrushOp::Pinch); ++op)
  {
    for (lvdif::EditSession* s : { &gpu, &cpu })
    {
      s->brush() = lvdif::BrushSettings();
      s->brush().op = static_cast<lvdif::BrushOp>(op);
      s->brush().strength = op % 2 ? 0.6 : 1.0;
      s->brush().falloff = static_cast<lvdif::Falloff>(op % 3);
      s->brush().color = lvdif::Rgba{ static_cast<std::uint8_t>(30 * op), 120, 200, 255 };
      s->stroke().kind = lvdif::BrushKind::Drill;
      s->stroke().radius = 5;
      s->beginStroke();
      for (int i = 0; i < 6; ++i)
      {
        lvdif::BrushSample b;
        b.position = { 32.0 + 2.0 * i, 32.0 + 0.5 * op, 51.0 };
        b.buttons = 1;
        s->addSample(b);
      }
      s->endStroke();
    }
    store.take(gpu.collectMeshes());
    EXPECT_EQ(gpu.undoCount(), cpu.undoCount()) << "op " << op;
    EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0) << "op " << op;
  }
  for (int k = 0; k < 3; ++k)
  {
    gpu.undo();
    cpu.undo();
  }
  gpu.redo();
  cpu.redo();
  store.take(gpu.collectMeshes());
  EXPECT_EQ(differences(gpu.volume(), cpu.volume()), 0);
  expectMeshesEqualFullRemesh(store, pair);
}
