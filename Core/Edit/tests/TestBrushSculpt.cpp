// The sculpting brushes (strength, falloff, smooth, inflate, grab, flatten,
// crease, pinch, soft paint, symmetry) against oracles that do not use the brush's
// formulas: marching cubes' surface area and a discrete curvature for smooth,
// the centroid of the inside voxels for grab, the surface's zero crossings
// along rays (trilinear, bisection) against analytic surfaces for pinch,
// the mirror image voxel by voxel
// for symmetry, analytic fields in long double for the per-voxel rules.
#include "EditTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

using namespace lvdif;
using edittest::options;

namespace
{
long double dist3(long double x, long double y, long double z, long double cx, long double cy, long double cz)
{
  return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz));
}

// Surface area of the chunked marching cubes mesh (triangle areas in double).
double surfaceArea(const DictionaryVolume& v)
{
  ChunkedMarchingCubes mc(v);
  double area = 0;
  for (const ChunkMesh& m : mc.extractAll())
    for (const auto& t : m.triangles)
    {
      const Vec3f& a = m.points[t[0]];
      const Vec3f& b = m.points[t[1]];
      const Vec3f& c = m.points[t[2]];
      const double u[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
      const double w[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
      const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
      area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
  return area;
}

// Two quantization steps of the SDF dictionary at distance d (0.001 near the
// surface, coarser beyond; docs/DICTIONARY.md), for a value read, changed and written.
double tol(long double d)
{
  return std::fabs(double(d)) < 1 ? 3e-3 : 0.1;
}

// Trilinear interpolation of the stored distances (a point inside the volume).
double sampleAt(const DictionaryVolume& v, double x, double y, double z)
{
  const double p[3] = { x, y, z };
  std::int64_t i[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    i[a] = static_cast<std::int64_t>(std::floor(p[a]));
    f[a] = p[a] - double(i[a]);
  }
  double r = 0;
  for (int c = 0; c < 8; ++c)
  {
    const double w = ((c & 1) ? f[0] : 1 - f[0]) * ((c & 2) ? f[1] : 1 - f[1]) * ((c & 4) ? f[2] : 1 - f[2]);
    r += w * v.sdf(i[0] + (c & 1), i[1] + ((c >> 1) & 1), i[2] + ((c >> 2) & 1));
  }
  return r;
}

// Distance along the ray o + t u (unit u) to the surface, t in [lo, hi] with
// the inside at lo and the outside at hi (bisection on the trilinear field).
double zeroCrossing(const DictionaryVolume& v, const double o[3], const double u[3], double lo, double hi)
{
  auto f = [&](double t) { return sampleAt(v, o[0] + t * u[0], o[1] + t * u[1], o[2] + t * u[2]); };
  EXPECT_LT(f(lo), 0);
  EXPECT_GT(f(hi), 0);
  for (int i = 0; i < 60; ++i)
  {
    const double m = 0.5 * (lo + hi);
    (f(m) < 0 ? lo : hi) = m;
  }
  return 0.5 * (lo + hi);
}

std::int64_t insideCount(const DictionaryVolume& v)
{
  std::int64_t n = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) { n += v.sdf(x, y, z) < 0; });
  return n;
}

// Mean |discrete Laplacian| of the distance over voxels next to the surface.
double meanAbsLaplacian(const DictionaryVolume& v)
{
  double sum = 0;
  std::int64_t n = 0;
  const auto& d = v.dims();
  for (std::int64_t z = 1; z + 1 < d[2]; ++z)
    for (std::int64_t y = 1; y + 1 < d[1]; ++y)
      for (std::int64_t x = 1; x + 1 < d[0]; ++x)
      {
        const double c = v.sdf(x, y, z);
        if (std::fabs(c) > 1.0)
          continue;
        const double lap = v.sdf(x - 1, y, z) + v.sdf(x + 1, y, z) + v.sdf(x, y - 1, z) + v.sdf(x, y + 1, z) +
          v.sdf(x, y, z - 1) + v.sdf(x, y, z + 1) - 6 * c;
        sum += std::fabs(lap);
        ++n;
      }
  return sum / double(n);
}

std::array<double, 3> insideCentroid(const DictionaryVolume& v)
{
  double s[3] = { 0, 0, 0 };
  double n = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    // weight by the inside fraction of a voxel-sized cell (smooth in sub-voxel moves)
    const double w = std::min(1.0, std::max(0.0, 0.5 - double(v.sdf(x, y, z))));
    s[0] += w * x, s[1] += w * y, s[2] += w * z;
    n += w;
  });
  return { s[0] / n, s[1] / n, s[2] / n };
}

