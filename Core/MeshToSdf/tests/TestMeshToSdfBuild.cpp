// The host build of mesh to SDF on OpenMP threads: prepareMesh against a
// plain serial reference written here (welding by a std::map in order of
// first appearance, pseudo-normals and edge normals summed in triangle order,
// the boundary chain by net edge multiplicity), bit for bit, with 1 and 4
// threads, also when the pseudo-normals are added later (addPseudoNormals); the Bvh (boxes bottom-up) and NearestIndex the same for any
// thread count and exact against brute force; a closed mesh's winding
// closure shares the mesh's tree.
#include "../src/MeshToSdfInternal.h"
#include "../src/MeshToSdfNearest.h"
#include "MeshToSdfOracle.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <future>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
/// Runs f with n OpenMP threads, then restores the previous count.
template <typename F>
auto withThreads(int n, F&& f)
{
  const int before = omp_get_max_threads();
  omp_set_num_threads(n);
  auto r = f();
  omp_set_num_threads(before);
  return r;
}

bool sameBits(const V3& a, const V3& b) { return std::memcmp(&a, &b, sizeof(V3)) == 0; }
/// Two records' fields bit for bit (their padding bytes are not written).
bool sameRecord(const Tri& a, const Tri& b)
{
  return std::memcmp(a.v, b.v, sizeof(a.v)) == 0 && sameBits(a.n, b.n) &&
    std::memcmp(&a.area, &b.area, sizeof(a.area)) == 0 && a.source == b.source;
}
bool sameRecords(const TriList& a, const TriList& b)
{
  if (a.size() != b.size()) return false;
  for (std::size_t t = 0; t < a.size(); ++t)
    if (!sameRecord(a[t], b[t])) return false;
  return true;
}

/// A damaged soup: a sphere with every triangle on its own three points
/// (welding must find the shared vertices), a few faces removed (holes),
/// reversed and duplicated, plus zero-area triangles.
TriangleMesh damagedSoup()
{
  const TriangleMesh s = makeSphereMesh(0.1f, -0.05f, 0.02f, 1.0f, 24, 40);
  TriangleMesh m;
  std::mt19937 rng(5);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    if (t % 97 == 13) continue; // a hole
    auto ix = s.triangles[t];
    if (t % 61 == 7) std::swap(ix[1], ix[2]); // reversed
    const int copies = t % 83 == 5 ? 2 : 1;   // duplicated
    for (int c = 0; c < copies; ++c)
    {
      const auto base = static_cast<std::uint32_t>(m.points.size());
      for (int k = 0; k < 3; ++k) m.points.push_back(s.points[ix[k]]);
      m.triangles.push_back({ base, base + 1, base + 2 });
    }
  }
  // zero-area triangles (two equal corners), skipped by prepareMesh
  for (int i = 0; i < 5; ++i) m.triangles.push_back({ static_cast<std::uint32_t>(3 * i), static_cast<std::uint32_t>(3 * i), 7 });
  std::shuffle(m.triangles.begin(), m.triangles.end(), rng);
  return m;
}

double angleAtRef(V3 p, V3 q, V3 r)
{
  const V3 u = normalized(q - p), v = normalized(r - p);
  double c = dot(u, v);
  c = c > 1 ? 1 : (c < -1 ? -1 : c);
  return std::acos(c);
}
} // namespace

