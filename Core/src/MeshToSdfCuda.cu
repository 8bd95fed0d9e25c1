// CUDA path of mesh to SDF: the same double-precision algorithms as the CPU
// (MeshToSdf.cpp distanceRow, MeshToSdfWinding.cpp signRow), run over the
// requested extent one slab of z layers at a time so device memory stays
// bounded (the slab buffer is at most 256 MiB, plus the mesh and BVHs).
// Kernel 1: one thread per run of 16 voxels along x (nearest triangle on the
// BVH, warm-started, far voxels skipped by the Lipschitz bound); a warp takes
// the same run in 32 neighbouring rows so its queries follow similar BVH
// paths (consecutive runs of one row, as before, diverge more).
// Kernel 2 (WindingNumber): one warp per scan line: lane 0 casts the ray
// (crossings of the closed chain) into shared memory, the lanes compute the
// drift bounds of 32 voxels at a time, every lane walks the carried interval
// (the same values in every lane, so control flow stays uniform) and an
// exact evaluation of the cone's solid angle is split over the 32 lanes
// (lane-strided partial sums, xor-butterfly reduction: the order the CPU's
// laneOrderedSum reproduces). Triangles are read from compact leaf-ordered
// records (vertices + normal, 96 bytes) rather than the 328-byte Tri.
#include "MeshToSdfCuda.h"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <vector>

namespace lvdif
{
namespace cudasdf
{

using namespace sdfdetail;

namespace
{
// distance kernel: a thread takes a run of voxels along x, a warp a tile of
// runs x rows (see launchDistance for the shape in use)
constexpr int SignWarps = 4;   // warps (scan lines) per block of the sign kernel
constexpr unsigned FullMask = 0xffffffffu;
constexpr int MaxHits = 96;    // crossings a scan line may hold (more: per-voxel fallback)
constexpr double FourPi = 12.566370614359172;

struct GpuNode
{
  double lo[3], hi[3];
  int left, right, first, count;
};

using GpuTri = LeafTri; // vertices and unit normal, in BVH leaf order

struct DevBvh
{
  const Tri* tris = nullptr;    // full records by triangle index: mesh BVH, Normal/PseudoNormal sessions only
  const GpuTri* leaf = nullptr; // leaf[i] = triangle order[i]
  const GpuNode* nodes = nullptr;
  const int* order = nullptr;
};

struct Params
{
  double origin[3], spacing[3];
  long long lo[3], hi[3]; // the slab, in grid indices
  double toOut, band, bandWorld, reach;
  int sign; // 0 normal, 1 pseudo-normal, 2 winding, 3 unsigned
  int useVertexNormals;
  int bounded;
};

struct WindingDev
{
  DevBvh closed;      // tris unused (null): leaf records only
  int meshTris = 0;
  const GpuTri* meshLeaf = nullptr; // the mesh BVH's leaves and the slot of each triangle there:
  const int* meshSlot = nullptr;    // the mesh in index order, for the all-solid-angle fallback
  const GpuTri* cone = nullptr;
  int coneCount = 0;
  const WindingSigner::Cluster* clusters = nullptr;
  int clusterCount = 0;
};

__device__ V3 positionOf(const Params& P, long long i, long long j, long long k)
{
  return { P.origin[0] + i * P.spacing[0], P.origin[1] + j * P.spacing[1], P.origin[2] + k * P.spacing[2] };
}

/// Bvh::nearest; the hint and the result's place are leaf slots (bestSlot).
__device__ NearestResult nearestDev(const DevBvh& b, V3 p, int hintSlot, double maxDist2, int& bestSlot)
{
  NearestResult best;
  best.dist2 = maxDist2;
  bestSlot = -1;
  if (hintSlot >= 0)
  {
    const GpuTri& t = b.leaf[hintSlot];
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 <= best.dist2)
    {
      best.dist2 = d2;
      best.tri = b.order[hintSlot];
      best.closest = c;
      bestSlot = hintSlot;
    }
  }
  int stackNode[64];
  double stackD2[64];
  int top = 0;
  stackNode[top] = 0;
  stackD2[top++] = pointBoxDist2(p, b.nodes[0].lo, b.nodes[0].hi);
  while (top > 0)
  {
    --top;
    if (stackD2[top] > best.dist2) continue;
    const GpuNode n = b.nodes[stackNode[top]];
    if (n.left < 0)
    {
      for (int i = n.first; i < n.first + n.count; ++i)
      {
        const int ti = b.order[i];
        if (ti == best.tri) continue;
        const GpuTri& t = b.leaf[i];
        const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
        const V3 d = c.point - p;
        const double d2 = dot(d, d);
        if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || ti < best.tri)))
        {
          best.dist2 = d2;
          best.tri = ti;
          best.closest = c;
          bestSlot = i;
        }
      }
      continue;
    }
    const double dl = pointBoxDist2(p, b.nodes[n.left].lo, b.nodes[n.left].hi);
    const double dr = pointBoxDist2(p, b.nodes[n.right].lo, b.nodes[n.right].hi);
    const int nearC = dl <= dr ? n.left : n.right, farC = dl <= dr ? n.right : n.left;
    const double nearD = dl <= dr ? dl : dr, farD = dl <= dr ? dr : dl;
    if (farD <= best.dist2 && top < 64) { stackNode[top] = farC; stackD2[top++] = farD; }
    if (nearD <= best.dist2 && top < 64) { stackNode[top] = nearC; stackD2[top++] = nearD; }
  }
  return best;
}

