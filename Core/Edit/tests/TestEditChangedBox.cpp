// EditResult::changedBox: every voxel whose 4 bytes an edit changed (found by
// comparing against a clone taken before the edit) lies inside the box, and
// where no chunk is filled in one go (blend > 0, paint) the box is exactly the
// bounding box of the changed voxels. Also through the Editor (strokes merge boxes).
#include "EditTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/Editor.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

using namespace lvdif;

namespace
{
/// Bounding box of the voxels that differ between a and b (empty if none).
VoxelBox differenceBox(const DictionaryVolume& a, const DictionaryVolume& b)
{
  VoxelBox box;
  edittest::forEachVoxel(a, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    if (a.get(x, y, z) != b.get(x, y, z)) box.include(x, y, z);
  });
  return box;
}

bool covers(const VoxelBox& outer, const VoxelBox& inner)
{
  if (inner.empty()) return true;
  return !outer.empty() && outer.intersect(inner).voxelCount() == inner.voxelCount();
}

/// Per storage chunk with a differing voxel: the bounding box of those voxels (by chunk id).
std::map<std::int64_t, VoxelBox> differenceBoxesPerChunk(const DictionaryVolume& a, const DictionaryVolume& b)
{
  std::map<std::int64_t, VoxelBox> boxes;
  edittest::forEachVoxel(a, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    if (a.get(x, y, z) != b.get(x, y, z)) boxes[a.chunkOf(x, y, z)].include(x, y, z);
  });
  return boxes;
}

/// The per-chunk boxes of an edit: one per changed chunk, each inside its chunk,
/// covering (exact: equal to) the chunk's changed voxels.
void checkChunkBoxes(const EditResult& r, const std::map<std::int64_t, VoxelBox>& truth, const DictionaryVolume& v, bool exact)
{
  ASSERT_EQ(r.changedChunkBoxes.size(), r.changedChunks.size());
  ASSERT_EQ(r.changedChunks.size(), truth.size());
  for (std::size_t i = 0; i < r.changedChunks.size(); ++i)
  {
    const auto t = truth.find(r.changedChunks[i]);
    ASSERT_TRUE(t != truth.end()) << "chunk " << r.changedChunks[i] << " reported but unchanged";
    const VoxelBox& b = r.changedChunkBoxes[i];
    EXPECT_TRUE(covers(v.chunkBox(r.changedChunks[i]), b));
    EXPECT_TRUE(covers(b, t->second));
    if (exact)
    {
      EXPECT_EQ(b.lo, t->second.lo);
      EXPECT_EQ(b.hi, t->second.hi);
    }
  }
}

} // namespace

TEST(EditChangedBox, CoversEveryChangedVoxel)
{
  DictionaryVolume vol(edittest::options(72, 16, 6.0f));
  fillFromFunction(vol, sphereSdf(35.3, 36.1, 34.7, 20));
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> pos(-6, 78), rad(1.0, 14.0), blend(0, 4);
  std::uniform_int_distribution<int> pick(0, 2);
  int exactChecked = 0, nonEmpty = 0;
  for (int round = 0; round < 40; ++round)
  {
    BrushSettings s;
    s.op = static_cast<BrushOp>(pick(rng));
    s.blend = round % 3 == 0 ? 0.0 : blend(rng);
    s.color = Rgba{ static_cast<std::uint8_t>(round * 37), 90, 200, 255 };
    std::vector<Dab> dabs;
    const int n = 1 + round % 4;
    for (int k = 0; k < n; ++k)
    {
      Dab d;
      d.shape = static_cast<BrushShape>(pick(rng));
      d.center = { pos(rng), pos(rng), pos(rng) };
      d.end = { d.center[0] + pos(rng) / 8, d.center[1] - pos(rng) / 9, d.center[2] + 3 };
      d.radius = rad(rng);
      dabs.push_back(d);
    }
    const auto before = vol.clone();
    const EditResult r = applyDabs(vol, dabs, s);
    const VoxelBox truth = differenceBox(*before, vol);
    SCOPED_TRACE("round " + std::to_string(round));
    checkChunkBoxes(r, differenceBoxesPerChunk(*before, vol), vol, s.blend > 0 || s.op == BrushOp::Paint);
    EXPECT_EQ(truth.empty(), r.changedBox.empty());
    EXPECT_EQ(truth.empty(), r.changedVoxels == 0);
    EXPECT_TRUE(covers(r.changedBox, truth));
    EXPECT_TRUE(covers(vol.bounds(), r.changedBox)); // never outside the volume
    nonEmpty += !truth.empty();
    if (s.blend > 0 || s.op == BrushOp::Paint)
    {
      // no whole-chunk fill: the box is tight
      EXPECT_EQ(r.changedBox.lo, truth.lo);
      EXPECT_EQ(r.changedBox.hi, truth.hi);
      exactChecked += !truth.empty();
    }
  }
  EXPECT_GT(nonEmpty, 20);
  EXPECT_GT(exactChecked, 10);
}