TEST(MeshToSdfBuild, PrepareMeshEqualsASerialReferenceOnAnyThreadCount)
{
  const TriangleMesh m = damagedSoup();
  // the reference: weld ids in order of first appearance
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> idOf;
  std::vector<std::uint32_t> weld(m.points.size());
  std::vector<V3> pos;
  for (std::size_t i = 0; i < m.points.size(); ++i)
  {
    std::array<std::uint32_t, 3> key;
    std::memcpy(key.data(), m.points[i].data(), sizeof(key));
    const auto it = idOf.emplace(key, static_cast<std::uint32_t>(idOf.size())).first;
    weld[i] = it->second;
    if (it->second == pos.size()) pos.push_back({ m.points[i][0], m.points[i][1], m.points[i][2] });
  }
  // kept triangles, normals, pseudo-normals summed in triangle order
  LargeVector<std::array<std::uint32_t, 3>> w; // the type of PreparedMesh::welded
  std::vector<V3> n;
  std::vector<V3> vsum(pos.size());
  for (const auto& ix : m.triangles)
  {
    const std::array<std::uint32_t, 3> t{ weld[ix[0]], weld[ix[1]], weld[ix[2]] };
    const V3 v[3] = { { m.points[ix[0]][0], m.points[ix[0]][1], m.points[ix[0]][2] },
      { m.points[ix[1]][0], m.points[ix[1]][1], m.points[ix[1]][2] },
      { m.points[ix[2]][0], m.points[ix[2]][1], m.points[ix[2]][2] } };
    const V3 c = cross(v[1] - v[0], v[2] - v[0]);
    if (!(norm(c) > 0)) continue;
    w.push_back(t);
    n.push_back((1.0 / norm(c)) * c);
    for (int k = 0; k < 3; ++k) vsum[t[k]] = vsum[t[k]] + angleAtRef(v[k], v[(k + 1) % 3], v[(k + 2) % 3]) * n.back();
  }
  // edges: summed normals in triangle order, net multiplicity lo -> hi
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<V3, int>> edges;
  for (std::size_t t = 0; t < w.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = w[t][k], b = w[t][(k + 1) % 3];
      auto& e = edges[{ std::min(a, b), std::max(a, b) }];
      e.first = e.first + n[t];
      e.second += a < b ? 1 : -1;
    }
  }
  std::vector<std::array<V3, 2>> boundary;
  for (const auto& [key, e] : edges)
  {
    for (int k = 0; k < std::abs(e.second); ++k)
    {
      const V3 a = pos[key.first], b = pos[key.second];
      boundary.push_back(e.second > 0 ? std::array<V3, 2>{ a, b } : std::array<V3, 2>{ b, a });
    }
  }
  ASSERT_GT(boundary.size(), 10u);

  for (int threads : { 1, 4 })
  {
    const PreparedMesh p = withThreads(threads, [&] { return prepareMesh(m); });
    ASSERT_EQ(p.tris.size(), w.size()) << threads;
    EXPECT_EQ(p.degenerate, 5u);
    EXPECT_EQ(p.welded, w) << threads;
    // the welded points: the first input point of each id, bit for bit
    ASSERT_EQ(p.points.size(), pos.size()) << threads;
    ASSERT_EQ(p.vertices, pos.size()) << threads;
    for (std::size_t v = 0; v < pos.size(); ++v)
    {
      const V3 q{ p.points[v][0], p.points[v][1], p.points[v][2] };
      EXPECT_EQ(std::memcmp(&q, &pos[v], sizeof(V3)), 0) << v;
    }
    std::size_t bad = 0;
    for (std::size_t t = 0; t < w.size(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        V3 vn = normalized(vsum[w[t][k]]);
        if (dot(vn, vn) == 0) vn = n[t];
        const std::uint32_t a = w[t][k], b = w[t][(k + 1) % 3];
        V3 en = normalized(edges[{ std::min(a, b), std::max(a, b) }].first);
        if (dot(en, en) == 0) en = n[t];
        bad += !sameBits(p.normals[t].vn[k], vn) || !sameBits(p.normals[t].en[k], en) || !sameBits(p.tris[t].n, n[t]);
      }
    }
    EXPECT_EQ(bad, 0u) << threads;
    ASSERT_EQ(p.boundary.size(), boundary.size()) << threads;
    EXPECT_EQ(std::memcmp(p.boundary.data(), boundary.data(), boundary.size() * sizeof(boundary[0])), 0) << threads;
    EXPECT_TRUE(p.pseudoNormals);

    // prepared without the pseudo-normals (the WindingNumber/Unsigned route):
    // the same records, no pseudo-normals, the same boundary; then
    // addPseudoNormals (on another thread count) adds the above's
    PreparedMesh lean = withThreads(threads, [&] { return prepareMesh(m, false); });
    EXPECT_FALSE(lean.pseudoNormals);
    EXPECT_EQ(lean.welded, w) << threads;
    EXPECT_EQ(lean.boundary.size(), p.boundary.size());
    EXPECT_EQ(std::memcmp(lean.boundary.data(), boundary.data(), boundary.size() * sizeof(boundary[0])), 0) << threads;
    EXPECT_EQ(lean.boundaryLength, p.boundaryLength);
    EXPECT_TRUE(sameRecords(lean.tris, p.tris)) << threads;
    EXPECT_TRUE(lean.normals.empty()) << threads;
    EXPECT_TRUE(lean.cornerNormals.empty() && p.cornerNormals.empty()) << threads; // the soup has no vertex normals
    withThreads(5 - threads, [&] { return addPseudoNormals(lean), 0; });
    EXPECT_TRUE(lean.pseudoNormals);
    ASSERT_EQ(lean.normals.size(), p.normals.size());
    EXPECT_EQ(std::memcmp(lean.normals.data(), p.normals.data(), p.normals.size() * sizeof(TriNormals)), 0) << threads;
    EXPECT_TRUE(sameRecords(lean.tris, p.tris)) << threads;
  }
}

