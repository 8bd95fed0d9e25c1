// Chunked marching cubes on CUDA, one chunk at a time, without atomics:
//  1. classify: per point a 3-bit mask of its cut edges (+x, +y, +z inside the
//     chunk) and their count; per cell its case and triangle count;
//  2. exclusive prefix sums (CUB) give each point its first vertex id and each
//     cell its first triangle;
//  3. generate: one thread per point writes its vertices, one per cell its
//     triangles (a cut edge's vertex id = its point's first id + the rank of
//     the axis among the point's cut edges).
// The output is deterministic; the vertex arithmetic is MarchingCubesVertex.h
// (explicitly rounded on the device), so vertices equal the CPU's bit for bit
// and the triangles are the same (the CPU numbers vertices in sweep order,
// this path in point order: compare by edge id).
#include "MarchingCubesImpl.h"
#include "MarchingCubesVertex.h"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/MarchingCubesTables.h"

#include <cub/cub.cuh>

#include <mutex>

namespace lvdif
{
namespace
{

__constant__ std::uint8_t cTriCount[256];
__constant__ std::int8_t cTris[256][16];

template <typename T>
struct Buffer
{
  T* p = nullptr;
  std::size_t cap = 0;
  void reserve(std::size_t n)
  {
    n = n < 1 ? 1 : n;
    if (n <= cap) return;
    if (p) cudaFree(p);
    p = nullptr;
    cap = 0;
    LVDIF_CUDA_CHECK(cudaMalloc(&p, n * sizeof(T)));
    cap = n;
  }
  ~Buffer()
  {
    if (p) cudaFree(p);
  }
};

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
      g[a] = mc::gradient(l, mid, h, p[a], dims[a], inv[a]);
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

__global__ void classifyPoints(Box b, std::uint8_t* masks, unsigned int* counts, long long n)
{
  const long long p = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (p >= n) return;
  const long long px = b.ex + 1, py = b.ey + 1;
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

__global__ void classifyCells(Box b, std::uint8_t* cases, unsigned int* counts, long long n)
{
  const long long c = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (c >= n) return;
  const long long i = c % b.ex, j = (c / b.ex) % b.ey, k = c / (b.ex * b.ey);
  const long long x = b.c0[0] + i, y = b.c0[1] + j, z = b.c0[2] + k;
  int cs = 0;
  for (int q = 0; q < 8; ++q)
    cs |= (b.v(x + (q & 1), y + ((q >> 1) & 1), z + ((q >> 2) & 1)) >= b.iso) << q;
  cases[c] = static_cast<std::uint8_t>(cs);
  counts[c] = cTriCount[cs];
}

__global__ void generateVertices(Box b, const std::uint8_t* masks, const unsigned int* first, Out o, long long n)
{
  const long long p = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (p >= n || masks[p] == 0) return;
  const long long px = b.ex + 1, py = b.ey + 1;
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
    const float t = mc::edgeT(b.iso, va, vb);
    for (int k = 0; k < 3; ++k)
      o.points[3 * id + k] = mc::coord(b.origin[k], b.spacing[k], pt[k] + b.goff[k], k == axis ? t : 0.0f);
    o.edgeIds[id] = 3ull * static_cast<unsigned long long>(pt[0] + b.dims[0] * (pt[1] + b.dims[1] * pt[2])) +
      static_cast<unsigned long long>(axis);
    if (b.normals)
    {
      float g1[3];
      b.gradient(q, g1);
      float nx = mc::lerp(g0[0], g1[0], t), ny = mc::lerp(g0[1], g1[1], t), nz = mc::lerp(g0[2], g1[2], t);
      mc::normalize(nx, ny, nz);
      o.normals[3 * id] = nx;
      o.normals[3 * id + 1] = ny;
      o.normals[3 * id + 2] = nz;
    }
    if (b.colors)
    {
      const Rgba c0 = b.colors[b.local(pt[0], pt[1], pt[2])], c1 = b.colors[b.local(q[0], q[1], q[2])];
      Rgba c;
      c.r = mc::lerpChannel(c0.r, c1.r, t);
      c.g = mc::lerpChannel(c0.g, c1.g, t);
      c.b = mc::lerpChannel(c0.b, c1.b, t);
      c.a = mc::lerpChannel(c0.a, c1.a, t);
      o.colors[id] = c;
    }
    ++id;
  }
}

__global__ void generateTriangles(Box b, const std::uint8_t* cases, const unsigned int* firstTri,
  const std::uint8_t* masks, const unsigned int* firstVertex, Out o, long long n)
{
  const long long c = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (c >= n) return;
  const int cs = cases[c];
  const int nt = cTriCount[cs];
  if (nt == 0) return;
  const long long px = b.ex + 1, py = b.ey + 1;
  const long long i = c % b.ex, j = (c / b.ex) % b.ey, k = c / (b.ex * b.ey);
  const unsigned int t0 = firstTri[c];
  for (int t = 0; t < nt; ++t)
    for (int corner = 0; corner < 3; ++corner)
    {
      const int e = cTris[cs][3 * t + corner];
      const int axis = e >> 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
      long long off[3] = { 0, 0, 0 };
      off[u] = (e >> 1) & 1;
      off[v] = e & 1;
      const long long pp = (i + off[0]) + px * ((j + off[1]) + py * (k + off[2]));
      o.tris[3 * (t0 + t) + corner] = firstVertex[pp] + __popc(masks[pp] & ((1u << axis) - 1u));
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

unsigned int blocks(long long n) { return static_cast<unsigned int>((n + 255) / 256); }

} // namespace

struct MarchingCubesCudaState
{
  std::mutex lock;
  // the float grid's device copy (inputs that view the grid)
  const float* hostGrid = nullptr;
  Buffer<float> grid;
  Buffer<Rgba> gridColors;
  // gathered inputs
  Buffer<float> boxValues;
  Buffer<Rgba> boxColors;
  Buffer<ColorKey> boxKeys;
  // classification and scans
  Buffer<std::uint8_t> masks, cases;
  Buffer<unsigned int> vcount, vfirst, tcount, tfirst;
  Buffer<unsigned char> scratch;
  // output
  Buffer<float> points, normals;
  Buffer<unsigned long long> edgeIds;
  Buffer<Rgba> colors;
  Buffer<unsigned int> tris;
  Buffer<long long> cells;
  Buffer<ColorKey> keys;

  void scan(const unsigned int* in, unsigned int* out, long long n)
  {
    std::size_t bytes = 0;
    LVDIF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, static_cast<int>(n)));
    scratch.reserve(bytes);
    LVDIF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(scratch.p, bytes, in, out, static_cast<int>(n)));
  }
};

