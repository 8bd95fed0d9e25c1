// The GPU's scan-line ray split over the lanes of a warp
// (MeshToSdfRayWalk.h: rayFrontier, then one rayWalk per subtree), run here
// on the CPU lane after lane, against the CPU's own Bvh::rayHits: the same
// crossings (t bit for bit, triangle, sign), the same ambiguity, and the
// overflow past MaxHits crossings exactly when the CPU finds more. Rays: the
// +x scan lines of a grid (as the sign kernels cast them), oblique rays
// (the per-voxel fallback's direction), and rays through vertices (ambiguous).
#include "../src/MeshToSdfInternal.h"
#include "../src/MeshToSdfRayWalk.h"
#include "MeshToSdfDamagedMeshes.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
struct Crossing
{
  double t;
  int tri, sign;
  bool operator<(const Crossing& o) const { return std::tie(t, tri, sign) < std::tie(o.t, o.tri, o.sign); }
  bool operator==(const Crossing& o) const
  {
    return std::memcmp(&t, &o.t, sizeof(t)) == 0 && tri == o.tri && sign == o.sign;
  }
};

struct Outcome
{
  bool ok = true;
  int sum = 0;
  std::vector<Crossing> hits; // sorted
};

Outcome cpuRay(const Bvh& b, V3 o, V3 dir)
{
  std::vector<Bvh::RayHit> hits;
  Outcome r;
  r.ok = b.rayHits(o, dir, 0.0, hits);
  for (const Bvh::RayHit& h : hits)
  {
    r.hits.push_back({ h.t, h.tri, h.sign });
    r.sum += h.sign;
  }
  std::sort(r.hits.begin(), r.hits.end());
  return r;
}

/// What castRowRay does, one lane after another: at most `cap` crossings in all.
Outcome splitRay(const Bvh& b, const LargeVector<LeafTri>& leaves, V3 o, V3 dir, int lanes, int cap, int& subtrees)
{
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  std::vector<int> frontier(static_cast<std::size_t>(lanes)), scratch(2 * static_cast<std::size_t>(lanes));
  subtrees = rayFrontier(b.nodes().data(), o, dir, inv, lanes, frontier.data(), scratch.data());
  Outcome r;
  int count = 0; // the warp's shared counter
  for (int lane = 0; lane < subtrees; ++lane)
  {
    int sum = 0;
    const bool ok = rayWalk(b.nodes().data(), leaves.data(), b.order().data(), frontier[static_cast<std::size_t>(lane)],
      o, dir, inv, sum, [&](double t, int tri, int sg) {
        if (count++ >= cap) return false;
        r.hits.push_back({ t, tri, sg });
        return true;
      });
    r.ok = r.ok && ok;
    r.sum += sum;
  }
  std::sort(r.hits.begin(), r.hits.end());
  return r;
}
} // namespace

TEST(MeshToSdfRayWalk, SplitWalkFindsWhatRayHitsFinds)
{
  std::vector<std::pair<std::string, TriangleMesh>> meshes = oracle::damagedMeshes();
  meshes.emplace_back("bumpy sphere", oracle::bumpySphere());
  constexpr int MaxHits = 96; // the sign kernels' shared hits per scan line
  std::int64_t rays = 0, ambiguous = 0, crossings = 0, split = 0, overflows = 0;
  for (const auto& [name, mesh] : meshes)
  {
    const PreparedMesh pm = prepareMesh(mesh);
    const Bvh b(pm.tris);
    const LargeVector<LeafTri> leaves = leafCopies(b);
    const GridGeometry g = fitGridToMesh(mesh, 64, 2);
    std::vector<std::pair<V3, V3>> list;
    const V3 oblique = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
    for (std::int64_t k = 0; k < g.dims[2]; ++k)
      for (std::int64_t j = 0; j < g.dims[1]; ++j)
      {
        const V3 p{ g.origin[0] - 0.5 * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
        list.push_back({ p, V3{ 1, 0, 0 } });
        if ((j + k) % 7 == 0) list.push_back({ p + V3{ (j % 50) * g.spacing[0], 0, 0 }, oblique });
      }
    for (std::size_t v = 0; v < mesh.points.size(); v += 17) // through a vertex: ambiguous
    {
      const auto& q = mesh.points[v];
      list.push_back({ V3{ g.origin[0] - 1.0, q[1], q[2] }, V3{ 1, 0, 0 } });
    }
    for (const auto& [o, dir] : list)
    {
      const Outcome want = cpuRay(b, o, dir);
      // one walk from the root (rayDev) and the walk split over 32 lanes (castRowRay), no cap
      int subtrees = 0, one = 0;
      const Outcome whole = splitRay(b, leaves, o, dir, 1, 1 << 30, one);
      const Outcome lanes = splitRay(b, leaves, o, dir, 32, 1 << 30, subtrees);
      ++rays;
      ambiguous += !want.ok;
      split += subtrees > 1;
      ASSERT_EQ(whole.ok, want.ok) << name;
      ASSERT_EQ(lanes.ok, want.ok) << name;
      if (want.ok)
      {
        crossings += static_cast<std::int64_t>(want.hits.size());
        ASSERT_EQ(whole.sum, want.sum) << name;
        ASSERT_EQ(lanes.sum, want.sum) << name;
        ASSERT_TRUE(whole.hits == want.hits) << name;
        ASSERT_TRUE(lanes.hits == want.hits) << name;
      }
      // the cap: refused exactly when the CPU finds more crossings than it holds
      for (int cap : { 0, 1, 2, MaxHits })
      {
        const Outcome capped = splitRay(b, leaves, o, dir, 32, cap, subtrees);
        const bool fits = want.ok && static_cast<int>(want.hits.size()) <= cap;
        ASSERT_EQ(capped.ok, fits) << name << " cap " << cap;
        overflows += want.ok && !fits;
        if (fits) ASSERT_TRUE(capped.hits == want.hits) << name;
      }
    }
  }
  std::printf("[ ray walk ] %lld rays, %lld ambiguous, %lld crossings, %lld split over lanes, %lld over a cap\n",
    static_cast<long long>(rays), static_cast<long long>(ambiguous), static_cast<long long>(crossings),
    static_cast<long long>(split), static_cast<long long>(overflows));
  EXPECT_GT(ambiguous, 0);
  EXPECT_GT(split, rays / 2);
  EXPECT_GT(overflows, 0);
}