// The one-call CUDA route builds the mesh BVH on its own thread beside the
// edge pass (prepareMesh's recordsReady): the prepared mesh and the tree are
// bit for bit those built one after the other, with and without the
// pseudo-normals (whose edge pass writes the records the tree reads from).
TEST(MeshToSdfBuild, TreeBuiltBesideTheEdgePassEqualsTheTreeBuiltAfter)
{
  const TriangleMesh m = damagedSoup();
  for (bool pseudo : { false, true })
  {
    const PreparedMesh ref = prepareMesh(m, pseudo);
    const Bvh refTree(ref.tris);
    PreparedMesh out;
    std::future<std::unique_ptr<Bvh>> tree;
    bool called = false;
    prepareMesh(m, out, pseudo, [&] {
      called = true;
      ASSERT_EQ(out.tris.size(), ref.tris.size()); // the records are there already
      EXPECT_TRUE(out.boundary.empty());             // and the edge pass has not run yet (the soup has holes)
      tree = std::async(std::launch::async, [&out] { return std::make_unique<Bvh>(out.tris); });
    });
    ASSERT_TRUE(called);
    ASSERT_FALSE(ref.boundary.empty()); // the guard above can fail
    const std::unique_ptr<Bvh> beside = tree.get();
    ASSERT_EQ(out.tris.size(), ref.tris.size());
    EXPECT_TRUE(sameRecords(out.tris, ref.tris)) << pseudo;
    ASSERT_EQ(out.normals.size(), ref.normals.size());
    EXPECT_EQ(std::memcmp(out.normals.data(), ref.normals.data(), ref.normals.size() * sizeof(TriNormals)), 0) << pseudo;
    EXPECT_EQ(out.welded, ref.welded);
    ASSERT_EQ(out.boundary.size(), ref.boundary.size());
    EXPECT_EQ(std::memcmp(out.boundary.data(), ref.boundary.data(), ref.boundary.size() * sizeof(ref.boundary[0])), 0);
    EXPECT_EQ(out.boundaryEdges, ref.boundaryEdges);
    EXPECT_EQ(out.pseudoNormals, pseudo);
    ASSERT_EQ(beside->nodes().size(), refTree.nodes().size());
    EXPECT_EQ(std::memcmp(beside->nodes().data(), refTree.nodes().data(), refTree.nodes().size() * sizeof(Bvh::Node)), 0);
    EXPECT_EQ(beside->order(), refTree.order());
  }
}

