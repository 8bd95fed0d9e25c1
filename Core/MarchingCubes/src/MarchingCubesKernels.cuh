// The kernels of the CUDA marching cubes (MarchingCubes.cu) over a batch of
// chunks: blockIdx.y is the chunk, blockIdx.x * blockDim.x + threadIdx.x its
// point or cell; per-chunk arrays are concatenated at pBase / cBase.
#pragma once

#include "MarchingCubesVertex.h"

#include "lvdif/ColorDictionary.h"

#include <cstdint>

namespace lvdif
{
namespace detail::mc_cuda
{

/// Triangles per case: the same for every valid case table (marchingCubesTablesWith
/// keeps the loops, hence the counts). The triangles themselves are the mesher's
/// table, in device memory (generateTriangles' `tris`).
__constant__ std::uint8_t cTriCount[256];

/// What the kernels read: a box of values (grid coordinates) and the chunk's cells.
struct Box
{
  const float* values;
  const Rgba* colors;    // same layout, or null
  const ColorKey* keys;  // same layout, or null
  long long lo[3], size[3];
  long long c0[3];       // first cell
  long long ex, ey, ez;  // cells per axis
  long long dims[3];     // grid points (borders of the gradient)
  long long goff[3];     // MarchingCubesOptions::gridOffset
  double origin[3], spacing[3];
  float inv[3];
  float iso;
  bool normals, cells;

  __device__ long long local(long long x, long long y, long long z) const
  {
    return (x - lo[0]) + size[0] * ((y - lo[1]) + size[1] * (z - lo[2]));
  }
  __device__ float v(long long x, long long y, long long z) const { return values[local(x, y, z)]; }
  __device__ void gradient(const long long p[3], float g[3]) const
  {
    const float mid = v(p[0], p[1], p[2]);
    for (int a = 0; a < 3; ++a)
    {
      long long q[3] = { p[0], p[1], p[2] };
      float l = mid, h = mid;
      if (p[a] > 0)
      {
        q[a] = p[a] - 1;
        l = v(q[0], q[1], q[2]);
      }
      if (p[a] < dims[a] - 1)
      {
        q[a] = p[a] + 1;
        h = v(q[0], q[1], q[2]);
      }
      g[a] = detail::mc::gradient(l, mid, h, p[a], dims[a], inv[a]);
    }
  }
};

struct Out
{
  float* points;
  unsigned long long* edgeIds;
  float* normals;
  Rgba* colors;
  unsigned int* tris;
  long long* cells;
  ColorKey* keys;
};

__global__ void classifyPoints(const Box* boxes, const long long* pBase, std::uint8_t* masks, unsigned int* counts)
{
  const Box& b = boxes[blockIdx.y];
  const long long px = b.ex + 1, py = b.ey + 1;
  const long long p = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (p >= px * py * (b.ez + 1)) return;
  masks += pBase[blockIdx.y];
  counts += pBase[blockIdx.y];
  const long long i = p % px, j = (p / px) % py, k = p / (px * py);
  const long long x = b.c0[0] + i, y = b.c0[1] + j, z = b.c0[2] + k;
  const bool a = b.v(x, y, z) >= b.iso;
  unsigned m = 0;
  if (i < b.ex && (b.v(x + 1, y, z) >= b.iso) != a) m |= 1u;
  if (j < b.ey && (b.v(x, y + 1, z) >= b.iso) != a) m |= 2u;
  if (k < b.ez && (b.v(x, y, z + 1) >= b.iso) != a) m |= 4u;
  masks[p] = static_cast<std::uint8_t>(m);
  counts[p] = __popc(m);
}

__global__ void classifyCells(const Box* boxes, const long long* cBase, std::uint8_t* cases, unsigned int* counts)
{
  const Box& b = boxes[blockIdx.y];
  const long long c = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (c >= b.ex * b.ey * b.ez) return;
  cases += cBase[blockIdx.y];
  counts += cBase[blockIdx.y];
  const long long i = c % b.ex, j = (c / b.ex) % b.ey, k = c / (b.ex * b.ey);
  const long long x = b.c0[0] + i, y = b.c0[1] + j, z = b.c0[2] + k;
  int cs = 0;
  for (int q = 0; q < 8; ++q)
    cs |= (b.v(x + (q & 1), y + ((q >> 1) & 1), z + ((q >> 2) & 1)) >= b.iso) << q;
  cases[c] = static_cast<std::uint8_t>(cs);
  counts[c] = cTriCount[cs];
}

/// Vertex ids in `first` are global (the batch's scan); outputs are written at them.
__global__ void generateVertices(
  const Box* boxes, const long long* pBase, const std::uint8_t* masks, const unsigned int* first, Out o)
{
  const Box& b = boxes[blockIdx.y];
  const long long px = b.ex + 1, py = b.ey + 1;
  const long long p = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (p >= px * py * (b.ez + 1)) return;
  masks += pBase[blockIdx.y];
  first += pBase[blockIdx.y];
  if (masks[p] == 0) return;
  const long long pt[3] = { b.c0[0] + p % px, b.c0[1] + (p / px) % py, b.c0[2] + p / (px * py) };
  unsigned int id = first[p];
  float g0[3];
  if (b.normals) b.gradient(pt, g0);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!((masks[p] >> axis) & 1u)) continue;
    long long q[3] = { pt[0], pt[1], pt[2] };
    q[axis] += 1;
    const float va = b.v(pt[0], pt[1], pt[2]), vb = b.v(q[0], q[1], q[2]);
    const float t = detail::mc::edgeT(b.iso, va, vb);
    for (int k = 0; k < 3; ++k)
      o.points[3 * id + k] = detail::mc::coord(b.origin[k], b.spacing[k], pt[k] + b.goff[k], k == axis ? t : 0.0f);
    o.edgeIds[id] = 3ull * static_cast<unsigned long long>(pt[0] + b.dims[0] * (pt[1] + b.dims[1] * pt[2])) +
      static_cast<unsigned long long>(axis);
    if (b.normals)
    {
      float g1[3];
      b.gradient(q, g1);
      float nx = detail::mc::lerp(g0[0], g1[0], t), ny = detail::mc::lerp(g0[1], g1[1], t), nz = detail::mc::lerp(g0[2], g1[2], t);
      detail::mc::normalize(nx, ny, nz);
      o.normals[3 * id] = nx;
      o.normals[3 * id + 1] = ny;
      o.normals[3 * id + 2] = nz;
    }
    if (b.colors)
    {
      const Rgba c0 = b.colors[b.local(pt[0], pt[1], pt[2])], c1 = b.colors[b.local(q[0], q[1], q[2])];
      Rgba c;
      c.r = detail::mc::lerpChannel(c0.r, c1.r, t);
      c.g = detail::mc::lerpChannel(c0.g, c1.g, t);
      c.b = detail::mc::lerpChannel(c0.b, c1.b, t);
      c.a = detail::mc::lerpChannel(c0.a, c1.a, t);
      o.colors[id] = c;
    }
    ++id;
  }
}

