// Winding-number sign on meshes with reversed faces: the sign of
// meshToSdf's WindingNumber mode against the exact winding number by brute
// force (sum of solid angles in long double, MeshToSdfOracle.h) on every
// voxel farther than 1 voxel, for flipped fractions 10-90 %, flipped + holes,
// duplicated faces, intersecting closed meshes, a Moebius strip (non
// orientable) and three faces on one edge (non manifold). Also: the dipole
// tree's intervals hold against long double solid angles, and the
// orientation finds exactly the reversed faces of a closed sphere.
#include "../src/MeshToSdfDipoleDecide.h"
#include "../src/MeshToSdfDipoleLocal.h"
#include "../src/MeshToSdfDipoleTree.h"
#include "../src/MeshToSdfInternal.h"
#include "../src/MeshToSdfOrientation.h"
#include "../src/MeshToSdfParallelSort.h"
#include "MeshToSdfOracle.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
using oracle::merge;

/// Reverses a random fraction of the faces; returns how many.
std::size_t flip(TriangleMesh& m, double fraction, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t n = 0;
  for (auto& t : m.triangles)
    if (u(rng) < fraction)
    {
      std::swap(t[1], t[2]);
      ++n;
    }
  return n;
}

TriangleMesh moebius(int n, float width)
{
  // centre circle of radius 0.8 in z = 0; the strip turns by half a turn, so
  // the last column joins the first one upside down (non-orientable)
  TriangleMesh m;
  const int across = 3;
  for (int i = 0; i < n; ++i)
  {
    const double u = 2 * M_PI * i / n;
    for (int j = 0; j < across; ++j)
    {
      const double v = width * (2.0 * j / (across - 1) - 1);
      m.points.push_back({ static_cast<float>((0.8 + v * std::cos(u / 2)) * std::cos(u)),
        static_cast<float>((0.8 + v * std::cos(u / 2)) * std::sin(u)), static_cast<float>(v * std::sin(u / 2)) });
    }
  }
  auto id = [&](int i, int j) {
    if (i == n) return static_cast<std::uint32_t>(across - 1 - j); // glued upside down
    return static_cast<std::uint32_t>(i * across + j);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j + 1 < across; ++j)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return m;
}

/// 600 small random triangles of weight 2 in a slab (float points, as a
/// mesh has), and the same triangles as a mesh of two copies each for the
/// long-double oracle (which then sees the same points).
std::vector<detail::meshtosdf::WeightedTri> randomWeightedSoup(std::mt19937& rng, TriangleMesh& ref)
{
  using namespace detail::meshtosdf;
  std::uniform_real_distribution<float> uf(-1, 1), sf(-0.1f, 0.1f);
  std::vector<WeightedTri> tris(600);
  for (auto& t : tris)
  {
    const float cx = uf(rng), cy = uf(rng), cz = 0.3f * uf(rng);
    for (auto& v : t.v)
    {
      const Vec3f f{ cx + sf(rng), cy + sf(rng), cz + sf(rng) };
      v = V3{ f[0], f[1], f[2] };
    }
    t.w = 2;
    for (int copy = 0; copy < 2; ++copy)
    {
      const std::uint32_t b = static_cast<std::uint32_t>(ref.points.size());
      for (const auto& v : t.v) ref.points.push_back({ static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z) });
      ref.triangles.push_back({ b, b + 1, b + 2 });
    }
  }
  return tris;
}

/// The tests' random soup (randomWeightedSoup, seeded), its oracle mesh and
/// its dipole tree.
struct RandomSoup
{
  explicit RandomSoup(unsigned seed)
    : rng(seed)
    , tree(randomWeightedSoup(rng, ref))
  {
  }
  std::mt19937 rng;
  TriangleMesh ref; // the same triangles, weight 2 as two copies
  detail::meshtosdf::DipoleTree tree;
};