TEST(MeshToSdfBuild, BvhAndNearestIndexAreTheSameOnAnyThreadCountAndExact)
{
  // more than 2^16 triangles: many subtrees built on threads (tasks in the
  // Bvh, parallel subtrees in NearestIndex)
  const TriangleMesh mesh = makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 190, 190);
  const PreparedMesh pm = prepareMesh(mesh);
  ASSERT_GT(pm.tris.size(), 65536u);
  const auto oneBvh = withThreads(1, [&] { return std::make_unique<Bvh>(pm.tris); });
  const auto manyBvh = withThreads(4, [&] { return std::make_unique<Bvh>(pm.tris); });
  ASSERT_EQ(oneBvh->nodes().size(), manyBvh->nodes().size());
  EXPECT_EQ(std::memcmp(oneBvh->nodes().data(), manyBvh->nodes().data(), oneBvh->nodes().size() * sizeof(Bvh::Node)), 0);
  EXPECT_EQ(oneBvh->order(), manyBvh->order());
  const auto oneIndex = withThreads(1, [&] { return std::make_unique<NearestIndex>(pm.tris); });
  const auto manyIndex = withThreads(4, [&] { return std::make_unique<NearestIndex>(pm.tris); });
  ASSERT_EQ(oneIndex->nodes().size(), manyIndex->nodes().size());
  EXPECT_EQ(std::memcmp(oneIndex->nodes().data(), manyIndex->nodes().data(),
              oneIndex->nodes().size() * sizeof(NearestIndex::Node)),
    0);
  // every box of the Bvh holds its triangles (the boxes are built bottom-up)
  for (const Bvh::Node& nd : manyBvh->nodes())
  {
    for (std::int32_t i = nd.first; i < nd.first + nd.count; ++i)
      for (const V3& v : pm.tris[static_cast<std::size_t>(manyBvh->order()[static_cast<std::size_t>(i)])].v)
        for (int a = 0; a < 3; ++a) ASSERT_TRUE(nd.lo[a] <= v[a] && v[a] <= nd.hi[a]);
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int q = 0; q < 200; ++q)
  {
    const V3 p{ u(rng), u(rng), u(rng) };
    NearestResult want;
    want.dist2 = 1e300;
    for (std::size_t t = 0; t < pm.tris.size(); ++t)
    {
      const Closest c = closestPointOnTriangle(p, pm.tris[t].v[0], pm.tris[t].v[1], pm.tris[t].v[2]);
      const double d2 = dot(c.point - p, c.point - p);
      if (d2 < want.dist2) want = { d2, static_cast<std::int32_t>(t), c };
    }
    const NearestResult a = manyBvh->nearest(p, -1, 1e300), b = manyIndex->nearest(p, -1, 1e300);
    EXPECT_EQ(a.tri, want.tri);
    EXPECT_EQ(a.dist2, want.dist2);
    EXPECT_EQ(b.tri, want.tri);
    EXPECT_EQ(b.dist2, want.dist2);
  }
}

/// Two parallel grids of 1/8 squares (z = 0 and z = 1, the second reversed)
/// and 200 copies of one triangle: many equal centroid coordinates (ties of
/// the split's order) and query points equidistant from many triangles.
TriangleMesh tiedGrids()
{
  TriangleMesh m;
  constexpr int N = 64;
  for (int z = 0; z < 2; ++z)
  {
    const auto base = static_cast<std::uint32_t>(m.points.size());
    for (int j = 0; j <= N; ++j)
      for (int i = 0; i <= N; ++i) m.points.push_back({ i / 8.0f, j / 8.0f, static_cast<float>(z) });
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const std::uint32_t a = base + static_cast<std::uint32_t>(j * (N + 1) + i), b = a + 1, c = a + N + 1, d = c + 1;
        if (z == 0)
        {
          m.triangles.push_back({ a, b, d });
          m.triangles.push_back({ a, d, c });
        }
        else
        {
          m.triangles.push_back({ a, d, b });
          m.triangles.push_back({ a, c, d });
        }
      }
  }
  const auto base = static_cast<std::uint32_t>(m.points.size());
  m.points.push_back({ 1.0f, 1.0f, 0.5f });
  m.points.push_back({ 1.5f, 1.0f, 0.5f });
  m.points.push_back({ 1.0f, 1.5f, 0.5f });
  for (int c = 0; c < 200; ++c) m.triangles.push_back({ base, base + 1, base + 2 });
  return m;
}

/// Centroid sums as the Bvh compares them.
std::array<double, 3> centroidSum(const Tri& t)
{
  std::array<double, 3> c;
  for (int a = 0; a < 3; ++a) c[a] = t.v[0][a] + t.v[1][a] + t.v[2][a];
  return c;
}

