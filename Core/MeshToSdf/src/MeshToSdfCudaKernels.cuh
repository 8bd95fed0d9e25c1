// Device side of mesh to SDF on CUDA (included by MeshToSdfCuda.cu only):
// the data layouts on the GPU, the distance pass (runs of 16 voxels along x:
// a run farther than the band from every leaf box of the tree saturated after
// one traversal, the others listed and queried by full warps, one thread per
// run: nearest triangle on the BVH, warm-started, far voxels skipped by the
// Lipschitz bound), the sign kernel (one
// warp per scan line: the lanes cast the ray of the closed chain together,
// each walking one subtree of the BVH (MeshToSdfRayWalk.h), into shared
// memory; the lanes compute the drift bounds of 32 voxels at a time, every
// lane walks the carried interval with the same values so control flow stays
// uniform (a closed chain carries none: each lane counts the crossings up to
// its own voxels), and an exact evaluation of the cone's solid angle is split
// over the lanes as lane-strided partial sums reduced by an xor butterfly: the
// order the CPU's laneOrderedSum reproduces) and the chunk-encoding kernels of
// the dictionary-volume path. Triangles are read from compact leaf-ordered
// records (vertices + normal, 96 bytes; MeshToSdfCudaLayout.cuh) rather than
// the triangle records.
#pragma once

#include "MeshToSdfCudaLayout.cuh"
#include "MeshToSdfCudaNearest.cuh"
#include "MeshToSdfFarBlocks.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfRayWalk.h"
#include "lvdif/CudaCheck.cuh"
#include "lvdif/SdfDictionary.h"

#include <cstdlib>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

using namespace detail::meshtosdf;

namespace
{
constexpr int SignWarps = 4;   // warps (scan lines) per block of the sign kernel
constexpr unsigned FullMask = 0xffffffffu;
constexpr int MaxHits = 96;    // crossings a scan line may hold (more: per-voxel fallback)

struct Params
{
  double origin[3], spacing[3];
  long long lo[3], hi[3]; // the slab, in grid indices
  double toOut, band, bandWorld, reach;
  int sign; // 0 normal, 1 pseudo-normal, 2 winding, 3 unsigned
  int useVertexNormals;
  int bounded;
  // far cells of the slab (MeshToSdfCudaFar.cuh; null: none): per cell the
  // side and the mask of its voxels (bit x + 2 y + 4 z) that are side * band
  const signed char* far = nullptr;
  const unsigned char* farMask = nullptr;
  long long farCount[2] = { 0, 0 }; // cells along x and y
};

__device__ V3 positionOf(const Params& P, long long i, long long j, long long k)
{
  return { P.origin[0] + i * P.spacing[0], P.origin[1] + j * P.spacing[1], P.origin[2] + k * P.spacing[2] };
}

/// Whether every leaf box of the tree lies farther than sqrt(r2) from the box
/// [a, b] (so every triangle does); nearer children first, so that a box near
/// the surface meets a leaf soon and stops.
__device__ bool boxFarDev(const DevBvh& bvh, V3 a, V3 b, double r2)
{
  auto dist2 = [&](const GpuNode& n) {
    double s = 0;
    for (int ax = 0; ax < 3; ++ax)
    {
      const double d = b[ax] < n.lo[ax] ? n.lo[ax] - b[ax] : (a[ax] > n.hi[ax] ? a[ax] - n.hi[ax] : 0.0);
      s += d * d;
    }
    return s;
  };
  if (dist2(bvh.nodes[0]) > r2) return true;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const GpuNode n = bvh.nodes[stack[--top]];
    if (n.left < 0) return false;
    const double dl = dist2(bvh.nodes[n.left]), dr = dist2(bvh.nodes[n.right]);
    const int nearC = dl <= dr ? n.left : n.right, farC = dl <= dr ? n.right : n.left;
    const double nearD = dl <= dr ? dl : dr, farD = dl <= dr ? dr : dl;
    if (top + 2 > 64) return false;
    if (farD <= r2) stack[top++] = farC;
    if (nearD <= r2) stack[top++] = nearC;
  }
  return true;
}