/// Every voxel farther than 1 voxel from the mesh must have the sign of the
/// exact winding number (|w| >= 0.5 inside).
MeshToSdfStats expectExactSigns(const std::string& name, const TriangleMesh& mesh, GridGeometry g = {})
{
  if (g.dims[0] == 0)
  {
    g.dims = { 18, 17, 16 };
    g.origin = { -1.3, -1.25, -1.2 };
    g.spacing = { 0.15, 0.15, 0.15 };
  }
  const double h = std::min(g.spacing[0], std::min(g.spacing[1], g.spacing[2])); // the voxel unit
  MeshToSdfOptions o;
  o.sign = SignMode::WindingNumber;
  o.device = Device::Cpu;
  std::vector<float> sdf(static_cast<std::size_t>(g.count()));
  const MeshToSdfStats st = meshToSdf(mesh, FloatGridView{ sdf.data(), g }, o);
  std::int64_t far = 0, wrong = 0, inside = 0;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
      {
        const oracle::P p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
        if (oracle::distance(mesh, p) <= h) continue;
        const double w = oracle::winding(mesh, p);
        if (std::fabs(std::fabs(w) - 0.5) < 1e-6) continue; // the oracle cannot decide
        ++far;
        const bool in = std::fabs(w) >= 0.5;
        inside += in;
        wrong += (sdf[static_cast<std::size_t>(g.index(i, j, k))] < 0) != in;
      }
  EXPECT_EQ(wrong, 0) << name << ": " << wrong << " of " << far << " far voxels wrong (evaluations "
                      << st.windingEvaluations << ", full sums " << st.windingFullSums << ")";
  EXPECT_GT(far, g.count() / 2) << name;
  std::printf("[ %s ] far voxels %lld, inside %lld, evaluations %lld, full sums %lld\n", name.c_str(),
    static_cast<long long>(far), static_cast<long long>(inside), static_cast<long long>(st.windingEvaluations),
    static_cast<long long>(st.windingFullSums));
  return st;
}
} // namespace

TEST(MeshToSdfWindingFlip, DipoleTreeIntervalsHoldAgainstLongDoubleSolidAngles)
{
  using namespace detail::meshtosdf;
  RandomSoup soup(3);
  std::mt19937& rng = soup.rng;
  const TriangleMesh& ref = soup.ref;
  const DipoleTree& tree = soup.tree;
  std::uniform_real_distribution<double> u(-1, 1);
  int done = 0, checked = 0, failed = 0;
  std::int64_t leafTris = 0;
  for (int n = 0; n < 300; ++n)
  {
    const V3 q{ 2 * u(rng), 2 * u(rng), 2 * u(rng) };
    for (double rho : { 0.0, 0.05, 0.3 })
      for (double width : { 0.2, 0.02, 0.0 })
      {
        // goal: an interval narrower than width (0: only the exact sum)
        double lo = 0, hi = 0;
        const auto r = tree.refine(q, rho, [&](double a, double b) { return b - a < width ? 1 : 0; }, lo, hi, leafTris);
        if (r == DipoleTree::Refined::Failed)
        {
          EXPECT_GT(rho, 0); // only a ball may fail (a leaf too close)
          ++failed;
          continue;
        }
        ++done;
        if (r == DipoleTree::Refined::Done) EXPECT_LT(hi - lo, width);
        for (int k = 0; k < 4; ++k)
        {
          // points within rho of q: the centre and three random ones
          V3 d{ u(rng), u(rng), u(rng) };
          d = (k == 0 ? 0.0 : rho * std::fabs(u(rng)) / std::max(norm(d), 1e-12)) * d;
          const V3 p = q + d;
          const double w = oracle::winding(ref, { p.x, p.y, p.z });
          EXPECT_LE(lo, w) << "rho " << rho << " width " << width;
          EXPECT_GE(hi, w) << "rho " << rho << " width " << width;
          ++checked;
        }
        if (rho == 0 && width == 0) EXPECT_NEAR(tree.exact(q), oracle::winding(ref, { q.x, q.y, q.z }), 1e-9);
        if (rho == 0 && width > 0)
        {
          // warm start: a neighbour's final cut as the starting clusters
          std::vector<std::int32_t> cut;
          tree.refine(q, 0, [&](double a, double b) { return b - a < width ? 1 : 0; }, lo, hi, leafTris, &cut);
          EXPECT_FALSE(cut.empty());
          const V3 p = q + V3{ 0.03, -0.02, 0.01 };
          const auto r2 =
            tree.refine(p, 0, [&](double a, double b) { return b - a < width / 2 ? 1 : 0; }, lo, hi, leafTris, &cut);
          const double w = oracle::winding(ref, { p.x, p.y, p.z });
          EXPECT_NE(r2, DipoleTree::Refined::Failed);
          EXPECT_LE(lo, w);
          EXPECT_GE(hi, w);
          ++checked;
        }
      }
  }
  EXPECT_GT(done, 900);
  EXPECT_GT(failed, 10);
  EXPECT_GT(checked, 3600);
  EXPECT_GT(leafTris, 0);
}

