// Chunked marching cubes on CUDA, a batch of chunks at a time, without atomics:
//  1. classify: per point a 3-bit mask of its cut edges (+x, +y, +z inside its
//     chunk) and their count; per cell its case and triangle count;
//  2. exclusive prefix sums (CUB) over the batch give each point its first
//     vertex and each cell its first triangle (a chunk's are contiguous);
//  3. generate: one thread per point writes its vertices, one per cell its
//     triangles (a cut edge's vertex = its point's first vertex + the rank of
//     the axis among the point's cut edges);
//  4. lists of chunks (extractAll, extractChunks, extractAllPacked) run as a
//     pipeline: batch k+1 is classified and generated on one stream while
//     batch k's arrays are copied on another straight into a page-locked
//     packed block (PackedChunkMeshes); extractChunks then splits it per chunk.
//     One chunk (meshChunkCuda) is one synchronous batch.
// The output is deterministic; the vertex arithmetic is MarchingCubesVertex.h
// (explicitly rounded on the device), so vertices equal the CPU's bit for bit
// and the triangles are the same (the CPU numbers vertices in sweep order,
// this path in point order: compare by edge id). Kernels: MarchingCubesKernels.cuh.
#include "MarchingCubesImpl.h"
#include "MarchingCubesKernels.cuh"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/MarchingCubesTables.h"

#include <cub/cub.cuh>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

namespace lvdif
{
namespace
{
using detail::mc_cuda::Box;
using detail::mc_cuda::Out;

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

/// Device output arrays of one batch (two sets: one filled while the other is copied out).
struct MarchingCubesOutBuffers
{
  Buffer<float> points, normals;
  Buffer<unsigned long long> edgeIds;
  Buffer<Rgba> colors;
  Buffer<unsigned int> tris;
  Buffer<long long> cells;
  Buffer<ColorKey> keys;
  Out reserve(std::size_t NV, std::size_t NT, bool normals, bool colors, bool cells, bool keys)
  {
    this->points.reserve(3 * NV);
    this->edgeIds.reserve(NV);
    if (normals) this->normals.reserve(3 * NV);
    if (colors) this->colors.reserve(NV);
    this->tris.reserve(3 * NT);
    if (cells) this->cells.reserve(NT);
    if (keys) this->keys.reserve(8 * NT);
    return Out{ this->points.p, this->edgeIds.p, normals ? this->normals.p : nullptr, colors ? this->colors.p : nullptr,
      this->tris.p, cells ? this->cells.p : nullptr, keys ? this->keys.p : nullptr };
  }
};

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
  /// the mesher's case table (MarchingCubesTables::triangles, 256 x 16)
  Buffer<std::int8_t> tris;
  // output (set 0 also serves the one-chunk path)
  MarchingCubesOutBuffers out[2];
  // the streamed pipeline: kernels on `compute`, copies to the host on `copy`
  cudaStream_t compute = nullptr, copy = nullptr;
  cudaEvent_t generated[2] = { nullptr, nullptr }, copied[2] = { nullptr, nullptr };
  bool copyPending[2] = { false, false };
  /// extractChunks/extractAll on the GPU pack here first (page-locked, reused).
  PackedChunkMeshes staging;

  void ensureStreams()
  {
    if (compute) return;
    LVDIF_CUDA_CHECK(cudaStreamCreateWithFlags(&compute, cudaStreamNonBlocking));
    LVDIF_CUDA_CHECK(cudaStreamCreateWithFlags(&copy, cudaStreamNonBlocking));
    for (int i = 0; i < 2; ++i)
    {
      LVDIF_CUDA_CHECK(cudaEventCreateWithFlags(&generated[i], cudaEventDisableTiming));
      LVDIF_CUDA_CHECK(cudaEventCreateWithFlags(&copied[i], cudaEventDisableTiming));
    }
  }
  ~MarchingCubesCudaState()
  {
    // no checks: the device may already be shutting down
    if (compute) cudaStreamSynchronize(compute);
    if (copy) cudaStreamSynchronize(copy);
    for (int i = 0; i < 2; ++i)
    {
      if (generated[i]) cudaEventDestroy(generated[i]);
      if (copied[i]) cudaEventDestroy(copied[i]);
    }
    if (compute) cudaStreamDestroy(compute);
    if (copy) cudaStreamDestroy(copy);
  }