/// The distance pass in two kernels. distanceSettleKernel takes every run of
/// DistanceRun voxels along x (a warp: that run in 32 neighbouring rows) and
/// settles the runs that need no query: farther than the band from every
/// leaf box of the tree (saturated after one traversal), or decided voxel by
/// voxel by the far cells; it lists the others. distanceRunKernel then runs
/// the queries of the listed runs, each warp taking the next 32 (in list
/// order: neighbouring rows, so its queries follow similar paths). Before,
/// one kernel did both: most lanes of a warp settled at once and idled while
/// the few in the band queried (NVIDIA H200, 13.3M triangles at 1024^3, the
/// first slab: 4.7 of 32 lanes active; the 832k-triangle mesh's distance
/// pass 9 % shorter with the list, docs/BENCHMARKS.md). A run's values
/// depend on that run alone (its hint and bound start afresh), so the list's
/// order, which the atomics make vary, changes no value.
constexpr int DistanceRun = 16;

struct DistanceRunAt
{
  long long i0, i1, j, k, row;
};

__device__ DistanceRunAt distanceRunAt(const Params& P, long long run, long long row)
{
  const long long ny = P.hi[1] - P.lo[1] + 1;
  DistanceRunAt r;
  r.row = row;
  r.j = P.lo[1] + row % ny;
  r.k = P.lo[2] + row / ny;
  r.i0 = P.lo[0] + run * DistanceRun;
  r.i1 = min(P.hi[0], r.i0 + DistanceRun - 1);
  return r;
}

/// Whether voxel i of the run is decided by the far cells; then its value.
__device__ bool farCellValue(const Params& P, const DistanceRunAt& r, long long i, float& value)
{
  if (!P.far) return false;
  const long long jj = r.j - P.lo[1], kk = r.k - P.lo[2];
  const long long at = P.farCount[0] * (jj / FarCell + P.farCount[1] * (kk / FarCell)) + (i - P.lo[0]) / FarCell;
  const int bit = static_cast<int>(2 * (jj & 1) + 4 * (kk & 1) + ((i - P.lo[0]) & 1));
  if (((P.farMask[at] >> bit) & 1) == 0) return false;
  value = static_cast<float>(P.far[at]) * static_cast<float>(P.band);
  return true;
}

/// Settles the run if it needs no query (true), writing its voxels.
__device__ bool settleRun(const DevBvh& bvh, const Params& P, const DistanceRunAt& r, float* rowOut)
{
  if (P.bounded && boxFarDev(bvh, positionOf(P, r.i0, r.j, r.k), positionOf(P, r.i1, r.j, r.k), P.bandWorld * P.bandWorld))
  {
    // every voxel of the run is farther than the band from every triangle:
    // saturated, as its query would leave it (one traversal instead of a
    // query every few voxels; the CPU skips by its own bounds, to the same values)
    for (long long i = r.i0; i <= r.i1; ++i) rowOut[i] = static_cast<float>(P.band);
    return true;
  }
  if (!P.far) return false;
  float v;
  for (long long i = r.i0; i <= r.i1; ++i)
    if (!farCellValue(P, r, i, v)) return false;
  for (long long i = r.i0; i <= r.i1; ++i)
  {
    farCellValue(P, r, i, v);
    rowOut[i] = v;
  }
  return true;
}

/// The queries of one run, warm-started from the previous voxel's triangle,
/// voxels within the previous distance's Lipschitz bound of the band skipped.
__device__ void queryRun(const DevBvh& bvh, const Params& P, const DistanceRunAt& r, float* rowOut)
{
  const double h = P.spacing[0];
  double lower = -1;
  int hint = -1;
  for (long long i = r.i0; i <= r.i1; ++i)
  {
    float farValue;
    if (farCellValue(P, r, i, farValue))
    {
      rowOut[i] = farValue;
      continue;
    }
    lower -= h;
    if (P.bounded && lower >= P.bandWorld)
    {
      rowOut[i] = static_cast<float>(P.band);
      continue;
    }
    const V3 p = positionOf(P, i, r.j, r.k);
    int slot = -1;
    const NearestResult nr = nearestDev(bvh, p, hint, P.bounded ? P.reach * P.reach : 1e300, slot);
    double d = nr.tri < 0 ? P.band : sqrt(nr.dist2) * P.toOut;
    lower = nr.tri < 0 ? P.reach : sqrt(nr.dist2);
    d = fmin(d, P.band);
    float s = 1.0f;
    if (nr.tri >= 0)
    {
      hint = slot;
      if (P.sign == 0 || P.sign == 1)
      {
        const Tri& tr = bvh.tris[nr.tri];
        const V3 n = P.sign == 1 ? featureNormal(tr, bvh.normals[nr.tri], nr.closest.feature)
                                 : interpolatedNormal(tr, P.useVertexNormals && bvh.corners ? &bvh.corners[nr.tri] : nullptr,
                                     nr.closest.b1, nr.closest.b2);
        s = normalSign(p, nr.closest.point, n);
      }
    }
    rowOut[i] = s * static_cast<float>(d);
  }
}

