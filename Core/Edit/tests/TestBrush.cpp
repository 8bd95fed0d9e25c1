// Brushes and CSG against analytic SDFs computed here in long double
// (independent of the brush code's formulas).
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace lvdif;
using edittest::options;

namespace
{
long double oracleSphere(long double x, long double y, long double z, long double cx, long double cy,
  long double cz, long double r)
{
  return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r;
}

// Box distance by the closest point (clamp) and, inside, by the nearest face.
long double oracleCube(long double x, long double y, long double z, long double cx, long double cy,
  long double cz, long double h)
{
  const long double p[3] = { x - cx, y - cy, z - cz };
  bool inside = true;
  long double out2 = 0, nearestFace = 1e30L;
  for (int a = 0; a < 3; ++a)
  {
    const long double q = std::fabs(p[a]);
    if (q > h)
    {
      inside = false;
      out2 += (q - h) * (q - h);
    }
    nearestFace = std::min(nearestFace, h - q);
  }
  return inside ? -nearestFace : std::sqrt(out2);
}

long double clampBand(long double v, long double band)
{
  return std::max(-band, std::min(band, v));
}

long double oracleSmoothMin(long double a, long double b, long double k)
{
  // Quilez: h = clamp(0.5 + 0.5 (b - a) / k, 0, 1); mix(b, a, h) - k h (1 - h)
  const long double h = std::max(0.0L, std::min(1.0L, 0.5L + 0.5L * (b - a) / k));
  return b + (a - b) * h - k * h * (1 - h);
}

double tolerance(const DictionaryVolume& v, int quantizations)
{
  return quantizations * v.sdfDictionary().maxErrorInRange() + 1e-4;
}
} // namespace

TEST(Brush, SphereUnionOnEmptyVolumeMatchesAnalyticField)
{
  DictionaryVolume v(options(64));
  BrushSettings s;
  applyDab(v, Dab{ BrushShape::Sphere, { 30.3, 31.7, 29.1 }, 12.4, {} }, s);
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const long double expect = clampBand(std::min(8.0L, oracleSphere(x, y, z, 30.3L, 31.7L, 29.1L, 12.4L)), 8);
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - expect)));
  });
  EXPECT_LE(worst, tolerance(v, 1));
}

TEST(Brush, CubeUnionAndSphereSubtractionOnSphereVolumeMatchAnalyticCsg)
{
  DictionaryVolume v(options(72, 16));
  fillFromFunction(v, sphereSdf(36, 36, 36, 20));
  BrushSettings add;
  applyDab(v, Dab{ BrushShape::Cube, { 50.5, 40.2, 36 }, 9.5, {} }, add);
  BrushSettings sub;
  sub.op = BrushOp::Subtract;
  applyDab(v, Dab{ BrushShape::Sphere, { 22, 30, 40 }, 10.7, {} }, sub);
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    long double d = clampBand(oracleSphere(x, y, z, 36, 36, 36, 20), 8);
    d = clampBand(std::min(d, oracleCube(x, y, z, 50.5L, 40.2L, 36, 9.5L)), 8);
    d = clampBand(std::max(d, -oracleSphere(x, y, z, 22, 30, 40, 10.7L)), 8);
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - d)));
  });
  // three quantizations: the fill, the union, the subtraction
  EXPECT_LE(worst, tolerance(v, 3));
}

TEST(Brush, SmoothUnionMatchesQuilezPolynomialSmoothMin)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(26, 32, 32, 12));
  BrushSettings s;
  s.blend = 6;
  applyDab(v, Dab{ BrushShape::Sphere, { 44, 32, 32 }, 9, {} }, s);
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const long double a = clampBand(oracleSphere(x, y, z, 26, 32, 32, 12), 8);
    const long double d = clampBand(oracleSmoothMin(a, oracleSphere(x, y, z, 44, 32, 32, 9), 6), 8);
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - d)));
  });
  EXPECT_LE(worst, tolerance(v, 2));
  // the blend really fills the neck: a point between the spheres is inside
  EXPECT_LT(v.sdf(38, 32, 32), 0.0f);
}

