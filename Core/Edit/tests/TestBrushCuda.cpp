// The CUDA brush equals the CPU brush bit for bit (skipped without a GPU), and
// the device encoder restated in BrushKernel.h equals the dictionary's (CPU).
#include "../src/BrushKernel.h"
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/BrushCuda.h"
#include "lvdif/Cuda.h"
#include "lvdif/Error.h"
#include "lvdif/UndoStack.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace lvdif;

TEST(BrushEncoder, RestatedEncoderEqualsTheDictionary)
{
  const SdfDictionary& d = defaultSdfDictionary();
  for (float band : { 8.0f, 3.5f, 1e30f })
  {
    const detail::edit::EncodeParams e = detail::edit::EncodeParams::of(d, band);
    for (int k = 0; k + 1 < 65536; ++k)
    {
      const float a = d.decode(static_cast<SdfKey>(k)), b = d.decode(static_cast<SdfKey>(k + 1));
      const float mid = 0.5f * (a + b);
      for (float v : { a, mid, std::nextafter(mid, -1e30f), std::nextafter(mid, 1e30f) })
        ASSERT_EQ(e(double(v)), d.encodeClamped(v, band)) << v;
    }
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-4000, 4000);
    for (int i = 0; i < 200000; ++i)
    {
      const double v = u(rng) * (i % 2 ? 1e-3 : 1.0);
      ASSERT_EQ(e(v), d.encodeClamped(static_cast<float>(v), band)) << v;
    }
    ASSERT_EQ(e(NAN), d.encodeClamped(NAN, band));
  }
}

namespace
{
// One edit through the CPU brush and through the CUDA brush on two equal volumes: the same
// counts, the same dirty chunks, the same voxels.
void expectSameEdit(DictionaryVolume& cpu, DictionaryVolume& gpu, const std::vector<Dab>& dabs, const BrushSettings& s)
{
  cpu.takeDirtyChunks();
  gpu.takeDirtyChunks();
  const EditResult a = applyDabs(cpu, dabs, s);
  const EditResult b = cuda::applyDabs(gpu, dabs, s);
  ASSERT_EQ(a.changedVoxels, b.changedVoxels);
  ASSERT_EQ(a.changedChunks, b.changedChunks);
  ASSERT_EQ(cpu.takeDirtyChunks(), gpu.takeDirtyChunks());
  ASSERT_EQ(edittest::countDifferences(cpu, gpu), 0);
}
} // namespace

TEST(BrushCuda, GpuDabsEqualCpuDabsBitForBit)
{
  if (!cuda::available())
  {
    GTEST_SKIP() << "no CUDA device";
  }
  VolumeOptions o = edittest::options(150, 16); // not a multiple of the chunk edge
  DictionaryVolume cpu(o);
  fillFromFunction(cpu, sphereSdf(70, 75, 72, 45));
  auto gpu = cpu.clone();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> pos(-5, 155), rad(1, 30);
  for (int i = 0; i < 40; ++i)
  {
    BrushSettings s;
    s.op = static_cast<BrushOp>(i % 3);
    s.blend = i % 4 == 1 ? 3.5 : 0;
    s.rounding = i % 5 == 2 ? 2 : 0;
    s.color = Rgba{ static_cast<std::uint8_t>(i), 9, 9, 255 };
    const std::vector<Dab> dabs = edittest::randomDabs(rng, pos, rad, i);
    SCOPED_TRACE("edit " + std::to_string(i) + " " + toString(s.op));
    expectSameEdit(cpu, *gpu, dabs, s);
    if (HasFatalFailure())
      return;
  }
  // the undo observer sees the GPU edits too
  UndoStack undo(*gpu);
  auto before = gpu->clone();
  undo.beginStep("gpu");
  cuda::applyDabs(*gpu, { Dab{ BrushShape::Sphere, { 70, 75, 117 }, 15, {} } }, BrushSettings(), &undo);
  undo.endStep();
  ASSERT_GT(edittest::countDifferences(*gpu, *before), 0);
  undo.undo();
  EXPECT_EQ(edittest::countDifferences(*gpu, *before), 0);
}

