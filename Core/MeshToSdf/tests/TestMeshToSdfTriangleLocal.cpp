// The Taylor expansion of one triangle's exact solid angle about a ball's
// centre (MeshToSdfTriangleLocal.h): at every point of the ball the
// quadratic lies within its remainder bound 4 A rho^3 / g^5 (plus the
// rounding slack) of the solid angle in long double, for triangles of every
// shape (thin ones included) and balls from nearly touching the face to far;
// with a tenth of the bound some point misses (the negative control: the test
// catches a remainder too small). And localBounds, which now takes such
// expansions for near triangles, keeps every interval around the long-double
// winding number on soups where it takes many of them.
#include "../src/MeshToSdfDipoleLocal.h"
#include "../src/MeshToSdfDipoleTree.h"
#include "../src/MeshToSdfTriangleLocal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
/// Van Oosterom & Strackee's solid angle of (a, b, c) seen from p, in long double.
long double solidAngleLong(V3 p, V3 a, V3 b, V3 c)
{
  using R = long double;
  const R x[3] = { R(a.x) - p.x, R(a.y) - p.y, R(a.z) - p.z };
  const R y[3] = { R(b.x) - p.x, R(b.y) - p.y, R(b.z) - p.z };
  const R z[3] = { R(c.x) - p.x, R(c.y) - p.y, R(c.z) - p.z };
  auto dotL = [](const R* u, const R* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const R yz[3] = { y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0] };
  const R lx = std::sqrt(dotL(x, x)), ly = std::sqrt(dotL(y, y)), lz = std::sqrt(dotL(z, z));
  const R num = dotL(x, yz);
  const R den = lx * ly * lz + dotL(x, y) * lz + dotL(x, z) * ly + dotL(y, z) * lx;
  return 2 * std::atan2(num, den);
}

V3 randomUnit(std::mt19937& rng)
{
  std::normal_distribution<double> n(0, 1);
  V3 d{ n(rng), n(rng), n(rng) };
  return (1 / std::max(norm(d), 1e-12)) * d;
}

/// A random triangle about the origin: every fourth thin (one side 1e-3 of the others).
WeightedTri randomTriangle(std::mt19937& rng, int k)
{
  std::uniform_real_distribution<double> u(-1, 1);
  WeightedTri t;
  for (auto& v : t.v) v = V3{ u(rng), u(rng), u(rng) };
  if (k % 4 == 3) t.v[2] = t.v[0] + 1e-3 * (t.v[2] - t.v[0]) + 0.5 * (t.v[1] - t.v[0]);
  t.w = k % 3 == 0 ? 2.0 : (k % 3 == 1 ? 1.0 : -1.0);
  return t;
}
} // namespace

// One triangle: the quadratic against the long-double solid angle at points
// of balls at gap / rho from 0.05 to 20 (the remainder's whole range), and
// the negative control with a tenth of the bound.
TEST(MeshToSdfTriangleLocal, TaylorOfATriangleHoldsOverItsBall)
{
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u01(0, 1);
  std::int64_t checked = 0, misses = 0, missesTenth = 0, tight = 0;
  for (int k = 0; k < 400; ++k)
  {
    const WeightedTri t = randomTriangle(rng, k);
    for (int b = 0; b < 6; ++b)
    {
      // a centre at distance dist from the face (near its plane, an edge's line, a vertex, or anywhere)
      const double dist = 0.02 + 3 * u01(rng) * u01(rng);
      const V3 onFace = (b % 3 == 0) ? t.v[b % 3] : (1.0 / 3.0) * (t.v[0] + t.v[1] + t.v[2]);
      V3 c = onFace + dist * randomUnit(rng);
      if (b == 5) c = t.v[0] + (1 + dist) * (t.v[0] - t.v[1]); // on the line of an edge, past its end
      double d = 0;
      triangleTaylorError(c, 0, t, d);
      const double gapOverRho = std::exp(std::log(0.05) + u01(rng) * std::log(20 / 0.05));
      const double rho = d / (1 + gapOverRho);
      double dist2 = 0;
      const double e = triangleTaylorError(c, rho, t, dist2);
      ASSERT_TRUE(std::isfinite(e));
      double mag = 0;
      const LocalPoly poly = triangleTaylor(c, rho, t.v[0], t.v[1], t.v[2], t.w, mag);
      for (int p = 0; p < 10; ++p)
      {
        const V3 x = (p == 0 ? 0.0 : rho * (p < 6 ? 1.0 : u01(rng))) * randomUnit(rng);
        const long double exact = t.w * solidAngleLong(c + x, t.v[0], t.v[1], t.v[2]);
        const double dev = static_cast<double>(std::fabs(static_cast<long double>(poly.at(x)) - exact));
        const double slack = 1e-9 * (1 + mag); // far below what localInterval allows (1e-12 x terms x mag, 1e-9 floor)
        misses += dev > e + slack;
        missesTenth += dev > 0.1 * e + slack;
        tight += dev > 0.01 * e;
        ++checked;
      }
    }
  }
  std::printf("[ triangle Taylor ] %lld points checked, %lld misses, %lld with a tenth of the bound, %lld beyond 1 %% of it\n",
    static_cast<long long>(checked), static_cast<long long>(misses), static_cast<long long>(missesTenth),
    static_cast<long long>(tight));
  EXPECT_EQ(misses, 0) << "of " << checked;
  EXPECT_GT(missesTenth, 0) << "the negative control: a tenth of the remainder bound must miss somewhere";
  EXPECT_GT(checked, 20000);
}