// A sphere with bumps: hard unions of small spheres on its surface.
std::unique_ptr<DictionaryVolume> bumpySphere(std::int64_t n, double r)
{
  auto v = std::make_unique<DictionaryVolume>(options(n));
  const double c = 0.5 * double(n - 1);
  fillFromFunction(*v, sphereSdf(c, c, c, r));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  BrushSettings add;
  for (int i = 0; i < 40; ++i)
  {
    double p[3] = { u(rng), u(rng), u(rng) };
    const double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (l < 1e-3)
      continue;
    Dab d;
    for (int a = 0; a < 3; ++a)
      d.center[a] = c + p[a] / l * r;
    d.radius = 2.5;
    applyDab(*v, d, add);
  }
  return v;
}
} // namespace

TEST(BrushSculpt, FalloffCurvesAreTheStatedPolynomials)
{
  for (double t = 0; t <= 1.0; t += 0.125)
  {
    EXPECT_EQ(falloffCurve(int(Falloff::Constant), t), 1.0);
    EXPECT_NEAR(falloffCurve(int(Falloff::Linear), t), 1 - t, 1e-15);
    EXPECT_NEAR(falloffCurve(int(Falloff::Smooth), t), 1 - 3 * t * t + 2 * t * t * t, 1e-15);
    EXPECT_NEAR(falloffCurve(int(Falloff::Sharp), t), (1 - t) * (1 - t), 1e-15);
  }
  for (int f = 0; f < 4; ++f)
    EXPECT_EQ(falloffCurve(f, 1.01), 0.0);
}

TEST(BrushSculpt, StrengthAndFalloffMoveAddPartWayToTheUnion)
{
  DictionaryVolume v(options(48));
  fillFromFunction(v, sphereSdf(24, 24, 24, 12));
  auto before = v.clone();
  BrushSettings s;
  s.strength = 0.5;
  s.falloff = Falloff::Linear;
  applyDab(v, Dab{ BrushShape::Sphere, { 34, 24, 24 }, 8, {} }, s);
  double worst = 0;
  std::int64_t moved = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const long double d = before->sdf(x, y, z);
    const long double r = dist3(x, y, z, 34, 24, 24);
    const long double p = r - 8;
    const long double t = std::min<long double>(r / 8, 1);
    const long double w = 0.5L * (1 - t);
    long double e = d;
    if (p < d && p <= 8 + 0)
      e = std::max<long double>(-8, std::min<long double>(8, d + w * (p - d)));
    worst = std::max(worst, double(std::fabs(v.sdf(x, y, z) - e)) / tol(e) * 3e-3);
    moved += v.get(x, y, z) != before->get(x, y, z);
  });
  EXPECT_LE(worst, 2e-3);
  EXPECT_GT(moved, 100);
}

