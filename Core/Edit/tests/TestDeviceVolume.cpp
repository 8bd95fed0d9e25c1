// The device-resident volume equals the CPU brush bit for bit after sync (the
// oracle is lvdif::applyDabs on a clone, itself tested against analytic SDFs),
// the undo stack sees synced writes, refresh() follows host edits, and the
// device memory bound is enforced. Skipped without a GPU (the stub refuses).
#include "EditTestUtil.h"
#include "ErrorTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Cuda.h"
#include "lvdif/DeviceVolume.h"
#include "lvdif/Error.h"
#include "lvdif/UndoStack.h"

#include <gtest/gtest.h>

#include <random>

using namespace lvdif;

namespace
{
// A mixed sequence of edits: every op, blends, rounded cubes, capsule strokes, far-away dabs.
std::vector<std::pair<std::vector<Dab>, BrushSettings>> editSequence(int count, double n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-5, n + 5), rad(1, 0.2 * n);
  std::vector<std::pair<std::vector<Dab>, BrushSettings>> out;
  for (int i = 0; i < count; ++i)
  {
    BrushSettings s;
    // the per-voxel operations the resident volume applies (Brush.h); strength,
    // falloff and symmetry on some (paint stays hard: soft paint is refused here)
    const BrushOp ops[] = { BrushOp::Add, BrushOp::Subtract, BrushOp::Paint, BrushOp::Inflate, BrushOp::Crease };
    s.op = i < 12 ? static_cast<BrushOp>(i % 3) : ops[i % 5];
    s.blend = i % 4 == 1 ? 3.5 : 0;
    s.rounding = i % 5 == 2 ? 2 : 0;
    s.color = Rgba{ static_cast<std::uint8_t>(i * 7), 9, static_cast<std::uint8_t>(i), 255 };
    if (i >= 12 && s.op != BrushOp::Paint)
    {
      s.strength = i % 3 == 0 ? 1.0 : 0.6;
      s.falloff = static_cast<Falloff>(i % 4);
      s.invert = i % 2 == 1;
    }
    if (i >= 12 && i % 3 == 1)
    {
      s.symmetry.mirror = { true, i % 2 == 0, false };
      s.symmetry.plane = { 0.5 * n, 0.4 * n, 0 };
    }
    const std::vector<Dab> dabs = edittest::randomDabs(rng, pos, rad, i);
    out.emplace_back(dabs, s);
  }
  return out;
}

bool sameUniformity(const DictionaryVolume& a, const DictionaryVolume& b)
{
  for (std::int64_t id = 0; id < a.chunkCount(); ++id)
    if (a.isUniform(id) != b.isUniform(id))
      return false;
  return true;
}
} // namespace

TEST(DeviceVolumeCuda, RefusedWithoutCuda)
{
  if (cuda::available())
    GTEST_SKIP() << "a CUDA device is present";
  DictionaryVolume v(edittest::options(32));
  errortest::errorMessageOf([&] { cuda::DeviceVolume d(v); }, ErrorCode::Unsupported);
}

TEST(DeviceVolumeCuda, EveryDabSyncedEqualsTheCpuBitForBit)
{
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  DictionaryVolume cpu(edittest::options(150, 16)); // not a multiple of the chunk edge
  fillFromFunction(cpu, sphereSdf(70, 75, 72, 45));
  auto gpuHost = cpu.clone();
  cuda::DeviceVolume dev(*gpuHost);
  int i = 0;
  for (const auto& [dabs, s] : editSequence(40, 150, 9))
  {
    cpu.takeDirtyChunks();
    gpuHost->takeDirtyChunks();
    const EditResult a = applyDabs(cpu, dabs, s);
    const EditResult b = dev.applyDabs(dabs, s);
    ASSERT_EQ(a.changedVoxels, b.changedVoxels) << "edit " << i;
    ASSERT_EQ(a.changedChunks, b.changedChunks) << "edit " << i;
    EXPECT_EQ(dev.pendingChunks(), b.changedChunks.size());
    const EditResult c = dev.sync();
    EXPECT_EQ(dev.pendingChunks(), 0u);
    ASSERT_EQ(c.changedChunks, a.changedChunks) << "edit " << i;
    ASSERT_EQ(cpu.takeDirtyChunks(), gpuHost->takeDirtyChunks()) << "edit " << i;
    ASSERT_EQ(edittest::countDifferences(cpu, *gpuHost), 0) << "edit " << i;
    ASSERT_TRUE(sameUniformity(cpu, *gpuHost)) << "edit " << i;
    ++i;
  }
  EXPECT_LE(dev.slotsUsed(), dev.slotCapacity());
}

