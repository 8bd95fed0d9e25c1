// Which changed voxels can change a marching cubes mesh of iso value t.
//
// A mesh chunk's mesh (ChunkedMarchingCubes, CPU and CUDA alike) is a function
// of the voxels of its points box grown by one (its gather region):
//   - which cells and edges are cut, and so the triangles, edge ids and
//     triangle cells: the side (value >= t or not) of every point;
//   - a vertex on the cut edge (p, q): the values at p and q (position), the
//     gradients at p and q (normal; central or one-sided differences, so the
//     values of the 6 axis neighbours of p and of q), the colours at p and q;
//   - the corner colour keys of each cut cell.
// So a voxel v is read for its value or colour only when the points S(v) = its
// 3^3 box and the 6 points 2 away along an axis hold both sides, two points of
// the chunk's points box among them: v = p has q in its 3^3 box; v = p +- e_a
// has p in its box and q = p + e_b in its box (a != b) or 2 away along axis b
// (v = p - e_b); a cut cell's corner has the whole cell in its box.
//
// Claim: if no changed voxel of C's gather region G has (a) changed side or
// (b) both sides in S(v) after the edit, C's mesh is the same. By (a) no point
// of G changed side, so the cut cells and edges of C are the same before and
// after; a voxel read for its value or colour then has the two points that make
// it read, on both sides, in S(v) after the edit, so by (b) it did not change.
// Hence the mesh reads the same numbers. (Transitive: the union of the boxes of
// two edits covers the two in a row, as Editor's merge of a stroke does.)
// The edit reports, per changed storage chunk, the box of the voxels with (a)
// or (b); ChunkedMarchingCubes::chunksAffectedBy(box) names exactly the mesh
// chunks whose gather region meets the box (EditSession's meshChunksToRemesh).
// Tested against re-meshing everything: EditSession.SurfaceRuleCoversBruteForce.
#include "BrushSurface.h"

#include "lvdif/SdfDictionary.h"

#include <algorithm>
#include <cstring>

