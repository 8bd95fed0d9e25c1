// The CPU marching cubes kernel for one gathered chunk (Lorensen & Cline 1987),
// swept layer by layer in z as in Synchronized Templates (Montani et al.
// 1994): vertex ids of the cut edges of two point layers are kept in small
// arrays, so each cut edge gets one vertex (indexed output) and memory is
// O(chunkEdge^2).
#include "MarchingCubesImpl.h"
#include "MarchingCubesVertex.h"

#include "lvdif/MarchingCubesTables.h"

#include <algorithm>
#include <cstring>

namespace lvdif
{
namespace
{

/// Float values (a float grid, or a decoded copy) and decoded colours.
struct FloatSource
{
  const float* values;
  const Rgba* colors; // or null
  const ColorKey* keys; // corner colour keys, or null
  float iso;
  bool hasColors() const { return colors != nullptr; }
  float value(std::int64_t l) const { return values[l]; }
  bool above(std::int64_t l) const { return values[l] >= iso; }
  Rgba color(std::int64_t l) const { return colors[l]; }
  ColorKey key(std::int64_t l) const { return keys[l]; }
};

/// A dictionary volume's voxels as they are (ChunkInput::voxels): the side by
/// key, the value and colour decoded only where read (the same numbers).
struct VoxelSource
{
  const Voxel* voxels;
  const float* table;
  const Rgba* palette; // or null (no colours)
  std::int32_t isoKey;
  bool hasColors() const { return palette != nullptr; }
  float value(std::int64_t l) const { return table[voxels[l].sdf]; }
  bool above(std::int64_t l) const { return std::int32_t(voxels[l].sdf) >= isoKey; }
  Rgba color(std::int64_t l) const { return palette[voxels[l].color]; }
  ColorKey key(std::int64_t l) const { return voxels[l].color; }
};

template <typename Source>
struct Sweep
{
  const ChunkedMarchingCubes::Impl& impl;
  const ChunkedMarchingCubes::ChunkInput& in;
  ChunkMesh& out;
  bool normals;
  Source src;

  float value(std::int64_t x, std::int64_t y, std::int64_t z) const { return src.value(in.local(x, y, z)); }

  void gradientAt(std::int64_t x, std::int64_t y, std::int64_t z, float g[3]) const
  {
    const std::int64_t p[3] = { x, y, z };
    const float mid = value(x, y, z);
    for (int a = 0; a < 3; ++a)
    {
      std::int64_t lo[3] = { x, y, z }, hi[3] = { x, y, z };
      const std::int64_t n = impl.Dims[a];
      float l = mid, h = mid;
      if (p[a] > 0)
      {
        lo[a] -= 1;
        l = value(lo[0], lo[1], lo[2]);
      }
      if (p[a] < n - 1)
      {
        hi[a] += 1;
        h = value(hi[0], hi[1], hi[2]);
      }
      g[a] = detail::mc::gradient(l, mid, h, p[a], n, impl.InvSpacing[a]);
    }
  }