// A ball close to a face (its leaf's cluster bound has none: the ball
// meets the leaf's bounding sphere) is bounded triangle by triangle: the
// exact value at the centre plus rho times the Lipschitz bound, an interval
// that holds at every point of the ball and narrows with rho; a ball that
// meets the triangle still fails.
TEST(MeshToSdfWindingFlip, BallsNextToALeafAreBoundedTriangleByTriangle)
{
  using namespace detail::meshtosdf;
  std::vector<WeightedTri> tris(1);
  tris[0].v[0] = { 0, 0, 0 };
  tris[0].v[1] = { 1, 0, 0 };
  tris[0].v[2] = { 0, 1, 0 };
  TriangleMesh ref;
  ref.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  ref.triangles = { { 0, 1, 2 } };
  const DipoleTree tree(tris);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::int64_t leafTris = 0;
  double lastWidth = 1;
  for (const double rho : { 0.02, 0.01, 0.005 })
  {
    const V3 q{ 0.3, 0.3, 0.05 };
    double lo = 0, hi = 0;
    const auto r = tree.refine(q, rho, [](double a, double b) { return b - a < 0.2 ? 1 : 0; }, lo, hi, leafTris);
    ASSERT_EQ(r, DipoleTree::Refined::Done) << rho;
    EXPECT_LT(hi - lo, lastWidth);
    lastWidth = hi - lo;
    for (int k = 0; k < 200; ++k)
    {
      V3 d{ u(rng), u(rng), u(rng) };
      d = (k == 0 ? 0.0 : rho * std::fabs(u(rng)) / std::max(norm(d), 1e-12)) * d;
      const V3 p = q + d;
      const double w = oracle::winding(ref, { p.x, p.y, p.z });
      EXPECT_LE(lo, w) << rho;
      EXPECT_GE(hi, w) << rho;
    }
  }
  double lo = 0, hi = 0;
  EXPECT_EQ(tree.refine({ 0.3, 0.3, 0.01 }, 0.02, [](double, double) { return 0; }, lo, hi, leafTris),
    DipoleTree::Refined::Failed); // the ball meets the face
}

