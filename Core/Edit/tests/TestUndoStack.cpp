// Undo/redo restores bit-identical volumes (every voxel compared to clones
// taken before each step), the memory cap, and the per-dab snapshot cost.
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Editor.h"
#include "lvdif/Memory.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

using namespace lvdif;

TEST(UndoStack, UndoAndRedoRestoreBitIdenticalVolumes)
{
  DictionaryVolume v(edittest::options(64, 16));
  fillFromFunction(v, sphereSdf(32, 32, 32, 18));
  Editor e(v);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(4, 60), rad(2, 9);
  std::vector<std::unique_ptr<DictionaryVolume>> states;
  states.push_back(v.clone());
  for (int i = 0; i < 12; ++i)
  {
    e.brush.op = static_cast<BrushOp>(i % 3);
    e.brush.color = Rgba{ static_cast<std::uint8_t>(i * 20), 100, 50, 255 };
    e.brush.blend = i % 4 == 0 ? 3.0 : 0.0;
    if (i % 2)
    {
      e.dab(Dab{ i % 5 ? BrushShape::Sphere : BrushShape::Cube, { pos(rng), pos(rng), pos(rng) }, rad(rng), {} });
    }
    else
    {
      std::vector<BrushSample> s(3);
      for (auto& p : s)
        p.position = { pos(rng), pos(rng), pos(rng) };
      e.stroke.kind = i % 4 ? BrushKind::Dynamic : BrushKind::Basic;
      e.stroke.radius = rad(rng);
      e.strokeThrough(s);
    }
    if (e.undoStack().undoCount() == states.size()) // an edit that changed nothing adds no step
      states.push_back(v.clone());
  }
  const int steps = static_cast<int>(e.undoStack().undoCount());
  ASSERT_EQ(states.size(), static_cast<size_t>(steps) + 1);
  ASSERT_GE(steps, 9);
  for (int i = steps - 1; i >= 0; --i)
  {
    v.takeDirtyChunks();
    ASSERT_TRUE(e.undo());
    ASSERT_EQ(edittest::countDifferences(v, *states[static_cast<size_t>(i)]), 0) << "after undo to state " << i;
    // every chunk that differs from the state before the undo is reported dirty
    const auto changed = edittest::differingChunks(v, *states[static_cast<size_t>(i) + 1]);
    const auto dirty = v.takeDirtyChunks();
    for (auto id : changed)
      ASSERT_TRUE(std::binary_search(dirty.begin(), dirty.end(), id));
  }
  EXPECT_FALSE(e.undo());
  for (int i = 1; i <= steps; ++i)
  {
    ASSERT_TRUE(e.redo());
    ASSERT_EQ(edittest::countDifferences(v, *states[static_cast<size_t>(i)]), 0) << "after redo to state " << i;
  }
  EXPECT_FALSE(e.redo());
  // undo twice, then a new edit drops the redo steps
  e.undo();
  e.undo();
  EXPECT_EQ(e.undoStack().redoCount(), 2u);
  e.brush.op = BrushOp::Add;
  e.dab(Dab{ BrushShape::Sphere, { 10, 10, 10 }, 3, {} });
  EXPECT_EQ(e.undoStack().redoCount(), 0u);
  ASSERT_TRUE(e.undo());
  EXPECT_EQ(edittest::countDifferences(v, *states[static_cast<size_t>(steps) - 2]), 0);
}

TEST(UndoStack, EmptyStepsAreNotKept)
{
  DictionaryVolume v(edittest::options(32));
  Editor e(v);
  e.dab(Dab{ BrushShape::Sphere, { -50, 0, 0 }, 3, {} }); // outside: touches nothing
  EXPECT_EQ(e.undoStack().undoCount(), 0u);
}

TEST(UndoStack, CapDropsOldestStepsButKeepsMinSteps)
{
  DictionaryVolume v(edittest::options(64, 16));
  UndoStack::Options o;
  o.maxBytes = 600 * 1024; // a few 16 KiB chunks per dab
  o.minSteps = 2;
  Editor e(v, o);
  auto start = v.clone();
  for (int i = 0; i < 20; ++i)
  {
    e.dab(Dab{ BrushShape::Sphere, { 8.0 + 2.5 * i, 32, 32 }, 6, {} });
    EXPECT_TRUE(e.undoStack().bytes() <= o.maxBytes || e.undoStack().undoCount() <= o.minSteps);
  }
  const std::size_t kept = e.undoStack().undoCount();
  EXPECT_LT(kept, 20u);
  EXPECT_GE(kept, 2u);
  while (e.undo())
  {
  }
  // the oldest steps are gone, so the volume is not back at the start, but the
  // first kept step's own region is restored: the last dab centre is empty again
  EXPECT_GT(edittest::countDifferences(v, *start), 0);
  EXPECT_GT(v.sdf(8 + 25 * 19 / 10, 32, 32), 0.0f);

  o.maxBytes = 1; // tiny cap: minSteps are still kept
  Editor f(v, o);
  for (int i = 0; i < 5; ++i)
    f.dab(Dab{ BrushShape::Sphere, { 20.0 + 3 * i, 20, 20 }, 4, {} });
  EXPECT_EQ(f.undoStack().undoCount(), 2u);
}

TEST(UndoStack, HundredSurfaceDabsFitTheDefaultCapAtChunkEdge32)
{
  // The snapshot cost of a dab depends on the chunk edge and the dab radius, not on
  // the volume size: measure it on 256^3 with 32^3 chunks and extrapolate to 1024^3.
  VolumeOptions o = edittest::options(256, 32);
  DictionaryVolume v(o);
  fillFromFunction(v, sphereSdf(128, 128, 128, 100));
  Editor e(v);
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  for (int i = 0; i < 100; ++i)
  {
    double d[3] = { g(rng), g(rng), g(rng) };
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    e.brush.op = i % 2 ? BrushOp::Subtract : BrushOp::Add;
    e.dab(Dab{ BrushShape::Sphere, { 128 + 100 * d[0] / n, 128 + 100 * d[1] / n, 128 + 100 * d[2] / n }, 15, {} });
  }
  EXPECT_EQ(e.undoStack().undoCount(), 100u);
  EXPECT_LE(e.undoStack().bytes(), UndoStack::Options().maxBytes);
  std::cout << "[ info ] 100 radius-15 surface dabs hold " << formatBytes(e.undoStack().bytes()) << " of undo ("
            << formatBytes(e.undoStack().bytes() / 100) << " per dab)\n";
}