template <int Run, int TileRuns, int MinBlocks>
__global__ void __launch_bounds__(128, MinBlocks) distanceKernel(DevBvh bvh, Params P, float* out)
{
  constexpr int TileRows = 32 / TileRuns;
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  const long long runs = (nx + Run - 1) / Run;
  const long long tilesX = (runs + TileRuns - 1) / TileRuns, tilesY = (ny + TileRows - 1) / TileRows;
  const long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  const long long tile = t / 32;
  const int lane = static_cast<int>(t % 32);
  if (tile >= tilesX * tilesY * nz) return;
  const long long run = (tile % tilesX) * TileRuns + lane % TileRuns;
  const long long jj = ((tile / tilesX) % tilesY) * TileRows + lane / TileRuns;
  if (run >= runs || jj >= ny) return;
  const long long kk = tile / (tilesX * tilesY);
  const long long row = jj + ny * kk;
  const long long j = P.lo[1] + jj, k = P.lo[2] + kk;
  const long long i0 = P.lo[0] + run * Run, i1 = min(P.hi[0], i0 + Run - 1);
  float* rowOut = out + row * nx - P.lo[0];
  const double h = P.spacing[0];
  double lower = -1;
  int hint = -1;
  for (long long i = i0; i <= i1; ++i)
  {
    lower -= h;
    if (P.bounded && lower >= P.bandWorld)
    {
      rowOut[i] = static_cast<float>(P.band);
      continue;
    }
    const V3 p = positionOf(P, i, j, k);
    int slot = -1;
    const NearestResult r = nearestDev(bvh, p, hint, P.bounded ? P.reach * P.reach : 1e300, slot);
    double d = r.tri < 0 ? P.band : sqrt(r.dist2) * P.toOut;
    lower = r.tri < 0 ? P.reach : sqrt(r.dist2);
    d = fmin(d, P.band);
    float s = 1.0f;
    if (r.tri >= 0)
    {
      hint = slot;
      if (P.sign == 0 || P.sign == 1)
      {
        const Tri& tr = bvh.tris[r.tri];
        V3 n = tr.n;
        if (P.sign == 1)
        {
          n = featureNormal(tr, r.closest.feature);
        }
        else if (P.useVertexNormals && dot(tr.nv[0], tr.nv[0]) > 0)
        {
          const double b0 = 1 - r.closest.b1 - r.closest.b2;
          n = b0 * tr.nv[0] + r.closest.b1 * tr.nv[1] + r.closest.b2 * tr.nv[2];
        }
        s = dot(p - r.closest.point, n) < 0 ? -1.0f : 1.0f;
      }
    }
    rowOut[i] = s * static_cast<float>(d);
  }
}

template <int Run, int TileRuns, int MinBlocks>
void launchDistanceAs(const DevBvh& bvh, const Params& P, float* out)
{
  constexpr int TileRows = 32 / TileRuns;
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  const long long runs = (nx + Run - 1) / Run;
  const long long tiles = ((runs + TileRuns - 1) / TileRuns) * ((ny + TileRows - 1) / TileRows) * nz;
  distanceKernel<Run, TileRuns, MinBlocks><<<static_cast<unsigned>((tiles * 32 + 127) / 128), 128>>>(bvh, P, out);
  LVDIF_CUDA_CHECK(cudaGetLastError());
}