  void scan(const unsigned int* in, unsigned int* out, long long n, cudaStream_t stream = nullptr)
  {
    std::size_t bytes = 0;
    LVDIF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, static_cast<int>(n), stream));
    scratch.reserve(bytes);
    LVDIF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(scratch.p, bytes, in, out, static_cast<int>(n), stream));
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
/// Device buffers of one batch of n chunks, P and C being the batch's totals
/// behind pBase and cBase (both extraction paths size them the same way).
void reserveBatch(MarchingCubesCudaState& S, int n, long long P, long long C)
{
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
}

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

// Uploads a batch's n boxes and per-chunk point/cell bases and clears the counters' tails.
void uploadBatch(MarchingCubesCudaState& S, const Box* boxes, int n, const std::vector<long long>& pb,
  const std::vector<long long>& cb, long long P, long long C, cudaStream_t cs)
{
  LVDIF_CUDA_CHECK(cudaMemcpyAsync(S.boxes.p, boxes, n * sizeof(Box), cudaMemcpyHostToDevice, cs));
  LVDIF_CUDA_CHECK(cudaMemcpyAsync(S.pBase.p, pb.data(), (n + 1) * sizeof(long long), cudaMemcpyHostToDevice, cs));
  LVDIF_CUDA_CHECK(cudaMemcpyAsync(S.cBase.p, cb.data(), (n + 1) * sizeof(long long), cudaMemcpyHostToDevice, cs));
  LVDIF_CUDA_CHECK(cudaMemsetAsync(S.vcount.p + P, 0, sizeof(unsigned int), cs));
  LVDIF_CUDA_CHECK(cudaMemsetAsync(S.tcount.p + C, 0, sizeof(unsigned int), cs));
}