/// The runs of the slab in P: settles what needs no query, lists the rest
/// (run + runs * row) in list[0, work[0]) (work[0] zeroed before).
__global__ void __launch_bounds__(128) distanceSettleKernel(DevBvh bvh, Params P, float* out, long long* list,
  unsigned long long* work)
{
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  const long long runs = (nx + DistanceRun - 1) / DistanceRun;
  const long long tilesY = (ny + 31) / 32;
  const long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  const long long tile = t / 32;
  const int lane = static_cast<int>(t % 32);
  // a warp: run (tile % runs) in rows 32 (tile / runs % tilesY) + lane of layer tile / (runs tilesY)
  const long long run = tile % runs;
  const long long jj = ((tile / runs) % tilesY) * 32 + lane;
  const long long kk = tile / (runs * tilesY);
  bool listed = false;
  long long id = 0;
  if (kk < nz && jj < ny)
  {
    const long long row = jj + ny * kk;
    const DistanceRunAt r = distanceRunAt(P, run, row);
    float* rowOut = out + row * nx - P.lo[0];
    listed = !settleRun(bvh, P, r, rowOut);
    id = run + runs * row;
  }
  // one atomic per warp; the lanes keep their order in the list
  const unsigned mask = __ballot_sync(FullMask, listed);
  if (mask == 0) return;
  unsigned long long base = 0;
  if (lane == 0) base = atomicAdd(work, static_cast<unsigned long long>(__popc(mask)));
  base = __shfl_sync(FullMask, base, 0);
  if (listed) list[base + __popc(mask & ((1u << lane) - 1u))] = id;
}

/// The listed runs' queries; each warp takes the next 32 runs of the list
/// (work[1] the next unclaimed) until none is left. At most 64 registers (8
/// blocks of 128 per SM; the spills cost less than the occupancy gains, as
/// measured for the single kernel before).
__global__ void __launch_bounds__(128, 8) distanceRunKernel(DevBvh bvh, Params P, float* out, const long long* list,
  unsigned long long* work)
{
  const long long nx = P.hi[0] - P.lo[0] + 1;
  const long long runs = (nx + DistanceRun - 1) / DistanceRun;
  const int lane = static_cast<int>(threadIdx.x % 32);
  const unsigned long long n = work[0];
  for (;;)
  {
    unsigned long long base = 0;
    if (lane == 0) base = atomicAdd(work + 1, 32ull);
    base = __shfl_sync(FullMask, base, 0);
    if (base >= n) break;
    const unsigned long long k = base + static_cast<unsigned long long>(lane);
    if (k < n)
    {
      const long long id = list[k];
      const long long row = id / runs;
      const DistanceRunAt r = distanceRunAt(P, id % runs, row);
      queryRun(bvh, P, r, out + row * nx - P.lo[0]);
    }
  }
}

/// Where the distance pass keeps its run list between its two kernels.
struct DistanceLists
{
  long long* list = nullptr;
  unsigned long long* work = nullptr; // [0] listed runs, [1] the next to claim
  long long capacity = 0;
  int runGrid = 0; // CUDA blocks of distanceRunKernel that fill the GPU
};

/// Runs in a slab of P (what DistanceLists::list must hold).
inline long long distanceRuns(const Params& P)
{
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  return ((nx + DistanceRun - 1) / DistanceRun) * ny * nz;
}

