// Stroke resampling, taper, pressure and drill against hand-computed geometry.
#include "EditTestUtil.h"
#include "lvdif/Brush.h"
#include "lvdif/Error.h"
#include "lvdif/Stroke.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lvdif;

namespace
{
BrushSample at(double x, double y, double z, double pressure = -1)
{
  BrushSample s;
  s.position = { x, y, z };
  s.pressure = pressure;
  s.buttons = 1;
  return s;
}
double dist(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
} // namespace

TEST(Stroke, StraightLineIsSampledAtTheFixedSpacingAndKeepsBothEnds)
{
  StrokeSettings s;
  s.spacing = 1.6;
  s.radius = 3;
  // three collinear samples, uneven gaps, and a repeated one
  const auto dabs = strokeDabs({ at(0, 0, 0), at(2.5, 0, 0), at(2.5, 0, 0), at(10, 0, 0) }, s);
  // positions 0, 1.6, ..., 9.6, then the last sample 10
  ASSERT_EQ(dabs.size(), 8u);
  for (size_t i = 0; i + 1 < dabs.size(); ++i)
    EXPECT_NEAR(dabs[i].center[0], 1.6 * i, 1e-9);
  EXPECT_DOUBLE_EQ(dabs.back().center[0], 10.0);
  for (const Dab& d : dabs)
  {
    EXPECT_EQ(d.radius, 3.0);
    EXPECT_EQ(d.center[1], 0.0);
  }
}

TEST(Stroke, SpacingFollowsArcLengthAroundCorners)
{
  StrokeSettings s;
  s.spacing = 1.0;
  const auto dabs = strokeDabs({ at(0, 0, 0), at(2.5, 0, 0), at(2.5, 2.5, 0) }, s);
  // arc length 5: dabs at arc 0,1,2,3,4,5 -> 6 dabs; arc 3 is (2.5, 0.5)
  ASSERT_EQ(dabs.size(), 6u);
  EXPECT_NEAR(dabs[3].center[0], 2.5, 1e-12);
  EXPECT_NEAR(dabs[3].center[1], 0.5, 1e-12);
  for (size_t i = 0; i + 1 < dabs.size(); ++i)
    EXPECT_LE(dist(dabs[i].center, dabs[i + 1].center), 1.0 + 1e-12);
}

TEST(Stroke, DynamicBrushTapersLinearlyWithArcLength)
{
  StrokeSettings s;
  s.kind = BrushKind::Dynamic;
  s.radius = 9;
  s.minRadius = 1;
  s.spacing = 2;
  const auto dabs = strokeDabs({ at(0, 0, 0), at(20, 0, 0) }, s);
  ASSERT_EQ(dabs.size(), 11u);
  for (const Dab& d : dabs)
    EXPECT_NEAR(d.radius, 9 + (1 - 9) * d.center[0] / 20.0, 1e-12);
  EXPECT_DOUBLE_EQ(dabs.front().radius, 9.0);
  EXPECT_DOUBLE_EQ(dabs.back().radius, 1.0);
}

TEST(Stroke, PressureDrivesTheRadiusAndIsInterpolated)
{
  StrokeSettings s;
  s.radius = 10;
  s.spacing = 1;
  s.minRadius = 0.5;
  const auto dabs = strokeDabs({ at(0, 0, 0, 0.2), at(4, 0, 0, 0.6) }, s);
  ASSERT_EQ(dabs.size(), 5u);
  for (const Dab& d : dabs)
    EXPECT_NEAR(d.radius, 10 * (0.2 + 0.4 * d.center[0] / 4), 1e-12);
  s.pressureDrivesRadius = false;
  for (const Dab& d : strokeDabs({ at(0, 0, 0, 0.2), at(4, 0, 0, 0.6) }, s))
    EXPECT_EQ(d.radius, 10.0);
  // pressure 0 clamps to the minimum radius
  s.pressureDrivesRadius = true;
  EXPECT_EQ(strokeDabs({ at(0, 0, 0, 0.0) }, s).front().radius, 0.5);
}

TEST(Stroke, SingleUsesOnlyTheFirstSample)
{
  StrokeSettings s;
  s.kind = BrushKind::Single;
  const auto dabs = strokeDabs({ at(5, 6, 7), at(20, 0, 0), at(30, 0, 0) }, s);
  ASSERT_EQ(dabs.size(), 1u);
  EXPECT_EQ(dabs[0].center, (std::array<double, 3>{ 5, 6, 7 }));
}

TEST(Stroke, DrillReleasesDabsInRealTimeAndMatchesTheBasicStroke)
{
  StrokeSettings drill;
  drill.kind = BrushKind::Drill;
  StrokeSettings basic;
  basic.kind = BrushKind::Basic;
  StrokeBuilder b(drill), c(basic);
  std::vector<Dab> got;
  const std::vector<BrushSample> path{ at(0, 0, 0), at(3, 1, 0), at(7, 4, 2), at(7.5, 4, 2), at(12, 0, 5) };
  size_t releasedBeforeEnd = 0;
  for (const auto& p : path)
  {
    b.add(p);
    c.add(p);
    auto r = b.takeReady();
    releasedBeforeEnd += r.size();
    got.insert(got.end(), r.begin(), r.end());
    EXPECT_TRUE(c.takeReady().empty()); // basic waits for the end
  }
  EXPECT_GT(releasedBeforeEnd, 5u);
  auto rest = b.finish();
  got.insert(got.end(), rest.begin(), rest.end());
  const auto all = c.finish();
  ASSERT_EQ(got.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i)
    EXPECT_EQ(got[i].center, all[i].center);
}

TEST(Stroke, AppliedStrokeApproximatesTheCapsule)
{
  // Spheres of radius r every h = 1.6 voxels: a point at distance D >= r from the
  // axis is at most sqrt(D^2 + (h/2)^2) - D <= sqrt(r^2 + 0.64) - r farther from the
  // nearest dab than from the axis; anywhere, at most h/2 = 0.8.
  DictionaryVolume v(edittest::options(48));
  StrokeSettings s;
  s.radius = 4;
  applyDabs(v, strokeDabs({ at(10, 20, 24), at(38, 26, 24) }, s), BrushSettings());
  const double q = v.sdfDictionary().maxErrorInRange() + 1e-4;
  const double outsideBound = std::sqrt(16 + 0.64) - 4;
  double worstOut = 0, worst = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const double capsule = std::min(8.0, capsuleDistance(x - 10.0, y - 20.0, z - 24.0, 28, 6, 0, 4));
    const double e = std::fabs(v.sdf(x, y, z) - capsule);
    worst = std::max(worst, e);
    if (capsule >= 0)
      worstOut = std::max(worstOut, e);
  });
  EXPECT_LE(worstOut, outsideBound + q);
  EXPECT_LE(worst, 0.8 + q);
}

TEST(Stroke, BadSettingsAreRefused)
{
  StrokeSettings s;
  s.spacing = 0;
  EXPECT_THROW(StrokeBuilder b(s), Error);
  s.spacing = 1;
  s.radius = NAN;
  EXPECT_THROW(StrokeBuilder b(s), Error);
  s.radius = 1;
  StrokeBuilder ok(s);
  EXPECT_THROW(ok.add(at(NAN, 0, 0)), Error);
}