namespace lvdif
{
namespace detail::edit
{

namespace
{
std::uint64_t ones(std::int64_t n)
{
  return n >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1;
}

int lowBit(std::uint64_t m) { return __builtin_ctzll(m); }
int highBit(std::uint64_t m) { return 63 - __builtin_clzll(m); }
} // namespace

namespace
{
// Bit i = (row[i].sdf >= isoKey), n <= 64: a byte per voxel (vectorises), then 8 bytes of 0/1 into 8 bits by one
// multiply (byte k lands on bit 56 + k)
std::uint64_t sideBits(const Voxel* row, std::int64_t n, std::int32_t isoKey)
{
  alignas(8) std::uint8_t f[64] = {};
  for (std::int64_t i = 0; i < n; ++i)
    f[i] = std::int32_t(row[i].sdf) >= isoKey;
  std::uint64_t bits = 0;
  for (std::int64_t k = 0; k < n; k += 8)
  {
    std::uint64_t w;
    std::memcpy(&w, f + k, 8);
    bits |= ((w * 0x0102040810204080ULL) >> 56) << k;
  }
  return bits;
}
} // namespace

void addMixedPending(const DictionaryVolume& volume, std::int32_t isoKey, std::int64_t id, const SurfacePending& pending,
  VoxelBox& box)
{
  if (pending.rows.empty())
    return;
  const std::int64_t E = volume.chunkEdge();
  const VoxelBox cb = volume.chunkBox(id);
  // the pending voxels the box does not hold yet, and their bounding box
  const std::uint64_t inBoxX = box.empty() || box.hi[0] < cb.lo[0] || box.lo[0] > cb.hi[0]
    ? 0
    : ones(std::min(box.hi[0], cb.hi[0]) - cb.lo[0] + 1) & ~ones(std::max(box.lo[0], cb.lo[0]) - cb.lo[0]);
  thread_local std::vector<std::uint64_t> todo;
  todo.assign(pending.rows.size(), 0);
  VoxelBox pb;
  for (std::int64_t z = cb.lo[2]; z <= cb.hi[2]; ++z)
    for (std::int64_t y = cb.lo[1]; y <= cb.hi[1]; ++y)
    {
      const std::size_t r = static_cast<std::size_t>((y - cb.lo[1]) + E * (z - cb.lo[2]));
      std::uint64_t m = pending.rows[r];
      if (m && !box.empty() && y >= box.lo[1] && y <= box.hi[1] && z >= box.lo[2] && z <= box.hi[2])
        m &= ~inBoxX;
      if (!m)
        continue;
      todo[r] = m;
      pb.include(cb.lo[0] + lowBit(m), y, z);
      pb.include(cb.lo[0] + highBit(m), y, z);
    }
  if (pb.empty())
    return;
  // the voxels within 2 of those
  VoxelBox f;
  for (int a = 0; a < 3; ++a)
  {
    f.lo[a] = pb.lo[a] - 2;
    f.hi[a] = pb.hi[a] + 2;
  }
  f = f.intersect(volume.bounds());
  // the sides as bit rows (bit i: x = f.lo[0] + i); voxels outside the volume are on neither
  const std::int64_t nx = f.hi[0] - f.lo[0] + 1, ny = f.hi[1] - f.lo[1] + 1, nz = f.hi[2] - f.lo[2] + 1;
  thread_local std::vector<std::uint64_t> above, below;
  above.assign(static_cast<std::size_t>(ny * nz), 0);
  below.assign(static_cast<std::size_t>(ny * nz), 0);
  const std::uint64_t inside = ones(nx);
  // only the rows some pending voxel's neighbourhood meets (a crescent's box is mostly empty)
  thread_local std::vector<std::uint8_t> needed;
  needed.assign(static_cast<std::size_t>(ny * nz), 0);
  for (std::int64_t z = pb.lo[2]; z <= pb.hi[2]; ++z)
    for (std::int64_t y = pb.lo[1]; y <= pb.hi[1]; ++y)
      if (todo[static_cast<std::size_t>((y - cb.lo[1]) + E * (z - cb.lo[2]))])
        for (std::int64_t dz = -2; dz <= 2; ++dz)
          for (std::int64_t dy = -2; dy <= 2; ++dy)
          {
            const std::int64_t yy = y + dy, zz = z + dz;
            if ((dy < -1 || dy > 1 || dz < -1 || dz > 1) && dy != 0 && dz != 0)
              continue; // not in the 3 x 3 rows nor 2 away along y or z
            if (yy >= f.lo[1] && yy <= f.hi[1] && zz >= f.lo[2] && zz <= f.hi[2])
              needed[static_cast<std::size_t>((yy - f.lo[1]) + ny * (zz - f.lo[2]))] = 1;
          }
  // the chunks f can reach: this one and its neighbours (f is within 2 of it)
  struct Near
  {
    const Voxel* data = nullptr;
    bool uniformAbove = false;
  };
  Near near[27];
  const Index3 c0{ cb.lo[0] / E - 1, cb.lo[1] / E - 1, cb.lo[2] / E - 1 };
  const Index3& counts = volume.chunkCounts();
  for (int k = 0; k < 27; ++k)
  {
    const std::int64_t cx = c0[0] + k % 3, cy = c0[1] + (k / 3) % 3, cz = c0[2] + k / 9;
    if (cx < 0 || cy < 0 || cz < 0 || cx >= counts[0] || cy >= counts[1] || cz >= counts[2])
      continue;
    const std::int64_t s = volume.chunkId(cx, cy, cz);
    near[k].data = volume.chunkData(s);
    near[k].uniformAbove = std::int32_t(volume.uniformValue(s).sdf) >= isoKey;
  }
  for (std::int64_t z = f.lo[2]; z <= f.hi[2]; ++z)
    for (std::int64_t y = f.lo[1]; y <= f.hi[1]; ++y)
    {
      if (!needed[static_cast<std::size_t>((y - f.lo[1]) + ny * (z - f.lo[2]))])
        continue;
      std::uint64_t up = 0;
      const std::int64_t kyz = 3 * (y / E - c0[1]) + 9 * (z / E - c0[2]);
      for (std::int64_t x = f.lo[0]; x <= f.hi[0];)
      {
        const std::int64_t end = std::min(f.hi[0], (x / E + 1) * E - 1);
        const Near& c = near[x / E - c0[0] + kyz];
        const int shift = static_cast<int>(x - f.lo[0]);
        const std::int64_t m = end - x + 1;
        if (c.data)
          up |= sideBits(c.data + volume.localIndex(x, y, z), m, isoKey) << shift;
        else if (c.uniformAbove)
          up |= ones(m) << shift;
        x = end + 1;
      }
      const std::size_t r = static_cast<std::size_t>((y - f.lo[1]) + ny * (z - f.lo[2]));
      above[r] = up;
      below[r] = inside & ~up;
    }
  // Each pending voxel v: both sides among the voxels a mesh could read v for
  // (BrushSurface.h): v's 3^3 box and the points 2 away along an axis.
  auto at = [&](const std::vector<std::uint64_t>& rows, std::int64_t y, std::int64_t z) -> std::uint64_t {
    if (y < f.lo[1] || y > f.hi[1] || z < f.lo[2] || z > f.hi[2])
      return 0;
    return rows[static_cast<std::size_t>((y - f.lo[1]) + ny * (z - f.lo[2]))];
  };
  for (std::int64_t z = pb.lo[2]; z <= pb.hi[2]; ++z)
    for (std::int64_t y = pb.lo[1]; y <= pb.hi[1]; ++y)
    {
      std::uint64_t m = todo[static_cast<std::size_t>((y - cb.lo[1]) + E * (z - cb.lo[2]))];
      if (!m)
        continue;
      // into f's frame (f.lo[0] is cb.lo[0] - 2 .. cb.lo[0] + E - 1)
      const std::int64_t off = cb.lo[0] - f.lo[0];
      m = off >= 0 ? m << off : m >> -off;
      std::uint64_t up = 0, down = 0;
      for (std::int64_t dz = -1; dz <= 1; ++dz)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
        {
          const std::uint64_t a = at(above, y + dy, z + dz), b = at(below, y + dy, z + dz);
          up |= a | (a << 1) | (a >> 1);
          down |= b | (b << 1) | (b >> 1);
        }
      const std::uint64_t a = at(above, y, z), b = at(below, y, z);
      up |= (a << 2) | (a >> 2) | at(above, y - 2, z) | at(above, y + 2, z) | at(above, y, z - 2) | at(above, y, z + 2);
      down |= (b << 2) | (b >> 2) | at(below, y - 2, z) | at(below, y + 2, z) | at(below, y, z - 2) | at(below, y, z + 2);
      const std::uint64_t hit = m & up & down;
      if (!hit)
        continue;
      box.include(f.lo[0] + lowBit(hit), y, z);
      box.include(f.lo[0] + highBit(hit), y, z);
    }
}

} // namespace detail::edit
} // namespace lvdif
