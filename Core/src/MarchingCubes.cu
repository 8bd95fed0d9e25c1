// Chunked marching cubes on CUDA, a batch of chunks at a time, without atomics:
//  1. classify: per point a 3-bit mask of its cut edges (+x, +y, +z inside its
//     chunk) and their count; per cell its case and triangle count;
//  2. exclusive prefix sums (CUB) over the batch give each point its first
//     vertex and each cell its first triangle (a chunk's are contiguous);
//  3. generate: one thread per point writes its vertices, one per cell its
//     triangles (a cut edge's vertex = its point's first vertex + the rank of
//     the axis among the point's cut edges);
//  4. one copy back per array for the whole batch, split into chunk meshes.
// The output is deterministic; the vertex arithmetic is MarchingCubesVertex.h
// (explicitly rounded on the device), so vertices equal the CPU's bit for bit
// and the triangles are the same (the CPU numbers vertices in sweep order,
// this path in point order: compare by edge id). Kernels: MarchingCubesKernels.cuh.
#include "MarchingCubesImpl.h"
#include "MarchingCubesKernels.cuh"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/MarchingCubesTables.h"

#include <cub/cub.cuh>

#include <cstring>
#include <mutex>

namespace lvdif
{
namespace
{
using mccuda::Box;
using mccuda::Out;

/// Points (and cells) per batch: ~12 bytes of classification per point and
/// per cell, so a batch needs well under 2 GB of device memory.
constexpr long long BatchPoints = 64ll << 20;
constexpr int BatchChunks = 65535; // gridDim.y

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
  // batch description, classification and scans
  Buffer<Box> boxes;
  Buffer<long long> pBase, cBase;
  Buffer<unsigned int> vBase, tBase;
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

namespace
{
template <typename T>
void download(std::vector<T>& dst, const void* src, std::size_t n)
{
  dst.resize(n);
  if (n) LVDIF_CUDA_CHECK(cudaMemcpy(dst.data(), src, n * sizeof(T), cudaMemcpyDeviceToHost));
}

/// The fields every chunk's box shares; values/colors/keys and the chunk's cells are set by the caller.
Box commonBox(const ChunkedMarchingCubes::Impl& impl)
{
  Box b{};
  for (int a = 0; a < 3; ++a)
  {
    b.dims[a] = impl.Dims[a];
    b.goff[a] = impl.Options.gridOffset[a];
    b.origin[a] = impl.Origin[a];
    b.spacing[a] = impl.Spacing[a];
    b.inv[a] = impl.InvSpacing[a];
  }
  b.iso = impl.Options.isoValue;
  b.normals = impl.Options.computeNormals;
  b.cells = impl.wantsTriangleCells();
  return b;
}

void setCells(Box& b, const VoxelBox& cells)
{
  for (int a = 0; a < 3; ++a) b.c0[a] = cells.lo[a];
  b.ex = cells.hi[0] - cells.lo[0] + 1;
  b.ey = cells.hi[1] - cells.lo[1] + 1;
  b.ez = cells.hi[2] - cells.lo[2] + 1;
}

/// The float grid's device copy, uploaded once (invalidate() drops it).
void ensureGrid(const ChunkedMarchingCubes::Impl& impl, MarchingCubesCudaState& S)
{
  if (S.hostGrid == impl.Grid.data) return;
  S.hostGrid = nullptr;
  const std::int64_t n = impl.Dims[0] * impl.Dims[1] * impl.Dims[2];
  const bool colors = impl.wantsColors();
  if (static_cast<std::uint64_t>(n) * (sizeof(float) + (colors ? sizeof(Rgba) : 0)) > cuda::freeMemory())
    throw Error(ErrorCode::OutOfMemory, "marching cubes: the float grid does not fit in device memory");
  S.grid.reserve(static_cast<std::size_t>(n));
  LVDIF_CUDA_CHECK(cudaMemcpy(S.grid.p, impl.Grid.data, n * sizeof(float), cudaMemcpyHostToDevice));
  if (colors)
  {
    S.gridColors.reserve(static_cast<std::size_t>(n));
    LVDIF_CUDA_CHECK(cudaMemcpy(S.gridColors.p, impl.GridColors, n * sizeof(Rgba), cudaMemcpyHostToDevice));
  }
  S.hostGrid = impl.Grid.data;
}

/// Meshes one batch of chunks whose boxes point at device data.
std::vector<ChunkMesh> runBatch(const ChunkedMarchingCubes::Impl& impl, MarchingCubesCudaState& S,
  const std::vector<Box>& boxes, const std::vector<std::int64_t>& ids)
{
  const int n = static_cast<int>(boxes.size());
  std::vector<long long> pb(n + 1, 0), cb(n + 1, 0);
  long long maxP = 1, maxC = 1;
  for (int i = 0; i < n; ++i)
  {
    const Box& b = boxes[i];
    const long long np = (b.ex + 1) * (b.ey + 1) * (b.ez + 1), nc = b.ex * b.ey * b.ez;
    pb[i + 1] = pb[i] + np;
    cb[i + 1] = cb[i] + nc;
    maxP = std::max(maxP, np);
    maxC = std::max(maxC, nc);
  }
  const long long P = pb[n], C = cb[n];
  S.boxes.reserve(n);
  S.pBase.reserve(n + 1);
  S.cBase.reserve(n + 1);
  S.vBase.reserve(n + 1);
  S.tBase.reserve(n + 1);
  S.masks.reserve(P);
  S.vcount.reserve(P + 1);
  S.vfirst.reserve(P + 1);
  S.cases.reserve(C);
  S.tcount.reserve(C + 1);
  S.tfirst.reserve(C + 1);
  LVDIF_CUDA_CHECK(cudaMemcpy(S.boxes.p, boxes.data(), n * sizeof(Box), cudaMemcpyHostToDevice));
  LVDIF_CUDA_CHECK(cudaMemcpy(S.pBase.p, pb.data(), (n + 1) * sizeof(long long), cudaMemcpyHostToDevice));
  LVDIF_CUDA_CHECK(cudaMemcpy(S.cBase.p, cb.data(), (n + 1) * sizeof(long long), cudaMemcpyHostToDevice));
  LVDIF_CUDA_CHECK(cudaMemset(S.vcount.p + P, 0, sizeof(unsigned int)));
  LVDIF_CUDA_CHECK(cudaMemset(S.tcount.p + C, 0, sizeof(unsigned int)));
  mccuda::classifyPoints<<<dim3(blocks(maxP), n), 256>>>(S.boxes.p, S.pBase.p, S.masks.p, S.vcount.p);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  mccuda::classifyCells<<<dim3(blocks(maxC), n), 256>>>(S.boxes.p, S.cBase.p, S.cases.p, S.tcount.p);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  S.scan(S.vcount.p, S.vfirst.p, P + 1);
  S.scan(S.tcount.p, S.tfirst.p, C + 1);
  mccuda::chunkBases<<<blocks(n + 1), 256>>>(S.pBase.p, S.cBase.p, S.vfirst.p, S.tfirst.p, S.vBase.p, S.tBase.p, n);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  std::vector<unsigned int> vb, tb;
  download(vb, S.vBase.p, n + 1);
  download(tb, S.tBase.p, n + 1);

  std::vector<ChunkMesh> out(n);
  for (int i = 0; i < n; ++i)
  {
    out[i].chunkId = ids[i];
    out[i].chunkCoord = impl.globalCoord(ids[i]);
    out[i].cells = impl.cells(ids[i]);
  }
  const std::size_t NV = vb[n], NT = tb[n];
  if (NT == 0) return out;
  const bool normals = boxes[0].normals, colors = boxes[0].colors != nullptr, cells = boxes[0].cells,
             keys = boxes[0].keys != nullptr;
  S.points.reserve(3 * NV);
  S.edgeIds.reserve(NV);
  if (normals) S.normals.reserve(3 * NV);
  if (colors) S.colors.reserve(NV);
  S.tris.reserve(3 * NT);
  if (cells) S.cells.reserve(NT);
  if (keys) S.keys.reserve(8 * NT);
  const Out o{ S.points.p, S.edgeIds.p, S.normals.p, S.colors.p, S.tris.p, S.cells.p, S.keys.p };
  mccuda::generateVertices<<<dim3(blocks(maxP), n), 256>>>(S.boxes.p, S.pBase.p, S.masks.p, S.vfirst.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  mccuda::generateTriangles<<<dim3(blocks(maxC), n), 256>>>(
    S.boxes.p, S.pBase.p, S.cBase.p, S.vBase.p, S.cases.p, S.tfirst.p, S.masks.p, S.vfirst.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());

  // one copy per array, then split by chunk (each chunk's range is contiguous)
  std::vector<Vec3f> pts, nrm;
  std::vector<std::uint64_t> eids;
  std::vector<Rgba> col;
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::int64_t> tcell;
  std::vector<std::array<ColorKey, 8>> tkeys;
  download(pts, S.points.p, NV);
  download(eids, S.edgeIds.p, NV);
  download(tri, S.tris.p, NT);
  if (normals) download(nrm, S.normals.p, NV);
  if (colors) download(col, S.colors.p, NV);
  if (cells) download(tcell, S.cells.p, NT);
  if (keys) download(tkeys, S.keys.p, NT);
#pragma omp parallel for schedule(dynamic, 4)
  for (int i = 0; i < n; ++i)
  {
    ChunkMesh& m = out[i];
    const std::size_t v0 = vb[i], v1 = vb[i + 1], t0 = tb[i], t1 = tb[i + 1];
    if (t1 == t0) continue;
    m.points.assign(pts.begin() + v0, pts.begin() + v1);
    m.edgeIds.assign(eids.begin() + v0, eids.begin() + v1);
    m.triangles.assign(tri.begin() + t0, tri.begin() + t1);
    if (normals) m.normals.assign(nrm.begin() + v0, nrm.begin() + v1);
    if (colors) m.colors.assign(col.begin() + v0, col.begin() + v1);
    if (cells) m.triangleCells.assign(tcell.begin() + t0, tcell.begin() + t1);
    if (keys) m.cornerColors.assign(tkeys.begin() + t0, tkeys.begin() + t1);
  }
  return out;
}
} // namespace

std::shared_ptr<MarchingCubesCudaState> makeMarchingCubesCudaState()
{
  static std::once_flag once;
  std::call_once(once, [] {
    const MarchingCubesTables& T = marchingCubesTables();
    LVDIF_CUDA_CHECK(cudaMemcpyToSymbol(mccuda::cTriCount, T.triangleCount, sizeof(T.triangleCount)));
    LVDIF_CUDA_CHECK(cudaMemcpyToSymbol(mccuda::cTris, T.triangles, sizeof(T.triangles)));
  });
  return std::make_shared<MarchingCubesCudaState>();
}

ChunkMesh meshChunkCuda(const ChunkedMarchingCubes::Impl& impl, const ChunkedMarchingCubes::ChunkInput& in)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  Box b = commonBox(impl);
  setCells(b, in.cells);
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = in.lo[a];
    b.size[a] = in.size[a];
  }
  if (in.view)
  {
    ensureGrid(impl, S);
    b.values = S.grid.p;
    b.colors = in.viewColors ? S.gridColors.p : nullptr;
  }
  else
  {
    const std::size_t n = in.values.size();
    S.boxValues.reserve(n);
    LVDIF_CUDA_CHECK(cudaMemcpy(S.boxValues.p, in.values.data(), n * sizeof(float), cudaMemcpyHostToDevice));
    b.values = S.boxValues.p;
    if (!in.colors.empty())
    {
      S.boxColors.reserve(n);
      LVDIF_CUDA_CHECK(cudaMemcpy(S.boxColors.p, in.colors.data(), n * sizeof(Rgba), cudaMemcpyHostToDevice));
      b.colors = S.boxColors.p;
    }
    if (!in.colorKeys.empty())
    {
      S.boxKeys.reserve(n);
      LVDIF_CUDA_CHECK(cudaMemcpy(S.boxKeys.p, in.colorKeys.data(), n * sizeof(ColorKey), cudaMemcpyHostToDevice));
      b.keys = S.boxKeys.p;
    }
  }
  return std::move(runBatch(impl, S, { b }, { in.chunkId })[0]);
}

std::vector<ChunkMesh> meshChunksCuda(const ChunkedMarchingCubes::Impl& impl, const std::vector<std::int64_t>& ids,
  Interrupter& interrupter)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  std::vector<ChunkMesh> out(ids.size());
  std::vector<std::size_t> where;
  std::vector<std::int64_t> batchIds;
  std::vector<Box> batch;
  long long points = 0;
  Box common = commonBox(impl);
  auto flush = [&] {
    if (batch.empty()) return;
    interrupter.checkInterrupt();
    std::vector<ChunkMesh> meshes = runBatch(impl, S, batch, batchIds);
    for (std::size_t k = 0; k < meshes.size(); ++k) out[where[k]] = std::move(meshes[k]);
    batch.clear();
    batchIds.clear();
    where.clear();
    points = 0;
  };
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const std::int64_t id = ids[i];
    require(id >= 0 && id < impl.Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
    if (impl.empty(id))
    {
      out[i].chunkId = id;
      out[i].chunkCoord = impl.globalCoord(id);
      out[i].cells = impl.cells(id);
      continue;
    }
    if (S.hostGrid != impl.Grid.data)
    {
      ensureGrid(impl, S);
    }
    Box b = common;
    b.values = S.grid.p;
    b.colors = impl.wantsColors() ? S.gridColors.p : nullptr;
    for (int a = 0; a < 3; ++a) b.size[a] = impl.Dims[a];
    setCells(b, impl.cells(id));
    const long long np = (b.ex + 1) * (b.ey + 1) * (b.ez + 1);
    if (!batch.empty() && (points + np > BatchPoints || static_cast<int>(batch.size()) == BatchChunks)) flush();
    batch.push_back(b);
    batchIds.push_back(id);
    where.push_back(i);
    points += np;
  }
  flush();
  return out;
}

void dropMarchingCubesCudaGrid(MarchingCubesCudaState& state)
{
  std::lock_guard<std::mutex> guard(state.lock);
  state.hostGrid = nullptr;
}

} // namespace lvdif
