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

namespace
{
/// The side every voxel of the box is on (-1, +1), or 0 when undecided.
int farSide(const NearestIndex& index, const std::vector<Tri>& tris, const FarBox& box, double bandWorld,
  double margin, std::int32_t& hint)
{
  const NearestResult r = index.nearest(box.centre, hint, 1e300);
  if (r.tri < 0) return 0;
  hint = r.tri;
  const double dist = std::sqrt(r.dist2);
  if (!farPastBand(dist, box, bandWorld, margin)) return 0;
  const double reach = farRadius(dist, box, margin);
  int side = 0;
  const bool all = index.visitWithin(box.centre, reach * reach, [&](std::int32_t t, const V3* v) {
    const int s = farFaceSide(v[0], v[1], v[2], tris[static_cast<std::size_t>(t)].n, box, reach, margin);
    if (s == 2) return true;
    if (s == 0 || (side != 0 && s != side)) return false;
    side = s;
    return true;
  });
  return all ? side : 0;
}
} // namespace

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

std::int64_t classifyFarCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
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
  // the box of voxels [v0, v0 + edge) (box-relative, clipped)
  auto boxOf = [&](const std::int64_t v0[3], std::int64_t edge) {
    std::int64_t hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = std::min(v0[a] + edge, n[a]) - 1;
    return farBox(pos(box.lo[0] + v0[0], box.lo[1] + v0[1], box.lo[2] + v0[2]),
      pos(box.lo[0] + hi[0], box.lo[1] + hi[1], box.lo[2] + hi[2]), big);
  };
  constexpr int Sub = FarBlock / FarCell;
  const std::int64_t total = blocks[0] * blocks[1] * blocks[2];
  std::int64_t decided = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : decided)
  for (std::int64_t b = 0; b < total; ++b)
  {
    const std::int64_t bi[3] = { b % blocks[0], (b / blocks[0]) % blocks[1], b / (blocks[0] * blocks[1]) };
    const std::int64_t v0[3] = { bi[0] * FarBlock, bi[1] * FarBlock, bi[2] * FarBlock };
    std::int32_t hint = -1;
    const int whole = farSide(index, mesh.tris, boxOf(v0, FarBlock), bandWorld, margin, hint);
    for (int d = 0; d < Sub * Sub * Sub; ++d)
    {
      const std::int64_t c[3] = { bi[0] * Sub + d % Sub, bi[1] * Sub + (d / Sub) % Sub, bi[2] * Sub + d / (Sub * Sub) };
      if (c[0] >= cells.count[0] || c[1] >= cells.count[1] || c[2] >= cells.count[2]) continue;
      const std::int64_t c0[3] = { c[0] * FarCell, c[1] * FarCell, c[2] * FarCell };
      const int s = whole != 0 ? whole : farSide(index, mesh.tris, boxOf(c0, FarCell), bandWorld, margin, hint);
      if (s == 0) continue;
      cells.sign[static_cast<std::size_t>(c[0] + cells.count[0] * (c[1] + cells.count[1] * c[2]))] =
        static_cast<std::int8_t>(s);
      decided += (std::min(c0[0] + FarCell, n[0]) - c0[0]) * (std::min(c0[1] + FarCell, n[1]) - c0[1]) *
        (std::min(c0[2] + FarCell, n[2]) - c0[2]);
    }
  }
  return decided;
}

} // namespace detail::meshtosdf
} // namespace lvdif