TEST(BrushSculpt, SmoothLowersCurvatureAndAreaAndKeepsVolume)
{
  auto v = bumpySphere(64, 18);
  const double area0 = surfaceArea(*v), lap0 = meanAbsLaplacian(*v);
  const std::int64_t vol0 = insideCount(*v);
  BrushSettings s;
  s.op = BrushOp::Smooth;
  s.falloff = Falloff::Constant;
  std::vector<Dab> dabs(8, Dab{ BrushShape::Sphere, { 31.5, 31.5, 31.5 }, 30, {} });
  const EditResult r = applyDabs(*v, dabs, s);
  EXPECT_GT(r.changedVoxels, 1000);
  const double area1 = surfaceArea(*v), lap1 = meanAbsLaplacian(*v);
  const std::int64_t vol1 = insideCount(*v);
  // the oracle sphere (no bumps) has area 4 pi 18^2 = 4072
  EXPECT_LT(area1, area0 * 0.97) << area0 << " -> " << area1;
  EXPECT_LT(lap1, lap0 * 0.8) << lap0 << " -> " << lap1;
  // stated bound: 8 smoothing steps lose less than 4% of the inside voxels
  EXPECT_LT(std::fabs(double(vol1 - vol0)) / double(vol0), 0.04) << vol0 << " -> " << vol1;
  std::printf("smooth: area %.1f -> %.1f, mean |laplacian| %.4f -> %.4f, inside voxels %lld -> %lld\n", area0,
    area1, lap0, lap1, static_cast<long long>(vol0), static_cast<long long>(vol1));
}

TEST(BrushSculpt, SmoothOutsideTheBrushChangesNothing)
{
  auto v = bumpySphere(64, 18);
  auto before = v->clone();
  BrushSettings s;
  s.op = BrushOp::Smooth;
  s.falloff = Falloff::Smooth;
  applyDab(*v, Dab{ BrushShape::Sphere, { 31.5, 31.5, 49.5 }, 7, {} }, s);
  std::int64_t changed = 0;
  edittest::forEachVoxel(*v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    if (v->get(x, y, z) != before->get(x, y, z))
    {
      ++changed;
      ASSERT_LE(dist3(x, y, z, 31.5, 31.5, 49.5), 7.0L);
    }
  });
  EXPECT_GT(changed, 50);
}

TEST(BrushSculpt, GrabMovesTheRegionsCentroidByTheDrag)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(24, 32, 32, 6));
  const auto c0 = insideCentroid(v);
  Editor ed(v);
  ed.brush.op = BrushOp::Grab;
  ed.stroke.radius = 20;
  ed.beginStroke();
  for (int i = 0; i <= 4; ++i)
  {
    BrushSample s;
    s.position = { 24 + 1.5 * i, 32, 32 };
    ed.addSample(s);
  }
  ed.endStroke();
  const auto c1 = insideCentroid(v);
  EXPECT_NEAR(c1[0] - c0[0], 6.0, 0.25);
  EXPECT_NEAR(c1[1] - c0[1], 0.0, 0.05);
  EXPECT_NEAR(c1[2] - c0[2], 0.0, 0.05);
  // undone as one step
  ASSERT_TRUE(ed.undo());
  const auto c2 = insideCentroid(v);
  EXPECT_NEAR(c2[0], c0[0], 1e-9);
}

TEST(BrushSculpt, InflateMovesTheSurfaceOutwardDeflateInward)
{
  for (bool invert : { false, true })
  {
    DictionaryVolume v(options(48));
    fillFromFunction(v, sphereSdf(24, 24, 24, 10));
    BrushSettings s;
    s.op = BrushOp::Inflate;
    s.invert = invert;
    s.strength = 0.5;
    applyDab(v, Dab{ BrushShape::Sphere, { 24, 24, 24 }, 16, {} }, s);
    // constant falloff over the whole sphere: the surface moves by exactly 0.5
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      const long double r = dist3(x, y, z, 24, 24, 24);
      if (r > 15 || std::fabs(r - 10) > 6)
        return;
      const long double e = r - 10 + (invert ? 0.5L : -0.5L);
      ASSERT_NEAR(v.sdf(x, y, z), double(e), tol(e)) << x << " " << y << " " << z;
    });
  }
}