// The local expansion of one cluster (MeshToSdfDipoleLocal.h): at every
// point of a ball its quadratic lies within the cluster's error bound of the
// long-double sum of the cluster's solid angles (the expansion's truncation
// plus the Taylor remainder over the ball), and within the Taylor remainder
// of the expansion itself, for clusters near and far; with a tenth of the
// remainder some point misses: the check catches a remainder too small.
TEST(MeshToSdfWindingFlip, LocalExpansionOfAClusterHoldsOverItsBall)
{
  using namespace detail::meshtosdf;
  RandomSoup soup(11);
  std::mt19937& rng = soup.rng;
  const TriangleMesh& ref = soup.ref;
  const DipoleTree& tree = soup.tree;
  std::uniform_real_distribution<double> u(-1, 1);
  std::int64_t checked = 0, bounded[3] = {}, misses = 0, missesWithoutRemainder = 0;
  for (std::size_t id = 0; id < tree.nodes().size(); id += 7)
  {
    const DipoleTree::Node& nd = tree.nodes()[id];
    TriangleMesh part; // the cluster's triangles, two copies each (weight 2)
    for (std::int32_t t = nd.first; t < nd.first + nd.count; ++t)
      for (int copy = 0; copy < 2; ++copy)
      {
        const std::uint32_t b = static_cast<std::uint32_t>(part.points.size());
        for (const auto& v : tree.tris()[static_cast<std::size_t>(t)].v)
          part.points.push_back({ static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z) });
        part.triangles.push_back({ b, b + 1, b + 2 });
      }
    for (int k = 0; k < 6; ++k)
    {
      // a ball at 1.2 to 6 cluster radii (plus rho) from the centre
      V3 dir{ u(rng), u(rng), u(rng) };
      dir = (1 / std::max(norm(dir), 1e-12)) * dir;
      const double rho = nd.r * (k < 3 ? 0.3 : 1.5) * std::fabs(u(rng));
      const double r0 = rho + nd.r * (1.2 + 4.8 * std::fabs(u(rng)));
      const V3 b = nd.c - r0 * dir;
      int order = 0;
      ASSERT_TRUE(std::isfinite(clusterLocalError(nd, r0, rho, order))); // the ball clears the cluster
      for (int o = 1; o <= 2; ++o)
      {
        ++bounded[o];
        const LocalPoly poly = clusterLocal(nd, nd.c - b, o);
        const double trunc = o == 1 ? 2 * nd.mass * nd.r / std::pow(r0 - rho - nd.r, 3)
                                    : 3 * nd.mass * nd.r * nd.r / std::pow(r0 - rho - nd.r, 4);
        const double rem = clusterLocalRemainder(nd, r0 - rho, rho, o);
        for (int p = 0; p < 8; ++p)
        {
          V3 x{ u(rng), u(rng), u(rng) };
          x = (p == 0 ? 0.0 : rho * (p < 4 ? 1.0 : std::fabs(u(rng))) / std::max(norm(x), 1e-12)) * x;
          const V3 q = b + x;
          const double exact = oracle::winding(part, { q.x, q.y, q.z }) * FourPi;
          const double slack = 1e-9 * (1 + std::fabs(exact));
          misses += std::fabs(poly.at(x) - exact) > trunc + rem + slack;
          // the Taylor part alone: the quadratic against the expansion itself at q
          const V3 y = nd.c - q;
          double mag = 0;
          const double expansion = clusterValue(nd, y, norm(y), o, mag);
          const double taylor = std::fabs(poly.at(x) - expansion);
          misses += taylor > rem + slack;
          missesWithoutRemainder += taylor > 0.1 * rem + slack;
          ++checked;
        }
      }
    }
  }
  std::printf("[ local expansion ] %lld points checked, %lld misses, %lld with a tenth of the remainder\n",
    static_cast<long long>(checked), static_cast<long long>(misses), static_cast<long long>(missesWithoutRemainder));
  EXPECT_EQ(misses, 0) << "of " << checked;
  EXPECT_GT(missesWithoutRemainder, 0) << "the negative control: a tenth of the Taylor remainder must miss somewhere";
  EXPECT_GT(checked, 2000);
  EXPECT_GT(bounded[1] + bounded[2], 200);
}