  /// Adds the vertex on the edge from point (x,y,z) along axis.
  std::uint32_t addVertex(std::int64_t x, std::int64_t y, std::int64_t z, int axis)
  {
    std::int64_t q[3] = { x, y, z };
    q[axis] += 1;
    const float a = value(x, y, z), b = value(q[0], q[1], q[2]);
    const float t = detail::mc::edgeT(impl.Options.isoValue, a, b);
    const std::int64_t p[3] = { x, y, z };
    Vec3f pos;
    for (int k = 0; k < 3; ++k)
      pos[k] = detail::mc::coord(impl.Origin[k], impl.Spacing[k], p[k] + impl.Options.gridOffset[k], k == axis ? t : 0.0f);
    const std::uint32_t id = static_cast<std::uint32_t>(out.points.size());
    out.points.push_back(pos);
    out.edgeIds.push_back(3 * static_cast<std::uint64_t>(x + impl.Dims[0] * (y + impl.Dims[1] * z)) +
      static_cast<std::uint64_t>(axis));
    if (normals)
    {
      float g0[3], g1[3];
      gradientAt(x, y, z, g0);
      gradientAt(q[0], q[1], q[2], g1);
      Vec3f nrm{ detail::mc::lerp(g0[0], g1[0], t), detail::mc::lerp(g0[1], g1[1], t), detail::mc::lerp(g0[2], g1[2], t) };
      detail::mc::normalize(nrm[0], nrm[1], nrm[2]);
      out.normals.push_back(nrm);
    }
    if (src.hasColors())
    {
      const Rgba c0 = src.color(in.local(x, y, z)), c1 = src.color(in.local(q[0], q[1], q[2]));
      out.colors.push_back(Rgba{ detail::mc::lerpChannel(c0.r, c1.r, t), detail::mc::lerpChannel(c0.g, c1.g, t),
        detail::mc::lerpChannel(c0.b, c1.b, t), detail::mc::lerpChannel(c0.a, c1.a, t) });
    }
    return id;
  }
};

} // namespace

namespace
{
/// Per point row of a layer: the first and last x-edge whose two points are
/// on different sides (Flying Edges' trim, Schroeder et al. 2015). Points
/// 0..L all equal the row's first point, points R+1.. its last point. A row
/// without cut: L = px-1 (its last point), R = -1.
struct RowTrim
{
  std::int32_t L, R;
};

/// Calls f(i) for the points i in 0..px-1 where rows a and b (of flags) differ,
/// testing only where the trims say they can (both rows are constant outside).
template <typename F>
void forDiffering(const std::uint8_t* a, const std::uint8_t* b, RowTrim ta, RowTrim tb, std::int64_t px, F&& f)
{
  const std::int64_t m = std::min(ta.L, tb.L), M = std::max(ta.R, tb.R) + 1;
  if (a[0] != b[0])
    for (std::int64_t i = 0; i <= m; ++i) f(i);
  for (std::int64_t i = m + 1; i < M; ++i)
    if (a[i] != b[i]) f(i);
  if (a[px - 1] != b[px - 1])
    for (std::int64_t i = std::max(M, m + 1); i < px; ++i) f(i);
}
} // namespace

namespace
{
template <typename Source>
ChunkMesh meshWith(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in, const Source& source,
  bool keys)
{
  const MarchingCubesTables& T = *impl.Tables;
  ChunkMesh out;
  out.chunkId = in.chunkId;
  out.chunkCoord = impl.globalCoord(in.chunkId);
  out.cells = in.cells;
  Sweep<Source> s{ impl, in, out, impl.Options.computeNormals, source };
  const bool cells = impl.wantsTriangleCells();
  const VoxelBox& c = in.cells;
  const std::int64_t ex = c.hi[0] - c.lo[0] + 1, ey = c.hi[1] - c.lo[1] + 1, ez = c.hi[2] - c.lo[2] + 1;
  const std::int64_t px = ex + 1, py = ey + 1, plane = px * py;
  // per point layer (two kept): above flags, row trims, vertex ids of x- and y-edges; z-edges of one slab
  std::vector<std::uint8_t> above(2 * plane);
  std::vector<RowTrim> trim(2 * py);
  std::vector<std::uint32_t> xv(2 * plane), yv(2 * plane), zv(plane);
  for (std::int64_t kz = 0; kz <= ez; ++kz)
  {
    const std::int64_t z = c.lo[2] + kz;
    const int cur = static_cast<int>(kz & 1), prev = cur ^ 1;
    std::uint8_t* A = above.data() + cur * plane;
    const std::uint8_t* B = above.data() + prev * plane;
    RowTrim* TA = trim.data() + cur * py;
    const RowTrim* TB = trim.data() + prev * py;
    bool any = false, all = true;
    for (std::int64_t j = 0; j < py; ++j)
    {
      const std::int64_t row = in.local(c.lo[0], c.lo[1] + j, z);
      std::uint8_t* a = A + px * j;
      std::uint8_t rowOr = 0, rowAnd = 1;
      for (std::int64_t i = 0; i < px; ++i)
      {
        const std::uint8_t f = source.above(row + i);
        a[i] = f;
        rowOr |= f;
        rowAnd &= f;
      }
      any |= rowOr != 0;
      all &= rowAnd != 0;
      RowTrim t{ static_cast<std::int32_t>(px - 1), -1 };
      if (rowOr != rowAnd)
      {
        std::int64_t l = 0, r = ex - 1;
        while (a[l] == a[l + 1]) ++l;
        while (a[r] == a[r + 1]) --r;
        t = RowTrim{ static_cast<std::int32_t>(l), static_cast<std::int32_t>(r) };
      }
      TA[j] = t;
    }
    const bool layerCut = any && !all;
    std::uint32_t* X = xv.data() + cur * plane;
    std::uint32_t* Y = yv.data() + cur * plane;
    if (layerCut)
    {
      for (std::int64_t j = 0; j < py; ++j)
      {
        const std::uint8_t* a = A + px * j;
        const std::int64_t y = c.lo[1] + j;
        for (std::int64_t i = TA[j].L; i <= TA[j].R; ++i)
          if (a[i] != a[i + 1]) X[i + px * j] = s.addVertex(c.lo[0] + i, y, z, 0);
        if (j < ey)
          forDiffering(a, a + px, TA[j], TA[j + 1], px,
            [&](std::int64_t i) { Y[i + px * j] = s.addVertex(c.lo[0] + i, y, z, 1); });
      }
    }
    if (kz == 0) continue;
    // z-edges between the previous layer and this one, then the cells of that slab
    bool slabCut = layerCut;
    for (std::int64_t o = 0; o < plane && !slabCut; ++o) slabCut = A[o] != B[0] || B[o] != B[0];
    if (!slabCut) continue;
    for (std::int64_t j = 0; j < py; ++j)
      forDiffering(A + px * j, B + px * j, TA[j], TB[j], px,
        [&](std::int64_t i) { zv[i + px * j] = s.addVertex(c.lo[0] + i, c.lo[1] + j, z - 1, 2); });
    const std::uint32_t* X0 = xv.data() + prev * plane;
    const std::uint32_t* Y0 = yv.data() + prev * plane;
    for (std::int64_t j = 0; j < ey; ++j)
    {
      auto cellsOf = [&](std::int64_t i0, std::int64_t i1) {
        for (std::int64_t i = i0; i < i1; ++i)
        {
          const std::int64_t o = i + px * j;
          const int cs = B[o] | (B[o + 1] << 1) | (B[o + px] << 2) | (B[o + px + 1] << 3) | (A[o] << 4) |
            (A[o + 1] << 5) | (A[o + px] << 6) | (A[o + px + 1] << 7);
          if (cs == 0 || cs == 255) continue;
          // the cell's 12 edge vertices (edge = 4*axis + 2*bu + bv, see MarchingCubesTables.h)
          std::uint32_t ev[12];
          ev[0] = X0[o];
          ev[1] = X[o];
          ev[2] = X0[o + px];
          ev[3] = X[o + px];
          ev[4] = Y0[o];
          ev[5] = Y0[o + 1];
          ev[6] = Y[o];
          ev[7] = Y[o + 1];
          ev[8] = zv[o];
          ev[9] = zv[o + px];
          ev[10] = zv[o + 1];
          ev[11] = zv[o + 1 + px];
          const std::int8_t* tri = T.triangles[cs];
          const int nt = T.triangleCount[cs];
          for (int t = 0; t < nt; ++t)
          {
            out.triangles.push_back({ ev[tri[3 * t]], ev[tri[3 * t + 1]], ev[tri[3 * t + 2]] });
          }
          if (cells)
          {
            const std::int64_t x = c.lo[0] + i, y = c.lo[1] + j, zc = z - 1;
            const std::int64_t cell = x + impl.Dims[0] * (y + impl.Dims[1] * zc);
            out.triangleCells.insert(out.triangleCells.end(), static_cast<std::size_t>(nt), cell);
            if (keys)
            {
              std::array<ColorKey, 8> k;
              for (int q = 0; q < 8; ++q)
                k[q] = source.key(in.local(x + (q & 1), y + ((q >> 1) & 1), zc + ((q >> 2) & 1)));
              out.cornerColors.insert(out.cornerColors.end(), static_cast<std::size_t>(nt), k);
            }
          }
        }
      };
      // the four point rows of this cell row are constant left of the smallest
      // L and right of the largest R: there every cell has the case of the first
      // (last) cell, so those spans are skipped whole when that case is empty
      const std::int64_t minL = std::min({ TB[j].L, TB[j + 1].L, TA[j].L, TA[j + 1].L });
      const std::int64_t maxR = std::max({ TB[j].R, TB[j + 1].R, TA[j].R, TA[j + 1].R });
      const std::int64_t o = px * j, last = o + ex;
      const bool leftCut = !(B[o] == B[o + px] && B[o] == A[o] && B[o] == A[o + px]);
      const bool rightCut = !(B[last] == B[last + px] && B[last] == A[last] && B[last] == A[last + px]);
      const std::int64_t leftEnd = std::min(minL, ex);
      if (leftCut) cellsOf(0, leftEnd);
      if (minL <= maxR) cellsOf(minL, maxR + 1);
      if (rightCut) cellsOf(std::max(maxR + 1, leftEnd), ex);
    }
  }
  return out;
}

} // namespace

ChunkMesh meshChunkCpu(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in)
{
  if (!in.voxels.empty())
    return meshWith(impl, in,
      VoxelSource{ in.voxels.data(), in.sdfTable, in.palette.empty() ? nullptr : in.palette.data(), in.isoKey },
      impl.wantsCornerColors());
  return meshWith(impl, in,
    FloatSource{ in.valueData(), in.colorData(), in.colorKeys.empty() ? nullptr : in.colorKeys.data(), impl.Options.isoValue },
    impl.wantsCornerColors() && !in.colorKeys.empty());
}

} // namespace lvdif
