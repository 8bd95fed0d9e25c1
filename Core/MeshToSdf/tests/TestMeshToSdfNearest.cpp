// The CPU nearest-triangle index (MeshToSdfNearest.h) against a brute-force
// scan of every triangle (same closest-point routine, ties to the lowest
// index: the definition the index must reproduce bit for bit) and against the
// independent long-double oracle, on random soups, meshes full of exact ties,
// slivers and tiny triangles, and query points from on the surface to 1e6 away.
#include "../src/MeshToSdfNearestRow.h"
#include "MeshToSdfFarCases.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
NearestResult bruteForce(const TriList& tris, V3 p, double maxDist2)
{
  NearestResult best;
  best.dist2 = maxDist2;
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    const Closest c = closestPointOnTriangle(p, tris[t].v[0], tris[t].v[1], tris[t].v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 < best.dist2 || (d2 == best.dist2 && best.tri < 0))
    {
      best = { d2, static_cast<std::int32_t>(t), c };
    }
  }
  return best;
}

/// Every query against brute force, with no bound and with a bound, with no
/// hint and a random one, and as the first of a row of 1 to RowPoints points
/// (nearestRow); returns the number of queries checked.
int checkAll(const TriangleMesh& mesh, const std::vector<V3>& queries, std::mt19937& rng)
{
  const PreparedMesh pm = prepareMesh(mesh);
  const NearestIndex index(pm.tris);
  const std::int32_t nt = static_cast<std::int32_t>(pm.tris.size());
  std::uniform_int_distribution<std::int32_t> pick(-1, nt - 1);
  int checked = 0;
  for (const V3& p : queries)
  {
    const NearestResult ref = bruteForce(pm.tris, p, 1e300);
    for (int pass = 0; pass < 3; ++pass)
    {
      const std::int32_t hint = pass == 0 ? -1 : pick(rng);
      // pass 2: a bound between the nearest and the second-nearest scale
      const double bound = pass == 2 ? ref.dist2 * (pick(rng) % 2 ? 1.0 : 0.5) : 1e300;
      const NearestResult want = pass == 2 ? bruteForce(pm.tris, p, bound) : ref;
      const NearestResult got = index.nearest(p, hint, bound);
      EXPECT_EQ(got.tri, want.tri) << "query " << p.x << " " << p.y << " " << p.z << " hint " << hint;
      EXPECT_EQ(got.dist2, want.dist2); // bit for bit
      if (want.tri >= 0 && got.tri == want.tri)
      {
        EXPECT_EQ(got.closest.feature, want.closest.feature);
        EXPECT_EQ(got.closest.point.x, want.closest.point.x);
      }
      ++checked;
    }
    // up to RowPoints points of a row (equal y and z) in one traversal, each exact
    {
      const double steps[3] = { 1e-3, 0.05, 3.0 };
      const double h = steps[std::uniform_int_distribution<int>(0, 2)(rng)];
      const int n = std::uniform_int_distribution<int>(1, NearestIndex::RowPoints)(rng);
      V3 row[NearestIndex::RowPoints];
      NearestResult res[NearestIndex::RowPoints];
      for (int i = 0; i < n; ++i) row[i] = { p.x + i * h, p.y, p.z };
      const std::int32_t hint = pick(rng);
      std::int32_t lanes[NearestIndex::RowPoints];
      for (int i = 0; i < n; ++i) lanes[i] = pick(rng);
      const bool useLanes = pick(rng) % 2 != 0;
      // both traversals: SSE, and AVX2 where the CPU has it
      const bool avx2 = nearestRowUseAvx2;
      for (const bool withAvx2 : { false, true })
      {
        if (withAvx2 && !avx2) continue;
        nearestRowUseAvx2 = withAvx2;
        index.nearestRow(row, n, hint, useLanes ? lanes : nullptr, res);
        nearestRowUseAvx2 = avx2;
        for (int i = 0; i < n; ++i)
        {
          const NearestResult want = bruteForce(pm.tris, row[i], 1e300);
          EXPECT_EQ(res[i].tri, want.tri) << "row point " << i << " of " << n << " hint " << hint << " avx2 " << withAvx2;
          EXPECT_EQ(res[i].dist2, want.dist2);
          if (res[i].tri == want.tri)
          {
            // the whole closest point, bit for bit (the AVX2 traversal computes it four points at a time)
            EXPECT_EQ(res[i].closest.feature, want.closest.feature);
            EXPECT_EQ(res[i].closest.point.x, want.closest.point.x);
            EXPECT_EQ(res[i].closest.point.y, want.closest.point.y);
            EXPECT_EQ(res[i].closest.point.z, want.closest.point.z);
            EXPECT_EQ(res[i].closest.b1, want.closest.b1);
            EXPECT_EQ(res[i].closest.b2, want.closest.b2);
          }
          ++checked;
        }
      }
    }
    // and the independent oracle (another method, long double, over every triangle)
    const oracle::P q{ p.x, p.y, p.z };
    auto P = [](V3 v) { return oracle::P{ v.x, v.y, v.z }; };
    long double o = std::numeric_limits<long double>::infinity();
    for (const Tri& t : pm.tris) o = std::min(o, oracle::triangleDist2(q, P(t.v[0]), P(t.v[1]), P(t.v[2])));
    EXPECT_NEAR(static_cast<double>(o), ref.dist2, 1e-9 * (1 + ref.dist2));
  }
  return checked;
}