TEST(Brush, SmoothSubtractionMatchesQuilezFormula)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(32, 32, 32, 16));
  BrushSettings s;
  s.op = BrushOp::Subtract;
  s.blend = 4;
  applyDab(v, Dab{ BrushShape::Cube, { 46, 32, 32 }, 6, {} }, s);
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const long double a = clampBand(oracleSphere(x, y, z, 32, 32, 32, 16), 8);
    // smooth max(a, -s) = -smin(-a, s)
    const long double d = clampBand(-oracleSmoothMin(-a, oracleCube(x, y, z, 46, 32, 32, 6), 4), 8);
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - d)));
  });
  EXPECT_LE(worst, tolerance(v, 2));
}

TEST(Brush, AddColoursOnlyWhereTheNewSurfaceLies)
{
  // the primitive's inside, and its skin where the primitive (not the old
  // surface) is the nearer surface: no halo on the old surface around the add
  DictionaryVolume v(options(48));
  fillFromFunction(v, sphereSdf(24, 24, 24, 14));
  auto before = v.clone();
  BrushSettings s;
  s.color = Rgba{ 250, 10, 20, 255 };
  applyDab(v, Dab{ BrushShape::Sphere, { 30, 24, 24 }, 6, {} }, s);
  ColorKey key = 0;
  ASSERT_TRUE(v.colors().find(s.color, key));
  std::int64_t painted = 0, haloOfTheOldRule = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const long double p = oracleSphere(x, y, z, 30, 24, 24, 6);
    const bool near = p <= 0 || (p <= 1.5L && p < before->sdf(x, y, z));
    haloOfTheOldRule += p <= 1.5L && !near;
    const ColorKey expect = near ? key : before->get(x, y, z).color;
    ASSERT_EQ(v.get(x, y, z).color, expect) << x << " " << y << " " << z;
    painted += near;
  });
  EXPECT_GT(painted, 800);
  EXPECT_GT(haloOfTheOldRule, 50); // the skin the old rule coloured on the old surface
}

TEST(Brush, PaintLeavesEverySdfKeyBitIdenticalAndColoursTheSkin)
{
  DictionaryVolume v(options(48));
  fillFromFunction(v, sphereSdf(24, 24, 24, 14));
  auto before = v.clone();
  BrushSettings s;
  s.op = BrushOp::Paint;
  s.color = Rgba{ 1, 2, 3, 255 };
  applyDab(v, Dab{ BrushShape::Cube, { 24, 24, 38 }, 7, {} }, s);
  ColorKey key = 0;
  ASSERT_TRUE(v.colors().find(s.color, key));
  std::int64_t painted = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    ASSERT_EQ(v.get(x, y, z).sdf, before->get(x, y, z).sdf);
    const bool expectPaint =
      oracleCube(x, y, z, 24, 24, 38, 7) <= 0 && std::fabs(before->sdf(x, y, z)) <= 1.5f;
    ASSERT_EQ(v.get(x, y, z).color, expectPaint ? key : before->get(x, y, z).color);
    painted += expectPaint;
  });
  EXPECT_GT(painted, 100);
}

TEST(Brush, DirtyChunksAreExactlyTheChangedChunksAndRangesStayExact)
{
  DictionaryVolume v(options(80, 8));
  fillFromFunction(v, sphereSdf(40, 40, 40, 22));
  v.takeDirtyChunks();
  for (BrushOp op : { BrushOp::Add, BrushOp::Subtract, BrushOp::Paint })
  {
    auto before = v.clone();
    BrushSettings s;
    s.op = op;
    s.color = Rgba{ 9, 9, static_cast<std::uint8_t>(int(op)), 255 };
    const EditResult r = applyDab(v, Dab{ BrushShape::Sphere, { 60.2, 41, 39.5 }, 7.3, {} }, s);
    const std::set<std::int64_t> expect = edittest::differingChunks(v, *before);
    const std::vector<std::int64_t> dirty = v.takeDirtyChunks();
    EXPECT_EQ(std::set<std::int64_t>(dirty.begin(), dirty.end()), expect) << toString(op);
    EXPECT_EQ(std::set<std::int64_t>(r.changedChunks.begin(), r.changedChunks.end()), expect);
    EXPECT_EQ(r.changedVoxels, edittest::countDifferences(v, *before));
    EXPECT_FALSE(expect.empty());
    // the dab's influence box holds every change
    const VoxelBox box = dabInfluenceBox(v, Dab{ BrushShape::Sphere, { 60.2, 41, 39.5 }, 7.3, {} }, s);
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      if (!box.contains(x, y, z))
        ASSERT_EQ(v.get(x, y, z), before->get(x, y, z));
    });
  }
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    const VoxelBox b = v.chunkBox(id);
    SdfKey lo = 65535, hi = 0;
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          lo = std::min(lo, v.get(x, y, z).sdf);
          hi = std::max(hi, v.get(x, y, z).sdf);
        }
    ASSERT_EQ(v.chunkRange(id), std::make_pair(lo, hi));
  }
}