/// Runs of 16 voxels along x, a warp = one run in each of 32 neighbouring
/// rows (y), at most 64 registers (8 blocks of 128 per SM; the spills cost
/// less than the occupancy gains): the fastest shape measured on the H200
/// (docs/BENCHMARKS.md). LVDIF_SDF_DISTANCE_VARIANT (benchmarks only; every
/// shape computes the same values, and the CUDA tests pass with each) picks
/// another: 1 = the same without the register cap, 2 = at most 80 registers,
/// 3 = warps of 4 runs x 8 rows, no cap.
void launchDistance(const DevBvh& bvh, const Params& P, float* out)
{
  static const int variant = [] {
    const char* v = std::getenv("LVDIF_SDF_DISTANCE_VARIANT");
    return v ? std::atoi(v) : 0;
  }();
  switch (variant)
  {
    case 1: return launchDistanceAs<16, 1, 1>(bvh, P, out);
    case 2: return launchDistanceAs<16, 1, 6>(bvh, P, out);
    case 3: return launchDistanceAs<16, 4, 1>(bvh, P, out);
    default: return launchDistanceAs<16, 1, 8>(bvh, P, out);
  }
}

struct Hit
{
  double t;
  int tri;
  int sign;
};

/// Mirrors Bvh::rayHits. Returns false when ambiguous or (collecting) when
/// more than MaxHits crossings; otherwise the signed sum is in *sum.
__device__ bool rayDev(const DevBvh& b, V3 o, V3 dir, Hit* hits, int* count, int* sum)
{
  constexpr double Eps = 1e-9;
  const double tmin = 0.0;
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  *sum = 0;
  if (count) *count = 0;
  while (top > 0)
  {
    const GpuNode n = b.nodes[stack[--top]];
    double t0 = tmin, t1 = 1e300;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a)
    {
      const double da = dir[a], oa = o[a];
      if (da == 0)
      {
        miss = oa < n.lo[a] || oa > n.hi[a];
        continue;
      }
      double ta = (n.lo[a] - oa) * inv[a], tb = (n.hi[a] - oa) * inv[a];
      if (ta > tb) { const double x = ta; ta = tb; tb = x; }
      const double pad = 1e-9 * (fabs(ta) + fabs(tb)) + 1e-300;
      t0 = fmax(t0, ta - pad);
      t1 = fmin(t1, tb + pad);
      miss = t0 > t1;
    }
    if (miss) continue;
    if (n.left >= 0)
    {
      if (top + 2 > 64) return false;
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (int i = n.first; i < n.first + n.count; ++i)
    {
      const int ti = b.order[i];
      const GpuTri& t = b.leaf[i];
      const V3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
      const V3 pv = cross(dir, e2);
      const double det = dot(e1, pv);
      const double scale = norm(e1) * norm(e2) * norm(dir);
      const V3 tv = o - t.v[0];
      if (fabs(det) <= Eps * scale)
      {
        if (fabs(dot(tv, t.n)) <= Eps * (norm(tv) + norm(e1))) return false;
        continue;
      }
      const double invDet = 1.0 / det;
      const double u = dot(tv, pv) * invDet;
      const V3 qv = cross(tv, e1);
      const double v = dot(dir, qv) * invDet;
      const double tt = dot(e2, qv) * invDet;
      const double w = 1 - u - v;
      if (u < -Eps || v < -Eps || w < -Eps) continue;
      const double tScale = 1e-9 * (fabs(tt) + fabs(tmin) + norm(e1) / norm(dir));
      if (tt < tmin - tScale) continue;
      if (u <= Eps || v <= Eps || w <= Eps || fabs(tt - tmin) <= tScale) return false;
      const int sg = dot(dir, t.n) > 0 ? 1 : -1;
      *sum += sg;
      if (hits)
      {
        if (*count >= MaxHits) return false;
        hits[(*count)++] = { tt, ti, sg };
      }
    }
  }
  return true;
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
  return warpOrderedSum(W.meshTris, lane, [&](int i) {
    const GpuTri& t = W.meshLeaf[W.meshSlot[i]];
    return solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }) / FourPi;
}

__device__ bool insideOf(double w) { return fabs(w) >= 0.5; }
__device__ bool decidedDev(double lo, double hi) { return !(lo < 0.5 && hi >= 0.5) && !(lo <= -0.5 && hi > -0.5); }