/// Queues both kernels of the distance pass on the legacy stream.
void launchDistance(const DevBvh& bvh, const Params& P, float* out, const DistanceLists& w)
{
  const long long ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  const long long runs = (P.hi[0] - P.lo[0] + DistanceRun) / DistanceRun;
  const long long warps = runs * ((ny + 31) / 32) * nz;
  LVDIF_CUDA_CHECK(cudaMemsetAsync(w.work, 0, 2 * sizeof(unsigned long long)));
  distanceSettleKernel<<<static_cast<unsigned>((warps * 32 + 127) / 128), 128>>>(bvh, P, out, w.list, w.work);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  distanceRunKernel<<<static_cast<unsigned>(w.runGrid), 128>>>(bvh, P, out, w.list, w.work);
  LVDIF_CUDA_CHECK(cudaGetLastError());
}

struct Hit
{
  double t;
  int tri;
  int sign;
};

/// Mirrors Bvh::rayHits (MeshToSdfRayWalk.h). Returns false when ambiguous
/// or (collecting) when more than MaxHits crossings; otherwise the signed sum
/// is in *sum.
__device__ bool rayDev(const DevBvh& b, V3 o, V3 dir, Hit* hits, int* count, int* sum)
{
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  *sum = 0;
  if (count) *count = 0;
  return rayWalk(b.nodes, b.leaf, b.order, 0, o, dir, inv, *sum, [&](double t, int tri, int sg) {
    if (!hits) return true;
    if (*count >= MaxHits) return false;
    hits[(*count)++] = { t, tri, sg };
    return true;
  });
}

/// Sum of f(c) for c in [0, n) in the order of the CPU's laneOrderedSum:
/// lane l adds c = l, l + 32, ... in order, then an xor butterfly (every lane
/// ends with the same bits: IEEE addition is commutative).
template <typename F>
__device__ double warpOrderedSum(int n, int lane, F f)
{
  double s = 0;
  for (int c = lane; c < n; c += 32) s += f(c);
  for (int off = 16; off > 0; off >>= 1) s += __shfl_xor_sync(FullMask, s, off);
  return s;
}

