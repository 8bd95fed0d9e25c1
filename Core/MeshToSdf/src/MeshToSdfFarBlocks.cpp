// Far blocks of the Normal and PseudoNormal signs on the CPU: the blocks of a
// box of voxels whose voxels are all +-band (MeshToSdfFarBlocks.h; proof in
// docs/MESH_TO_SDF.md, "Far blocks"), found before the per-voxel rows.
#include "MeshToSdfFarBlocks.h"

#include "MeshToSdfNearest.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

double farScale(const PreparedMesh& mesh, const GridGeometry& grid)
{
  double big = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double last = grid.origin[a] + static_cast<double>(grid.dims[a] - 1) * grid.spacing[a];
    big = std::max({ big, std::fabs(mesh.lo[a]), std::fabs(mesh.hi[a]), std::fabs(grid.origin[a]), std::fabs(last) });
  }
  return big;
}

std::int64_t classifyFarCells(const NearestIndex& index, const Bvh& bvh, const std::vector<FarCone>& cones,
  const PreparedMesh& mesh, const GridGeometry& grid, const VoxelBox& box, double bandWorld, bool pseudo,
  FarCells& cells)
{
  const double big = farScale(mesh, grid);
  const double margin = farMargin(big, static_cast<double>(mesh.tris.size()));
  std::int64_t n[3], blocks[3];
  for (int a = 0; a < 3; ++a)
  {
    n[a] = box.hi[a] - box.lo[a] + 1;
    cells.count[a] = (n[a] + FarCell - 1) / FarCell;
    blocks[a] = (n[a] + FarBlock - 1) / FarBlock;
  }
  cells.sign.assign(static_cast<std::size_t>(cells.count[0] * cells.count[1] * cells.count[2]), 0);
  auto pos = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return V3{ grid.origin[0] + i * grid.spacing[0], grid.origin[1] + j * grid.spacing[1],
      grid.origin[2] + k * grid.spacing[2] };
  };
  // the box of voxels [v0, v0 + edge) (box-relative, clipped)
  auto boxOf = [&](const std::int64_t v0[3], std::int64_t edge) {
    std::int64_t hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = std::min(v0[a] + edge, n[a]) - 1;
    return farBox(pos(box.lo[0] + v0[0], box.lo[1] + v0[1], box.lo[2] + v0[2]),
      pos(box.lo[0] + hi[0], box.lo[1] + hi[1], box.lo[2] + hi[2]), big);
  };
  const std::int64_t total = blocks[0] * blocks[1] * blocks[2];
  const Bvh::Node* nodes = bvh.nodes().data();
  const std::int32_t* order = bvh.order().data();
  auto triAt = [&](int i) -> const Tri& { return mesh.tris[static_cast<std::size_t>(order[i])]; };
  std::int64_t decided = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : decided)
  for (std::int64_t b = 0; b < total; ++b)
  {
    const long long origin[3] = { (b % blocks[0]) * FarBlock, ((b / blocks[0]) % blocks[1]) * FarBlock,
      (b / (blocks[0] * blocks[1])) * FarBlock };
    const long long size[3] = { n[0], n[1], n[2] };
    std::int32_t hint = -1;
    // the last box tried at each level and its centre's distance: the box
    // enclosing the one being tried (farClassifyBlock tries the halves of a
    // box right after it, its cells right after each half)
    FarBox last[3];
    double lastDist[3] = { 0, 0, 0 };
    decided += farClassifyBlock(origin, size,
      [&](const long long o[3], long long edge) {
        const std::int64_t o64[3] = { o[0], o[1], o[2] };
        const FarBox sub = boxOf(o64, edge);
        const int level = edge == FarBlock ? 0 : (edge == FarBlock / 2 ? 1 : 2);
        // certainly within the band by the enclosing box's distance: no query
        // (only a shortcut: an undecided box is never wrong)
        if (level > 0)
        {
          const double bound = farChildBound(lastDist[level - 1], sub, last[level - 1], big);
          if (bound - sub.radius <= bandWorld)
          {
            // the bound stands in for this box's distance for its own cells,
            // so that they are not tried against a stale box (as on the GPU)
            last[level] = sub;
            lastDist[level] = bound;
            return 0;
          }
        }
        const NearestResult q = index.nearest(sub.centre, hint, 1e300);
        if (q.tri < 0) return 0;
        hint = q.tri;
        const double dq = std::sqrt(q.dist2);
        last[level] = sub;
        lastDist[level] = dq;
        const int expect = farSideAt(mesh.tris[static_cast<std::size_t>(q.tri)], q.closest, sub.centre, pseudo);
        return farBoxSide(nodes, cones.data(), triAt, pseudo, sub, dq, dq, bandWorld, margin, expect);
      },
      [&](const long long c[3], int s) {
        cells.sign[static_cast<std::size_t>(c[0] + cells.count[0] * (c[1] + cells.count[1] * c[2]))] =
          static_cast<std::int8_t>(s);
      });
  }
  return decided;
}