// localBounds: far clusters as one local polynomial per ball, near leaves
// summed at each point; every interval (decided or not, whatever the budget)
// holds against the long-double sum at points of balls near and far, the
// decided ones avoid the half-integers, and a cut to start from gives the
// same guarantee.
TEST(MeshToSdfWindingFlip, LocalBoundsHoldAgainstLongDoubleSolidAngles)
{
  using namespace detail::meshtosdf;
  RandomSoup soup(12);
  std::mt19937& rng = soup.rng;
  const TriangleMesh& ref = soup.ref;
  const DipoleTree& tree = soup.tree;
  std::uniform_real_distribution<double> u(-1, 1);
  std::int64_t checked = 0, decided = 0, points = 0;
  std::int64_t leafTris = 0;
  for (int n = 0; n < 120; ++n)
  {
    const V3 c{ 1.5 * u(rng), 1.5 * u(rng), (n % 2 ? 0.3 : 1.5) * u(rng) }; // half of them in the slab
    for (const double rho : { 0.02, 0.1, 0.3 })
      for (const std::int64_t budget : { std::int64_t{ 50 }, std::int64_t{ 1000000 } })
      {
        std::vector<V3> pts(12);
        for (std::size_t p = 0; p < pts.size(); ++p)
        {
          V3 x{ u(rng), u(rng), u(rng) };
          x = (p == 0 ? 0.0 : rho * std::fabs(u(rng)) / std::max(norm(x), 1e-12)) * x;
          pts[p] = c + x;
        }
        std::vector<double> lo(pts.size()), hi(pts.size());
        std::vector<std::int32_t> start;
        if (n % 3 == 0)
        {
          double a = 0, b = 0; // a cut from a failed ball bound, as the engine passes
          tree.refine(c, rho, [](double, double) { return 0; }, a, b, leafTris, &start);
        }
        const int k = localBounds(tree, c, rho, pts.data(), static_cast<int>(pts.size()), lo.data(), hi.data(), budget,
          start.empty() ? nullptr : &start);
        decided += k;
        points += static_cast<std::int64_t>(pts.size());
        for (std::size_t p = 0; p < pts.size(); ++p)
        {
          const double w = oracle::winding(ref, { pts[p].x, pts[p].y, pts[p].z });
          EXPECT_LE(lo[p], w) << "rho " << rho << " budget " << budget;
          EXPECT_GE(hi[p], w) << "rho " << rho << " budget " << budget;
          ++checked;
        }
        // an unlimited budget sums what it must: every point decided (none lies within rounding of a half-integer)
        if (budget > 50) EXPECT_EQ(k, static_cast<int>(pts.size())) << "rho " << rho;
      }
  }
  std::printf("[ local bounds ] %lld points checked, %lld of %lld decided\n", static_cast<long long>(checked),
    static_cast<long long>(decided), static_cast<long long>(points));
  EXPECT_GT(checked, 8000);
  EXPECT_GT(decided, points / 2);
}

TEST(MeshToSdfWindingFlip, OrientationFindsExactlyTheReversedFaces)
{
  // a closed manifold sphere: F must be exactly the reversed minority
  for (double f : { 0.1, 0.3, 0.7 })
  {
    TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 10, 20);
    const std::size_t n = flip(m, f, 9);
    const auto prepared = detail::meshtosdf::prepareMesh(m);
    const detail::meshtosdf::WindingSigner w(prepared);
    const std::size_t minority = std::min(n, prepared.tris.size() - n);
    EXPECT_EQ(w.flippedTriangles(), minority) << f;
    // the CUDA kernel takes the CPU's closure; the older cone construction
    // (kept for a boundary that cannot be split into walks) closes M itself
    // by a cone over dM (every edge of a reversed face is uncancelled there)
    EXPECT_TRUE(w.gpuTakesCpuClosure());
    EXPECT_GT(prepared.boundary.size(), 0u);
    EXPECT_EQ(w.cone().size(), prepared.boundary.size());
    EXPECT_EQ(w.meshTriangles(), prepared.tris.size());
    EXPECT_EQ(w.closedTris().size(), prepared.tris.size() + prepared.boundary.size());
  }
}

TEST(MeshToSdfWindingFlip, CancellingDuplicatesLeaveNoHoleAndOneFaceHolesAreExact)
{
  // a face and its reversed copy cancel as chains: the orientation pass
  // keeps one of them (no one-face hole in M+), so M+ is closed
  TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 10, 20);
  const std::size_t n = m.triangles.size();
  for (std::size_t t = 0; t < n; t += 9)
  {
    auto r = m.triangles[t];
    std::swap(r[1], r[2]);
    m.triangles.push_back(r);
  }
  const auto prepared = detail::meshtosdf::prepareMesh(m);
  const detail::meshtosdf::OrientedMesh om = detail::meshtosdf::orientMesh(prepared.tris, prepared.welded);
  EXPECT_TRUE(om.boundary.empty());
  EXPECT_EQ(om.removedCount, m.triangles.size() - n); // one face of each pair
  expectExactSigns("sphere + reversed copies of every 9th face", m);
  // many small holes: each closed by its own cap (a triangle), exact
  TriangleMesh h = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 10, 20);
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (std::size_t t = 0; t < h.triangles.size(); ++t)
    if (t % 13 != 5) kept.push_back(h.triangles[t]);
  h.triangles = kept;
  expectExactSigns("sphere with 15 one-face holes", h);
}