std::vector<V3> randomQueries(std::mt19937& rng, int n, double lo, double hi)
{
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<V3> q;
  for (int i = 0; i < n; ++i) q.push_back({ u(rng), u(rng), u(rng) });
  return q;
}
} // namespace

TEST(MeshToSdfNearest, RandomSoupsNearAndFar)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), small(-0.05f, 0.05f);
  for (int n : { 1, 2, 3, 5, 17, 64, 300 })
  {
    TriangleMesh m;
    for (int t = 0; t < n; ++t)
    {
      const Vec3f c{ u(rng), u(rng), u(rng) };
      for (int k = 0; k < 3; ++k) m.points.push_back({ c[0] + small(rng), c[1] + small(rng), c[2] + small(rng) });
      const std::uint32_t b = static_cast<std::uint32_t>(3 * t);
      m.triangles.push_back({ b, b + 1, b + 2 });
    }
    std::vector<V3> q = randomQueries(rng, 150, -0.5, 1.5);
    for (const V3& f : randomQueries(rng, 20, -1e3, 1e3)) q.push_back(f);
    for (const V3& f : randomQueries(rng, 10, -1e6, 1e6)) q.push_back(f);
    for (std::size_t i = 0; i < m.points.size(); i += 2) q.push_back({ m.points[i][0], m.points[i][1], m.points[i][2] });
    EXPECT_GT(checkAll(m, q, rng), 0) << n << " triangles";
  }
}

TEST(MeshToSdfNearest, ExactTiesGoToTheLowestIndex)
{
  // a lattice plane of unit squares (two triangles each), a box, and each
  // triangle of the plane again (same vertices, rotated): lattice queries are
  // equidistant from many triangles
  TriangleMesh m;
  const int s = 6;
  for (int y = 0; y <= s; ++y)
    for (int x = 0; x <= s; ++x) m.points.push_back({ float(x), float(y), 0.0f });
  auto id = [&](int x, int y) { return static_cast<std::uint32_t>(x + (s + 1) * y); };
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x)
    {
      m.triangles.push_back({ id(x, y), id(x + 1, y), id(x + 1, y + 1) });
      m.triangles.push_back({ id(x, y), id(x + 1, y + 1), id(x, y + 1) });
    }
  const std::size_t planeTris = m.triangles.size();
  for (std::size_t t = 0; t < planeTris; ++t)
  {
    const auto tr = m.triangles[t];
    m.triangles.push_back({ tr[1], tr[2], tr[0] });
  }
  m = oracle::merge(m, makeBoxMesh({ 1.0f, 1.0f, 2.0f }, { 3.0f, 3.0f, 4.0f }));
  std::vector<V3> q;
  for (int z = -2; z <= 6; ++z)
    for (int y = -1; y <= 2 * s + 1; y += 2)
      for (int x = -1; x <= 2 * s + 1; x += 3) q.push_back({ 0.5 * x, 0.5 * y, 0.5 * z });
  q.push_back({ 3.0, 3.0, 1e6 });
  q.push_back({ 3.0, 3.0, -1e6 });
  std::mt19937 rng(11);
  EXPECT_GT(checkAll(m, q, rng), 0);
}