TEST(EditChangedBox, GatherBrushesReportExactChunkBoxes)
{
  DictionaryVolume vol(edittest::options(64, 16, 6.0f));
  fillFromFunction(vol, sphereSdf(32, 31.5, 32.2, 18));
  for (BrushOp op : { BrushOp::Smooth, BrushOp::Grab, BrushOp::Pinch })
  {
    BrushSettings s;
    s.op = op;
    s.falloff = Falloff::Smooth;
    Dab d;
    d.center = { 32.0, 31.0, 50.5 };
    d.radius = 9;
    d.vec = { 1.5, -0.5, 2.0 };
    const auto before = vol.clone();
    const EditResult r = applyDabs(vol, { d, d }, s);
    SCOPED_TRACE(toString(op));
    EXPECT_GT(r.changedVoxels, 0);
    checkChunkBoxes(r, differenceBoxesPerChunk(*before, vol), vol, true);
  }
}

TEST(EditChangedBox, EditorStrokeUnitesTheBoxes)
{
  DictionaryVolume vol(edittest::options(64, 16, 6.0f));
  fillFromFunction(vol, sphereSdf(32, 31.5, 32.2, 18));
  Editor ed(vol);
  ed.brush.op = BrushOp::Subtract;
  ed.brush.blend = 1.0;
  ed.stroke.radius = 4;
  const auto before = vol.clone();
  ed.beginStroke();
  EditResult all;
  for (int i = 0; i < 12; ++i)
  {
    BrushSample s;
    s.position = { 14.0 + 3 * i, 32.0 + 0.5 * i, 50.0 };
    s.pressure = 1.0;
    const EditResult r = ed.addSample(s);
    all.changedBox = all.changedBox.unite(r.changedBox);
  }
  const EditResult last = ed.endStroke();
  all.changedBox = all.changedBox.unite(last.changedBox);
  const VoxelBox truth = differenceBox(*before, vol);
  ASSERT_FALSE(truth.empty());
  // the stroke's merged per-chunk boxes are exact too (blend > 0: no whole-chunk fill)
  checkChunkBoxes(last, differenceBoxesPerChunk(*before, vol), vol, true);
  EXPECT_EQ(all.changedBox.lo, truth.lo);
  EXPECT_EQ(all.changedBox.hi, truth.hi);
  // endStroke returns the whole stroke's merged result
  EXPECT_EQ(last.changedBox.lo, truth.lo);
  EXPECT_EQ(last.changedBox.hi, truth.hi);
}

TEST(EditChangedBox, LastWriteIsWhatEachCallWrote)
{
  // A live (Drill) stroke: lastWrite() after every addSample and after
  // endStroke covers exactly the voxels that call changed (clone before each
  // call as the oracle), and endStroke's lastWrite is not the whole stroke's box.
  DictionaryVolume vol(edittest::options(64, 16, 6.0f));
  fillFromFunction(vol, sphereSdf(32, 31.5, 32.2, 18));
  Editor ed(vol);
  ed.brush.op = BrushOp::Add;
  ed.brush.blend = 1.0; // no whole-chunk fills: boxes are tight
  ed.stroke.kind = BrushKind::Drill;
  ed.stroke.radius = 3;
  ed.beginStroke();
  VoxelBox whole;
  int nonEmpty = 0;
  for (int i = 0; i < 10; ++i)
  {
    BrushSample s;
    s.position = { 12.0 + 4 * i, 32.0, 50.0 };
    s.pressure = 1.0;
    s.time = 0.02 * i;
    s.buttons = 1;
    const auto before = vol.clone();
    const EditResult r = ed.addSample(s);
    const VoxelBox truth = differenceBox(*before, vol);
    SCOPED_TRACE("sample " + std::to_string(i));
    EXPECT_EQ(ed.lastWrite().changedBox.lo, truth.lo);
    EXPECT_EQ(ed.lastWrite().changedBox.hi, truth.hi);
    EXPECT_EQ(ed.lastWrite().changedVoxels, r.changedVoxels);
    whole = whole.unite(truth);
    nonEmpty += !truth.empty();
  }
  const auto before = vol.clone();
  const EditResult all = ed.endStroke();
  const VoxelBox tail = differenceBox(*before, vol);
  whole = whole.unite(tail);
  EXPECT_GT(nonEmpty, 5);
  EXPECT_EQ(ed.lastWrite().changedBox.lo, tail.lo);
  EXPECT_EQ(ed.lastWrite().changedBox.hi, tail.hi);
  EXPECT_EQ(all.changedBox.lo, whole.lo);
  EXPECT_EQ(all.changedBox.hi, whole.hi);
  EXPECT_LT(ed.lastWrite().changedBox.voxelCount(), all.changedBox.voxelCount());
}