TEST(MeshToSdfWindingFlip, FlippedFractionsAreExact)
{
  for (double f : { 0.1, 0.3, 0.5, 0.9 })
  {
    TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 10, 20);
    flip(m, f, 17);
    expectExactSigns("sphere, " + std::to_string(int(f * 100)) + "% flipped", m);
  }
  TriangleMesh box = makeBoxMesh({ -0.9f, -0.7f, -0.8f }, { 0.8f, 0.9f, 0.6f });
  std::swap(box.triangles[3][1], box.triangles[3][2]);
  std::swap(box.triangles[8][1], box.triangles[8][2]);
  expectExactSigns("box, 2 of 12 flipped", box);
}

/// Reverses the faces whose centroid lies within `radius` of one of the
/// centres (round patches, as a broken export flips whole parts); returns how many.
std::size_t flipPatches(TriangleMesh& m, const std::vector<std::array<float, 3>>& centres, float radius)
{
  std::size_t n = 0;
  for (auto& t : m.triangles)
  {
    std::array<float, 3> c{};
    for (const std::uint32_t v : t)
      for (int k = 0; k < 3; ++k) c[k] += m.points[v][k] / 3;
    for (const auto& q : centres)
    {
      const float d2 = (c[0] - q[0]) * (c[0] - q[0]) + (c[1] - q[1]) * (c[1] - q[1]) + (c[2] - q[2]) * (c[2] - q[2]);
      if (d2 <= radius * radius)
      {
        std::swap(t[1], t[2]);
        ++n;
        break;
      }
    }
  }
  return n;
}

TEST(MeshToSdfWindingFlip, ReversedPatchesClosedByCapsOverTheirRimsAreExact)
{
  // reversed patches have more faces than rim edges: the CPU closes M itself
  // by caps over dM (the rims, each edge twice) instead of reversing them
  TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 16, 32);
  const std::size_t n = flipPatches(m, { { 0.85f, 0.3f, 0.45f }, { -0.4f, -0.6f, -0.7f } }, 0.6f);
  ASSERT_GT(n, 40u);
  {
    const auto prepared = detail::meshtosdf::prepareMesh(m);
    const detail::meshtosdf::WindingSigner w(prepared);
    EXPECT_EQ(w.flippedTriangles(), n); // found by the orientation pass (Device::Auto reads it)
    EXPECT_FALSE(w.closesReorientedMesh());
    EXPECT_LT(prepared.boundary.size(), n);
  }
  expectExactSigns("sphere, two reversed patches", m);
  // with holes in a patch and elsewhere, and a patch reaching a hole
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (t % 37 != 3) kept.push_back(m.triangles[t]);
  m.triangles = kept;
  expectExactSigns("sphere, two reversed patches and holes", m);
  // scattered reversals on top: many more rim edges, M+ again
  flip(m, 0.2, 21);
  const auto prepared = detail::meshtosdf::prepareMesh(m);
  const detail::meshtosdf::WindingSigner w(prepared);
  EXPECT_TRUE(w.closesReorientedMesh());
  expectExactSigns("sphere, two reversed patches, holes and 20% flipped", m);
}

TEST(MeshToSdfWindingFlip, LongRowsUseTheSegmentBounds)
{
  // long rows past a small flipped sphere: most 16-voxel segments are far
  // enough for the segment bound to decide without per-voxel evaluation
  TriangleMesh m = makeSphereMesh(0.02f, 0.01f, -0.03f, 0.5f, 6, 12);
  flip(m, 0.3, 12);
  GridGeometry g;
  g.dims = { 96, 11, 10 };
  g.origin = { -3.3, -0.62, -0.6 };
  g.spacing = { 0.07, 0.12, 0.13 };
  const MeshToSdfStats st = expectExactSigns("small sphere, 30% flipped, long rows", m, g);
  EXPECT_LT(st.windingEvaluations, g.count() / 2);
}

TEST(MeshToSdfWindingFlip, FlippedWithHolesIsExact)
{
  TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (t >= 24 * 2 && t % 31 != 7) kept.push_back(m.triangles[t]); // a polar opening and scattered holes
  m.triangles = kept;
  flip(m, 0.1, 4);
  expectExactSigns("holes + 10% flipped", m);
  flip(m, 0.5, 5);
  expectExactSigns("holes + ~50% flipped", m);
}