/// The cone's winding number at p, all lanes of the warp together.
__device__ double coneWindingWarp(const WindingDev& W, V3 p, int lane)
{
  return warpOrderedSum(W.coneCount, lane, [&](int c) {
    const GpuTri& t = W.cone[c];
    return solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

__device__ double driftDev(const WindingDev& W, V3 p, V3 q, double h)
{
  double sum = 0;
  for (int c = 0; c < W.clusterCount; ++c)
  {
    const WindingSigner::Cluster cl = W.clusters[c];
    const double m = 0.5 * (norm(p - cl.centre) + norm(q - cl.centre) - h) - cl.radius;
    if (!(m > 0)) return 1e300;
    sum += cl.length / (m * m);
  }
  return h * sum / FourPi;
}

/// WindingSigner::evaluate, all lanes of the warp together (each lane casts
/// the same oblique ray: same result, uniform control flow).
__device__ double evaluateWarp(const WindingDev& W, V3 p, int lane)
{
  const V3 dir = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
  int sum = 0;
  if (rayDev(W.closed, p, dir, nullptr, nullptr, &sum))
  {
    return sum - coneWindingWarp(W, p, lane);
  }
  // canonical solid angles: the same bits as the CPU's WindingSigner::evaluate
  return warpOrderedSum(W.allTris, lane, [&](int i) {
    const GpuTri& t = W.meshLeaf[W.meshSlot[i]];
    return solidAngleCanonical(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

__device__ bool insideOf(double w) { return fabs(w) >= 0.5; }
__device__ bool decidedDev(double lo, double hi) { return !(lo < 0.5 && hi >= 0.5) && !(lo <= -0.5 && hi > -0.5); }

/// The +x ray of a scan line (from half a voxel before its first voxel)
/// against the closed surface, the whole warp together: lane 0 splits the
/// walk into at most 32 subtrees (rayFrontier), each lane walks one and
/// appends its crossings to the warp's shared hits, lane 0 sorts them by t.
/// Every lane gets whether the ray was unambiguous (and held at most MaxHits
/// crossings), their number and their signed sum: what one walk gives
/// (MeshToSdfRayWalk.h). shared: the warp's RayShared.
struct RowRay
{
  int ok, count, sum;
};
struct RayShared
{
  Hit hits[MaxHits];
  int frontier[32], scratch[64];
  int count;
};
__device__ RowRay castRowRay(const WindingDev& W, V3 start, double h, RayShared& shared, int lane)
{
  const V3 o = start - V3{ 0.5 * h, 0, 0 }, dir{ 1, 0, 0 };
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  int subtrees = 0;
  if (lane == 0)
  {
    shared.count = 0;
    subtrees = rayFrontier(W.closed.nodes, o, dir, inv, 32, shared.frontier, shared.scratch);
  }
  subtrees = __shfl_sync(FullMask, subtrees, 0);
  __syncwarp();
  int sum = 0, ok = 1;
  if (lane < subtrees)
  {
    ok = rayWalk(W.closed.nodes, W.closed.leaf, W.closed.order, shared.frontier[lane], o, dir, inv, sum,
           [&](double t, int tri, int sg) {
             const int slot = atomicAdd(&shared.count, 1);
             if (slot >= MaxHits) return false;
             shared.hits[slot] = { t, tri, sg };
             return true;
           })
      ? 1
      : 0;
  }
  __syncwarp();
  RowRay r;
  r.ok = __all_sync(FullMask, ok) ? 1 : 0;
  for (int off = 16; off > 0; off >>= 1) sum += __shfl_xor_sync(FullMask, sum, off);
  r.sum = sum;
  r.count = min(shared.count, MaxHits);
  if (lane == 0 && r.ok)
  {
    Hit* hits = shared.hits;
    for (int a = 1; a < r.count; ++a) // insertion sort by t
    {
      const Hit x = hits[a];
      int b = a - 1;
      while (b >= 0 && hits[b].t > x.t)
      {
        hits[b + 1] = hits[b];
        --b;
      }
      hits[b + 1] = x;
    }
  }
  __syncwarp();
  return r;
}

/// The +x rays of the scan lines [rowBegin, rowEnd) of the slab, one thread
/// per line, before the sign kernels: each walk from the root (rayWalk, what
/// rayDev does) keeps at most RowHits crossings, sorted by t, in hits (RowHits
/// per line) and its outcome in meta: x = 1 unambiguous, 0 ambiguous, 2 more
/// than RowHits crossings (the sign kernel's warp casts that line again, up
/// to MaxHits); y = the crossings, z = their signed sum. A warp-wide cast per
/// line left the ray's walk to one latency-bound lane or a few (the tree's
/// nodes met by one ray are a thin path): here 32 lines walk at once.
constexpr int RowHits = 8;
__global__ void rowRayKernel(WindingDev W, Params P, long long rowBegin, long long rowEnd, Hit* hits, int4* meta)
{
  const long long row = rowBegin + static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (row >= rowEnd) return;
  const long long ny = P.hi[1] - P.lo[1] + 1;
  const long long j = P.lo[1] + row % ny, k = P.lo[2] + row / ny;
  const double h = P.spacing[0];
  const V3 start = positionOf(P, P.lo[0], j, k);
  const V3 o = start - V3{ 0.5 * h, 0, 0 }, dir{ 1, 0, 0 };
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  Hit local[RowHits];
  int count = 0, sum = 0;
  bool overflow = false;
  const bool ok = rayWalk(W.closed.nodes, W.closed.leaf, W.closed.order, 0, o, dir, inv, sum, [&](double t, int tri, int sg) {
    if (count >= RowHits)
    {
      overflow = true;
      return false;
    }
    local[count++] = { t, tri, sg };
    return true;
  });
  Hit* out = hits + (row - rowBegin) * RowHits;
  if (ok)
  {
    for (int a = 1; a < count; ++a) // insertion sort by t
    {
      const Hit x = local[a];
      int b = a - 1;
      while (b >= 0 && local[b].t > x.t)
      {
        local[b + 1] = local[b];
        --b;
      }
      local[b + 1] = x;
    }
    for (int a = 0; a < count; ++a) out[a] = local[a];
  }
  meta[row - rowBegin] = make_int4(ok ? 1 : (overflow ? 2 : 0), count, sum, 0);
}

/// The ray of scan line `row` as castRowRay gives it, from rowRayKernel's
/// results for the lines from rowBegin (a line with more than RowHits
/// crossings is cast again by the warp); the crossings end up in shared.hits.
__device__ RowRay rowRayOf(const WindingDev& W, V3 start, double h, RayShared& shared, int lane, const int4* meta,
  const Hit* hits, long long local)
{
  const int4 m = meta[local];
  if (m.x == 2) return castRowRay(W, start, h, shared, lane);
  if (m.x == 1 && lane < m.y) shared.hits[lane] = hits[local * RowHits + lane];
  __syncwarp();
  RowRay r;
  r.ok = m.x;
  r.count = m.y;
  r.sum = m.z;
  return r;
}

/// WindingSigner::signRow, one warp per scan line (see the file comment).
__global__ void signKernel(WindingDev W, Params P, long long rowBegin, long long rowEnd, const int4* rayMeta,
  const Hit* rayHits, float* out, unsigned long long* evals, unsigned long long* fallbacks)
{
  __shared__ RayShared sharedRay[SignWarps];
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1;
  const int lane = static_cast<int>(threadIdx.x % 32), warp = static_cast<int>(threadIdx.x / 32);
  const long long row = rowBegin + static_cast<long long>(blockIdx.x) * SignWarps + warp;
  if (row >= rowEnd) return; // the whole warp
  const long long j = P.lo[1] + row % ny, k = P.lo[2] + row / ny;
  float* rowOut = out + row * nx;
  const double h = P.spacing[0];
  const V3 start = positionOf(P, P.lo[0], j, k);
  auto pos = [&](long long i) { return start + V3{ static_cast<double>(i) * h, 0, 0 }; };
  const Hit* hits = sharedRay[warp].hits;
  const RowRay ray = rowRayOf(W, start, h, sharedRay[warp], lane, rayMeta, rayHits, row - rowBegin);
  const int ok = ray.ok, count = ray.count, sum = ray.sum;
  if (!ok)
  {
    for (long long i = 0; i < nx; ++i)
    {
      const double w = evaluateWarp(W, pos(i), lane);
      if (lane == static_cast<int>(i % 32) && insideOf(w)) rowOut[i] = -rowOut[i];
    }
    if (lane == 0)
    {
      atomicAdd(fallbacks, static_cast<unsigned long long>(nx));
      atomicAdd(evals, static_cast<unsigned long long>(nx));
    }
    return;
  }
  int ahead = sum;
  int next = 0;
  const bool open = W.coneCount > 0;
  if (!open)
  {
    // a closed chain: w is the crossing count, each lane walks the sorted
    // crossings up to its own voxels (they advance by 32 a step)
    for (long long mine = lane; mine < nx; mine += 32)
    {
      const double ti = 0.5 * h + static_cast<double>(mine) * h;
      while (next < count && hits[next].t <= ti) ahead -= hits[next++].sign;
      if (insideOf(ahead)) rowOut[mine] = -rowOut[mine];
    }
    return;
  }
  bool have = false;
  double lo = 0, hi = 0;
  unsigned long long ev = 0;
  for (long long base = 0; base < nx; base += 32)
  {
    const long long mine = base + lane;
    // the drift bound from voxel mine - 1 to mine (used only while an interval is carried)
    const double myDrift = open && mine > 0 && mine < nx ? driftDev(W, pos(mine - 1), pos(mine), h) : 0.0;
    const long long end = base + 32 < nx ? base + 32 : nx;
    bool myInside = false;
    for (long long i = base; i < end; ++i)
    {
      const double ti = 0.5 * h + static_cast<double>(i) * h;
      int jumpMesh = 0;
      while (next < count && hits[next].t <= ti)
      {
        ahead -= hits[next].sign;
        if (hits[next].tri < W.meshTris) jumpMesh += hits[next].sign;
        ++next;
      }
      double w;
      if (!open)
      {
        w = ahead;
      }
      else
      {
        const double drift = __shfl_sync(FullMask, myDrift, static_cast<int>(i - base));
        if (have)
        {
          if (drift < 1e299)
          {
            lo = lo - jumpMesh - drift;
            hi = hi - jumpMesh + drift;
          }
          else
          {
            have = false;
          }
        }
        if (!have || !decidedDev(lo, hi))
        {
          const double exact = ahead - coneWindingWarp(W, pos(i), lane);
          lo = exact - 1e-9;
          hi = exact + 1e-9;
          have = true;
          ++ev;
        }
        w = 0.5 * (lo + hi);
      }
      if (i - base == lane) myInside = insideOf(w);
    }
    if (mine < nx && myInside) rowOut[mine] = -rowOut[mine];
  }
  if (lane == 0 && ev) atomicAdd(evals, ev);
}

/// One thread block per chunk of the slab: encodes every voxel (the host's
/// SdfDictionary::encodeWith, band-clamped as DictionaryVolume::encode) and
/// records the chunk's key when all are equal, NotUniform otherwise.
__global__ void chunkUniformKernel(const float* slab, long long nx, long long ny, long long nz, int edge, int ccx,
  int ccy, SdfDictionary::EncodeConstants E, float band, unsigned* flags)
{
  const long long c = blockIdx.x;
  const long long cx = c % ccx, cy = (c / ccx) % ccy, cz = c / (static_cast<long long>(ccx) * ccy);
  const long long x0 = cx * edge, y0 = cy * edge, z0 = cz * edge;
  const long long ex = min(nx - x0, static_cast<long long>(edge)), ey = min(ny - y0, static_cast<long long>(edge));
  const long long ez = min(nz - z0, static_cast<long long>(edge));
  auto keyAt = [&](long long lx, long long ly, long long lz) {
    float v = slab[(x0 + lx) + nx * ((y0 + ly) + ny * (z0 + lz))];
    if (v > band) v = band;
    if (v < -band) v = -band;
    return SdfDictionary::encodeWith(E, v);
  };
  const SdfKey first = keyAt(0, 0, 0);
  int differs = 0;
  const long long count = ex * ey * ez;
  for (long long l = threadIdx.x; l < count && !differs; l += blockDim.x)
  {
    differs = keyAt(l % ex, (l / ex) % ey, l / (ex * ey)) != first;
  }
  differs = __syncthreads_or(differs);
  if (threadIdx.x == 0) flags[c] = differs ? ChunkKeys::NotUniform : static_cast<unsigned>(first);
}

/// One thread block per listed chunk: its keys in localIndex layout (x fastest
/// inside the chunk); voxels outside the grid are left unwritten.
__global__ void chunkKeysKernel(const float* slab, long long nx, long long ny, long long nz, int edge, int ccx,
  int ccy, SdfDictionary::EncodeConstants E, float band, const long long* list, unsigned short* keys)
{
  const long long c = list[blockIdx.x];
  const long long cx = c % ccx, cy = (c / ccx) % ccy, cz = c / (static_cast<long long>(ccx) * ccy);
  const long long x0 = cx * edge, y0 = cy * edge, z0 = cz * edge;
  const long long e3 = static_cast<long long>(edge) * edge * edge;
  unsigned short* out = keys + static_cast<long long>(blockIdx.x) * e3;
  for (long long l = threadIdx.x; l < e3; l += blockDim.x)
  {
    const long long x = x0 + l % edge, y = y0 + (l / edge) % edge, z = z0 + l / (static_cast<long long>(edge) * edge);
    if (x >= nx || y >= ny || z >= nz) continue;
    float v = slab[x + nx * (y + ny * z)];
    if (v > band) v = band;
    if (v < -band) v = -band;
    out[l] = SdfDictionary::encodeWith(E, v);
  }
}

__global__ void encodeKernel(SdfDictionary::EncodeConstants E, float band, const float* in, long long n,
  unsigned short* out)
{
  const long long i = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= n) return;
  float v = in[i];
  if (v > band) v = band;
  if (v < -band) v = -band;
  out[i] = SdfDictionary::encodeWith(E, v);
}
} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
