// Brushes and CSG against analytic SDFs computed here in long double
// (independent of the brush code's formulas).
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Stroke.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

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

namespace
{
// A volume that is not cubic, with a sphere and a band of a second colour.
std::unique_ptr<DictionaryVolume> strokeTestVolume()
{
  VolumeOptions o = options(0);
  o.dims = { 150, 118, 97 };
  auto v = std::make_unique<DictionaryVolume>(o);
  fillFromFunction(*v, sphereSdf(74.3, 58.6, 47.9, 36.5));
  BrushSettings paint;
  paint.op = BrushOp::Paint;
  paint.color = Rgba{ 20, 200, 60, 255 };
  applyDab(*v, Dab{ BrushShape::Sphere, { 60, 40, 50 }, 30, {} }, paint);
  return v;
}

// Samples along an arc over the sphere's top, 2.8 voxels apart (50 Hz drag).
std::vector<BrushSample> strokeTestSamples(int n, double phase)
{
  std::vector<BrushSample> out;
  for (int i = 0; i < n; ++i)
  {
    const double a = phase + 0.045 * i;
    BrushSample s;
    s.position = { 74.3 + 62.0 * std::cos(a) * 0.7, 58.6 + 62.0 * std::sin(a) * 0.6, 47.9 + 36.5 * 0.4 };
    s.time = 0.02 * i;
    out.push_back(s);
  }
  return out;
}
} // namespace

TEST(Brush, StrokeSamplesEqualThePerVoxelRuleBitForBit)
{
  // An interactive stroke applies each sample's dabs (3-4 overlapping ones at
  // radius 40) in one call; the hard add keeps a lowered voxel's exact distance
  // and encodes it once per row. Replayed through the Editor (Drill: applied as
  // it goes; Basic: one call at the end), every voxel (distance key and colour)
  // must equal the per-voxel rule (a mirror plane whose images miss the volume
  // selects it) and dab-by-dab application (one call per dab).
  struct Case
  {
    BrushOp op;
    BrushKind kind;
    double radius;
    Rgba color;
  };
  const Case cases[] = {
    { BrushOp::Add, BrushKind::Drill, 15, Rgba{ 200, 40, 90, 255 } },
    { BrushOp::Subtract, BrushKind::Drill, 15, Rgba{ 0, 0, 0, 255 } },
    { BrushOp::Paint, BrushKind::Drill, 15, Rgba{ 90, 10, 160, 255 } },
    { BrushOp::Paint, BrushKind::Drill, 40, Rgba{ 250, 250, 0, 255 } },
    { BrushOp::Add, BrushKind::Drill, 40, Rgba{ 200, 40, 90, 255 } },
    { BrushOp::Add, BrushKind::Basic, 40, Rgba{ 10, 40, 250, 255 } },
    { BrushOp::Subtract, BrushKind::Drill, 40, Rgba{ 0, 0, 0, 255 } },
  };
  // every case on the result of the previous ones: colours and keys mixed
  auto rows = strokeTestVolume(), perVoxel = strokeTestVolume(), dabByDab = strokeTestVolume();
  int c = 0;
  for (const Case& k : cases)
  {
    const std::vector<BrushSample> samples = strokeTestSamples(24, 1.1 * c++);
    BrushSettings s;
    s.op = k.op;
    s.color = k.color;
    StrokeSettings st;
    st.kind = k.kind;
    st.radius = k.radius;
    st.spacing = 1.0; // 2-3 dabs per sample at 2.8 voxels a sample
    std::int64_t changedA = 0, changedB = 0;
    for (int pass = 0; pass < 2; ++pass)
    {
      DictionaryVolume& v = pass == 0 ? *rows : *perVoxel;
      Editor ed(v);
      ed.brush = s;
      ed.stroke = st;
      if (pass == 1)
      {
        ed.brush.symmetry.mirror[0] = true;
        ed.brush.symmetry.plane[0] = -500; // images at x < -800: outside the volume
      }
      ed.beginStroke();
      std::int64_t changed = 0;
      for (const BrushSample& smp : samples)
        changed += ed.addSample(smp).changedVoxels;
      changed += ed.endStroke().changedVoxels;
      (pass == 0 ? changedA : changedB) = changed;
    }
    for (const Dab& d : strokeDabs(samples, st))
      applyDab(*dabByDab, d, s);
    EXPECT_GT(changedA, 0) << toString(k.op) << " radius " << k.radius;
    EXPECT_EQ(changedA, changedB) << toString(k.op) << " radius " << k.radius;
    EXPECT_EQ(edittest::countDifferences(*rows, *perVoxel), 0) << toString(k.op) << " radius " << k.radius;
    EXPECT_EQ(edittest::countDifferences(*rows, *dabByDab), 0) << toString(k.op) << " radius " << k.radius;
  }
  // negative control: the comparison sees one voxel's colour
  Voxel v = rows->get(70, 60, 84);
  v.color = static_cast<std::uint16_t>(v.color + 1);
  rows->set(70, 60, 84, v);
  EXPECT_EQ(edittest::countDifferences(*rows, *perVoxel), 1);
}