TEST(BrushCuda, GpuSculptBrushesEqualCpuBitForBit)
{
  if (!cuda::available())
  {
    GTEST_SKIP() << "no CUDA device";
  }
  DictionaryVolume cpu(edittest::options(120, 16));
  fillFromFunction(cpu, sphereSdf(60, 58, 61, 38));
  auto gpu = cpu.clone();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> pos(10, 110), rad(2, 20);
  const BrushOp ops[] = { BrushOp::Add, BrushOp::Subtract, BrushOp::Paint, BrushOp::Inflate, BrushOp::Flatten,
    BrushOp::Crease };
  for (int i = 0; i < 36; ++i)
  {
    BrushSettings s;
    s.op = ops[i % 6];
    s.strength = i % 5 == 0 ? 1.0 : 0.3 + 0.1 * (i % 7);
    s.falloff = static_cast<Falloff>((i / 6) % 4);
    s.invert = i % 2 == 1;
    s.blend = i % 4 == 1 ? 2.5 : 0;
    s.color = Rgba{ static_cast<std::uint8_t>(40 * (i % 6)), static_cast<std::uint8_t>(i), 90, 255 };
    if (i % 3 == 2)
    {
      s.symmetry.mirror = { true, i % 2 == 0, i % 4 == 3 };
      s.symmetry.plane = { 59.5, 61.25, 57 };
    }
    std::vector<Dab> dabs;
    for (int k = 0; k < 1 + i % 4; ++k)
    {
      Dab d;
      d.shape = static_cast<BrushShape>((i + k) % 3);
      d.center = { pos(rng), pos(rng), pos(rng) };
      d.end = { pos(rng), pos(rng), pos(rng) };
      d.radius = rad(rng);
      dabs.push_back(d);
    }
    SCOPED_TRACE("edit " + std::to_string(i) + " " + toString(s.op));
    expectSameEdit(cpu, *gpu, dabs, s);
    if (HasFatalFailure())
      return;
  }
}

TEST(BrushCuda, NeighbourBrushesRunOnTheCpuUnderAuto)
{
  DictionaryVolume a(edittest::options(48, 16));
  fillFromFunction(a, sphereSdf(24, 24, 24, 12));
  auto b = a.clone();
  BrushSettings s;
  s.op = BrushOp::Smooth;
  const std::vector<Dab> dabs{ Dab{ BrushShape::Sphere, { 24, 24, 36 }, 6, {} } };
  applyDabs(a, dabs, s);
  applyDabs(Device::Auto, *b, dabs, s);
  EXPECT_EQ(edittest::countDifferences(a, *b), 0);
  // the CUDA path itself refuses them (no GPU: refused before that for want of a device)
  EXPECT_THROW(cuda::applyDabs(*b, dabs, s), Error);
}

TEST(BrushCuda, DispatchFallsBackToTheCpu)
{
  DictionaryVolume a(edittest::options(32)), b(edittest::options(32));
  applyDabs(Device::Auto, a, { Dab{ BrushShape::Sphere, { 16, 16, 16 }, 6, {} } }, BrushSettings());
  applyDabs(b, { Dab{ BrushShape::Sphere, { 16, 16, 16 }, 6, {} } }, BrushSettings());
  EXPECT_EQ(edittest::countDifferences(a, b), 0);
  EXPECT_LT(a.sdf(16, 16, 16), 0.0f); // the dab did land
  if (!cuda::available())
  {
    // the CUDA entry point itself refuses here, so Auto's success was the fallback
    DictionaryVolume c(edittest::options(32));
    EXPECT_THROW(cuda::applyDabs(c, { Dab{ BrushShape::Sphere, { 16, 16, 16 }, 6, {} } }, BrushSettings()), Error);
  }
}