std::shared_ptr<MarchingCubesCudaState> makeMarchingCubesCudaState()
{
  static std::once_flag once;
  std::call_once(once, [] {
    const MarchingCubesTables& T = marchingCubesTables();
    LVDIF_CUDA_CHECK(cudaMemcpyToSymbol(cTriCount, T.triangleCount, sizeof(T.triangleCount)));
    LVDIF_CUDA_CHECK(cudaMemcpyToSymbol(cTris, T.triangles, sizeof(T.triangles)));
  });
  return std::make_shared<MarchingCubesCudaState>();
}

ChunkMesh meshChunkCuda(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  ChunkMesh out;
  out.chunkId = in.chunkId;
  out.chunkCoord = impl.globalCoord(in.chunkId);
  out.cells = in.cells;

  Box b{};
  const std::int64_t boxCount = in.size[0] * in.size[1] * in.size[2];
  const bool colors = in.colorData() != nullptr;
  if (in.view)
  {
    // the grid's device copy, uploaded once (invalidate() drops it)
    if (S.hostGrid != in.view)
    {
      S.hostGrid = nullptr;
      if (static_cast<std::uint64_t>(boxCount) * (sizeof(float) + (colors ? sizeof(Rgba) : 0)) > cuda::freeMemory())
        throw Error(ErrorCode::OutOfMemory, "marching cubes: the float grid does not fit in device memory");
      S.grid.reserve(static_cast<std::size_t>(boxCount));
      LVDIF_CUDA_CHECK(cudaMemcpy(S.grid.p, in.view, boxCount * sizeof(float), cudaMemcpyHostToDevice));
      if (colors)
      {
        S.gridColors.reserve(static_cast<std::size_t>(boxCount));
        LVDIF_CUDA_CHECK(cudaMemcpy(S.gridColors.p, in.viewColors, boxCount * sizeof(Rgba), cudaMemcpyHostToDevice));
      }
      S.hostGrid = in.view;
    }
    b.values = S.grid.p;
    b.colors = colors ? S.gridColors.p : nullptr;
    b.keys = nullptr;
  }
  else
  {
    S.boxValues.reserve(static_cast<std::size_t>(boxCount));
    LVDIF_CUDA_CHECK(cudaMemcpy(S.boxValues.p, in.values.data(), boxCount * sizeof(float), cudaMemcpyHostToDevice));
    b.values = S.boxValues.p;
    b.colors = nullptr;
    b.keys = nullptr;
    if (colors)
    {
      S.boxColors.reserve(static_cast<std::size_t>(boxCount));
      LVDIF_CUDA_CHECK(cudaMemcpy(S.boxColors.p, in.colors.data(), boxCount * sizeof(Rgba), cudaMemcpyHostToDevice));
      b.colors = S.boxColors.p;
    }
    if (!in.colorKeys.empty())
    {
      S.boxKeys.reserve(static_cast<std::size_t>(boxCount));
      LVDIF_CUDA_CHECK(cudaMemcpy(S.boxKeys.p, in.colorKeys.data(), boxCount * sizeof(ColorKey), cudaMemcpyHostToDevice));
      b.keys = S.boxKeys.p;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = in.lo[a];
    b.size[a] = in.size[a];
    b.c0[a] = in.cells.lo[a];
    b.dims[a] = impl.Dims[a];
    b.goff[a] = impl.Options.gridOffset[a];
    b.origin[a] = impl.Origin[a];
    b.spacing[a] = impl.Spacing[a];
    b.inv[a] = impl.InvSpacing[a];
  }
  b.ex = in.cells.hi[0] - in.cells.lo[0] + 1;
  b.ey = in.cells.hi[1] - in.cells.lo[1] + 1;
  b.ez = in.cells.hi[2] - in.cells.lo[2] + 1;
  b.iso = impl.Options.isoValue;
  b.normals = impl.Options.computeNormals;
  b.cells = impl.wantsTriangleCells();

  const long long np = (b.ex + 1) * (b.ey + 1) * (b.ez + 1), nc = b.ex * b.ey * b.ez;
  S.masks.reserve(np);
  S.vcount.reserve(np + 1);
  S.vfirst.reserve(np + 1);
  S.cases.reserve(nc);
  S.tcount.reserve(nc + 1);
  S.tfirst.reserve(nc + 1);
  LVDIF_CUDA_CHECK(cudaMemset(S.vcount.p + np, 0, sizeof(unsigned int)));
  LVDIF_CUDA_CHECK(cudaMemset(S.tcount.p + nc, 0, sizeof(unsigned int)));
  classifyPoints<<<blocks(np), 256>>>(b, S.masks.p, S.vcount.p, np);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  classifyCells<<<blocks(nc), 256>>>(b, S.cases.p, S.tcount.p, nc);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  S.scan(S.vcount.p, S.vfirst.p, np + 1);
  S.scan(S.tcount.p, S.tfirst.p, nc + 1);
  unsigned int nv = 0, nt = 0;
  LVDIF_CUDA_CHECK(cudaMemcpy(&nv, S.vfirst.p + np, sizeof(unsigned int), cudaMemcpyDeviceToHost));
  LVDIF_CUDA_CHECK(cudaMemcpy(&nt, S.tfirst.p + nc, sizeof(unsigned int), cudaMemcpyDeviceToHost));
  if (nt == 0) return out;

  const bool keys = b.keys != nullptr;
  S.points.reserve(3 * static_cast<std::size_t>(nv));
  S.edgeIds.reserve(nv);
  if (b.normals) S.normals.reserve(3 * static_cast<std::size_t>(nv));
  if (b.colors) S.colors.reserve(nv);
  S.tris.reserve(3 * static_cast<std::size_t>(nt));
  if (b.cells) S.cells.reserve(nt);
  if (keys) S.keys.reserve(8 * static_cast<std::size_t>(nt));
  Out o{ S.points.p, S.edgeIds.p, S.normals.p, S.colors.p, S.tris.p, S.cells.p, S.keys.p };
  generateVertices<<<blocks(np), 256>>>(b, S.masks.p, S.vfirst.p, o, np);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  generateTriangles<<<blocks(nc), 256>>>(b, S.cases.p, S.tfirst.p, S.masks.p, S.vfirst.p, o, nc);
  LVDIF_CUDA_CHECK(cudaGetLastError());

  out.points.resize(nv);
  out.edgeIds.resize(nv);
  out.triangles.resize(nt);
  LVDIF_CUDA_CHECK(cudaMemcpy(out.points.data(), S.points.p, nv * sizeof(Vec3f), cudaMemcpyDeviceToHost));
  LVDIF_CUDA_CHECK(cudaMemcpy(out.edgeIds.data(), S.edgeIds.p, nv * sizeof(std::uint64_t), cudaMemcpyDeviceToHost));
  LVDIF_CUDA_CHECK(cudaMemcpy(out.triangles.data(), S.tris.p, nt * sizeof(out.triangles[0]), cudaMemcpyDeviceToHost));
  if (b.normals)
  {
    out.normals.resize(nv);
    LVDIF_CUDA_CHECK(cudaMemcpy(out.normals.data(), S.normals.p, nv * sizeof(Vec3f), cudaMemcpyDeviceToHost));
  }
  if (b.colors)
  {
    out.colors.resize(nv);
    LVDIF_CUDA_CHECK(cudaMemcpy(out.colors.data(), S.colors.p, nv * sizeof(Rgba), cudaMemcpyDeviceToHost));
  }
  if (b.cells)
  {
    out.triangleCells.resize(nt);
    LVDIF_CUDA_CHECK(cudaMemcpy(out.triangleCells.data(), S.cells.p, nt * sizeof(std::int64_t), cudaMemcpyDeviceToHost));
  }
  if (keys)
  {
    out.cornerColors.resize(nt);
    LVDIF_CUDA_CHECK(cudaMemcpy(out.cornerColors.data(), S.keys.p, nt * sizeof(out.cornerColors[0]), cudaMemcpyDeviceToHost));
  }
  return out;
}

void dropMarchingCubesCudaGrid(MarchingCubesCudaState& state)
{
  std::lock_guard<std::mutex> guard(state.lock);
  state.hostGrid = nullptr;
}

} // namespace lvdif