TEST(DeviceVolumeCuda, LazySyncOfManyEditsEqualsTheCpu)
{
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  DictionaryVolume cpu(edittest::options(128, 32));
  fillFromFunction(cpu, sphereSdf(60, 64, 66, 40));
  auto gpuHost = cpu.clone();
  cuda::DeviceVolume dev(*gpuHost);
  const auto host0 = gpuHost->clone();
  for (const auto& [dabs, s] : editSequence(30, 128, 4))
  {
    applyDabs(cpu, dabs, s);
    dev.applyDabs(dabs, s);
  }
  // nothing reached the host yet
  EXPECT_EQ(edittest::countDifferences(*gpuHost, *host0), 0);
  EXPECT_GT(dev.pendingChunks(), 0u);
  // sync under an undo step: the undo stack snapshots what the device changed
  UndoStack undo(*gpuHost);
  undo.beginStep("device edits");
  const EditResult r = dev.sync(&undo);
  undo.endStep();
  EXPECT_EQ(edittest::countDifferences(cpu, *gpuHost), 0);
  const std::set<std::int64_t> expected = edittest::differingChunks(cpu, *host0);
  EXPECT_EQ(std::set<std::int64_t>(r.changedChunks.begin(), r.changedChunks.end()), expected);
  // undo on the host, refresh the device, edit again: still the CPU's bits
  ASSERT_TRUE(undo.undo());
  EXPECT_EQ(edittest::countDifferences(*gpuHost, *host0), 0);
  dev.refresh(undo.lastRestoredChunks());
  // the oracle starts from the host volume itself (same colour dictionary: host0's lacks the edits' colours)
  auto cpu2 = gpuHost->clone();
  const Dab d{ BrushShape::Sphere, { 60, 64, 106 }, 12, {} };
  applyDabs(*cpu2, { d }, BrushSettings());
  dev.applyDabs({ d }, BrushSettings());
  dev.sync();
  EXPECT_EQ(edittest::countDifferences(*cpu2, *gpuHost), 0);
}

TEST(DeviceVolumeCuda, RefreshRefusesPendingChunksAndTheBoundIsEnforced)
{
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  DictionaryVolume v(edittest::options(96, 16));
  fillFromFunction(v, sphereSdf(48, 48, 48, 30));
  std::int64_t expanded = 0;
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
    expanded += v.isUniform(id) ? 0 : 1;
  ASSERT_GT(expanded, 10);
  cuda::DeviceVolume::Options tiny;
  tiny.maxDeviceBytes = 16 * 16 * 16 * 4 * 3; // 3 chunks: far too small
  errortest::errorMessageOf([&] { cuda::DeviceVolume d(v, tiny); }, ErrorCode::OutOfMemory); // the bound is enforced
  // a pool with exactly no headroom: an edit that must expand uniform chunks is refused, nothing changes
  cuda::DeviceVolume::Options exact;
  exact.headroomSlots = 0;
  exact.historyBytes = 0; // the history's share of the pool: none
  cuda::DeviceVolume d(v, exact);
  EXPECT_EQ(d.slotCapacity(), static_cast<std::size_t>(expanded));
  auto before = v.clone();
  errortest::errorMessageOf( // the pool does not overflow
    [&] { d.applyDabs({ Dab{ BrushShape::Sphere, { 48, 48, 48 }, 45, {} } }, BrushSettings()); }, ErrorCode::OutOfMemory);
  EXPECT_EQ(d.pendingChunks(), 0u);
  d.sync();
  EXPECT_EQ(edittest::countDifferences(v, *before), 0);
  // an edit inside the expanded shell works, and refresh refuses its pending chunks
  const EditResult r = d.applyDabs({ Dab{ BrushShape::Sphere, { 48, 48, 78 }, 2, {} } }, BrushSettings());
  ASSERT_FALSE(r.changedChunks.empty());
  EXPECT_THROW(d.refresh(r.changedChunks), Error);
  d.sync();
  d.refresh(r.changedChunks);
}