// The Bvh is a function of the triangles: every inner node puts the count / 2
// smallest of its triangles by (centroid coordinate on the longest axis of
// their centroid bounds, index) on the left, every leaf lists its triangles
// by index; the same tree whether the top splits run on all threads
// (selection and partition in parallel, down to a small threshold here) or
// as tasks, on any thread count.
TEST(MeshToSdfBuild, BvhIsAFunctionOfTheTrianglesWhateverSplitsInParallel)
{
  for (const TriangleMesh& mesh : { tiedGrids(), makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 190, 190) })
  {
    const PreparedMesh pm = prepareMesh(mesh, false);
    const auto ref = withThreads(1, [&] { return std::make_unique<Bvh>(pm.tris); });
    for (const auto& [threads, splitMin] : { std::pair{ 1, 64 }, std::pair{ 4, 64 }, std::pair{ 3, 1000 }, std::pair{ 4, 1 << 19 } })
    {
      const auto b = withThreads(threads, [&] { return std::make_unique<Bvh>(pm.tris, splitMin); });
      ASSERT_EQ(b->nodes().size(), ref->nodes().size());
      EXPECT_EQ(std::memcmp(b->nodes().data(), ref->nodes().data(), ref->nodes().size() * sizeof(Bvh::Node)), 0)
        << threads << " " << splitMin;
      EXPECT_EQ(b->order(), ref->order()) << threads << " " << splitMin;
    }
    const auto& order = ref->order();
    std::size_t inner = 0;
    for (const Bvh::Node& nd : ref->nodes())
    {
      if (nd.left < 0)
      {
        for (std::int32_t i = nd.first + 1; i < nd.first + nd.count; ++i) ASSERT_LT(order[i - 1], order[i]);
        continue;
      }
      ++inner;
      double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
      for (std::int32_t i = nd.first; i < nd.first + nd.count; ++i)
      {
        const auto c = centroidSum(pm.tris[static_cast<std::size_t>(order[i])]);
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
      }
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
      const Bvh::Node& l = ref->nodes()[static_cast<std::size_t>(nd.left)];
      ASSERT_EQ(l.count, nd.count / 2);
      auto key = [&](std::int32_t i) {
        const std::int32_t t = order[static_cast<std::size_t>(i)];
        return std::pair{ centroidSum(pm.tris[static_cast<std::size_t>(t)])[axis], t };
      };
      auto maxLeft = key(l.first), minRight = key(l.first + l.count);
      for (std::int32_t i = l.first; i < l.first + l.count; ++i) maxLeft = std::max(maxLeft, key(i));
      for (std::int32_t i = l.first + l.count; i < nd.first + nd.count; ++i) minRight = std::min(minRight, key(i));
      ASSERT_LT(maxLeft, minRight);
    }
    EXPECT_GT(inner, 1000u);
  }
}

// nearest() against brute force where distances tie everywhere: lattice
// points over two grids of equal squares (several triangles at the same
// distance, the midplane equidistant from both grids) and 200 copies of one
// triangle; the lowest index wins, with or without a hint, on trees split in
// parallel or not.
TEST(MeshToSdfBuild, BvhNearestEqualsBruteForceWithManyTies)
{
  const TriangleMesh mesh = tiedGrids();
  const PreparedMesh pm = prepareMesh(mesh, false);
  const auto tasks = std::make_unique<Bvh>(pm.tris);
  const auto split = withThreads(4, [&] { return std::make_unique<Bvh>(pm.tris, 64); });
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::int32_t> anyTri(0, static_cast<std::int32_t>(pm.tris.size()) - 1);
  int tied = 0, queries = 0;
  for (const double z : { 0.5, 0.25, 0.0, 1.0, -0.125, 0.75 })
    for (int j = -2; j <= 130; j += 3)
      for (int i = -2; i <= 130; i += 5)
      {
        const V3 p{ i / 16.0, j / 16.0, z };
        NearestResult want;
        want.dist2 = 1e300;
        int atBest = 0;
        for (std::size_t t = 0; t < pm.tris.size(); ++t)
        {
          const Closest c = closestPointOnTriangle(p, pm.tris[t].v[0], pm.tris[t].v[1], pm.tris[t].v[2]);
          const double d2 = dot(c.point - p, c.point - p);
          if (d2 < want.dist2) want = { d2, static_cast<std::int32_t>(t), c }, atBest = 0;
          atBest += d2 == want.dist2;
        }
        tied += atBest > 1;
        ++queries;
        for (const Bvh* b : { tasks.get(), split.get() })
        {
          const NearestResult r = b->nearest(p, -1, 1e300);
          ASSERT_EQ(r.tri, want.tri) << p.x << " " << p.y << " " << p.z;
          ASSERT_EQ(r.dist2, want.dist2);
          const NearestResult h = b->nearest(p, anyTri(rng), 1e300);
          ASSERT_EQ(h.tri, want.tri);
          ASSERT_EQ(h.dist2, want.dist2);
        }
      }
  EXPECT_GT(tied, queries / 2); // the ties are there
}