TEST(BrushSculpt, FlattenPullsTheSurfaceToTheTangentPlane)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(32, 32, 32, 20));
  BrushSettings s;
  s.op = BrushOp::Flatten;
  std::vector<Dab> dabs(1, Dab{ BrushShape::Sphere, { 32, 32, 52 }, 6, {} });
  applyDabs(v, dabs, s);
  // inside the brush the field is the plane z = 52 (tangent at the top of the sphere)
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    if (dist3(x, y, z, 32, 32, 52) > 6 || std::fabs(z - 52.0) > 5)
      return;
    ASSERT_NEAR(v.sdf(x, y, z), z - 52.0, 0.05 + tol(z - 52.0)) << x << " " << y << " " << z;
  });
}

TEST(BrushSculpt, CreaseDentsDeepestAtTheCentre)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(32, 32, 32, 20));
  BrushSettings s;
  s.op = BrushOp::Crease;
  s.falloff = Falloff::Linear;
  applyDab(v, Dab{ BrushShape::Sphere, { 32, 32, 52 }, 6, {} }, s);
  // along the z axis: +1.5 at the centre (w = 1), nothing at the rim
  EXPECT_NEAR(v.sdf(32, 32, 52), 1.5, 2e-3);
  EXPECT_NEAR(v.sdf(32, 32, 49), -3 + 1.5 * std::pow(0.5, 3), 0.1);
  EXPECT_NEAR(v.sdf(32, 32, 58), 6.0, 0.1);
}

TEST(BrushSculpt, PinchPullsTheSurfaceTowardTheCentreAndInvertSpreadsIt)
{
  // A sphere of radius 10 wholly inside one dab of radius 16 at its centre,
  // constant falloff: every surface point p moves to p / (1 + s) (pinch) or
  // p / (1 - s) (invert); with a stroke direction along x only y and z
  // shrink, so the sphere becomes the ellipsoid with semi-axes (10, 10/(1+s),
  // 10/(1+s)). Measured by the zero crossings along rays from the centre.
  const double o[3] = { 32, 32, 32 }, R = 10;
  struct Case
  {
    bool invert;
    double strength;
    std::array<double, 3> dir;
  };
  for (const Case& k : { Case{ false, 0.5, { 0, 0, 0 } }, Case{ true, 0.25, { 0, 0, 0 } },
         Case{ false, 0.5, { 2, 0, 0 } } })
  {
    DictionaryVolume v(options(64));
    fillFromFunction(v, sphereSdf(o[0], o[1], o[2], R));
    BrushSettings s;
    s.op = BrushOp::Pinch;
    s.strength = k.strength;
    s.invert = k.invert;
    Dab d{ BrushShape::Sphere, { o[0], o[1], o[2] }, 16, {} };
    d.vec = k.dir;
    const auto before = v.clone();
    applyDab(v, d, s);
    const double scale = k.invert ? 1 / (1 - k.strength) : 1 / (1 + k.strength); // of y, z (and x when radial)
    const double ax[3] = { k.dir[0] != 0 ? R : R * scale, R * scale, R * scale };
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    double worst = 0;
    for (int i = 0; i < 200; ++i)
    {
      double u[3] = { g(rng), g(rng), g(rng) };
      const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      for (double& c : u)
        c /= l;
      // the ellipsoid's radius along u: 1 / sqrt(sum (u_a / a_a)^2)
      const double e = 1 / std::sqrt((u[0] / ax[0]) * (u[0] / ax[0]) + (u[1] / ax[1]) * (u[1] / ax[1]) +
                         (u[2] / ax[2]) * (u[2] / ax[2]));
      const double got = zeroCrossing(v, o, u, 0, 15.5);
      worst = std::max(worst, std::fabs(got - e));
      EXPECT_NEAR(got, e, 0.1) << "invert " << k.invert << " dir " << k.dir[0];
    }
    // the inside volume against the ellipsoid's (each voxel weighted by its inside fraction)
    double inside = 0;
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      inside += std::min(1.0, std::max(0.0, 0.5 - double(v.sdf(x, y, z))));
    });
    const double ratio = inside / (4.0 / 3.0 * M_PI * ax[0] * ax[1] * ax[2]);
    std::printf("pinch (invert %d, direction %g): surface within %.3f voxel of the oracle, volume ratio %.4f\n",
      int(k.invert), k.dir[0], worst, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.03);
    // nothing beyond the dab changes
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      if (dist3(x, y, z, o[0], o[1], o[2]) > 16)
        ASSERT_EQ(v.get(x, y, z), before->get(x, y, z)) << x << " " << y << " " << z;
    });
  }
}

