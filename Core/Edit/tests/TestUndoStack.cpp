// Undo/redo restores bit-identical volumes (every voxel compared to clones
// taken before each step), the memory cap, and the per-dab snapshot cost.
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Editor.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

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

namespace
{
std::vector<std::uint8_t> lvdvBytes(const DictionaryVolume& v)
{
  MemorySink sink;
  writeVolume(v, sink);
  return sink.buffer();
}
std::vector<std::uint8_t> bvBytes(const DictionaryVolume& v)
{
  MemorySink sink;
  writeLegacyBv(v, sink);
  return sink.buffer();
}
} // namespace

// An edit and its undo leave the file a save writes as it was, byte for byte:
// the .lvdv holds the colour dictionary, which kept the undone edits' colours
// (12 colours instead of 11 after `lvdif script` painted in red and undid it),
// so the file differed; the .bv (palette indices only) was already the same.
// Redo puts the colours back under the same keys.
TEST(UndoStack, UndoTakesOutTheStepsColoursSoTheSavedFileIsTheSame)
{
  DictionaryVolume v(edittest::options(48, 16));
  fillFromFunction(v, sphereSdf(24, 24, 24, 12));
  Editor e(v);
  e.brush.color = Rgba{ 10, 20, 30, 255 };
  e.dab(Dab{ BrushShape::Sphere, { 12, 24, 24 }, 4, {} }); // a step before: its colour stays
  const std::size_t before = v.colors().size();
  const std::vector<std::uint8_t> lvdv0 = lvdvBytes(v), bv0 = bvBytes(v);
  // an add in a new colour, a soft paint that mixes colours (many new ones), a stroke
  e.brush.color = Rgba{ 255, 0, 0, 255 };
  e.dab(Dab{ BrushShape::Sphere, { 36, 24, 24 }, 5, {} });
  e.brush.op = BrushOp::Paint;
  e.brush.color = Rgba{ 0, 0, 255, 255 };
  e.brush.strength = 0.5;
  e.brush.falloff = Falloff::Smooth;
  e.dab(Dab{ BrushShape::Sphere, { 24, 36, 24 }, 6, {} });
  e.brush = BrushSettings();
  e.brush.color = Rgba{ 0, 255, 0, 255 };
  std::vector<BrushSample> line(2);
  line[0].position = { 10, 10, 24 };
  line[1].position = { 38, 12, 24 };
  e.stroke.radius = 3;
  e.strokeThrough(line);
  ASSERT_EQ(e.undoStack().undoCount(), 4u);
  ASSERT_GT(v.colors().size(), before + 3) << "the edits added no colours: nothing is tested";
  const std::unique_ptr<DictionaryVolume> edited = v.clone();
  const std::vector<std::uint8_t> lvdv3 = lvdvBytes(v);
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(e.undo());
  EXPECT_EQ(v.colors().size(), before);
  EXPECT_TRUE(lvdvBytes(v) == lvdv0) << "the .lvdv after edit + undo differs from the one saved before";
  EXPECT_TRUE(bvBytes(v) == bv0) << "the .bv after edit + undo differs from the one saved before";
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(e.redo());
  EXPECT_TRUE(v.colors().colors() == edited->colors().colors());
  EXPECT_EQ(edittest::countDifferences(v, *edited), 0);
  EXPECT_TRUE(lvdvBytes(v) == lvdv3);
  // an edit that changes no voxel (outside the canvas) leaves no colour behind
  ASSERT_TRUE(e.undo());
  const std::size_t afterUndo = v.colors().size();
  e.brush.color = Rgba{ 1, 2, 3, 255 };
  e.dab(Dab{ BrushShape::Sphere, { -50, 0, 0 }, 3, {} });
  EXPECT_EQ(v.colors().size(), afterUndo);
  ASSERT_TRUE(e.redo()); // the no-op kept the redo step; its colours come back at their keys
  EXPECT_EQ(edittest::countDifferences(v, *edited), 0);
  EXPECT_TRUE(lvdvBytes(v) == lvdv3);
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