std::int64_t classifyBandCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
  const VoxelBox& box, double bandWorld, FarCells& cells)
{
  const double big = farScale(mesh, grid);
  const double margin = farMargin(big, static_cast<double>(mesh.tris.size()));
  std::int64_t n[3], blocks[3];
  for (int a = 0; a < 3; ++a)
  {
    n[a] = box.hi[a] - box.lo[a] + 1;
    cells.count[a] = (n[a] + FarCell - 1) / FarCell;
    blocks[a] = (n[a] + FarBlock - 1) / FarBlock;
  }
  cells.sign.assign(static_cast<std::size_t>(cells.count[0] * cells.count[1] * cells.count[2]), 0);
  auto pos = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return V3{ grid.origin[0] + i * grid.spacing[0], grid.origin[1] + j * grid.spacing[1],
      grid.origin[2] + k * grid.spacing[2] };
  };
  auto boxOf = [&](const std::int64_t v0[3], std::int64_t edge) {
    std::int64_t hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = std::min(v0[a] + edge, n[a]) - 1;
    return farBox(pos(box.lo[0] + v0[0], box.lo[1] + v0[1], box.lo[2] + v0[2]),
      pos(box.lo[0] + hi[0], box.lo[1] + hi[1], box.lo[2] + hi[2]), big);
  };
  const std::int64_t total = blocks[0] * blocks[1] * blocks[2];
  std::int64_t decided = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : decided)
  for (std::int64_t b = 0; b < total; ++b)
  {
    const long long origin[3] = { (b % blocks[0]) * FarBlock, ((b / blocks[0]) % blocks[1]) * FarBlock,
      (b / (blocks[0] * blocks[1])) * FarBlock };
    const long long size[3] = { n[0], n[1], n[2] };
    std::int32_t hint = -1;
    FarBox last[3];
    double lastDist[3] = { 0, 0, 0 };
    decided += farClassifyBlock(origin, size,
      [&](const long long o[3], long long edge) {
        const std::int64_t o64[3] = { o[0], o[1], o[2] };
        const FarBox sub = boxOf(o64, edge);
        const int level = edge == FarBlock ? 0 : (edge == FarBlock / 2 ? 1 : 2);
        if (level > 0) // certainly within the band by the enclosing box's distance: no query
        {
          const double bound = farChildBound(lastDist[level - 1], sub, last[level - 1], big);
          if (bound - sub.radius <= bandWorld)
          {
            last[level] = sub;
            lastDist[level] = bound;
            return 0;
          }
        }
        // nothing within `reach` proves the box past the band (farPastBand
        // holds for every distance beyond it): the query need not look farther
        const double reach = (bandWorld * (1 + 1e-12) + sub.radius + margin) / (1 - 1e-12) * (1 + 1e-12);
        const NearestResult q = index.nearest(sub.centre, hint, reach * reach * (1 + 1e-12));
        if (q.tri < 0) return 1;
        hint = q.tri;
        const double dq = std::sqrt(q.dist2);
        last[level] = sub;
        lastDist[level] = dq;
        return farPastBand(dq, sub, bandWorld, margin) ? 1 : 0;
      },
      [&](const long long c[3], int s) {
        cells.sign[static_cast<std::size_t>(c[0] + cells.count[0] * (c[1] + cells.count[1] * c[2]))] =
          static_cast<std::int8_t>(s);
      });
  }
  return decided;
}