TEST(Brush, RepeatedDabChangesNothingAndMarksNothing)
{
  DictionaryVolume v(options(48));
  BrushSettings s;
  applyDab(v, Dab{ BrushShape::Sphere, { 20, 20, 20 }, 8, {} }, s);
  v.takeDirtyChunks();
  const EditResult r = applyDab(v, Dab{ BrushShape::Sphere, { 20, 20, 20 }, 8, {} }, s);
  EXPECT_EQ(r.changedVoxels, 0);
  EXPECT_TRUE(v.takeDirtyChunks().empty());
}

TEST(Brush, DabListEqualsDabsAppliedOneByOne)
{
  DictionaryVolume a(options(64)), b(options(64));
  std::vector<Dab> dabs;
  for (int i = 0; i < 12; ++i)
    dabs.push_back(Dab{ i % 3 == 0 ? BrushShape::Cube : BrushShape::Sphere, { 10.0 + 3.7 * i, 30 + 0.4 * i, 32 }, 4.0 + 0.3 * i, {} });
  BrushSettings s;
  s.blend = 2.5;
  applyDabs(a, dabs, s);
  for (const Dab& d : dabs)
    applyDab(b, d, s);
  EXPECT_EQ(edittest::countDifferences(a, b), 0);
}

TEST(Brush, RowPathEqualsThePerVoxelPathBitForBit)
{
  // Without symmetry and weights the brush computes each dab's distances a row
  // at a time; with a mirror plane whose images all fall outside the volume it
  // takes the per-voxel path (applyGroupToVoxel) over the very same dabs. Both
  // must give the same bits, also on a sphere volume (keys and colours mixed).
  for (int opIndex = 0; opIndex < 3; ++opIndex)
    for (double blend : { 0.0, 2.0 })
    {
      DictionaryVolume rows(options(72)), perVoxel(options(72));
      fillFromFunction(rows, sphereSdf(35.5, 36, 36.25, 20));
      fillFromFunction(perVoxel, sphereSdf(35.5, 36, 36.25, 20));
      std::vector<Dab> dabs;
      for (int i = 0; i < 14; ++i)
      {
        const BrushShape shape = i % 4 == 1 ? BrushShape::Cube : (i % 4 == 3 ? BrushShape::Capsule : BrushShape::Sphere);
        Dab d{ shape, { 14.3 + 3.1 * i, 20.7 + 1.9 * i, 52.1 - 1.3 * i }, 3.5 + 0.9 * i, { 40.2, 30.5 + i, 36.0 } };
        dabs.push_back(d);
      }
      BrushSettings s;
      s.op = opIndex == 0 ? BrushOp::Add : (opIndex == 1 ? BrushOp::Subtract : BrushOp::Paint);
      s.blend = s.op == BrushOp::Paint ? 0.0 : blend;
      s.rounding = 1.5;
      s.color = Rgba{ 200, 40, 90, 255 };
      const EditResult a = applyDabs(rows, dabs, s);
      s.symmetry.mirror[0] = true;
      s.symmetry.plane[0] = -500; // every image at x < -900: none reaches the volume
      const EditResult b = applyDabs(perVoxel, dabs, s);
      EXPECT_EQ(edittest::countDifferences(rows, perVoxel), 0) << toString(s.op) << " blend " << blend;
      EXPECT_GT(a.changedVoxels, 0);
      EXPECT_EQ(a.changedVoxels, b.changedVoxels);
      EXPECT_EQ(a.changedChunks, b.changedChunks);
    }
}