TEST(BrushSculpt, PinchStrokeRaisesARidgeTowardItsLine)
{
  // The half space z < 30 and a pinch stroke along the line y = 32, z = 33
  // (above the surface): the surface rises toward the line, most under it,
  // symmetric in y, and nothing farther than the radius from the dabs changes.
  // With invert it sinks. The field is the plane's exact distance z - 30.
  for (bool invert : { false, true })
  {
    DictionaryVolume v(options(64));
    fillFromFunction(v, [](double, double, double z) { return float(z - 30.0); });
    const auto before = v.clone();
    Editor ed(v);
    ed.brush.op = BrushOp::Pinch;
    ed.brush.falloff = Falloff::Smooth;
    ed.brush.invert = invert;
    ed.stroke.radius = 8;
    ed.stroke.spacing = 2;
    std::vector<BrushSample> samples(2);
    samples[0].position = { 16, 32, 33 };
    samples[1].position = { 48, 32, 33 };
    ed.strokeThrough(samples);
    const double up[3] = { 0, 0, 1 };
    double prev = 0;
    for (int dy = 0; dy <= 9; ++dy)
    {
      double at[3] = { 32, 32.0 + dy, 0 }, atm[3] = { 32, 32.0 - dy, 0 };
      const double h = zeroCrossing(v, at, up, 20, 40) - 30;
      const double hm = zeroCrossing(v, atm, up, 20, 40) - 30;
      EXPECT_NEAR(h, hm, 1e-3) << dy;
      if (dy == 0)
        EXPECT_GT(invert ? -h : h, 0.5);
      if (dy >= 8)
        EXPECT_NEAR(h, 0, 2e-3) << dy; // beyond the radius
      else if (dy <= 5)
        EXPECT_GT(invert ? -h : h, 0.01) << dy;
      if (dy > 0)
        EXPECT_LE(invert ? -h : h, (invert ? -prev : prev) + 2e-3) << dy; // highest under the line
      prev = h;
    }
    // along the stroke the ridge is straight (the pull has no component along it)
    const double mid[3] = { 32, 32, 0 }, mid2[3] = { 36, 32, 0 };
    EXPECT_NEAR(zeroCrossing(v, mid, up, 20, 40), zeroCrossing(v, mid2, up, 20, 40), 0.05);
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      const long double far = x < 16 ? dist3(x, y, z, 16, 32, 33) : x > 48 ? dist3(x, y, z, 48, 32, 33)
                                                                       : dist3(0, y, z, 0, 32, 33);
      if (far > 8)
        ASSERT_EQ(v.get(x, y, z), before->get(x, y, z)) << x << " " << y << " " << z;
    });
  }
}