TEST(MeshToSdfWindingFlip, DuplicatedAndIntersectingAreExact)
{
  const TriangleMesh sphere = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 10, 20);
  TriangleMesh d = sphere;
  for (std::size_t t = 0; t < sphere.triangles.size(); t += 3)
  {
    auto x = sphere.triangles[t];
    if (t % 2) std::swap(x[1], x[2]); // some duplicates reversed (they cancel)
    d.triangles.push_back(x);
  }
  flip(d, 0.1, 6);
  expectExactSigns("duplicated faces + 10% flipped", d);

  TriangleMesh a = makeSphereMesh(-0.35f, 0, 0, 0.8f, 8, 16), b = makeSphereMesh(0.4f, 0.1f, 0.05f, 0.75f, 8, 16);
  flip(a, 0.1, 7);
  for (auto& t : b.triangles) std::swap(t[1], t[2]); // the second one inside out
  flip(b, 0.2, 8);
  expectExactSigns("two intersecting spheres, one inside out, flips", merge(a, b));
}

TEST(MeshToSdfWindingFlip, NonOrientableAndNonManifoldAreExact)
{
  TriangleMesh strip = moebius(40, 0.35f);
  expectExactSigns("Moebius strip", strip);
  flip(strip, 0.2, 10);
  expectExactSigns("Moebius strip, 20% flipped", strip);

  // a closed box with a fin on one edge (three faces on that edge) and a
  // second box glued along an edge, some faces flipped
  TriangleMesh m = makeBoxMesh({ -0.8f, -0.7f, -0.6f }, { 0.3f, 0.4f, 0.5f });
  const std::uint32_t b = static_cast<std::uint32_t>(m.points.size());
  m.points.push_back({ 0.3f, 0.4f, -0.6f });
  m.points.push_back({ 0.3f, 0.4f, 0.5f });
  m.points.push_back({ 1.0f, 1.1f, 0.0f });
  // the fin uses the box's edge (0.3, 0.4, z) by position (welded by exact position)
  m.triangles.push_back({ b, b + 1, b + 2 });
  TriangleMesh other = makeBoxMesh({ 0.3f, 0.4f, -0.6f }, { 1.1f, 1.0f, 0.5f });
  m = merge(m, other);
  flip(m, 0.25, 11);
  expectExactSigns("boxes on one edge + fin (non-manifold), flips", m);
}

TEST(MeshToSdfWindingFlip, OrientationIsIndependentOfThreads)
{
  // large enough for the parallel sorts (parts of >= 32768 entries): the
  // result must be the one thread's, entry for entry
  std::vector<std::array<std::uint32_t, 4>> keys(300000);
  std::mt19937 rng(5);
  for (std::size_t i = 0; i < keys.size(); ++i)
    keys[i] = { static_cast<std::uint32_t>(rng() % 50), static_cast<std::uint32_t>(rng() % 50),
      static_cast<std::uint32_t>(rng() % 50), static_cast<std::uint32_t>(i) };
  auto sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  const int threads = omp_get_max_threads();
  omp_set_num_threads(std::max(4, threads));
  detail::meshtosdf::parallelSort(keys, std::less<std::array<std::uint32_t, 4>>());
  EXPECT_TRUE(keys == sorted);

  TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 120, 160);
  flip(m, 0.2, 4);
  for (std::size_t t = 0; t < m.triangles.size(); t += 50) m.triangles.push_back(m.triangles[t]);
  const auto prepared = detail::meshtosdf::prepareMesh(m);
  omp_set_num_threads(1);
  const detail::meshtosdf::OrientedMesh one = detail::meshtosdf::orientMesh(prepared.tris, prepared.welded);
  omp_set_num_threads(std::max(4, threads));
  const detail::meshtosdf::OrientedMesh many = detail::meshtosdf::orientMesh(prepared.tris, prepared.welded);
  omp_set_num_threads(threads);
  EXPECT_GT(one.flippedCount, 0u);
  EXPECT_GT(one.removedCount, 0u);
  EXPECT_TRUE(one.state == many.state);
  EXPECT_EQ(one.boundary.size(), many.boundary.size());
}
