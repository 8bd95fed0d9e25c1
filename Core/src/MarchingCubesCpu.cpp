// The CPU marching cubes kernel for one gathered chunk (Lorensen & Cline 1987),
// swept layer by layer in z as in Synchronized Templates (Montani et al.
// 1994): vertex ids of the cut edges of two point layers are kept in small
// arrays, so each cut edge gets one vertex (indexed output) and memory is
// O(chunkEdge^2).
#include "MarchingCubesImpl.h"
#include "MarchingCubesVertex.h"

#include "lvdif/MarchingCubesTables.h"

#include <cstring>

namespace lvdif
{
namespace
{

struct Sweep
{
  const ChunkedMarchingCubes::Impl& impl;
  const ChunkedMarchingCubes::ChunkInput& in;
  ChunkMesh& out;
  bool normals, colors;

  float value(std::int64_t x, std::int64_t y, std::int64_t z) const { return in.values[in.local(x, y, z)]; }

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
      g[a] = mc::gradient(l, mid, h, p[a], n, impl.InvSpacing[a]);
    }
  }

  /// Adds the vertex on the edge from point (x,y,z) along axis.
  std::uint32_t addVertex(std::int64_t x, std::int64_t y, std::int64_t z, int axis)
  {
    std::int64_t q[3] = { x, y, z };
    q[axis] += 1;
    const float a = value(x, y, z), b = value(q[0], q[1], q[2]);
    const float t = mc::edgeT(impl.Options.isoValue, a, b);
    const std::int64_t p[3] = { x, y, z };
    Vec3f pos;
    for (int k = 0; k < 3; ++k)
      pos[k] = mc::coord(impl.Origin[k], impl.Spacing[k], p[k], k == axis ? t : 0.0f);
    const std::uint32_t id = static_cast<std::uint32_t>(out.points.size());
    out.points.push_back(pos);
    out.edgeIds.push_back(3 * static_cast<std::uint64_t>(x + impl.Dims[0] * (y + impl.Dims[1] * z)) +
      static_cast<std::uint64_t>(axis));
    if (normals)
    {
      float g0[3], g1[3];
      gradientAt(x, y, z, g0);
      gradientAt(q[0], q[1], q[2], g1);
      Vec3f nrm{ mc::lerp(g0[0], g1[0], t), mc::lerp(g0[1], g1[1], t), mc::lerp(g0[2], g1[2], t) };
      mc::normalize(nrm[0], nrm[1], nrm[2]);
      out.normals.push_back(nrm);
    }
    if (colors)
    {
      const Rgba c0 = in.colors[in.local(x, y, z)], c1 = in.colors[in.local(q[0], q[1], q[2])];
      out.colors.push_back(Rgba{ mc::lerpChannel(c0.r, c1.r, t), mc::lerpChannel(c0.g, c1.g, t),
        mc::lerpChannel(c0.b, c1.b, t), mc::lerpChannel(c0.a, c1.a, t) });
    }
    return id;
  }
};

} // namespace

ChunkMesh meshChunkCpu(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in)
{
  const MarchingCubesTables& T = marchingCubesTables();
  ChunkMesh out;
  out.chunkId = in.chunkId;
  out.chunkCoord = impl.coord(in.chunkId);
  out.cells = in.cells;
  Sweep s{ impl, in, out, impl.Options.computeNormals, !in.colors.empty() };
  const bool keys = !in.colorKeys.empty();
  const float iso = impl.Options.isoValue;
  const VoxelBox& c = in.cells;
  const std::int64_t ex = c.hi[0] - c.lo[0] + 1, ey = c.hi[1] - c.lo[1] + 1, ez = c.hi[2] - c.lo[2] + 1;
  const std::int64_t px = ex + 1, py = ey + 1, plane = px * py;
  // per point layer (two kept): above flags and vertex ids of x- and y-edges; z-edges of one slab
  std::vector<std::uint8_t> above(2 * plane);
  std::vector<std::uint32_t> xv(2 * plane), yv(2 * plane), zv(plane);
  for (std::int64_t kz = 0; kz <= ez; ++kz)
  {
    const std::int64_t z = c.lo[2] + kz;
    const int cur = static_cast<int>(kz & 1), prev = cur ^ 1;
    std::uint8_t* A = above.data() + cur * plane;
    const std::uint8_t* B = above.data() + prev * plane;
    bool any = false, all = true;
    for (std::int64_t j = 0; j < py; ++j)
    {
      const float* row = in.values.data() + in.local(c.lo[0], c.lo[1] + j, z);
      for (std::int64_t i = 0; i < px; ++i)
      {
        const std::uint8_t f = row[i] >= iso;
        A[i + px * j] = f;
        any |= f != 0;
        all &= f != 0;
      }
    }
    const bool layerCut = any && !all;
    std::uint32_t* X = xv.data() + cur * plane;
    std::uint32_t* Y = yv.data() + cur * plane;
    if (layerCut)
    {
      for (std::int64_t j = 0; j < py; ++j)
        for (std::int64_t i = 0; i < px; ++i)
        {
          const std::int64_t o = i + px * j;
          if (i < ex && A[o] != A[o + 1]) X[o] = s.addVertex(c.lo[0] + i, c.lo[1] + j, z, 0);
          if (j < ey && A[o] != A[o + px]) Y[o] = s.addVertex(c.lo[0] + i, c.lo[1] + j, z, 1);
        }
    }
    if (kz == 0) continue;
    // z-edges between the previous layer and this one, then the cells of that slab
    bool slabCut = layerCut;
    for (std::int64_t o = 0; o < plane && !slabCut; ++o) slabCut = A[o] != B[0] || B[o] != B[0];
    if (!slabCut) continue;
    for (std::int64_t j = 0; j < py; ++j)
      for (std::int64_t i = 0; i < px; ++i)
      {
        const std::int64_t o = i + px * j;
        if (A[o] != B[o]) zv[o] = s.addVertex(c.lo[0] + i, c.lo[1] + j, z - 1, 2);
      }
    const std::uint32_t* X0 = xv.data() + prev * plane;
    const std::uint32_t* Y0 = yv.data() + prev * plane;
    for (std::int64_t j = 0; j < ey; ++j)
      for (std::int64_t i = 0; i < ex; ++i)
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
        if (keys)
        {
          const std::int64_t x = c.lo[0] + i, y = c.lo[1] + j, zc = z - 1;
          std::array<ColorKey, 8> k;
          for (int q = 0; q < 8; ++q)
            k[q] = in.colorKeys[in.local(x + (q & 1), y + ((q >> 1) & 1), zc + ((q >> 2) & 1))];
          const std::int64_t cell = x + impl.Dims[0] * (y + impl.Dims[1] * zc);
          for (int t = 0; t < nt; ++t)
          {
            out.cornerColors.push_back(k);
            out.triangleCells.push_back(cell);
          }
        }
      }
  }
  return out;
}

} // namespace lvdif