TEST(BrushSculpt, SoftPaintKeepsEverySdfKeyAndBlendsByCoverage)
{
  DictionaryVolume v(options(48));
  fillFromFunction(v, sphereSdf(24, 24, 24, 14));
  auto before = v.clone();
  BrushSettings s;
  s.op = BrushOp::Paint;
  s.falloff = Falloff::Linear;
  s.color = Rgba{ 200, 40, 0, 255 };
  const double cx = 24, cy = 24, cz = 38, R = 7;
  applyDab(v, Dab{ BrushShape::Sphere, { cx, cy, cz }, R, {} }, s);
  const Rgba white = before->colors().color(before->get(24, 24, 38).color);
  std::int64_t partial = 0, full = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    ASSERT_EQ(v.get(x, y, z).sdf, before->get(x, y, z).sdf);
    const Rgba got = v.colors().color(v.get(x, y, z).color);
    const long double r = dist3(x, y, z, cx, cy, cz);
    const bool skin = std::fabs(before->sdf(x, y, z)) <= 1.5f;
    if (!(r <= R && skin))
    {
      ASSERT_EQ(v.get(x, y, z).color, before->get(x, y, z).color) << x << " " << y << " " << z;
      return;
    }
    // coverage in eighths of the linear falloff, mixed channel by channel
    const long double cov = 8 * (1 - r / R);
    if (std::fabs(cov - std::floor(cov) - 0.5L) < 1e-9)
      return;
    const int q = int(std::floor(cov + 0.5L));
    auto mix = [q](int a, int b) { return (a * (8 - q) + b * q + 4) / 8; };
    ASSERT_EQ(int(got.r), mix(white.r, 200)) << x << " " << y << " " << z;
    ASSERT_EQ(int(got.g), mix(white.g, 40));
    ASSERT_EQ(int(got.b), mix(white.b, 0));
    partial += q > 0 && q < 8;
    full += q == 8;
  });
  EXPECT_GT(partial, 100);
}

TEST(BrushSculpt, PaintColoursNoVoxelFartherThanTheRadiusFromTheSurface)
{
  for (Falloff f : { Falloff::Constant, Falloff::Smooth })
  {
    DictionaryVolume v(options(48));
    fillFromFunction(v, sphereSdf(24, 24, 24, 14));
    auto before = v.clone();
    BrushSettings s;
    s.op = BrushOp::Paint;
    s.falloff = f;
    s.color = Rgba{ 1, 2, 3, 255 };
    std::vector<Dab> dabs;
    for (int i = 0; i < 6; ++i)
      dabs.push_back(Dab{ BrushShape::Sphere, { 14.0 + 4 * i, 24, 38 }, 5, {} });
    applyDabs(v, dabs, s);
    std::int64_t coloured = 0;
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      ASSERT_EQ(v.get(x, y, z).sdf, before->get(x, y, z).sdf);
      if (v.get(x, y, z).color == before->get(x, y, z).color)
        return;
      ++coloured;
      // the surface lies within 1.5 voxels (the skin) and the voxel within a dab
      ASSERT_LE(std::fabs(dist3(x, y, z, 24, 24, 24) - 14), 1.5L + 1e-3L);
      long double nearest = 1e9L;
      for (const Dab& d : dabs)
        nearest = std::min(nearest, dist3(x, y, z, d.center[0], d.center[1], d.center[2]));
      ASSERT_LE(nearest, 5.0L);
    });
    EXPECT_GT(coloured, 100);
  }
}

TEST(BrushSculpt, SymmetryGivesItsOwnMirrorImage)
{
  const BrushOp ops[] = { BrushOp::Add, BrushOp::Subtract, BrushOp::Paint, BrushOp::Inflate, BrushOp::Crease,
    BrushOp::Smooth, BrushOp::Pinch };
  for (int axes = 1; axes < 8; axes += 3) // x; x and z... (1, 4, 7)
  {
    DictionaryVolume v(options(64));
    const double c = 31.5; // voxel i mirrors to 63 - i
    fillFromFunction(v, sphereSdf(c, c, c, 16));
    BrushSettings s;
    for (int a = 0; a < 3; ++a)
    {
      s.symmetry.mirror[a] = (axes >> a) & 1;
      s.symmetry.plane[a] = c;
    }
    int i = 0;
    for (BrushOp op : ops)
    {
      s.op = op;
      s.falloff = static_cast<Falloff>(i % 4);
      s.strength = i % 2 ? 0.75 : 1.0;
      s.color = Rgba{ 10, static_cast<std::uint8_t>(20 * i), 30, 255 };
      // arbitrary positions (not binary fractions): the images are still exact
      std::vector<Dab> dabs{ Dab{ BrushShape::Sphere, { 20.123, 40.517, 44.771 }, 6.1, {} },
        Dab{ BrushShape::Cube, { 29.613, 18.252, 46.07 }, 4.3, {} },
        Dab{ BrushShape::Capsule, { 14.33, 30.59, 20.01 }, 3.7, { 22.751, 36.2, 18.49 } } };
      applyDabs(v, dabs, s);
      ++i;
    }
    std::int64_t diff = 0;
    edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      const std::int64_t mx = (axes & 1) ? 63 - x : x, my = (axes & 2) ? 63 - y : y, mz = (axes & 4) ? 63 - z : z;
      diff += v.get(x, y, z) != v.get(mx, my, mz);
    });
    EXPECT_EQ(diff, 0) << "axes " << axes;
  }
}

