// Consistent orientation of a triangle soup by a breadth-first search over
// manifold edges (the classic "orient the faces of a connected manifold"
// propagation, e.g. Botsch et al., "Polygon Mesh Processing", 2010, ch. 2),
// for the winding-number sign: see MeshToSdfOrientation.h.
#include "MeshToSdfOrientation.h"

#include "MeshToSdfInternal.h"
#include "MeshToSdfParallelSort.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <tuple>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
struct EdgeUse
{
  std::uint32_t lo, hi; // welded vertex ids, lo < hi
  std::uint32_t tri;
  std::int8_t dir;      // +1: the triangle runs lo -> hi
};
} // namespace

std::vector<std::array<std::uint32_t, 4>> facesByCornerSet(const LargeVector<std::array<std::uint32_t, 3>>& welded)
{
  const std::size_t n = welded.size();
  std::vector<std::array<std::uint32_t, 4>> key(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t ti = 0; ti < static_cast<std::int64_t>(n); ++ti)
  {
    const auto t = static_cast<std::size_t>(ti);
    std::array<std::uint32_t, 3> c = welded[t];
    std::sort(c.begin(), c.end());
    key[t] = { c[0], c[1], c[2], static_cast<std::uint32_t>(t) };
  }
  parallelSort(key, std::less<std::array<std::uint32_t, 4>>());
  return key;
}