TEST(MeshToSdfBuild, ClosedMeshClosureIsTheMeshWithItsTree)
{
  const TriangleMesh mesh = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 20, 40);
  const PreparedMesh pm = prepareMesh(mesh);
  ASSERT_TRUE(pm.boundary.empty());
  const auto tree = std::make_shared<const Bvh>(pm.tris);
  const WindingSigner shared(pm, tree), own(pm);
  EXPECT_EQ(shared.meshBvh().get(), tree.get()); // no second tree
  EXPECT_EQ(&shared.closedTris(), &pm.tris);    // no copy of the triangles
  EXPECT_EQ(&own.closedTris(), &pm.tris);
  ASSERT_NE(own.meshBvh(), nullptr);
  ASSERT_EQ(own.meshBvh()->nodes().size(), tree->nodes().size());
  EXPECT_EQ(std::memcmp(own.meshBvh()->nodes().data(), tree->nodes().data(), tree->nodes().size() * sizeof(Bvh::Node)), 0);
  EXPECT_EQ(shared.cpuCorrection(), nullptr);
  // the winding number through the shared tree against the long-double oracle
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  int checked = 0;
  for (int q = 0; q < 300; ++q)
  {
    const V3 p{ u(rng), u(rng), u(rng) };
    const double want = oracle::winding(mesh, { p.x, p.y, p.z });
    if (std::fabs(std::fabs(want) - 0.5) < 0.05) continue; // too close to the surface to compare signs
    EXPECT_EQ(std::fabs(shared.evaluate(p)) >= 0.5, std::fabs(want) >= 0.5);
    EXPECT_EQ(std::fabs(shared.evaluate(p, true)) >= 0.5, std::fabs(want) >= 0.5);
    ++checked;
  }
  EXPECT_GT(checked, 250);
}

// LVDIF_MEMORY_LIMIT below what a preparation would hold (preparedBytes, by
// sign and by whether the CPU's nearest index follows): refused before
// prepareMesh allocates anything (its first traced phase never starts), with
// one message naming the triangles, what they need, the limit and the
// variable; at the estimate itself the call runs (each structure's own check
// is one part of the sum). Before, the one-call run got through at this
// limit: only the nearest index (800 bytes a triangle) was checked, after
// the prepared mesh and the winding structures existed.
TEST(MeshToSdfBuild, MemoryLimitRefusesThePreparationBeforeItStarts)
{
  const TriangleMesh mesh = makeSphereMesh(0, 0, 0, 1, 60, 120);
  const std::uint64_t n = mesh.triangles.size();
  const GridGeometry g = fitGridToMesh(mesh, 12, 2);
  VoxelBox box;
  box.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  const char* env = std::getenv("LVDIF_MEMORY_LIMIT");
  const std::string saved = env ? env : "";
  for (SignMode sign : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Unsigned })
  {
    for (bool oneCall : { true, false })
    {
      const bool pseudo = sign == SignMode::PseudoNormal, winding = sign == SignMode::WindingNumber;
      const std::uint64_t need = preparedBytes(n, pseudo, winding, oneCall);
      MeshToSdfOptions o;
      o.sign = sign;
      o.device = Device::Cpu;
      o.tracePhases = true;
      auto call = [&] {
        if (oneCall)
          meshToSdf(mesh, g, box, out.data(), o);
        else
          prepareMeshToSdf(mesh, sign);
      };
      const std::string what = std::string(toString(sign)) + (oneCall ? ", one call" : ", prepared");
      ::setenv("LVDIF_MEMORY_LIMIT", std::to_string(need - 1).c_str(), 1);
      testing::internal::CaptureStderr();
      std::string message;
      try
      {
        call();
      }
      catch (const Error& e)
      {
        EXPECT_EQ(e.code(), ErrorCode::OutOfMemory) << what;
        message = e.what();
      }
      const std::string traced = testing::internal::GetCapturedStderr();
      EXPECT_FALSE(message.empty()) << what << ": not refused";
      for (const std::string& part : { std::to_string(n) + " triangles", "needs " + formatBytes(need),
             "limit of " + formatBytes(need - 1), std::string("LVDIF_MEMORY_LIMIT") })
        EXPECT_NE(message.find(part), std::string::npos) << what << ": '" << part << "' not in: " << message;
      EXPECT_EQ(traced.find("prepare:"), std::string::npos) << what << ": the preparation started:\n" << traced;
      ::setenv("LVDIF_MEMORY_LIMIT", std::to_string(need).c_str(), 1);
      o.tracePhases = false;
      EXPECT_NO_THROW(call()) << what;
    }
  }
  if (env)
    ::setenv("LVDIF_MEMORY_LIMIT", saved.c_str(), 1);
  else
    ::unsetenv("LVDIF_MEMORY_LIMIT");
}