TEST(Brush, PendingEncodeIsExact)
{
  // The hard add's pending distances rely on encode being monotone over the
  // band (with encode(decode(k)) == k: SdfRoundTripMakesKeySpaceMinExact).
  const SdfDictionary& d = defaultSdfDictionary();
  const float band = 8.0f;
  const SdfKey lo = d.encodeClamped(-band, band), hi = d.encodeClamped(band, band);
  for (int k = lo; k < hi; ++k)
  {
    const float a = d.decode(static_cast<SdfKey>(k)), b = d.decode(static_cast<SdfKey>(k + 1));
    ASSERT_LT(a, b);
    ASSERT_EQ(d.encode(a), k);
    ASSERT_EQ(d.encode(b), k + 1);
    // around the midpoint, where encode turns from k to k+1: non-decreasing, k or k+1
    float x = a + 0.5f * (b - a);
    for (int i = 0; i < 64 && x > a; ++i)
      x = std::nextafter(x, a);
    SdfKey prev = static_cast<SdfKey>(k);
    for (int i = 0; i < 129 && x <= b; ++i, x = std::nextafter(x, b))
    {
      const SdfKey e = d.encode(x);
      ASSERT_GE(e, prev) << x;
      ASSERT_LE(e, k + 1) << x;
      prev = e;
    }
  }
}

TEST(Brush, HardAddColoursOnlyWhereTheSequenceWould)
{
  // Two add dabs in one call on an empty volume, built so that at voxel P the
  // first gives s1 just above colorOffset (no colour; its key rounds down to a
  // value at or below colorOffset) and the second s2 < s1 but at least that
  // rounded value: the per-voxel rule leaves P's distance key and does not
  // colour it. Taking min(s1, s2) and then the colour rule (not what the rule
  // does) would colour P: this is the case where the hard add's pending
  // distance must read table[encode(s1)].
  DictionaryVolume rows(options(40)), perVoxel(options(40)), dabByDab(options(40));
  BrushSettings s;
  s.color = Rgba{ 200, 40, 90, 255 };
  s.colorOffset = 1.5003; // keys at 1.500 and 1.501 (stepA 0.001): s1 1.5004 rounds to 1.500
  const double r = 5, s1 = 1.5004, s2 = 1.50015;
  const std::vector<Dab> dabs{ Dab{ BrushShape::Sphere, { 20 - (r + s1), 20, 20 }, r, {} },
    Dab{ BrushShape::Sphere, { 20 + (r + s2), 20, 20 }, r, {} } };
  applyDabs(rows, dabs, s);
  for (const Dab& d : dabs)
    applyDab(dabByDab, d, s);
  BrushSettings m = s;
  m.symmetry.mirror[0] = true;
  m.symmetry.plane[0] = -500;
  applyDabs(perVoxel, dabs, m);
  const std::uint16_t brush = rows.colors().add(s.color);
  EXPECT_NEAR(rows.sdf(20, 20, 20), 1.5, 1e-6);
  EXPECT_NE(perVoxel.get(20, 20, 20).color, brush);
  EXPECT_NE(rows.get(20, 20, 20).color, brush);
  EXPECT_EQ(edittest::countDifferences(rows, perVoxel), 0);
  EXPECT_EQ(edittest::countDifferences(rows, dabByDab), 0);
}