OrientedMesh orientMesh(const TriList& tris, const LargeVector<std::array<std::uint32_t, 3>>& welded)
{
  OrientedMesh out;
  const std::size_t n = tris.size();
  require(welded.size() == n, "mesh to SDF: orientation needs the welded corners of every triangle");
  // duplicate keys, edge uses (and a merge buffer for each), adjacency, BFS
  requireMemory(static_cast<std::uint64_t>(n) * WindingBytesPerTriangle, "mesh to SDF: face orientation for the winding number");
  out.state.assign(n, OrientedMesh::Keep);
  if (n == 0) return out;

  // corners welded by exact position (prepareMesh): id of corner c, and the
  // position of every id
  std::vector<std::uint32_t> id(3 * n);
  std::uint32_t nv = 0;
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
    {
      id[3 * t + k] = welded[t][k];
      nv = std::max(nv, welded[t][k] + 1);
    }
  std::vector<V3> pos(nv);
  for (std::size_t c = 0; c < 3 * n; ++c) pos[id[c]] = tris[c / 3].v[c % 3];

  // exact duplicates (same vertex set): keep one face of the net orientation
  // (of the group's first face when the orientations cancel)
  {
    const std::vector<std::array<std::uint32_t, 4>> key = facesByCornerSet(welded); // sorted ids, triangle
    // orientation of t relative to the sorted order (an even permutation: +1)
    auto parity = [&](std::uint32_t t, const std::array<std::uint32_t, 4>& k) { return cornerParity(welded[t], k); };
    for (std::size_t g = 0; g < n;)
    {
      std::size_t g1 = g;
      int net = 0;
      for (; g1 < n && key[g1][0] == key[g][0] && key[g1][1] == key[g][1] && key[g1][2] == key[g][2]; ++g1)
        net += parity(key[g1][3], key[g1]);
      if (g1 - g > 1)
      {
        out.opposedDuplicates += (g1 - g) - static_cast<std::size_t>(std::abs(net));
        bool kept = false;
        for (std::size_t i = g; i < g1; ++i)
        {
          const std::uint32_t t = key[i][3];
          // a group that cancels (net 0) still keeps one face: the search
          // orients it with its neighbours and the correction s restores w_M,
          // instead of a one-face hole whose cone term costs every voxel
          if (!kept && (net == 0 || parity(t, key[i]) == (net > 0 ? 1 : -1)))
          {
            kept = true;
            continue;
          }
          out.state[t] = OrientedMesh::Remove;
          ++out.removedCount;
        }
      }
      g = g1;
    }
  }

  // edge uses of the kept faces grouped by (lo, hi)
  std::vector<EdgeUse> uses;
  uses.reserve(3 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3 && out.state[t] != OrientedMesh::Remove; ++k)
    {
      const std::uint32_t a = id[3 * t + k], b = id[3 * t + (k + 1) % 3];
      uses.push_back({ std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(t),
        static_cast<std::int8_t>(a < b ? 1 : -1) });
    }
  // (lo, hi, tri) is a total order: a non-degenerate triangle uses an edge once
  parallelSort(uses, [](const EdgeUse& a, const EdgeUse& b) {
    return std::tie(a.lo, a.hi, a.tri) < std::tie(b.lo, b.hi, b.tri);
  });

  // manifold adjacency: neighbour across each corner's edge, and whether the
  // two faces agree (they run the shared edge in opposite directions)
  constexpr std::uint32_t None = 0xffffffffu;
  std::vector<std::array<std::uint32_t, 3>> nb(n, { None, None, None });
  std::vector<std::array<std::int8_t, 3>> agree(n, { 0, 0, 0 });
  std::vector<std::uint8_t> deg(n, 0);
  for (std::size_t e = 0; e < uses.size();)
  {
    std::size_t e1 = e;
    while (e1 < uses.size() && uses[e1].lo == uses[e].lo && uses[e1].hi == uses[e].hi) ++e1;
    if (e1 - e == 2 && uses[e].tri != uses[e + 1].tri)
    {
      const EdgeUse& a = uses[e];
      const EdgeUse& b = uses[e + 1];
      const std::int8_t same = a.dir != b.dir ? 1 : -1;
      nb[a.tri][deg[a.tri]] = b.tri;
      agree[a.tri][deg[a.tri]++] = same;
      nb[b.tri][deg[b.tri]] = a.tri;
      agree[b.tri][deg[b.tri]++] = same;
    }
    else
    {
      ++out.nonManifoldEdges;
    }
    e = e1;
  }

  // BFS per component; o = +1 keeps a face, -1 reverses it
  std::vector<std::int8_t> o(n, 0);
  std::vector<std::uint32_t> queue;
  queue.reserve(n);
  for (std::size_t seed = 0; seed < n; ++seed)
  {
    if (o[seed] != 0 || out.state[seed] == OrientedMesh::Remove) continue;
    ++out.components;
    queue.clear();
    queue.push_back(static_cast<std::uint32_t>(seed));
    o[seed] = 1;
    std::size_t reversed = 0;
    for (std::size_t q = 0; q < queue.size(); ++q)
    {
      const std::uint32_t t = queue[q];
      for (int k = 0; k < deg[t]; ++k)
      {
        const std::uint32_t u = nb[t][k];
        const std::int8_t want = static_cast<std::int8_t>(o[t] * agree[t][k]);
        if (o[u] == 0)
        {
          o[u] = want;
          if (want < 0) ++reversed;
          queue.push_back(u);
        }
        else if (o[u] != want && t < u)
        {
          ++out.conflicts; // non-orientable: counted once per edge
        }
      }
    }
    // keep the majority's orientation: F is the minority
    const bool invert = 2 * reversed > queue.size();
    for (std::uint32_t t : queue)
    {
      if (invert) o[t] = static_cast<std::int8_t>(-o[t]);
      if (o[t] < 0)
      {
        out.state[t] = OrientedMesh::Reverse;
        ++out.flippedCount;
      }
    }
  }

  // boundary of M+: net oriented multiplicity of every edge
  for (std::size_t e = 0; e < uses.size();)
  {
    std::size_t e1 = e;
    int mult = 0;
    for (; e1 < uses.size() && uses[e1].lo == uses[e].lo && uses[e1].hi == uses[e].hi; ++e1)
    {
      mult += uses[e1].dir * o[uses[e1].tri];
    }
    const V3 a = pos[uses[e].lo], b = pos[uses[e].hi];
    for (int k = 0; k < std::abs(mult); ++k)
    {
      out.boundary.push_back(mult > 0 ? std::array<V3, 2>{ a, b } : std::array<V3, 2>{ b, a });
    }
    e = e1;
  }
  return out;
}

} // namespace detail::meshtosdf
} // namespace lvdif