TEST(Brush, CapsuleIsTheSweptSphere)
{
  DictionaryVolume v(options(64));
  BrushSettings s;
  applyDab(v, Dab{ BrushShape::Capsule, { 12, 20, 30 }, 5, { 50, 40, 30 } }, s);
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    // brute force: nearest of 401 points along the segment (error <= half the 0.11-voxel sample gap)
    long double best = 1e30L;
    for (int i = 0; i <= 400; ++i)
    {
      const long double t = i / 400.0L;
      best = std::min(best, oracleSphere(x, y, z, 12 + 38 * t, 20 + 20 * t, 30, 5));
    }
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - clampBand(std::min(8.0L, best), 8))));
  });
  EXPECT_LE(worst, tolerance(v, 1) + 0.06);
}

TEST(Brush, InvalidDabIsRefusedBeforeAnyWrite)
{
  DictionaryVolume v(options(32));
  auto before = v.clone();
  std::vector<Dab> dabs{ Dab{ BrushShape::Sphere, { 10, 10, 10 }, 4, {} },
    Dab{ BrushShape::Sphere, { NAN, 10, 10 }, 4, {} } };
  EXPECT_THROW(applyDabs(v, dabs, BrushSettings()), Error);
  EXPECT_EQ(edittest::countDifferences(v, *before), 0);
  BrushSettings bad;
  bad.blend = -1;
  EXPECT_THROW(applyDab(v, dabs[0], bad), Error);
}

TEST(Brush, DabsOutsideOrClippedByTheVolumeAreSafe)
{
  DictionaryVolume v(options(32));
  BrushSettings s;
  EXPECT_EQ(applyDab(v, Dab{ BrushShape::Sphere, { -100, 5, 5 }, 4, {} }, s).changedVoxels, 0);
  EXPECT_EQ(applyDab(v, Dab{ BrushShape::Sphere, { 1e8, 5, 5 }, 4, {} }, s).changedVoxels, 0);
  const EditResult r = applyDab(v, Dab{ BrushShape::Cube, { 0, 0, 0 }, 5, {} }, s);
  EXPECT_GT(r.changedVoxels, 0);
  EXPECT_LT(v.sdf(0, 0, 0), 0.0f);
}

TEST(Brush, SdfRoundTripMakesKeySpaceMinExact)
{
  // the brush relies on encode(decode(k)) == k
  const SdfDictionary& d = defaultSdfDictionary();
  for (int k = 0; k < 65536; ++k)
    ASSERT_EQ(d.encode(d.decode(static_cast<SdfKey>(k))), k);
}

TEST(Brush, LargePrimitivesCoveringWholeChunksMatchTheAnalyticCsg)
{
  // chunks of edge 8 lie wholly inside these primitives by more than the band,
  // which the brush writes chunk-wise: the result must still be the analytic field
  DictionaryVolume v(options(96, 8));
  fillFromFunction(v, sphereSdf(48, 48, 48, 30));
  auto start = v.clone();
  BrushSettings add;
  add.color = Rgba{ 5, 6, 7, 255 };
  applyDab(v, Dab{ BrushShape::Cube, { 60, 50, 47 }, 28, {} }, add);
  BrushSettings sub;
  sub.op = BrushOp::Subtract;
  applyDab(v, Dab{ BrushShape::Sphere, { 30, 40, 50 }, 26, {} }, sub);
  ColorKey key = 0;
  ASSERT_TRUE(v.colors().find(add.color, key));
  double worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    long double d = clampBand(oracleSphere(x, y, z, 48, 48, 48, 30), 8);
    const long double c = oracleCube(x, y, z, 60, 50, 47, 28);
    d = clampBand(std::min(d, c), 8);
    d = clampBand(std::max(d, -oracleSphere(x, y, z, 30, 40, 50, 26)), 8);
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - d)));
    const bool own = c <= 0 || (c <= 1.5L && c < start->sdf(x, y, z));
    ASSERT_EQ(v.get(x, y, z).color, own ? key : start->get(x, y, z).color);
  });
  EXPECT_LE(worst, tolerance(v, 3));
}