// localBounds on a soup of large triangles (larger than the balls, where the
// Taylor expansions are taken): every interval holds against the long-double
// winding number, and with an unlimited budget every point is decided. A
// third of the balls just clear a triangle, whose Taylor bound is then huge:
// taken, it would be added to the running error and subtracted again, wiping
// out the other terms' errors (without the cap on such bounds, 3,600 of these
// 10,800 intervals missed).
TEST(MeshToSdfTriangleLocal, LocalBoundsWithTriangleTaylorHold)
{
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<WeightedTri> soup(300);
  for (std::size_t i = 0; i < soup.size(); ++i)
  {
    WeightedTri& t = soup[i];
    const V3 c{ 1.5 * u(rng), 1.5 * u(rng), 0.3 * u(rng) };
    for (auto& v : t.v) v = c + 0.35 * V3{ u(rng), u(rng), 0.3 * u(rng) };
    t.w = i % 5 == 0 ? 2.0 : (i % 7 == 0 ? -1.0 : 1.0);
  }
  const DipoleTree tree(soup);
  auto windingLong = [&](V3 p) {
    long double s = 0;
    for (const auto& t : soup) s += t.w * solidAngleLong(p, t.v[0], t.v[1], t.v[2]);
    return static_cast<double>(s / (4 * 3.14159265358979323846264338327950288L));
  };
  std::int64_t checked = 0, misses = 0, decided = 0, points = 0, taylors = 0;
  for (int n = 0; n < 150; ++n)
  {
    const V3 c0{ 1.6 * u(rng), 1.6 * u(rng), (n % 2 ? 0.4 : 1.2) * u(rng) };
    const WeightedTri& near = soup[static_cast<std::size_t>(n) % soup.size()];
    const V3 normal = cross(near.v[1] - near.v[0], near.v[2] - near.v[0]);
    const V3 mid = (1.0 / 3.0) * (near.v[0] + near.v[1] + near.v[2]);
    for (const double rho : { 0.02, 0.06, 0.15 })
    {
      // every third ball just clears a triangle (its Taylor bound huge: the
      // running error must not lose the other terms' errors to it)
      const V3 c = n % 3 == 2 ? mid + (rho * (1 + 1e-7) / norm(normal)) * normal : c0;
      std::vector<V3> pts(24);
      for (std::size_t p = 0; p < pts.size(); ++p)
        pts[p] = c + (p == 0 ? 0.0 : rho * (p < 12 ? 1.0 : std::fabs(u(rng)))) * randomUnit(rng);
      std::vector<double> wl(pts.size());
      for (std::size_t p = 0; p < pts.size(); ++p) wl[p] = windingLong(pts[p]);
      std::vector<double> lo(pts.size()), hi(pts.size());
      const int k = localBounds(tree, c, rho, pts.data(), static_cast<int>(pts.size()), lo.data(), hi.data(), 1000000,
        nullptr, 1, &taylors);
      for (std::size_t p = 0; p < pts.size(); ++p)
      {
        misses += lo[p] > wl[p] || hi[p] < wl[p];
        ++checked;
      }
      decided += k;
      points += static_cast<std::int64_t>(pts.size());
    }
  }
  std::printf("[ local bounds, triangle Taylor ] %lld points checked, %lld misses, %lld of %lld decided, %lld triangles expanded\n",
    static_cast<long long>(checked), static_cast<long long>(misses), static_cast<long long>(decided),
    static_cast<long long>(points), static_cast<long long>(taylors));
  EXPECT_EQ(misses, 0) << "of " << checked;
  EXPECT_EQ(decided, points);
  EXPECT_GT(taylors, 1000); // the expansions were taken
}
