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
#include "../src/MeshToSdfInternal.h"
#include "../src/MeshToSdfTriangleLocal.h"
#include "MeshToSdfDamagedMeshes.h"

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
// added to the running error and subtracted again, it wiped out the other
// terms' errors (3,600 of these 10,800 intervals missed before such bounds
// were capped at 4 pi; the running error is now summed afresh too, see
// RunningErrorSurvivesAHugeTerm).
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
  std::int64_t checked = 0, misses = 0, decided = 0, points = 0;
  LocalBoundsCounts counts;
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
        nullptr, 1, &counts);
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
    static_cast<long long>(points), static_cast<long long>(counts.triangleTaylors));
  EXPECT_EQ(misses, 0) << "of " << checked;
  EXPECT_EQ(decided, points);
  EXPECT_GT(counts.triangleTaylors, 1000); // the expansions were taken
}

namespace
{
/// The 4^3 voxels of edge h about c (as the engine's blocks: offsets +-h/2, +-3h/2).
std::vector<V3> block4(V3 c, double h)
{
  std::vector<V3> pts;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) pts.push_back(c + h * V3{ x - 1.5, y - 1.5, z - 1.5 });
  return pts;
}
} // namespace

// localBounds on the damaged test meshes' corrections s (WindingSigner's
// dipole tree): 4^3 blocks of a 64^3 grid's voxels next to the corrected
// faces and deep inside, the engine's budget. Every interval holds against
// DipoleTree::exact, and triangles are expanded about the centre. The
// negative control: with the remainders scaled to 1e-4 some intervals miss
// (an interval is only as tight as its voxel's margin needs, so only voxels
// near a half-integer can show it: 26 of the 15,360, on patch10 and patch30).
TEST(MeshToSdfTriangleLocal, LocalBoundsHoldOnDamagedMeshes)
{
  const auto meshes = oracle::damagedMeshes();
  std::int64_t missesScaledAll = 0;
  for (const char* name : { "patch10", "patch30", "flip10", "duprev20" })
  {
    const TriangleMesh* m = nullptr;
    for (const auto& [n, mesh] : meshes)
      if (n == name) m = &mesh;
    ASSERT_NE(m, nullptr) << name;
    const PreparedMesh prepared = prepareMesh(*m);
    const WindingSigner w(prepared);
    const DipoleTree* s = w.cpuCorrection();
    ASSERT_NE(s, nullptr) << name;
    std::mt19937 rng(24);
    std::uniform_real_distribution<double> u(-1, 1);
    const double h = 2.6 / 64;
    LocalBoundsCounts counts;
    std::int64_t checked = 0, misses = 0, missesScaled = 0, decided = 0;
    for (int b = 0; b < 60; ++b)
    {
      V3 c{ 0.8 * u(rng), 0.8 * u(rng), 0.8 * u(rng) }; // deep inside
      if (b % 2 == 0)
      {
        // next to a corrected face: 0 to 4 voxels off its centroid
        const WeightedTri& t = s->tris()[static_cast<std::size_t>(rng() % s->tris().size())];
        c = (1.0 / 3.0) * (t.v[0] + t.v[1] + t.v[2]) + 4 * h * std::fabs(u(rng)) * randomUnit(rng);
      }
      const std::vector<V3> pts = block4(c, h);
      const double rho = std::sqrt(3.0) * 1.5 * h * (1 + 1e-9);
      std::vector<double> lo(64), hi(64), loS(64), hiS(64);
      decided += localBounds(*s, c, rho, pts.data(), 64, lo.data(), hi.data(), 64000, nullptr, 1, &counts);
      localBounds(*s, c, rho, pts.data(), 64, loS.data(), hiS.data(), 64000, nullptr, 1e-4);
      for (std::size_t i = 0; i < pts.size(); ++i)
      {
        const double ex = s->exact(pts[i]);
        misses += lo[i] > ex || hi[i] < ex;
        missesScaled += loS[i] > ex || hiS[i] < ex;
        ++checked;
      }
    }
    std::printf("[ local bounds, %s ] %lld points, %lld misses, %lld with the remainders scaled to 1e-4; %lld decided; "
                "%lld triangles expanded, %lld exact solid angles\n",
      name, static_cast<long long>(checked), static_cast<long long>(misses), static_cast<long long>(missesScaled),
      static_cast<long long>(decided), static_cast<long long>(counts.triangleTaylors),
      static_cast<long long>(counts.exactSolidAngles));
    EXPECT_EQ(misses, 0) << name;
    EXPECT_GT(counts.triangleTaylors, 0) << name;
    missesScaledAll += missesScaled;
  }
  EXPECT_GT(missesScaledAll, 0) << "the negative control: remainders scaled to 1e-4 must miss somewhere";
}