// Classifies the batch's P points and C cells, scans the counts and reads back
// each chunk's first vertex and triangle (vb, tb; n + 1 entries, the last the
// totals): the one synchronization of a batch.
void classifyBatch(MarchingCubesCudaState& S, int n, long long P, long long C, long long maxP, long long maxC,
  std::vector<unsigned int>& vb, std::vector<unsigned int>& tb, cudaStream_t cs)
{
  detail::mc_cuda::classifyPoints<<<dim3(blocks(maxP), n), 256, 0, cs>>>(S.boxes.p, S.pBase.p, S.masks.p, S.vcount.p);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  detail::mc_cuda::classifyCells<<<dim3(blocks(maxC), n), 256, 0, cs>>>(S.boxes.p, S.cBase.p, S.cases.p, S.tcount.p);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  S.scan(S.vcount.p, S.vfirst.p, P + 1, cs);
  S.scan(S.tcount.p, S.tfirst.p, C + 1, cs);
  detail::mc_cuda::chunkBases<<<blocks(n + 1), 256, 0, cs>>>(S.pBase.p, S.cBase.p, S.vfirst.p, S.tfirst.p, S.vBase.p, S.tBase.p, n);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  vb.resize(n + 1);
  tb.resize(n + 1);
  LVDIF_CUDA_CHECK(cudaMemcpyAsync(vb.data(), S.vBase.p, (n + 1) * sizeof(unsigned int), cudaMemcpyDeviceToHost, cs));
  LVDIF_CUDA_CHECK(cudaMemcpyAsync(tb.data(), S.tBase.p, (n + 1) * sizeof(unsigned int), cudaMemcpyDeviceToHost, cs));
  LVDIF_CUDA_CHECK(cudaStreamSynchronize(cs));
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
  reserveBatch(S, n, P, C);
  uploadBatch(S, boxes.data(), n, pb, cb, P, C, 0);
  std::vector<unsigned int> vb, tb;
  classifyBatch(S, n, P, C, maxP, maxC, vb, tb, 0);

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
  if (S.copyPending[0]) LVDIF_CUDA_CHECK(cudaEventSynchronize(S.copied[0]));
  S.copyPending[0] = false;
  MarchingCubesOutBuffers& ob = S.out[0];
  const Out o = ob.reserve(NV, NT, normals, colors, cells, keys);
  detail::mc_cuda::generateVertices<<<dim3(blocks(maxP), n), 256>>>(S.boxes.p, S.pBase.p, S.masks.p, S.vfirst.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  detail::mc_cuda::generateTriangles<<<dim3(blocks(maxC), n), 256>>>(
    S.boxes.p, S.pBase.p, S.cBase.p, S.vBase.p, S.cases.p, S.tfirst.p, S.masks.p, S.vfirst.p, S.tris.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());

  // one copy per array, then split by chunk (each chunk's range is contiguous)
  std::vector<Vec3f> pts, nrm;
  std::vector<std::uint64_t> eids;
  std::vector<Rgba> col;
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::int64_t> tcell;
  std::vector<std::array<ColorKey, 8>> tkeys;
  download(pts, ob.points.p, NV);
  download(eids, ob.edgeIds.p, NV);
  download(tri, ob.tris.p, NT);
  if (normals) download(nrm, ob.normals.p, NV);
  if (colors) download(col, ob.colors.p, NV);
  if (cells) download(tcell, ob.cells.p, NT);
  if (keys) download(tkeys, ob.keys.p, NT);
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

std::shared_ptr<MarchingCubesCudaState> makeMarchingCubesCudaState(const MarchingCubesTables& tables)
{
  static std::once_flag once;
  std::call_once(once, [] {
    // the counts are those of every valid table (same loops), so they are uploaded once
    const MarchingCubesTables& T = marchingCubesTables();
    LVDIF_CUDA_CHECK(cudaMemcpyToSymbol(detail::mc_cuda::cTriCount, T.triangleCount, sizeof(T.triangleCount)));
  });
  auto state = std::make_shared<MarchingCubesCudaState>();
  state->tris.reserve(sizeof(tables.triangles));
  LVDIF_CUDA_CHECK(cudaMemcpy(state->tris.p, tables.triangles, sizeof(tables.triangles), cudaMemcpyHostToDevice));
  return state;
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

std::shared_ptr<std::uint8_t> allocatePageLocked(std::size_t bytes)
{
  void* p = nullptr;
  LVDIF_CUDA_CHECK(cudaHostAlloc(&p, bytes, cudaHostAllocDefault));
  return std::shared_ptr<std::uint8_t>(static_cast<std::uint8_t*>(p), [](std::uint8_t* q) { cudaFreeHost(q); });
}

namespace
{
// The vertices and triangles of a classified batch of n chunks, into `o` (on stream cs).
void generateBatch(MarchingCubesCudaState& S, const Out& o, int n, long long maxP, long long maxC, cudaStream_t cs)
{
  detail::mc_cuda::generateVertices<<<dim3(blocks(maxP), n), 256, 0, cs>>>(S.boxes.p, S.pBase.p, S.masks.p, S.vfirst.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  detail::mc_cuda::generateTriangles<<<dim3(blocks(maxC), n), 256, 0, cs>>>(
    S.boxes.p, S.pBase.p, S.cBase.p, S.vBase.p, S.cases.p, S.tfirst.p, S.masks.p, S.vfirst.p, S.tris.p, o);
  LVDIF_CUDA_CHECK(cudaGetLastError());
}

// Queues the copies of a generated batch into the host storage at vertex V and triangle T.
void copyBatchToHost(PackedChunkMeshes::Storage& st, const Out& o, std::uint64_t V, std::uint64_t T, std::uint64_t NV,
  std::uint64_t NT, bool normals, bool colors, bool cells, bool keys, cudaStream_t stream)
{
  auto get = [&](void* dst, const void* src, std::size_t bytes) {
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToHost, stream));
  };
  get(st.points + V, o.points, NV * sizeof(Vec3f));
  get(st.edgeIds + V, o.edgeIds, NV * sizeof(std::uint64_t));
  if (normals) get(st.normals + V, o.normals, NV * sizeof(Vec3f));
  if (colors) get(st.colors + V, o.colors, NV * sizeof(Rgba));
  get(st.tris + T, o.tris, NT * 3 * sizeof(unsigned int));
  if (cells) get(st.cells + T, o.cells, NT * sizeof(long long));
  if (keys) get(st.keys + T, o.keys, NT * 8 * sizeof(ColorKey));
}

// Closes the ranges of the N packed chunks (V vertices, T triangles in all) and
// drops the chunks without triangles (their ranges are empty).
void finishPacked(PackedChunkMeshes& out, std::size_t N, std::uint64_t V, std::uint64_t T)
{
  out.vertexStart[N] = V;
  out.triangleStart[N] = T;
  std::size_t k = 0;
  for (std::size_t i = 0; i < N; ++i)
  {
    if (out.triangleStart[i + 1] == out.triangleStart[i]) continue;
    out.chunkIds[k] = out.chunkIds[i];
    out.chunkCoords[k] = out.chunkCoords[i];
    out.chunkCells[k] = out.chunkCells[i];
    out.vertexStart[k] = out.vertexStart[i];
    out.triangleStart[k] = out.triangleStart[i];
    ++k;
  }
  out.chunkIds.resize(k);
  out.chunkCoords.resize(k);
  out.chunkCells.resize(k);
  out.vertexStart[k] = V;
  out.triangleStart[k] = T;
  out.vertexStart.resize(k + 1);
  out.triangleStart.resize(k + 1);
}

/// The streamed pipeline (S.lock held). Per batch: upload its boxes, classify,
/// scan and read back the per-chunk bases (the one synchronization: the host
/// needs the batch's sizes), then generate into output set `slot` on the
/// compute stream while the copy stream is still copying the previous batch's
/// set into the page-locked block; the set is reused only after its copy ended.
void packLocked(const ChunkedMarchingCubes::Impl& impl, MarchingCubesCudaState& S, const std::vector<std::int64_t>& ids,
  PackedChunkMeshes& out, Interrupter& interrupter)
{
  S.ensureStreams();
  const Box common = commonBox(impl);
  const bool normals = common.normals, colors = impl.wantsColors(), cells = common.cells;
  const std::size_t N = ids.size();
  out.chunkIds = ids;
  out.chunkCoords.resize(N);
  out.chunkCells.resize(N);
  out.vertexStart.assign(N + 1, 0);
  out.triangleStart.assign(N + 1, 0);
  if (!out.storage || out.storage.use_count() > 1) out.storage = std::make_shared<PackedChunkMeshes::Storage>();
  PackedChunkMeshes::Storage& st = *out.storage;
  if (N > 0) ensureGrid(impl, S);
  long long totalPoints = 0;
  std::vector<Box> all(N);
  for (std::size_t i = 0; i < N; ++i)
  {
    require(ids[i] >= 0 && ids[i] < impl.Total, "marching cubes: chunk id " + std::to_string(ids[i]) + " out of range");
    out.chunkCoords[i] = impl.globalCoord(ids[i]);
    out.chunkCells[i] = impl.cells(ids[i]);
    Box b = common;
    b.values = S.grid.p;
    b.colors = colors ? S.gridColors.p : nullptr;
    for (int a = 0; a < 3; ++a) b.size[a] = impl.Dims[a];
    setCells(b, out.chunkCells[i]);
    all[i] = b;
    totalPoints += (b.ex + 1) * (b.ey + 1) * (b.ez + 1);
  }
  const long long batchPoints = impl.Options.cudaBatchPoints > 0 ? impl.Options.cudaBatchPoints : BatchPoints;
  std::uint64_t V = 0, T = 0;
  long long pointsDone = 0;
  int slot = 0;
  std::vector<long long> pb, cb;
  std::vector<unsigned int> vb, tb;
  for (std::size_t first = 0; first < N;)
  {
    interrupter.checkInterrupt();
    // the batch: up to BatchPoints points and BatchChunks chunks
    std::size_t last = first;
    long long P = 0, C = 0, maxP = 1, maxC = 1;
    pb.assign(1, 0);
    cb.assign(1, 0);
    while (last < N && static_cast<int>(last - first) < BatchChunks)
    {
      const Box& b = all[last];
      const long long np = (b.ex + 1) * (b.ey + 1) * (b.ez + 1), nc = b.ex * b.ey * b.ez;
      if (last > first && P + np > batchPoints) break;
      P += np;
      C += nc;
      maxP = std::max(maxP, np);
      maxC = std::max(maxC, nc);
      pb.push_back(P);
      cb.push_back(C);
      ++last;
    }
    const int n = static_cast<int>(last - first);
    reserveBatch(S, n, P, C);
    cudaStream_t cs = S.compute;
    uploadBatch(S, all.data() + first, n, pb, cb, P, C, cs);
    classifyBatch(S, n, P, C, maxP, maxC, vb, tb, cs);
    const std::uint64_t NV = vb[n], NT = tb[n];
    for (int i = 0; i < n; ++i)
    {
      out.vertexStart[first + i] = V + vb[i];
      out.triangleStart[first + i] = T + tb[i];
    }
    pointsDone += P;
    if (NT > 0)
    {
      if (V + NV > st.vcap || T + NT > st.tcap || !st.block || !st.pinned || st.normalsOn != normals ||
        st.colorsOn != colors || st.cellsOn != cells || st.keysOn)
      {
        // grow the page-locked block: wait for the copies into it, estimate the total from the share done
        LVDIF_CUDA_CHECK(cudaStreamSynchronize(S.copy));
        const double scale = static_cast<double>(totalPoints) / static_cast<double>(pointsDone) * 1.1;
        st.reserve(static_cast<std::uint64_t>((V + NV) * scale) + 1, static_cast<std::uint64_t>((T + NT) * scale) + 1,
          V, T, true, normals, colors, cells, false);
      }
      if (S.copyPending[slot]) LVDIF_CUDA_CHECK(cudaEventSynchronize(S.copied[slot]));
      S.copyPending[slot] = false;
      const Out o = S.out[slot].reserve(NV, NT, normals, colors, cells, false);
      generateBatch(S, o, n, maxP, maxC, cs);
      LVDIF_CUDA_CHECK(cudaEventRecord(S.generated[slot], cs));
      cudaStream_t cp = S.copy;
      LVDIF_CUDA_CHECK(cudaStreamWaitEvent(cp, S.generated[slot], 0));
      copyBatchToHost(st, o, V, T, NV, NT, normals, colors, cells, false, cp);
      LVDIF_CUDA_CHECK(cudaEventRecord(S.copied[slot], cp));
      S.copyPending[slot] = true;
      slot ^= 1;
    }
    V += NV;
    T += NT;
    first = last;
    interrupter.progress(static_cast<double>(pointsDone) / static_cast<double>(std::max(totalPoints, 1ll)));
  }
  LVDIF_CUDA_CHECK(cudaStreamSynchronize(S.copy));
  S.copyPending[0] = S.copyPending[1] = false;
  finishPacked(out, N, V, T);
}
} // namespace

namespace
{
/// Decodes each chunk's input box (its points plus the gradient margin, the
/// boxes of ChunkedMarchingCubes::gather) from the device-resident volume into
/// the batch's value, colour and key buffers the boxes point at.
__global__ void gatherFromVolume(DeviceVolumeView v, const Box* boxes)
{
  const Box& b = boxes[blockIdx.y];
  const long long count = b.size[0] * b.size[1] * b.size[2];
  const long long p = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (p >= count) return;
  const long long x = b.lo[0] + p % b.size[0], y = b.lo[1] + (p / b.size[0]) % b.size[1],
                  z = b.lo[2] + p / (b.size[0] * b.size[1]);
  const long long m = v.chunkEdge - 1;
  const long long id =
    (x >> v.shift) + v.chunkCounts[0] * ((y >> v.shift) + v.chunkCounts[1] * (z >> v.shift));
  const int slot = v.slotOf[id];
  std::uint32_t bits;
  if (slot < 0)
    bits = v.uniform[id];
  else
  {
    const long long n = static_cast<long long>(v.chunkEdge) * v.chunkEdge * v.chunkEdge;
    bits = v.pool[slot * n + (x & m) + ((y & m) << v.shift) + ((z & m) << (2 * v.shift))];
  }
  const_cast<float*>(b.values)[p] = v.sdfTable[bits & 0xffffu];
  const std::uint32_t key = bits >> 16;
  if (b.colors)
  {
    const std::uint32_t c = v.palette[key];
    Rgba rgba;
    rgba.r = static_cast<std::uint8_t>(c & 0xffu);
    rgba.g = static_cast<std::uint8_t>((c >> 8) & 0xffu);
    rgba.b = static_cast<std::uint8_t>((c >> 16) & 0xffu);
    rgba.a = static_cast<std::uint8_t>(c >> 24);
    const_cast<Rgba*>(b.colors)[p] = rgba;
  }
  if (b.keys) const_cast<ColorKey*>(b.keys)[p] = static_cast<ColorKey>(key);
}

/// extractChunksFromDevice with S.lock held: per batch (up to BatchPoints points)
/// gather on the device, classify, scan, read back the per-chunk bases, generate,
/// copy the arrays into the page-locked block; all on the compute stream.
void packFromDeviceLocked(const ChunkedMarchingCubes::Impl& impl, MarchingCubesCudaState& S, const DeviceVolumeView& v,
  const std::vector<std::int64_t>& ids, PackedChunkMeshes& out)
{
  S.ensureStreams();
  const Box common = commonBox(impl);
  const bool normals = common.normals, colors = impl.wantsColors(), cells = common.cells,
             keys = impl.wantsCornerColors();
  const std::size_t N = ids.size();
  out.chunkIds = ids;
  out.chunkCoords.resize(N);
  out.chunkCells.resize(N);
  out.vertexStart.assign(N + 1, 0);
  out.triangleStart.assign(N + 1, 0);
  if (!out.storage || out.storage.use_count() > 1) out.storage = std::make_shared<PackedChunkMeshes::Storage>();
  PackedChunkMeshes::Storage& st = *out.storage;
  std::vector<Box> all(N);
  std::vector<long long> gatherPoints(N);
  for (std::size_t i = 0; i < N; ++i)
  {
    require(ids[i] >= 0 && ids[i] < impl.Total, "marching cubes: chunk id " + std::to_string(ids[i]) + " out of range");
    out.chunkCoords[i] = impl.globalCoord(ids[i]);
    out.chunkCells[i] = impl.cells(ids[i]);
    Box b = common;
    setCells(b, out.chunkCells[i]);
    for (int a = 0; a < 3; ++a)
    {
      // the box ChunkedMarchingCubes::gather copies: the points plus one on each side (gradients)
      b.lo[a] = std::max<long long>(out.chunkCells[i].lo[a] - 1, 0);
      const long long hi = std::min<long long>(out.chunkCells[i].hi[a] + 2, impl.Dims[a] - 1);
      b.size[a] = hi - b.lo[a] + 1;
    }
    gatherPoints[i] = b.size[0] * b.size[1] * b.size[2];
    all[i] = b;
  }
  cudaStream_t cs = S.compute;
  std::uint64_t V = 0, T = 0;
  std::vector<long long> pb, cb, gb;
  std::vector<unsigned int> vb, tb;
  for (std::size_t first = 0; first < N;)
  {
    std::size_t last = first;
    long long P = 0, C = 0, G = 0, maxP = 1, maxC = 1, maxG = 1;
    pb.assign(1, 0);
    cb.assign(1, 0);
    gb.assign(1, 0);
    while (last < N && static_cast<int>(last - first) < BatchChunks)
    {
      const Box& b = all[last];
      const long long np = (b.ex + 1) * (b.ey + 1) * (b.ez + 1), nc = b.ex * b.ey * b.ez, ng = gatherPoints[last];
      if (last > first && G + ng > BatchPoints) break;
      P += np;
      C += nc;
      G += ng;
      maxP = std::max(maxP, np);
      maxC = std::max(maxC, nc);
      maxG = std::max(maxG, ng);
      pb.push_back(P);
      cb.push_back(C);
      gb.push_back(G);
      ++last;
    }
    const int n = static_cast<int>(last - first);
    // interactive frames vary in size: grow with half again as slack, so that a
    // slightly larger frame does not pay a cudaFree + cudaMalloc (a device sync)
    auto slack = [](long long x) { return x + x / 2; };
    reserveBatch(S, static_cast<int>(slack(n)), slack(P), slack(C));
    S.boxValues.reserve(static_cast<std::size_t>(slack(G)));
    if (colors) S.boxColors.reserve(static_cast<std::size_t>(slack(G)));
    if (keys) S.boxKeys.reserve(static_cast<std::size_t>(slack(G)));
    for (int i = 0; i < n; ++i)
    {
      Box& b = all[first + i];
      b.values = S.boxValues.p + gb[i];
      b.colors = colors ? S.boxColors.p + gb[i] : nullptr;
      b.keys = keys ? S.boxKeys.p + gb[i] : nullptr;
    }
    uploadBatch(S, all.data() + first, n, pb, cb, P, C, cs);
    gatherFromVolume<<<dim3(blocks(maxG), n), 256, 0, cs>>>(v, S.boxes.p);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    classifyBatch(S, n, P, C, maxP, maxC, vb, tb, cs);
    const std::uint64_t NV = vb[n], NT = tb[n];
    for (int i = 0; i < n; ++i)
    {
      out.vertexStart[first + i] = V + vb[i];
      out.triangleStart[first + i] = T + tb[i];
    }
    if (NT > 0)
    {
      st.reserve(V + NV, T + NT, V, T, true, normals, colors, cells, keys);
      if (S.copyPending[0]) LVDIF_CUDA_CHECK(cudaEventSynchronize(S.copied[0]));
      S.copyPending[0] = false;
      S.out[0].reserve(slack(NV), slack(NT), normals, colors, cells, keys);
      const Out o = S.out[0].reserve(NV, NT, normals, colors, cells, keys);
      generateBatch(S, o, n, maxP, maxC, cs);
      copyBatchToHost(st, o, V, T, NV, NT, normals, colors, cells, keys, cs);
      LVDIF_CUDA_CHECK(cudaStreamSynchronize(cs));
    }
    V += NV;
    T += NT;
    first = last;
  }
  finishPacked(out, N, V, T);
}
} // namespace

void packChunksFromDeviceVolumeCuda(const ChunkedMarchingCubes::Impl& impl, const DeviceVolumeView& volume,
  const std::vector<std::int64_t>& ids, PackedChunkMeshes& out)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  packFromDeviceLocked(impl, S, volume, ids, out);
}

void packChunksCuda(const ChunkedMarchingCubes::Impl& impl, const std::vector<std::int64_t>& ids,
  PackedChunkMeshes& out, Interrupter& interrupter)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  packLocked(impl, S, ids, out, interrupter);
}