/// WindingSigner::signRow, one warp per scan line (see the file comment).
__global__ void signKernel(WindingDev W, Params P, long long rowBegin, long long rowEnd, float* out,
  unsigned long long* evals, unsigned long long* fallbacks)
{
  __shared__ Hit sharedHits[SignWarps][MaxHits];
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1;
  const int lane = static_cast<int>(threadIdx.x % 32), warp = static_cast<int>(threadIdx.x / 32);
  const long long row = rowBegin + static_cast<long long>(blockIdx.x) * SignWarps + warp;
  if (row >= rowEnd) return; // the whole warp
  const long long j = P.lo[1] + row % ny, k = P.lo[2] + row / ny;
  float* rowOut = out + row * nx;
  const double h = P.spacing[0];
  const V3 start = positionOf(P, P.lo[0], j, k);
  auto pos = [&](long long i) { return start + V3{ static_cast<double>(i) * h, 0, 0 }; };
  Hit* hits = sharedHits[warp];
  int count = 0, sum = 0, ok = 0;
  if (lane == 0)
  {
    ok = rayDev(W.closed, start - V3{ 0.5 * h, 0, 0 }, V3{ 1, 0, 0 }, hits, &count, &sum) ? 1 : 0;
    for (int a = 1; ok && a < count; ++a) // insertion sort by t
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
  ok = __shfl_sync(FullMask, ok, 0);
  count = __shfl_sync(FullMask, count, 0);
  sum = __shfl_sync(FullMask, sum, 0);
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

double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Device buffers freed on scope exit (also on exceptions).
class DeviceArena
{
public:
  ~DeviceArena()
  {
    for (void* p : this->Ptrs) cudaFree(p);
  }
  template <typename T>
  T* upload(const std::vector<T>& v)
  {
    T* d = this->alloc<T>(v.size());
    if (!v.empty()) LVDIF_CUDA_CHECK(cudaMemcpy(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice));
    return d;
  }
  /// Copies v into `into` (capacity `cap` elements) or, if it does not fit, a
  /// new buffer, on a non-blocking stream: never waits for running kernels.
  template <typename T>
  T* uploadOn(cudaStream_t stream, const std::vector<T>& v, T* into = nullptr, std::size_t cap = 0)
  {
    T* d = into && v.size() <= cap ? into : this->alloc<T>(v.size());
    if (!v.empty())
    {
      LVDIF_CUDA_CHECK(cudaMemcpyAsync(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice, stream));
      LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream)); // v may be freed after return
    }
    return d;
  }
  template <typename T>
  T* alloc(std::size_t n)
  {
    void* p = nullptr;
    const std::size_t bytes = std::max<std::size_t>(n, 1) * sizeof(T);
    LVDIF_CUDA_CHECK(cudaMalloc(&p, bytes));
    this->Ptrs.push_back(p);
    this->Sizes.push_back(bytes);
    this->Bytes += bytes;
    return static_cast<T*>(p);
  }
  /// Frees one buffer now (a slab outgrown by a later call).
  void release(void* p)
  {
    for (std::size_t i = 0; i < this->Ptrs.size(); ++i)
    {
      if (this->Ptrs[i] != p) continue;
      LVDIF_CUDA_CHECK(cudaDeviceSynchronize());
      LVDIF_CUDA_CHECK(cudaFree(p));
      this->Bytes -= this->Sizes[i];
      this->Ptrs.erase(this->Ptrs.begin() + static_cast<std::ptrdiff_t>(i));
      this->Sizes.erase(this->Sizes.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  }
  std::uint64_t bytes() const { return this->Bytes; }

private:
  std::vector<void*> Ptrs;
  std::vector<std::uint64_t> Sizes;
  std::uint64_t Bytes = 0;
};

std::vector<GpuNode> convertNodes(const Bvh& b)
{
  std::vector<GpuNode> out;
  out.reserve(b.nodes().size());
  for (const Bvh::Node& n : b.nodes())
  {
    GpuNode g;
    for (int a = 0; a < 3; ++a)
    {
      g.lo[a] = n.lo[a];
      g.hi[a] = n.hi[a];
    }
    g.left = n.left;
    g.right = n.right;
    g.first = n.first;
    g.count = n.count;
    out.push_back(g);
  }
  return out;
}

std::vector<GpuTri> compactTris(const std::vector<Tri>& tris)
{
  std::vector<GpuTri> out(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
  {
    for (int k = 0; k < 3; ++k) out[i].v[k] = tris[i].v[k];
    out[i].n = tris[i].n;
  }
  return out;
}

/// The BVH's nodes, order and leaf-ordered compact triangles (into the
/// reserved buffers of `into` where they fit).
DevBvh uploadBvh(DeviceArena& arena, cudaStream_t stream, const Bvh& b, const DevBvh& into = DevBvh(),
  std::size_t cap = 0)
{
  DevBvh d;
  d.leaf = arena.uploadOn(stream, b.leaves(), const_cast<GpuTri*>(into.leaf), cap);
  d.nodes = arena.uploadOn(stream, convertNodes(b), const_cast<GpuNode*>(into.nodes), 2 * cap);
  d.order = arena.uploadOn(stream, b.order(), const_cast<int*>(into.order), cap);
  return d;
}

/// A non-blocking CUDA stream (no implicit ordering with the legacy stream).
struct Stream
{
  cudaStream_t s = nullptr;
  Stream() { LVDIF_CUDA_CHECK(cudaStreamCreateWithFlags(&this->s, cudaStreamNonBlocking)); }
  ~Stream() { cudaStreamDestroy(this->s); }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
};

class CudaMesh : public DeviceMesh
{
public:
  /// windingLater: reserve (allocate now) the buffers of the winding
  /// structures, so that addWinding only copies (a cudaMalloc could wait for
  /// the distance kernel it is meant to overlap). Their sizes are bounded by
  /// the mesh: closed chain <= triangles + boundary edges, nodes <= 2 x that.
  CudaMesh(const PreparedMesh& mesh, const Bvh& bvh, const WindingSigner* winding, bool normals, bool windingLater)
    : Mesh(mesh)
    , MeshBvh(bvh)
  {
    this->Dbvh = uploadBvh(this->Arena, this->Upload.s, bvh);
    if (normals) this->addNormals();
    if (winding)
    {
      this->addWinding(*winding);
    }
    else if (windingLater)
    {
      this->ClosedCap = mesh.tris.size() + mesh.boundary.size();
      this->EdgeCap = mesh.boundary.size();
      this->Reserved.leaf = this->Arena.alloc<GpuTri>(this->ClosedCap);
      this->Reserved.nodes = this->Arena.alloc<GpuNode>(2 * this->ClosedCap);
      this->Reserved.order = this->Arena.alloc<int>(this->ClosedCap);
      this->ReservedSlot = this->Arena.alloc<int>(mesh.tris.size());
      this->ReservedCone = this->Arena.alloc<GpuTri>(this->EdgeCap);
      this->ReservedClusters = this->Arena.alloc<WindingSigner::Cluster>(this->EdgeCap);
    }
    LVDIF_CUDA_CHECK(cudaDeviceSynchronize());
  }
  bool hasNormals() const override { return this->Dbvh.tris != nullptr; }
  void addNormals() override
  {
    if (!this->Dbvh.tris) this->Dbvh.tris = this->Arena.uploadOn(this->Upload.s, this->Mesh.tris);
  }
  void addWinding(const WindingSigner& winding) override
  {
    if (this->Winding) return;
    const cudaStream_t st = this->Upload.s;
    this->W.closed = uploadBvh(this->Arena, st, winding.closedBvh(), this->Reserved, this->ClosedCap);
    this->W.meshTris = static_cast<int>(winding.meshTriangles());
    this->W.meshLeaf = this->Dbvh.leaf;
    std::vector<int> slot(this->MeshBvh.order().size());
    for (std::size_t i = 0; i < slot.size(); ++i) slot[static_cast<std::size_t>(this->MeshBvh.order()[i])] = static_cast<int>(i);
    this->W.meshSlot = this->Arena.uploadOn(st, slot, this->ReservedSlot, this->ReservedSlot ? slot.size() : 0);
    this->W.cone = this->Arena.uploadOn(st, compactTris(winding.cone()), this->ReservedCone, this->EdgeCap);
    this->W.coneCount = static_cast<int>(winding.cone().size());
    this->W.clusters = this->Arena.uploadOn(st, winding.clusters(), this->ReservedClusters, this->EdgeCap);
    this->W.clusterCount = static_cast<int>(winding.clusters().size());
    this->Winding = true;
  }
  bool hasWinding() const override { return this->Winding; }
  std::uint64_t bytes() const override { return this->Arena.bytes(); }
  DevBvh Dbvh;
  WindingDev W;

private:
  const PreparedMesh& Mesh; // owned by the prepared mesh, which owns this copy
  const Bvh& MeshBvh;
  DeviceArena Arena;
  Stream Upload;
  bool Winding = false;
  DevBvh Reserved; // windingLater buffers
  std::size_t ClosedCap = 0, EdgeCap = 0;
  int* ReservedSlot = nullptr;
  GpuTri* ReservedCone = nullptr;
  WindingSigner::Cluster* ReservedClusters = nullptr;
};

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

/// A CUDA event pair timing kernels without synchronising at each launch.
struct EventTimer
{
  cudaEvent_t a = nullptr, b = nullptr;
  EventTimer()
  {
    LVDIF_CUDA_CHECK(cudaEventCreate(&this->a));
    LVDIF_CUDA_CHECK(cudaEventCreate(&this->b));
  }
  ~EventTimer()
  {
    cudaEventDestroy(this->a);
    cudaEventDestroy(this->b);
  }
  double seconds() const
  {
    float ms = 0;
    LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, this->a, this->b));
    return 1e-3 * ms;
  }
};

/// Events without timing, one per part of the sign pass.
struct PartEvents
{
  static constexpr int Max = 4;
  cudaEvent_t e[Max] = {};
  PartEvents()
  {
    for (cudaEvent_t& x : this->e) LVDIF_CUDA_CHECK(cudaEventCreateWithFlags(&x, cudaEventDisableTiming));
  }
  ~PartEvents()
  {
    for (cudaEvent_t x : this->e) cudaEventDestroy(x);
  }
  cudaEvent_t operator[](int i) const { return this->e[i]; }
};

class CudaSession : public Session
{
public:
  CudaSession(const CudaMesh& mesh, const GridGeometry& grid, const MeshToSdfOptions& options, double toOut,
    double band, MeshToSdfStats& stats, std::function<void()> ensureWinding)
    : Options(options)
    , Mesh(mesh)
    , HasWinding(options.sign == SignMode::WindingNumber)
    , EnsureWinding(std::move(ensureWinding))
    , Stats(stats)
  {
    require(!this->HasWinding || mesh.hasWinding() || this->EnsureWinding,
      "mesh to SDF: the device mesh has no winding structures");
    require(!(options.sign == SignMode::Normal || options.sign == SignMode::PseudoNormal) || mesh.hasNormals(),
      "mesh to SDF: the device mesh has no triangle normals");
    this->Counters = this->Arena.alloc<unsigned long long>(2);
    for (int a = 0; a < 3; ++a)
    {
      this->P.origin[a] = grid.origin[a];
      this->P.spacing[a] = grid.spacing[a];
    }
    this->P.toOut = toOut;
    this->P.band = band;
    this->P.bandWorld = std::isfinite(band) ? band / toOut : 1e300;
    this->P.reach = this->P.bandWorld < 1e299 ? this->P.bandWorld + 4 * grid.spacing[0] : 1e300;
    this->P.sign = options.sign == SignMode::Normal ? 0 : options.sign == SignMode::PseudoNormal ? 1
      : options.sign == SignMode::WindingNumber ? 2 : 3;
    this->P.useVertexNormals = options.useVertexNormals ? 1 : 0;
    this->P.bounded = (this->P.sign >= 2 && this->P.bandWorld < 1e299) ? 1 : 0;
    LVDIF_CUDA_CHECK(cudaMemset(this->Counters, 0, 2 * sizeof(unsigned long long)));
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  ~CudaSession() override
  {
    if (this->Launched) cudaDeviceSynchronize(); // never free buffers under running kernels
  }

  void compute(const VoxelBox& extent, float* out, MeshToSdfStats& stats, Interrupter& interrupter) override
  {
    const long long nx = extent.hi[0] - extent.lo[0] + 1, ny = extent.hi[1] - extent.lo[1] + 1;
    const long long nz = extent.hi[2] - extent.lo[2] + 1;
    const std::uint64_t layerBytes = static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny) * sizeof(float);
    const long long slabLayers =
      std::max<long long>(1, std::min<long long>(nz, static_cast<long long>(this->Options.cudaSlabBytes / layerBytes)));
    this->reserveSlab(static_cast<std::size_t>(slabLayers * nx * ny), stats);
    for (long long z0 = extent.lo[2]; z0 <= extent.hi[2]; z0 += slabLayers)
    {
      interrupter.checkInterrupt();
      const long long z1 = std::min<long long>(extent.hi[2], z0 + slabLayers - 1);
      VoxelBox slab = extent;
      slab.lo[2] = z0;
      slab.hi[2] = z1;
      const long long rows = ny * (z1 - z0 + 1);
      // the sign pass in parts: part p is copied back while part p + 1 runs
      const int parts = this->HasWinding && rows >= 4 * 4096 ? 4 : 1;
      this->launchSlab(slab, parts);
      float* slabOut = out + (z0 - extent.lo[2]) * nx * ny;
      for (int p = 0; p < parts; ++p)
      {
        const long long r0 = rows * p / parts, r1 = rows * (p + 1) / parts;
        LVDIF_CUDA_CHECK(cudaEventSynchronize(this->PartDone[p]));
        const double t0 = now();
        LVDIF_CUDA_CHECK(cudaMemcpyAsync(slabOut + r0 * nx, this->Slab + r0 * nx,
          static_cast<std::size_t>((r1 - r0) * nx) * sizeof(float), cudaMemcpyDeviceToHost, this->Copy.s));
        LVDIF_CUDA_CHECK(cudaStreamSynchronize(this->Copy.s));
        stats.writeSeconds += now() - t0;
      }
      LVDIF_CUDA_CHECK(cudaEventSynchronize(this->SignDone.b));
      stats.distanceSeconds += this->DistanceDone.seconds();
      if (this->HasWinding) stats.signSeconds += this->SignDone.seconds();
      interrupter.progress(static_cast<double>(z1 - extent.lo[2] + 1) / static_cast<double>(nz));
    }
    this->readCounters(stats);
  }

  void launchKeys(const VoxelBox& box, int edge, const SdfDictionary::EncodeConstants& encode, float band,
    MeshToSdfStats& stats) override
  {
    const long long nx = box.hi[0] - box.lo[0] + 1, ny = box.hi[1] - box.lo[1] + 1;
    const long long nz = box.hi[2] - box.lo[2] + 1;
    this->reserveSlab(static_cast<std::size_t>(nx * ny * nz), stats);
    this->KeyBox = box;
    this->Edge = edge;
    this->Encode = encode;
    this->Band = band;
    this->Ccx = static_cast<int>((nx + edge - 1) / edge);
    this->Ccy = static_cast<int>((ny + edge - 1) / edge);
    this->Chunks = static_cast<long long>(this->Ccx) * this->Ccy * ((nz + edge - 1) / edge);
    if (this->Chunks > this->FlagCapacity)
    {
      this->Flags = this->Arena.alloc<unsigned>(static_cast<std::size_t>(this->Chunks));
      this->List = this->Arena.alloc<long long>(static_cast<std::size_t>(this->Chunks));
      this->FlagCapacity = this->Chunks;
    }
    this->launchSlab(box);
    chunkUniformKernel<<<static_cast<unsigned>(this->Chunks), 256>>>(
      this->Slab, nx, ny, nz, edge, this->Ccx, this->Ccy, encode, band, this->Flags);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  void fetchKeys(ChunkKeys& out, MeshToSdfStats& stats) override
  {
    const long long nx = this->KeyBox.hi[0] - this->KeyBox.lo[0] + 1, ny = this->KeyBox.hi[1] - this->KeyBox.lo[1] + 1;
    const long long nz = this->KeyBox.hi[2] - this->KeyBox.lo[2] + 1;
    out.uniform.resize(static_cast<std::size_t>(this->Chunks));
    LVDIF_CUDA_CHECK(cudaMemcpy(out.uniform.data(), this->Flags, out.uniform.size() * sizeof(unsigned),
      cudaMemcpyDeviceToHost)); // waits for the kernels
    this->Launched = false;
    stats.distanceSeconds += this->DistanceDone.seconds();
    if (this->HasWinding) stats.signSeconds += this->SignDone.seconds();
    const double t0 = now();
    out.listed.clear();
    for (long long c = 0; c < this->Chunks; ++c)
    {
      if (out.uniform[static_cast<std::size_t>(c)] == ChunkKeys::NotUniform) out.listed.push_back(c);
    }
    const long long e3 = static_cast<long long>(this->Edge) * this->Edge * this->Edge;
    const std::size_t keyCount = out.listed.size() * static_cast<std::size_t>(e3);
    out.keys.resize(keyCount);
    if (!out.listed.empty())
    {
      if (keyCount > this->KeyCapacity)
      {
        if (this->Keys) this->Arena.release(this->Keys);
        this->Keys = this->Arena.alloc<unsigned short>(keyCount);
        this->KeyCapacity = keyCount;
      }
      LVDIF_CUDA_CHECK(cudaMemcpy(this->List, out.listed.data(), out.listed.size() * sizeof(long long),
        cudaMemcpyHostToDevice));
      chunkKeysKernel<<<static_cast<unsigned>(out.listed.size()), 256>>>(this->Slab, nx, ny, nz, this->Edge,
        this->Ccx, this->Ccy, this->Encode, this->Band, this->List, this->Keys);
      LVDIF_CUDA_CHECK(cudaGetLastError());
      LVDIF_CUDA_CHECK(cudaMemcpy(out.keys.data(), this->Keys, keyCount * sizeof(unsigned short),
        cudaMemcpyDeviceToHost));
    }
    if (this->Options.cudaVerifyKeys)
    {
      out.floats.resize(static_cast<std::size_t>(nx * ny * nz));
      LVDIF_CUDA_CHECK(cudaMemcpy(out.floats.data(), this->Slab, out.floats.size() * sizeof(float),
        cudaMemcpyDeviceToHost));
    }
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
    stats.writeSeconds += now() - t0;
    this->readCounters(stats);
  }

private:
  void reserveSlab(std::size_t floats, MeshToSdfStats& stats)
  {
    if (floats > this->SlabCapacity)
    {
      if (this->Slab) this->Arena.release(this->Slab);
      this->Slab = this->Arena.alloc<float>(floats);
      this->SlabCapacity = floats;
    }
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  /// Queues the distance and sign kernels of one slab (box layout in Slab).
  /// parts: the sign kernel in that many launches over consecutive rows,
  /// PartDone[p] recorded after launch p (after the distance kernel when
  /// there is no sign pass).
  void launchSlab(const VoxelBox& box, int parts = 1)
  {
    Params P = this->P;
    for (int a = 0; a < 3; ++a)
    {
      P.lo[a] = box.lo[a];
      P.hi[a] = box.hi[a];
    }
    const long long rows = (box.hi[1] - box.lo[1] + 1) * (box.hi[2] - box.lo[2] + 1);
    LVDIF_CUDA_CHECK(cudaEventRecord(this->DistanceDone.a));
    launchDistance(this->Mesh.Dbvh, P, this->Slab);
    LVDIF_CUDA_CHECK(cudaEventRecord(this->DistanceDone.b));
    if (this->HasWinding && !this->Mesh.hasWinding())
    {
      // built and uploaded on the host while the distance kernel runs
      this->EnsureWinding();
      require(this->Mesh.hasWinding(), "mesh to SDF: the device mesh has no winding structures");
      this->Stats.devicePeakBytes = std::max(this->Stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
    }
    LVDIF_CUDA_CHECK(cudaEventRecord(this->SignDone.a));
    for (int p = 0; p < parts; ++p)
    {
      if (this->HasWinding)
      {
        const long long r0 = rows * p / parts, r1 = rows * (p + 1) / parts;
        signKernel<<<static_cast<unsigned>((r1 - r0 + SignWarps - 1) / SignWarps), 32 * SignWarps>>>(
          this->Mesh.W, P, r0, r1, this->Slab, this->Counters, this->Counters + 1);
        LVDIF_CUDA_CHECK(cudaGetLastError());
      }
      LVDIF_CUDA_CHECK(cudaEventRecord(this->PartDone[p]));
    }
    LVDIF_CUDA_CHECK(cudaEventRecord(this->SignDone.b));
    this->Launched = true;
  }

  void readCounters(MeshToSdfStats& stats)
  {
    unsigned long long host[2] = { 0, 0 };
    LVDIF_CUDA_CHECK(cudaMemcpy(host, this->Counters, sizeof(host), cudaMemcpyDeviceToHost));
    LVDIF_CUDA_CHECK(cudaMemset(this->Counters, 0, sizeof(host)));
    stats.windingEvaluations += static_cast<std::int64_t>(host[0]);
    stats.windingExact += static_cast<std::int64_t>(host[1]);
  }

  MeshToSdfOptions Options;
  const CudaMesh& Mesh;
  bool HasWinding;
  std::function<void()> EnsureWinding;
  MeshToSdfStats& Stats;
  bool Launched = false;
  DeviceArena Arena;
  Params P;
  EventTimer DistanceDone, SignDone;
  PartEvents PartDone;
  Stream Copy; // device -> host copies, beside the kernels of the legacy stream
  unsigned long long* Counters = nullptr;
  float* Slab = nullptr;
  std::size_t SlabCapacity = 0;
  // the group of chunk layers of the last launchKeys
  VoxelBox KeyBox;
  int Edge = 32, Ccx = 0, Ccy = 0;
  long long Chunks = 0, FlagCapacity = 0;
  SdfDictionary::EncodeConstants Encode;
  float Band = 0;
  unsigned* Flags = nullptr;
  long long* List = nullptr;
  unsigned short* Keys = nullptr;
  std::size_t KeyCapacity = 0;
};
} // namespace

std::unique_ptr<DeviceMesh> uploadMesh(
  const PreparedMesh& mesh, const Bvh& bvh, const WindingSigner* winding, bool normals, bool windingLater)
{
  return std::make_unique<CudaMesh>(mesh, bvh, winding, normals, windingLater);
}

std::unique_ptr<Session> openSession(const DeviceMesh& mesh, const GridGeometry& grid,
  const MeshToSdfOptions& options, double toOut, double band, MeshToSdfStats& stats,
  std::function<void()> ensureWinding)
{
  return std::make_unique<CudaSession>(
    static_cast<const CudaMesh&>(mesh), grid, options, toOut, band, stats, std::move(ensureWinding));
}

std::vector<std::uint16_t> encodeOnDevice(
  const SdfDictionary::EncodeConstants& encode, float band, const std::vector<float>& values)
{
  DeviceArena arena;
  const float* in = arena.upload(values);
  unsigned short* out = arena.alloc<unsigned short>(values.size());
  const long long n = static_cast<long long>(values.size());
  encodeKernel<<<static_cast<unsigned>((n + 255) / 256), 256>>>(encode, band, in, n, out);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  std::vector<std::uint16_t> host(values.size());
  LVDIF_CUDA_CHECK(cudaMemcpy(host.data(), out, host.size() * sizeof(unsigned short), cudaMemcpyDeviceToHost));
  return host;
}

} // namespace cudasdf
} // namespace lvdif