TEST(BrushSculpt, BadSettingsAreRefused)
{
  DictionaryVolume v(options(32));
  auto before = v.clone();
  BrushSettings s;
  s.strength = 0;
  EXPECT_THROW(applyDab(v, Dab{}, s), Error);
  s.strength = 1.5;
  EXPECT_THROW(applyDab(v, Dab{}, s), Error);
  s.strength = 1;
  s.falloff = static_cast<Falloff>(9);
  EXPECT_THROW(applyDab(v, Dab{}, s), Error);
  s.falloff = Falloff::Linear;
  s.symmetry.mirror[1] = true;
  s.symmetry.plane[1] = NAN;
  EXPECT_THROW(applyDab(v, Dab{}, s), Error);
  EXPECT_EQ(edittest::countDifferences(v, *before), 0);
}

TEST(BrushSculpt, RecordingsReplayTheSculptingBrushesBitForBit)
{
  DictionaryVolume v(options(64));
  fillFromFunction(v, sphereSdf(31.5, 31.5, 31.5, 18));
  auto start = v.clone();
  Editor ed(v);
  ed.startRecording();
  auto stroke = [&ed](std::initializer_list<std::array<double, 3>> pts) {
    ed.beginStroke();
    for (const auto& p : pts)
    {
      BrushSample s;
      s.position = p;
      ed.addSample(s);
    }
    ed.endStroke();
  };
  ed.stroke.radius = 8;
  ed.brush.op = BrushOp::Grab;
  ed.brush.falloff = Falloff::Smooth;
  stroke({ { 31.5, 31.5, 49.5 }, { 33, 32, 51 }, { 35, 33, 52.5 } });
  ed.brush.op = BrushOp::Inflate;
  ed.brush.strength = 0.35;
  ed.brush.invert = true;
  ed.brush.symmetry.mirror = { true, false, true };
  ed.brush.symmetry.plane = { 31.5, 0, 31.5 };
  stroke({ { 20, 40, 40 }, { 24, 44, 42 } });
  ed.brush = BrushSettings();
  ed.brush.op = BrushOp::Pinch;
  ed.brush.falloff = Falloff::Smooth;
  ed.brush.strength = 0.6;
  stroke({ { 31.5, 49.5, 31.5 }, { 34, 49, 33 }, { 37, 48, 34 } });
  ed.brush = BrushSettings();
  ed.brush.op = BrushOp::Paint;
  ed.brush.falloff = Falloff::Linear;
  ed.brush.color = Rgba{ 9, 99, 199, 255 };
  stroke({ { 31.5, 13.5, 31.5 }, { 36, 14, 30 } });
  std::ostringstream text;
  writeRecording(text, ed.stopRecording());
  std::istringstream in(text.str());
  const Recording back = readRecording(in);
  Editor player(*start);
  player.play(back);
  EXPECT_EQ(edittest::countDifferences(v, *start), 0);
  EXPECT_NE(text.str().find("op=grab"), std::string::npos);
  EXPECT_NE(text.str().find("op=pinch"), std::string::npos);
  EXPECT_NE(text.str().find("mirrorz=31.5"), std::string::npos);
}