std::vector<ChunkMesh> meshChunksCuda(const ChunkedMarchingCubes::Impl& impl, const std::vector<std::int64_t>& ids,
  Interrupter& interrupter)
{
  MarchingCubesCudaState& S = *impl.Cuda;
  std::lock_guard<std::mutex> guard(S.lock);
  std::vector<std::int64_t> work;
  for (std::int64_t id : ids)
  {
    require(id >= 0 && id < impl.Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
    if (!impl.empty(id)) work.push_back(id);
  }
  std::sort(work.begin(), work.end());
  work.erase(std::unique(work.begin(), work.end()), work.end());
  PackedChunkMeshes& pk = S.staging;
  packLocked(impl, S, work, pk, interrupter);
  // split into per-chunk vectors (pk.chunkIds is increasing)
  std::vector<ChunkMesh> out(ids.size());
  const std::int64_t n = static_cast<std::int64_t>(ids.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t i = 0; i < n; ++i)
  {
    const std::int64_t id = ids[i];
    const auto it = std::lower_bound(pk.chunkIds.begin(), pk.chunkIds.end(), id);
    if (it != pk.chunkIds.end() && *it == id)
    {
      out[i] = pk.chunk(static_cast<std::size_t>(it - pk.chunkIds.begin()));
      continue;
    }
    out[i].chunkId = id;
    out[i].chunkCoord = impl.globalCoord(id);
    out[i].cells = impl.cells(id);
  }
  return out;
}

void dropMarchingCubesCudaGrid(MarchingCubesCudaState& state)
{
  std::lock_guard<std::mutex> guard(state.lock);
  state.hostGrid = nullptr;
}

} // namespace lvdif