TEST(MeshToSdfNearest, SliversTinyAndNeedleTriangles)
{
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  TriangleMesh m;
  auto add = [&](Vec3f a, Vec3f b, Vec3f c) {
    const std::uint32_t i = static_cast<std::uint32_t>(m.points.size());
    m.points.push_back(a);
    m.points.push_back(b);
    m.points.push_back(c);
    m.triangles.push_back({ i, i + 1, i + 2 });
  };
  for (int t = 0; t < 120; ++t)
  {
    const Vec3f a{ u(rng), u(rng), u(rng) }, b{ u(rng), u(rng), u(rng) };
    const Vec3f mid{ 0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2]) };
    switch (t % 4)
    {
      case 0: add(a, b, { mid[0] + 1e-6f, mid[1], mid[2] }); break;              // sliver
      case 1: add(a, { a[0] + 1e-6f, a[1], a[2] }, { a[0], a[1] + 1e-6f, a[2] }); break; // tiny
      case 2: add(a, b, { b[0], b[1] + 1e-5f, b[2] + 1e-5f }); break;            // needle
      default: add(a, b, { u(rng), u(rng), u(rng) }); break;                     // ordinary
    }
  }
  std::vector<V3> q = randomQueries(rng, 300, -0.2, 1.2);
  for (const V3& f : randomQueries(rng, 20, -1e4, 1e4)) q.push_back(f);
  for (std::size_t i = 0; i < m.points.size(); i += 3) q.push_back({ m.points[i][0], m.points[i][1], m.points[i][2] });
  EXPECT_GT(checkAll(m, q, rng), 0);
}

TEST(MeshToSdfNearest, ParallelBuildIsExactAndIndependentOfThreads)
{
  // more triangles than one parallel subtree (4096): the top levels are split
  // serially and the subtrees built on threads; the tree must not depend on
  // the thread count, and queries stay exact
  const TriangleMesh mesh = makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 90, 120);
  const PreparedMesh pm = prepareMesh(mesh);
  ASSERT_GT(pm.tris.size(), 4u * 4096u);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const NearestIndex one(pm.tris);
  omp_set_num_threads(std::max(4, threads));
  const NearestIndex many(pm.tris);
  omp_set_num_threads(threads);
  ASSERT_EQ(one.nodes().size(), many.nodes().size());
  EXPECT_EQ(std::memcmp(one.nodes().data(), many.nodes().data(), one.nodes().size() * sizeof(one.nodes()[0])), 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  for (int q = 0; q < 300; ++q)
  {
    const V3 p{ u(rng), u(rng), u(rng) };
    const NearestResult want = bruteForce(pm.tris, p, 1e300);
    const NearestResult got = many.nearest(p, -1, 1e300);
    EXPECT_EQ(got.tri, want.tri);
    EXPECT_EQ(got.dist2, want.dist2);
  }
}

TEST(MeshToSdfNearest, BricksOfACoarseGridOnADenseMesh)
{
  // nearestBrick on the bricks (8 x 4 x 4) of a 12^3 grid over a dense mesh,
  // band 8 voxels: a brick spans a third of the mesh and thousands of small
  // triangles lie within reach of it. Every voxel's answer is brute force's
  // (bounded at the band) bit for bit, and the work per voxel stays that of
  // one query: the list scan alone made 540 exact closest points per voxel
  // here (the candidates nearest to the brick first, not to the voxel; now
  // about 32), 5,400 on the 832k-triangle armadillo at 32^3.
  const PreparedMesh pm = prepareMesh(farcases::denseMesh());
  const NearestIndex index(pm.tris);
  const int N = 12;
  const double h = 2.4 / N, band2 = (8 * h) * (8 * h);
  NearestIndex::BrickScratch scratch;
  std::int32_t hint = -1;
  int checked = 0;
  for (int z0 = 0; z0 < N; z0 += 4)
    for (int y0 = 0; y0 < N; y0 += 4)
      for (int x0 = 0; x0 < N; x0 += 8)
      {
        std::vector<V3> ps;
        for (int z = z0; z < z0 + 4; ++z)
          for (int y = y0; y < y0 + 4; ++y)
            for (int x = x0; x < std::min(N, x0 + 8); ++x) ps.push_back({ -1.2 + h * x, -1.2 + h * y, -1.2 + h * z });
        std::vector<NearestResult> res(ps.size());
        index.nearestBrick(ps.data(), static_cast<int>(ps.size()), band2, hint, res.data(), scratch);
        for (std::size_t i = 0; i < ps.size(); ++i)
        {
          const NearestResult want = bruteForce(pm.tris, ps[i], band2);
          EXPECT_EQ(res[i].tri, want.tri) << ps[i].x << " " << ps[i].y << " " << ps[i].z;
          EXPECT_EQ(res[i].dist2, want.dist2);
          if (res[i].tri >= 0) hint = res[i].tri;
          checked += want.tri >= 0;
        }
      }
  EXPECT_GT(checked, N * N * N / 2); // most voxels lie within the band
  ASSERT_GT(scratch.points, 0u);
  const double perVoxel = static_cast<double>(scratch.exact) / static_cast<double>(scratch.points);
  std::printf("coarse bricks: %llu bricks, %llu point by point, %.1f exact closest points per voxel\n",
    static_cast<unsigned long long>(scratch.bricks), static_cast<unsigned long long>(scratch.pointByPoint), perVoxel);
  EXPECT_LE(perVoxel, 100.0);
}
