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

namespace
{
/// What both classifications share: the box's size and blocks, the cells
/// sized and cleared, the FarBox of a sub-box, and the recording of a
/// decided cell's voxels.
struct FarSetup
{
  const GridGeometry& grid;
  const VoxelBox& box;
  FarCells& cells;
  double big;
  long long n[3];
  std::int64_t blocks[3], total;

  FarSetup(const GridGeometry& g, const VoxelBox& b, FarCells& c, double scale)
    : grid(g)
    , box(b)
    , cells(c)
    , big(scale)
  {
    for (int a = 0; a < 3; ++a)
    {
      n[a] = box.hi[a] - box.lo[a] + 1;
      cells.count[a] = (n[a] + FarCell - 1) / FarCell;
      blocks[a] = (n[a] + FarBlock - 1) / FarBlock;
    }
    total = blocks[0] * blocks[1] * blocks[2];
    const std::size_t cellCount = static_cast<std::size_t>(cells.count[0] * cells.count[1] * cells.count[2]);
    cells.sign.assign(cellCount, 0);
    cells.mask.assign(cellCount, 0);
  }
  V3 pos(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return V3{ grid.origin[0] + i * grid.spacing[0], grid.origin[1] + j * grid.spacing[1],
      grid.origin[2] + k * grid.spacing[2] };
  }
  /// The box of voxels [v0, v0 + edge) (box-relative, clipped).
  void boxOf(const long long v0[3], long long edge, FarBox& out) const
  {
    std::int64_t hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = std::min<std::int64_t>(v0[a] + edge, n[a]) - 1;
    out = farBox(pos(box.lo[0] + v0[0], box.lo[1] + v0[1], box.lo[2] + v0[2]),
      pos(box.lo[0] + hi[0], box.lo[1] + hi[1], box.lo[2] + hi[2]), big);
  }
  void blockOrigin(std::int64_t b, long long origin[3]) const
  {
    origin[0] = (b % blocks[0]) * FarBlock;
    origin[1] = ((b / blocks[0]) % blocks[1]) * FarBlock;
    origin[2] = (b / (blocks[0] * blocks[1])) * FarBlock;
  }
  /// set(cell, sign, mask) of farClassifyBlock / farFill.
  void set(const long long c[3], int s, int m) const
  {
    const std::size_t at = static_cast<std::size_t>(c[0] + cells.count[0] * (c[1] + cells.count[1] * c[2]));
    cells.sign[at] = static_cast<std::int8_t>(s);
    cells.mask[at] = static_cast<std::uint8_t>(cells.mask[at] | m);
  }
};
} // namespace

std::int64_t classifyFarCells(const NearestIndex& index, const Bvh& bvh, const std::vector<FarCone>& cones,
  const PreparedMesh& mesh, const GridGeometry& grid, const VoxelBox& box, double bandWorld, bool pseudo,
  FarCells& cells)
{
  const FarSetup fs(grid, box, cells, farScale(mesh, grid));
  const double margin = farMargin(fs.big, static_cast<double>(mesh.tris.size()));
  const Bvh::Node* nodes = bvh.nodes().data();
  const std::int32_t* order = bvh.order().data();
  auto triAt = [&](int i) { return farTriOf(mesh, static_cast<std::size_t>(order[i]), pseudo); };
  auto boxOf = [&](const long long v0[3], long long edge, FarBox& out) { fs.boxOf(v0, edge, out); };
  auto set = [&](const long long c[3], int s, int m) { fs.set(c, s, m); };
  std::int64_t decided = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : decided)
  for (std::int64_t b = 0; b < fs.total; ++b)
  {
    long long origin[3];
    fs.blockOrigin(b, origin);
    std::int32_t hint = -1;
    auto nearest = [&](V3 centre) {
      const NearestResult q = index.nearest(centre, hint, 1e300);
      FarQuery r;
      if (q.tri < 0) return r;
      hint = q.tri;
      r.found = true;
      r.tri = &mesh.tris[static_cast<std::size_t>(q.tri)];
      r.dist = std::sqrt(q.dist2);
      r.side = farSideAt(farTriOf(mesh, static_cast<std::size_t>(q.tri), pseudo), q.closest, centre, pseudo);
      return r;
    };
    decided += farClassifyBlock(nodes, cones.data(), triAt, nearest, pseudo, bandWorld, margin, fs.big, origin, fs.n,
      boxOf, set);
  }
  return decided;
}