// The running error of localBounds is a sum of bounds added and subtracted:
// a term of 1e30 (a triangle whose cluster ball all but touches the block's)
// entering absorbs the other terms' errors, and leaving (its own Taylor
// polynomial taken instead) it left the sum at 0, the others' errors lost:
// intervals too narrow, and the next terms subtracted took it below 0. Every
// interval must still hold (and not be empty).
TEST(MeshToSdfTriangleLocal, RunningErrorSurvivesAHugeTerm)
{
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(-1, 1);
  // triangle 0 near the block, 40 small ones about (2.5, 0, 0)
  std::vector<WeightedTri> soup(41);
  soup[0].v[0] = V3{ 0, 0, 0 };
  soup[0].v[1] = V3{ 1, 0, 0 };
  soup[0].v[2] = V3{ 0.5, 0.8, 0 };
  soup[0].w = 1;
  for (std::size_t i = 1; i < soup.size(); ++i)
  {
    const V3 c{ 2.5 + 0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng) };
    for (auto& v : soup[i].v) v = c + 0.2 * V3{ u(rng), u(rng), u(rng) };
    soup[i].w = i % 3 ? 1.0 : -1.0;
  }
  const DipoleTree tree(soup);
  std::vector<std::int32_t> start; // every triangle on its own
  std::int32_t near = -1;
  for (std::size_t t = 0; t < tree.tris().size(); ++t)
  {
    start.push_back(-static_cast<std::int32_t>(t) - 1);
    if (tree.tris()[t].v[2].y == 0.8) near = static_cast<std::int32_t>(t);
  }
  ASSERT_GE(near, 0);
  const DipoleTree::Node cl = triangleCluster(tree.tris()[static_cast<std::size_t>(near)], near);
  std::int64_t checked = 0, misses = 0;
  for (int k = 0; k < 20; ++k)
  {
    // the centre over the face, its ball (rho) a few ulps clear of the cluster's
    const double rho0 = 0.01 + 0.002 * k;
    const V3 c = cl.c + (cl.r + rho0) * V3{ 0.05 * u(rng), 0.05 * u(rng), 1 };
    const double r0 = norm(c - cl.c);
    double rho = r0 - cl.r;
    while (!(r0 - rho - cl.r > 0)) rho = std::nextafter(rho, 0.0);
    int order = 0;
    const double huge = clusterLocalError(cl, r0, rho, order);
    ASSERT_TRUE(std::isfinite(huge));
    ASSERT_GT(huge, 1e25);
    std::vector<V3> pts(16);
    for (std::size_t p = 0; p < pts.size(); ++p) pts[p] = c + (p == 0 ? 0.0 : rho * std::fabs(u(rng))) * randomUnit(rng);
    std::vector<double> lo(pts.size()), hi(pts.size());
    localBounds(tree, c, rho, pts.data(), static_cast<int>(pts.size()), lo.data(), hi.data(), 1000000, &start);
    for (std::size_t p = 0; p < pts.size(); ++p)
    {
      long double wl = 0;
      for (const auto& t : soup) wl += t.w * solidAngleLong(pts[p], t.v[0], t.v[1], t.v[2]);
      const double wn = static_cast<double>(wl / (4 * 3.14159265358979323846264338327950288L));
      misses += !(lo[p] <= wn && wn <= hi[p]);
      ++checked;
    }
  }
  std::printf("[ running error ] %lld points checked, %lld misses\n", static_cast<long long>(checked),
    static_cast<long long>(misses));
  EXPECT_EQ(misses, 0) << "of " << checked;
}