/// Triangles are written at their global index; their vertex ids are local to
/// the chunk (minus the chunk's first vertex, vBase). `tris`: the case table's
/// triangles, 16 entries per case (MarchingCubesTables::triangles).
__global__ void generateTriangles(const Box* boxes, const long long* pBase, const long long* cBase,
  const unsigned int* vBase, const std::uint8_t* cases, const unsigned int* firstTri, const std::uint8_t* masks,
  const unsigned int* firstVertex, const std::int8_t* tris, Out o)
{
  const Box& b = boxes[blockIdx.y];
  const long long c = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (c >= b.ex * b.ey * b.ez) return;
  cases += cBase[blockIdx.y];
  firstTri += cBase[blockIdx.y];
  masks += pBase[blockIdx.y];
  firstVertex += pBase[blockIdx.y];
  const unsigned int v0 = vBase[blockIdx.y];
  const int cs = cases[c];
  const int nt = cTriCount[cs];
  if (nt == 0) return;
  const long long px = b.ex + 1, py = b.ey + 1;
  const long long i = c % b.ex, j = (c / b.ex) % b.ey, k = c / (b.ex * b.ey);
  const unsigned int t0 = firstTri[c];
  for (int t = 0; t < nt; ++t)
    for (int corner = 0; corner < 3; ++corner)
    {
      const int e = tris[16 * cs + 3 * t + corner];
      const int axis = e >> 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
      long long off[3] = { 0, 0, 0 };
      off[u] = (e >> 1) & 1;
      off[v] = e & 1;
      const long long pp = (i + off[0]) + px * ((j + off[1]) + py * (k + off[2]));
      o.tris[3 * (t0 + t) + corner] = firstVertex[pp] - v0 + __popc(masks[pp] & ((1u << axis) - 1u));
    }
  if (!b.cells) return;
  const long long x = b.c0[0] + i, y = b.c0[1] + j, z = b.c0[2] + k;
  for (int t = 0; t < nt; ++t)
  {
    o.cells[t0 + t] = x + b.dims[0] * (y + b.dims[1] * z);
    if (b.keys)
      for (int q = 0; q < 8; ++q)
        o.keys[8 * (t0 + t) + q] = b.keys[b.local(x + (q & 1), y + ((q >> 1) & 1), z + ((q >> 2) & 1))];
  }
}

/// vBase[c] = first[pBase[c]], tBase[c] = firstTri[cBase[c]] for c = 0..n (n+1 entries).
__global__ void chunkBases(const long long* pBase, const long long* cBase, const unsigned int* first,
  const unsigned int* firstTri, unsigned int* vBase, unsigned int* tBase, int n)
{
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c > n) return;
  vBase[c] = first[pBase[c]];
  tBase[c] = firstTri[cBase[c]];
}

} // namespace detail::mc_cuda
} // namespace lvdif