std::vector<FarCone> farCones(const Bvh& bvh, const std::vector<Tri>& tris)
{
  // bottom-up (children have larger ids than their parent: preorder); angles
  // by atan2 (accurate near 0, unlike acos), rounded up
  const std::vector<Bvh::Node>& nodes = bvh.nodes();
  const std::vector<std::int32_t>& order = bvh.order();
  std::vector<FarCone> cones(nodes.size());
  std::vector<double> angle(nodes.size(), 4.0);
  auto angleTo = [](V3 a, V3 n) { return std::atan2(norm(cross(a, n)), dot(a, n)) * (1 + 1e-12) + 1e-12; };
  for (std::size_t k = nodes.size(); k-- > 0;)
  {
    const Bvh::Node& n = nodes[k];
    V3 axis;
    bool ok = true;
    double edgeDelta = 0, faceDot = 0, minHeight = 1e300, longest = 0;
    // the sign planes' normals of a triangle (farTriAgrees)
    auto normalsOf = [&](const Tri& t, auto&& f) {
      f(t.n);
      for (int e = 0; e < 3; ++e)
      {
        f(t.en[e]);
        f(t.vn[e]);
      }
    };
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
      {
        const Tri& t = tris[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
        ok = ok && farShaped(t);
        normalsOf(t, [&](V3 m) { axis = axis + m; });
        const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
        const double l = std::max({ norm(ab), norm(ac), norm(t.v[2] - t.v[1]) });
        longest = std::max(longest, l);
        minHeight = std::min(minHeight, norm(cross(ab, ac)) / l);
        faceDot = std::max(faceDot, std::fabs(dot(ab, t.n)) + std::fabs(dot(ac, t.n)));
        for (int e = 0; e < 3; ++e) edgeDelta = std::max(edgeDelta, std::fabs(dot(t.v[(e + 1) % 3] - t.v[e], t.en[e])));
      }
    }
    else
    {
      const FarCone &l = cones[static_cast<std::size_t>(n.left)], &r = cones[static_cast<std::size_t>(n.right)];
      ok = l.ok && r.ok;
      axis = V3{ l.axis[0], l.axis[1], l.axis[2] } + V3{ r.axis[0], r.axis[1], r.axis[2] };
      edgeDelta = std::max(l.edgeDelta, r.edgeDelta);
      faceDot = std::max(l.faceDot, r.faceDot);
      minHeight = std::min(l.minHeight, r.minHeight);
      longest = std::max(l.longest, r.longest);
    }
    const double len = norm(axis);
    if (!ok || !(len > 0)) continue;
    axis = (1.0 / len) * axis;
    double t = 0;
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
        normalsOf(tris[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])],
          [&](V3 m) { t = std::max(t, angleTo(axis, m)); });
    }
    else
    {
      for (std::int32_t c : { n.left, n.right })
      {
        const FarCone& cc = cones[static_cast<std::size_t>(c)];
        t = std::max(t, angleTo(axis, V3{ cc.axis[0], cc.axis[1], cc.axis[2] }) + angle[static_cast<std::size_t>(c)]);
      }
    }
    angle[k] = t;
    if (t >= 1.5) continue; // about 86 degrees: too wide to decide anything
    FarCone& c = cones[k];
    c.axis[0] = axis.x;
    c.axis[1] = axis.y;
    c.axis[2] = axis.z;
    c.cosT = std::cos(t) - 1e-12;
    c.sinT = std::sin(t) + 1e-12;
    c.edgeDelta = edgeDelta * (1 + 1e-12);
    c.faceDot = faceDot * (1 + 1e-12);
    c.minHeight = minHeight * (1 - 1e-12);
    c.longest = longest * (1 + 1e-12);
    c.ok = 1;
  }
  return cones;
}

} // namespace detail::meshtosdf
} // namespace lvdif