std::int64_t classifyBandCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
  const VoxelBox& box, double bandWorld, FarCells& cells)
{
  const FarSetup fs(grid, box, cells, farScale(mesh, grid));
  const double margin = farMargin(fs.big, static_cast<double>(mesh.tris.size()));
  auto set = [&](const long long c[3], int s, int m) { fs.set(c, s, m); };
  constexpr long long Half = FarBlock / 2;
  std::int64_t decided = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : decided)
  for (std::int64_t b = 0; b < fs.total; ++b)
  {
    long long v0[3];
    fs.blockOrigin(b, v0);
    std::int32_t hint = -1;
    // whether the box of edge^3 voxels at o is past the band; dist: its
    // centre's distance when a query found it (an upper bound that spares
    // its sub-boxes a query when it shows them within the band), else -1
    auto past = [&](const long long o[3], long long edge, const FarBox* parent, double parentDist, FarBox& fb,
                  double& dist) {
      fs.boxOf(o, edge, fb);
      dist = -1;
      if (parent && parentDist >= 0)
      {
        const double bound = farChildBound(parentDist, fb, *parent, fs.big);
        if (bound - fb.radius <= bandWorld)
        {
          dist = bound;
          return false;
        }
      }
      // nothing within `reach` proves the box past the band (farPastBand
      // holds for every distance beyond it): the query need not look farther
      const double reach = (bandWorld * (1 + 1e-12) + fb.radius + margin) / (1 - 1e-12) * (1 + 1e-12);
      const NearestResult q = index.nearest(fb.centre, hint, reach * reach * (1 + 1e-12));
      if (q.tri < 0) return true;
      hint = q.tri;
      dist = std::sqrt(q.dist2);
      return farPastBand(dist, fb, bandWorld, margin);
    };
    FarBox b0, b1;
    double d0, d1;
    if (past(v0, FarBlock, nullptr, -1, b0, d0))
    {
      decided += farFill(v0, FarBlock, fs.n, 1, set);
      continue;
    }
    // blocks and their halves only: the band bricks (MeshToSdf.cpp) take the
    // rest, a brick past the band for one bounded query, cheaper than the
    // cells' eight (measured: the bunny at 512 about 10 % faster without them)
    for (int h = 0; h < 8; ++h)
    {
      const long long o1[3] = { v0[0] + Half * (h & 1), v0[1] + Half * ((h >> 1) & 1), v0[2] + Half * (h >> 2) };
      if (o1[0] >= fs.n[0] || o1[1] >= fs.n[1] || o1[2] >= fs.n[2]) continue;
      if (past(o1, Half, &b0, d0, b1, d1)) decided += farFill(o1, Half, fs.n, 1, set);
    }
  }
  return decided;
}

std::vector<FarCone> farCones(const Bvh& bvh, const PreparedMesh& mesh)
{
  require(mesh.pseudoNormals, "far blocks: the node cones need the pseudo-normals");
  const TriList& tris = mesh.tris;
  // bottom-up (children have larger ids than their parent: preorder); angles
  // by atan2 (accurate near 0, unlike acos), rounded up. The leaves, most of
  // the work (every triangle's 7 normals), are independent: on the OpenMP
  // threads first (a warm GPU call computes this every time), then the inner
  // nodes in turn; each node's arithmetic is the same either way.
  const auto& nodes = bvh.nodes();
  const auto& order = bvh.order();
  std::vector<FarCone> cones(nodes.size());
  std::vector<double> angle(nodes.size(), 4.0);
  auto angleTo = [](V3 a, V3 n) { return std::atan2(norm(cross(a, n)), dot(a, n)) * (1 + 1e-12) + 1e-12; };
  auto coneOf = [&](std::size_t k) {
    const Bvh::Node& n = nodes[k];
    V3 axis;
    bool ok = true;
    double edgeDelta = 0, faceDot = 0, minHeight = 1e300, longest = 0;
    // the sign planes' normals of a triangle (farTriAgrees)
    auto normalsOf = [&](std::size_t tri, auto&& f) {
      f(tris[tri].n);
      const TriNormals& pn = mesh.normals[tri];
      for (int e = 0; e < 3; ++e)
      {
        f(pn.en[e]);
        f(pn.vn[e]);
      }
    };
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
      {
        const std::size_t tri = static_cast<std::size_t>(order[static_cast<std::size_t>(i)]);
        const Tri& t = tris[tri];
        const TriNormals& pn = mesh.normals[tri];
        ok = ok && farShaped(t);
        normalsOf(tri, [&](V3 m) { axis = axis + m; });
        const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
        const double l = std::max({ norm(ab), norm(ac), norm(t.v[2] - t.v[1]) });
        longest = std::max(longest, l);
        minHeight = std::min(minHeight, norm(cross(ab, ac)) / l);
        faceDot = std::max(faceDot, std::fabs(dot(ab, t.n)) + std::fabs(dot(ac, t.n)));
        for (int e = 0; e < 3; ++e) edgeDelta = std::max(edgeDelta, std::fabs(dot(t.v[(e + 1) % 3] - t.v[e], pn.en[e])));
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
    if (!ok || !(len > 0)) return;
    axis = (1.0 / len) * axis;
    double t = 0;
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
        normalsOf(static_cast<std::size_t>(order[static_cast<std::size_t>(i)]),
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
    if (t >= 1.5) return; // about 86 degrees: too wide to decide anything
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
  };
  const std::int64_t count = static_cast<std::int64_t>(nodes.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t k = 0; k < count; ++k)
    if (nodes[static_cast<std::size_t>(k)].left < 0) coneOf(static_cast<std::size_t>(k));
  for (std::size_t k = nodes.size(); k-- > 0;)
    if (nodes[k].left >= 0) coneOf(k);
  return cones;
}

} // namespace detail::meshtosdf
} // namespace lvdif
