// The winding sign of damaged meshes on CUDA (included by MeshToSdfCuda.cu,
// after MeshToSdfCudaKernels.cuh): the CPU's construction
// (MeshToSdfWinding.cpp), built on the host and uploaded. w_M = K - s, K the
// crossings of the closed chain (M+ or M, closed by local caps) counted by
// the scan-line ray as in signKernel, s the solid-angle sum of the caps, the
// reversed faces F (weight 2) and the removed duplicates R, bounded by the
// CPU's DipoleTree (MeshToSdfDipoleTree.cpp) with the same rigorous
// per-cluster bounds (dipole term with its Taylor error, or area / d^2).
//
// Why the signs equal the CPU's bit for bit: MeshToSdfDipoleDecide.h.
#pragma once

#include "MeshToSdfCudaKernels.cuh"
#include "MeshToSdfDipoleDecide.h"
#include "MeshToSdfDipoleLocal.h"

#include <cooperative_groups.h>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
namespace
{
/// The corners of block (ix, iy, iz) of edge voxels of the slab (clipped to it).
__device__ void dipoleBlockCorners(const Params& P, int edge, long long ix, long long iy, long long iz, V3& p0, V3& p1)
{
  const long long x0 = P.lo[0] + edge * ix, y0 = P.lo[1] + edge * iy, z0 = P.lo[2] + edge * iz;
  p0 = positionOf(P, x0, y0, z0);
  p1 = positionOf(P, min(x0 + edge - 1, P.hi[0]), min(y0 + edge - 1, P.hi[1]), min(z0 + edge - 1, P.hi[2]));
}

/// A block or voxel (dipoleListVoxel) with the margin of its next pass.
struct DipolePending
{
  long long item;
  double margin;
};

/// Appends e to list (count entries, capacity cap), one atomic per group of
/// converged threads; false when the list is full (the caller goes on).
template <class T>
__device__ bool dipoleAppend(T* list, unsigned long long* count, long long cap, const T& e)
{
  namespace cg = cooperative_groups;
  const cg::coalesced_group g = cg::coalesced_threads();
  unsigned long long first = 0;
  if (g.thread_rank() == 0) first = atomicAdd(count, static_cast<unsigned long long>(g.size()));
  first = g.shfl(first, 0);
  const unsigned long long at = first + g.thread_rank();
  if (at >= static_cast<unsigned long long>(cap)) return false;
  list[at] = e;
  return true;
}

/// Where the lists of one slab's block levels go (MeshToSdfCuda.cu).
struct DipoleBlockLists
{
  long long* fail = nullptr;           // this level's blocks without a bound (null: the finest level)
  unsigned long long* failCount = nullptr;
  DipolePending* next = nullptr;       // blocks for the next pass (null: the last pass)
  unsigned long long* nextCount = nullptr;
  long long nextCap = 0;
};

/// Block b of edge voxels (bx x by per layer), dipoleBlockBound from pass
/// `pass` with its margin: the bound (or none) is written, unless the block
/// is listed for the next pass (L.next, when not full); a block left
/// without a bound is listed for the level below.
__device__ void dipoleBlockFrom(const DipoleDev& D, const Params& P, int edge, long long bx, long long by, long long b,
  int pass, double margin, const DipoleBlockLists& L, double* bounds)
{
  V3 p0, p1, centre;
  dipoleBlockCorners(P, edge, b % bx, (b / bx) % by, b / (bx * by), p0, p1);
  double rho = 0, lo = 1, hi = 0;
  dipoleBlockBall(p0, p1, centre, rho);
  bool listNext = L.next != nullptr;
  for (; pass < DipoleBlockPasses; ++pass)
  {
    if (dipoleBlockPass(D, centre, rho, margin, lo, hi) != 0) break;
    if (pass + 1 < DipoleBlockPasses && listNext)
    {
      if (dipoleAppend(L.next, L.nextCount, L.nextCap, DipolePending{ b, margin })) return;
      listNext = false; // full: the passes go on here
    }
  }
  bounds[2 * b] = lo;
  bounds[2 * b + 1] = hi;
  if (!(lo <= hi) && L.fail) dipoleAppend(L.fail, L.failCount, 1ll << 62, static_cast<long long>(b));
}

/// boundDipole with the whole warp on one ball (q, rho and tolPerMass the
/// same in every lane): the lanes take up to 32 nodes a round from the top
/// of a stack in shared memory (BoundWarpStack entries per warp) and step
/// them (boundDipoleNode) into lane-partial sums, reduced over the warp at
/// the end. The nodes taken, opened and summed are boundDipole's (that does
/// not depend on the order); the sums are added in another order, inside the
/// slack (boundDipoleInterval). False in every lane where boundDipole fails
/// (the ball meets a triangle) and when the stack is full. Why: with a lane
/// per ball the 32 lanes walked 32 different trees one branch after the
/// other (docs/BENCHMARKS.md, "Session 17").
// A round pops up to 32 entries and pushes at most 2 per popped node, so the
// stack grows by at most 32 a round, about 32 entries per level of depth: the
// dipole tree of a 10M-triangle mesh has ~22 levels (~700 entries); 2,048
// leaves room for far deeper ones (8 KB per warp, 32 KB per CUDA block).
constexpr int BoundWarpStack = 2048;
constexpr int BoundWarpsPerBlock = 4; // the CUDA blocks of 128 threads the callers run in
__device__ bool boundDipoleWarp(const DipoleView& D, V3 q, double rho, double tolPerMass, double& sLo, double& sHi,
  bool& approx, int* stack, int lane)
{
  constexpr unsigned Full = 0xffffffffu;
  if (lane == 0) stack[0] = 0;
  __syncwarp();
  int top = 1;
  double value = 0, err = 0, mag = 0;
  long long terms = 0;
  bool anyApprox = false;
  while (top > 0)
  {
    const int k = min(32, top);
    const int node = lane < k ? stack[top - 1 - lane] : -1;
    top -= k;
    __syncwarp();
    int step = 0, left = 0, right = 0;
    if (node >= 0)
    {
      const DipoleTree::Node nd = D.nodes[node];
      step = boundDipoleNode(D, nd, q, rho, tolPerMass, value, err, mag, terms, anyApprox);
      left = nd.left;
      right = nd.right;
    }
    if (__any_sync(Full, step < 0)) return false;
    const unsigned opened = __ballot_sync(Full, step > 0);
    const int total = 2 * __popc(opened);
    if (top + total > BoundWarpStack) return false; // (the same in every lane)
    if (step > 0)
    {
      const int at = top + 2 * __popc(opened & ((1u << lane) - 1u));
      stack[at] = left;
      stack[at + 1] = right;
    }
    top += total;
    __syncwarp();
  }
  for (int o = 16; o > 0; o >>= 1)
  {
    value += __shfl_xor_sync(Full, value, o);
    err += __shfl_xor_sync(Full, err, o);
    mag += __shfl_xor_sync(Full, mag, o);
    terms += __shfl_xor_sync(Full, terms, o);
  }
  approx = __any_sync(Full, anyApprox);
  boundDipoleInterval(value, err, mag, terms, sLo, sHi);
  return true;
}

/// dipoleBlockFrom with the whole warp on block b (the same in every lane):
/// its passes from `pass` one after the other (boundDipoleWarp runs each in
/// a full warp, so no list between passes); lane 0 writes the bound and
/// lists a block left without one for the level below.
__device__ void dipoleBlockFromWarp(const DipoleDev& D, const Params& P, int edge, long long bx, long long by, long long b,
  int pass, double margin, const DipoleBlockLists& L, double* bounds, int* stack, int lane)
{
  V3 p0, p1, centre;
  dipoleBlockCorners(P, edge, b % bx, (b / bx) % by, b / (bx * by), p0, p1);
  double rho = 0, lo = 1, hi = 0;
  dipoleBlockBall(p0, p1, centre, rho);
  for (; pass < DipoleBlockPasses; ++pass)
  {
    double l = 0, u = 0;
    bool approx = false;
    const bool ok = boundDipoleWarp(D, centre, rho, dipoleTolerance(D, margin), l, u, approx, stack, lane);
    if (dipoleBlockDecide(ok, l, u, approx, margin, lo, hi) != 0) break;
  }
  if (lane != 0) return;
  bounds[2 * b] = lo;
  bounds[2 * b + 1] = hi;
  if (!(lo <= hi) && L.fail) dipoleAppend(L.fail, L.failCount, 1ll << 62, static_cast<long long>(b));
}

/// One thread per block of edge voxels (one level of DipoleEdges) of the
/// slab. The coarsest level (parent null): the first pass of
/// dipoleBlockBound (dipoleBlockFrom). The others take their parent's bound,
/// none or one (a parent's bound holds over the block too; its edge is
/// ratio x edge, bx / ratio rounded up per row); dipoleListedBlockKernel
/// then bounds the blocks of the parents without one.
__global__ void dipoleBlockKernel(DipoleDev D, Params P, int edge, long long bx, long long by, long long blocks,
  const double* parent, int ratio, double* bounds, DipoleBlockLists L)
{
  const long long b = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (b >= blocks) return;
  if (!parent)
  {
    dipoleBlockFrom(D, P, edge, bx, by, b, 0, DipoleFirstMargin, L, bounds);
    return;
  }
  const long long ix = b % bx, iy = (b / bx) % by, iz = b / (bx * by);
  const long long cx = (bx + ratio - 1) / ratio, cy = (by + ratio - 1) / ratio;
  const long long c = ix / ratio + cx * (iy / ratio + cy * (iz / ratio));
  bounds[2 * b] = parent[2 * c];
  bounds[2 * b + 1] = parent[2 * c + 1];
}

/// The blocks of edge voxels inside the listed blocks of the level above
/// (parents, parentCount of them, but the first skipParents; edge ratio x
/// edge, pbx x pby per layer),
/// one per warp of a grid-stride loop: dipoleBlockBound's passes
/// (dipoleBlockFromWarp).
__global__ void dipoleListedBlockKernel(DipoleDev D, Params P, int edge, long long bx, long long by, long long bz,
  long long pbx, long long pby, int ratio, const long long* parents, const unsigned long long* parentCount,
  long long skipParents, double* bounds, DipoleBlockLists L)
{
  __shared__ int stacks[BoundWarpsPerBlock][BoundWarpStack];
  const int lane = static_cast<int>(threadIdx.x % 32);
  const long long r3 = static_cast<long long>(ratio) * ratio * ratio;
  // the first skipParents parents went to the local step (dipoleLocalKernel): their voxels have intervals of their own
  parents += skipParents;
  const long long total = max(0ll, static_cast<long long>(*parentCount) - skipParents) * r3;
  const long long warps = static_cast<long long>(gridDim.x) * (blockDim.x / 32);
  for (long long t = static_cast<long long>(blockIdx.x) * (blockDim.x / 32) + threadIdx.x / 32; t < total; t += warps)
  {
    const long long b = dipoleChildBlock(parents[t / r3], t % r3, ratio, pbx, pby, bx, by, bz);
    if (b >= 0) dipoleBlockFromWarp(D, P, edge, bx, by, b, 0, DipoleFirstMargin, L, bounds, stacks[threadIdx.x / 32], lane);
  }
}

/// Pass `pass` (and on) of dipoleBlockBound for the blocks the coarsest
/// level's first pass listed (in, min(inCount, inCap) of them), one per warp
/// of a grid-stride loop (dipoleBlockFromWarp).
__global__ void dipoleBlockPassKernel(DipoleDev D, Params P, int edge, long long bx, long long by, int pass,
  const DipolePending* in, const unsigned long long* inCount, long long inCap, double* bounds, DipoleBlockLists L)
{
  __shared__ int stacks[BoundWarpsPerBlock][BoundWarpStack];
  const long long n = min(static_cast<long long>(*inCount), inCap);
  const long long warps = static_cast<long long>(gridDim.x) * (blockDim.x / 32);
  for (long long t = static_cast<long long>(blockIdx.x) * (blockDim.x / 32) + threadIdx.x / 32; t < n; t += warps)
    dipoleBlockFromWarp(D, P, edge, bx, by, in[t].item, pass, in[t].margin, L, bounds, stacks[threadIdx.x / 32],
      static_cast<int>(threadIdx.x % 32));
}

/// Where the local step's intervals go (MeshToSdfCuda.cu): per listed 4^3
/// block t < cap its voxels' lo (pool[128 t + v]) and hi (pool[128 t + 64 +
/// v]), v = a + 4 (b + 4 c); slot[b] = t for block b of the 4^3 level (-1:
/// none, the voxels are refined one by one).
struct DipoleLocalLists
{
  double* pool = nullptr;
  int* slot = nullptr;
  long long cap = 0;
  long long bx = 0, by = 0;             // 4^3 blocks per row and per layer of the slab
  unsigned long long* counts = nullptr; // blocks expanded, blocks failed, voxels decided by the intervals
};

/// The local step: the failed 4^3 blocks (failed, min(*failedCount, L.cap)
/// of them), one per warp of a grid-stride loop, pass by pass as
/// dipoleLocalBlock runs them (the same tolerances, per-cluster terms and
/// acceptance: clusterLocalError, clusterLocal, triangleCluster). The
/// block's walk is shared by the warp: each round the lanes take up to 32
/// entries (nodes, or triangles of opened leaves) from the top of a stack in
/// shared memory, accept them into lane-partial sums (reduced over the warp
/// at the end of the pass), push the children of those they open (a prefix
/// sum of the counts) and list the near triangles (a ballot); the listed
/// triangles' solid angles are summed at the open voxels (lane l at voxels l
/// and l + 32), the running sums in the pool, carried to the next pass while
/// a voxel stays open; at the end of a pass each voxel's interval
/// (dipoleLocalFinish) and the block's open voxels and smallest gap.
/// Why one warp per block: with a lane per block (the kernel before session
/// 17) the 32 lanes walked 32 different trees and their branches ran one
/// after the other, 16.8 of 32 lanes active on average (docs/BENCHMARKS.md,
/// "Session 17"). The walk visits the clusters dipoleLocalWalk visits (which
/// are accepted, opened or listed does not depend on the order), but adds
/// the accepted ones in another order, so an interval may differ from the
/// emulation's in its last bits; each is rigorous (localInterval's slack
/// bounds the rounding of any order), so the signs are the same. A stack
/// overflow leaves the block without intervals (its voxels are refined one
/// by one). Voxels at the positions signDipoleKernel computes.
// As BoundWarpStack, plus up to 4 triangles per opened leaf (LeafSize) a lane.
constexpr int LocalWarpStack = 2048;
constexpr int LocalWarpsPerBlock = 4; // the CUDA block of 128 threads (MeshToSdfCuda.cu's LocalThreads)
// (3 CUDA blocks per SM: 168 registers, 20 bytes spilled, against 2 at its own 172)
__global__ void __launch_bounds__(32 * LocalWarpsPerBlock, 3) dipoleLocalKernel(DipoleDev D, Params P, const long long* failed, const unsigned long long* failedCount,
  DipoleLocalLists L, int* near)
{
  constexpr unsigned Full = 0xffffffffu;
  __shared__ int stacks[LocalWarpsPerBlock][LocalWarpStack];
  const int lane = static_cast<int>(threadIdx.x % 32), inBlock = static_cast<int>(threadIdx.x / 32);
  int* stack = stacks[inBlock];
  const long long n = min(static_cast<long long>(*failedCount), L.cap);
  const long long warp = static_cast<long long>(blockIdx.x) * (blockDim.x / 32) + inBlock;
  const long long warps = static_cast<long long>(gridDim.x) * (blockDim.x / 32);
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1, nz = P.hi[2] - P.lo[2] + 1;
  const double h = P.spacing[0];
  int* list = near + warp * 32 * DipoleLocalNearCap; // this warp's near triangles (32 x DipoleLocalNearCap)
  unsigned long long expanded = 0, failures = 0;
  for (long long t = warp; t < n; t += warps) // the whole warp alike
  {
    const long long block = failed[t];
    const long long bi[3] = { block % L.bx, (block / L.bx) % L.by, block / (L.bx * L.by) };
    const int m[3] = { static_cast<int>(min(static_cast<long long>(DipoleLocalEdge), nx - DipoleLocalEdge * bi[0])),
      static_cast<int>(min(static_cast<long long>(DipoleLocalEdge), ny - DipoleLocalEdge * bi[1])),
      static_cast<int>(min(static_cast<long long>(DipoleLocalEdge), nz - DipoleLocalEdge * bi[2])) };
    V3 p0, p1, centre;
    double rho = 0;
    dipoleBlockCorners(P, DipoleLocalEdge, bi[0], bi[1], bi[2], p0, p1);
    dipoleBlockBall(p0, p1, centre, rho);
    // voxel v of the block, as the rows position it (dipoleLocalKernel's voxelAt)
    auto voxelAt = [&](int v) {
      const long long y = P.lo[1] + DipoleLocalEdge * bi[1] + (v / DipoleLocalEdge) % DipoleLocalEdge;
      const long long z = P.lo[2] + DipoleLocalEdge * bi[2] + v / (DipoleLocalEdge * DipoleLocalEdge);
      return positionOf(P, P.lo[0], y, z) + V3{ static_cast<double>(DipoleLocalEdge * bi[0] + v % DipoleLocalEdge) * h, 0, 0 };
    };
    unsigned long long open = 0; // the same in every lane
    for (int v = 0; v < DipoleLocalVoxels; ++v)
      if (v % DipoleLocalEdge < m[0] && (v / DipoleLocalEdge) % DipoleLocalEdge < m[1] && v / (DipoleLocalEdge * DipoleLocalEdge) < m[2])
        open |= 1ull << v;
    double* out = L.pool + 2 * DipoleLocalVoxels * t;
    for (int i = 0; i < 2; ++i)
      if ((open >> (lane + 32 * i)) & 1) out[lane + 32 * i] = out[DipoleLocalVoxels + lane + 32 * i] = 0;
    // the listed near triangles at this lane's open voxels (running sums in the pool)
    auto sumNear = [&](int count) {
      __syncwarp();
      for (int i = 0; i < 2 && count > 0; ++i)
      {
        const int v = lane + 32 * i;
        if (!((open >> v) & 1)) continue;
        double direct = out[v], directMag = out[DipoleLocalVoxels + v];
        dipoleLocalNearSum(D, list, 1, count, voxelAt(v), direct, directMag);
        out[v] = direct;
        out[DipoleLocalVoxels + v] = directMag;
      }
      __syncwarp();
    };
    bool failedHere = false;
    double margin = DipoleFirstMargin, prevMargin = 0;
    for (int pass = 0; pass < DipoleLocalPasses; ++pass)
    {
      const double tol = dipoleTolerance(D, margin), prevTol = pass > 0 ? dipoleTolerance(D, prevMargin) : 0.0;
      DipoleLocalFar far; // this lane's part
      // an entry: index << 2 | triangle << 1 | reached by the previous pass (dipoleLocalWalk's flags)
      if (lane == 0) stack[0] = pass > 0 ? 1 : 0;
      __syncwarp();
      int top = 1, nearCount = 0;
      bool overflow = false;
      while (top > 0)
      {
        if (nearCount > 32 * DipoleLocalNearCap - 32) // (room for one round's)
        {
          sumNear(nearCount);
          nearCount = 0;
        }
        const int k = min(32, top);
        const int entry = lane < k ? stack[top - 1 - lane] : -1;
        top -= k;
        __syncwarp();
        // what this lane's entry adds: two children of a node, a leaf's
        // triangles (pushes from `first`), or a near triangle (listed)
        int pushes = 0, first = 0, second = -1, flag = 0;
        bool listIt = false;
        if (entry >= 0)
        {
          const bool isTri = (entry >> 1) & 1, reached = entry & 1;
          const int index = entry >> 2;
          const DipoleTree::Node nd = isTri ? triangleCluster(D.tris[index], index) : D.nodes[index];
          const V3 y = nd.c - centre;
          const double r0 = norm(y);
          int order = 0;
          const double e = clusterLocalError(nd, r0, rho, order);
          const bool openedBefore = reached && !(e <= prevTol * nd.mass);
          if (e <= tol * nd.mass)
          {
            // accepted: joins the polynomial (dipoleLocalWalk's consider)
            far.err += e;
            far.mag += clusterLocalMag(nd, r0 - rho, rho);
            if (order > 0) far.poly.add(clusterLocal(nd, y, order), 1);
            ++far.terms;
          }
          else if (isTri)
          {
            listIt = !openedBefore; // summed by the previous pass: its sums carry over
            first = index;
            ++far.terms;
          }
          else
          {
            flag = openedBefore ? 1 : 0;
            if (nd.left >= 0)
            {
              pushes = 2;
              first = nd.left << 2 | flag;
              second = nd.right << 2 | flag;
            }
            else
            {
              pushes = nd.count;
              first = nd.first;
              flag |= 2; // triangle entries
            }
          }
        }
        // the entries' places on the stack: a prefix sum of the pushes
        int incl = pushes;
        for (int o = 1; o < 32; o <<= 1)
        {
          const int y = __shfl_up_sync(Full, incl, o);
          if (lane >= o) incl += y;
        }
        const int total = __shfl_sync(Full, incl, 31);
        if (top + total > LocalWarpStack) // (the same in every lane)
        {
          overflow = true;
          break;
        }
        const int at = top + incl - pushes;
        if (second >= 0)
        {
          stack[at] = first;
          stack[at + 1] = second;
        }
        else
          for (int j = 0; j < pushes; ++j) stack[at + j] = (first + j) << 2 | flag;
        top += total;
        const unsigned listed = __ballot_sync(Full, listIt);
        if (listIt) list[nearCount + __popc(listed & ((1u << lane) - 1u))] = first;
        nearCount += __popc(listed);
        __syncwarp();
      }
      if (overflow)
      {
        // no intervals at all for that block
        for (int i = 0; i < 2; ++i)
        {
          out[lane + 32 * i] = 1;
          out[DipoleLocalVoxels + lane + 32 * i] = 0;
        }
        failedHere = true;
        break;
      }
      sumNear(nearCount);
      // the pass's far sums, over the lanes
      for (int o = 16; o > 0; o >>= 1)
      {
        far.poly.v += __shfl_xor_sync(Full, far.poly.v, o);
        for (int k = 0; k < 3; ++k) far.poly.g[k] += __shfl_xor_sync(Full, far.poly.g[k], o);
        for (int k = 0; k < 6; ++k) far.poly.H[k] += __shfl_xor_sync(Full, far.poly.H[k], o);
        far.err += __shfl_xor_sync(Full, far.err, o);
        far.mag += __shfl_xor_sync(Full, far.mag, o);
        far.terms += __shfl_xor_sync(Full, far.terms, o);
      }
      double gap = margin;
      bool still[2] = { false, false };
      double l[2] = { 1, 1 }, u[2] = { 0, 0 };
      for (int i = 0; i < 2; ++i)
      {
        const int v = lane + 32 * i;
        if (!((open >> v) & 1)) continue;
        dipoleLocalFinish(far, voxelAt(v), centre, out[v], out[DipoleLocalVoxels + v], l[i], u[i]);
        still[i] = dipoleLocalVoxelState(l[i], u[i], gap) == 1;
      }
      const unsigned long long stillB = static_cast<unsigned long long>(__ballot_sync(Full, still[0])) |
        (static_cast<unsigned long long>(__ballot_sync(Full, still[1])) << 32);
      for (int o = 16; o > 0; o >>= 1) gap = fmin(gap, __shfl_xor_sync(Full, gap, o));
      const unsigned long long wasOpen = open;
      open = stillB;
      prevMargin = margin;
      const bool goesOn = dipoleLocalNextPass(pass, stillB != 0, gap, margin);
      // a voxel that takes the next pass keeps its near sums in the pool; the others their interval
      for (int i = 0; i < 2; ++i)
      {
        const int v = lane + 32 * i;
        if (!((wasOpen >> v) & 1) || (goesOn && still[i])) continue;
        out[v] = l[i];
        out[DipoleLocalVoxels + v] = u[i];
      }
      __syncwarp();
      if (!goesOn) break;
    }
    if (lane == 0)
    {
      if (!failedHere)
      {
        L.slot[block] = static_cast<int>(t);
        ++expanded;
      }
      failures += failedHere;
    }
  }
  if (expanded) atomicAdd(L.counts, expanded);
  if (failures) atomicAdd(L.counts + 1, failures);
}

/// WindingSigner::signRow with the correction s (closure without a cone):
/// one warp per scan line as signKernel; the lanes walk the crossings
/// together, then each lane takes its voxel: decided by the block's bound of
/// s if that decides it, else listed (queue; dipoleRefineKernel refines the
/// listed voxels with full warps), or refined here (insideDipole) when the
/// list is full. A row whose +x ray is ambiguous takes an oblique ray per
/// voxel (WindingSigner::insideAt), and a voxel whose oblique ray is
/// ambiguous too the sum over all of M. The rows' +x rays come from
/// rowRayKernel (rayMeta, rayHits: row - rowBegin).
__global__ void signDipoleKernel(WindingDev W, DipoleDev D, Params P, long long rowBegin, long long rowEnd,
  const int4* rayMeta, const Hit* rayHits, const double* bounds, long long bx, long long by, float* out,
  unsigned long long* counters, unsigned long long* queue, unsigned long long* queueCount, long long queueCap,
  DipoleLocalLists local)
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
  unsigned long long ev = 0, full = 0, fallback = 0, fromLocal = 0;
  // this row's 4^3 blocks (their local intervals, where they have them)
  const long long localRow = local.bx * ((j - P.lo[1]) / DipoleLocalEdge + local.by * ((k - P.lo[2]) / DipoleLocalEdge));
  const int localSub = DipoleLocalEdge * (static_cast<int>((j - P.lo[1]) % DipoleLocalEdge) +
    DipoleLocalEdge * static_cast<int>((k - P.lo[2]) % DipoleLocalEdge));
  const double* blockRow = bounds + 2 * bx * ((j - P.lo[1]) / DipoleBlock + by * ((k - P.lo[2]) / DipoleBlock));
  // each lane walks the sorted crossings up to its own voxels (they advance
  // by 32 a step): K = sum minus the crossings before the voxel, the value
  // the CPU carries voxel by voxel
  int ahead = sum, next = 0;
  for (long long base = 0; base < nx; base += 32)
  {
    const long long mine = base + lane;
    const long long end = base + 32 < nx ? base + 32 : nx;
    int myK = 0;
    bool myRay = true, myInside = false;
    if (ok)
    {
      const double ti = 0.5 * h + static_cast<double>(mine) * h;
      while (next < count && hits[next].t <= ti) ahead -= hits[next++].sign;
      myK = ahead;
    }
    for (long long i = base; i < end && !ok; ++i)
    {
      // ambiguous row: an oblique ray per voxel, all lanes alike
      const V3 dir = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
      int s = 0;
      if (rayDev(W.closed, pos(i), dir, nullptr, nullptr, &s))
      {
        if (i - base == lane) myK = s;
        continue;
      }
      const double w = evaluateWarp(W, pos(i), lane); // the same ray, then every solid angle of M
      if (i - base == lane)
      {
        myRay = false;
        myInside = insideOf(w);
        ++full;
      }
    }
    bool refine = false;
    if (mine < nx)
    {
      if (!ok) ++fallback;
      if (myRay)
      {
        // ambiguous rows use no block bounds (WindingSigner::insideAt)
        const double lo = ok ? blockRow[2 * (mine / DipoleBlock)] : 1.0, hi = ok ? blockRow[2 * (mine / DipoleBlock) + 1] : 0.0;
        refine = !dipoleBlockDecides(myK, lo, hi, myInside);
        // then the voxel's own interval from its 4^3 block's local expansion
        const int slot = refine && ok && local.slot ? local.slot[localRow + mine / DipoleLocalEdge] : -1;
        if (slot >= 0)
        {
          const double* in = local.pool + 2 * DipoleLocalVoxels * static_cast<long long>(slot) + localSub + mine % DipoleLocalEdge;
          refine = !dipoleBlockDecides(myK, in[0], in[DipoleLocalVoxels], myInside);
          fromLocal += !refine;
        }
        ev += refine;
      }
    }
    // list the voxels to refine, in lane order (one atomic per warp)
    const bool listable = refine && dipoleListable(myK);
    const unsigned mask = __ballot_sync(0xffffffffu, listable);
    if (mask)
    {
      const int leader = __ffs(mask) - 1;
      unsigned long long first = 0;
      if (lane == leader) first = atomicAdd(queueCount, static_cast<unsigned long long>(__popc(mask)));
      first = __shfl_sync(0xffffffffu, first, leader);
      const unsigned long long at = first + static_cast<unsigned long long>(__popc(mask & ((1u << lane) - 1u)));
      if (listable && at < static_cast<unsigned long long>(queueCap))
      {
        queue[at] = dipoleListVoxel(row * nx + mine, myK);
        refine = false;
      }
    }
    if (refine) myInside = insideDipole(D, myK, pos(mine), full);
    if (mine < nx && myInside) rowOut[mine] = -rowOut[mine];
  }
  if (ev) atomicAdd(counters, ev);
  if (fallback) atomicAdd(counters + 1, fallback);
  if (full) atomicAdd(counters + 2, full);
  if (fromLocal && local.counts) atomicAdd(local.counts + 2, fromLocal);
}

/// The voxels signDipoleKernel listed (queue, min(*queueCount, queueCap) of
/// them), one per warp of a grid-stride loop: insideDipole at the position
/// the row computes (pos(i) of signDipoleKernel, the same operations), every
/// pass by the whole warp (boundDipoleWarp), so the warp finishes each voxel
/// it takes (before session 17, one voxel per thread and a list between
/// passes). Inside: the sign is flipped.
__global__ void dipoleRefineKernel(DipoleDev D, Params P, const unsigned long long* queue, const unsigned long long* queueCount,
  long long queueCap, float* slab, unsigned long long* counters)
{
  __shared__ int stacks[BoundWarpsPerBlock][BoundWarpStack];
  int* stack = stacks[threadIdx.x / 32];
  const int lane = static_cast<int>(threadIdx.x % 32);
  const long long n = min(static_cast<long long>(*queueCount), queueCap);
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1;
  const long long warps = static_cast<long long>(gridDim.x) * (blockDim.x / 32);
  const double h = P.spacing[0];
  unsigned long long full = 0;
  for (long long t = static_cast<long long>(blockIdx.x) * (blockDim.x / 32) + threadIdx.x / 32; t < n; t += warps)
  {
    const long long item = static_cast<long long>(queue[t]);
    double margin = DipoleFirstMargin;
    long long v = 0;
    int K = 0;
    dipoleListedVoxel(static_cast<unsigned long long>(item), v, K);
    const long long row = v / nx, i = v % nx;
    const V3 start = positionOf(P, P.lo[0], P.lo[1] + row % ny, P.lo[2] + row / ny);
    const V3 p = start + V3{ static_cast<double>(i) * h, 0, 0 };
    bool inside = false;
    while (true)
    {
      double lo = 0, hi = 0;
      bool approx = false;
      const bool ok = boundDipoleWarp(D, p, 0, dipoleTolerance(D, margin), lo, hi, approx, stack, lane);
      const int r = insideDipoleDecide(ok, lo, hi, approx, K, margin, inside);
      if (r > 0) break;
      if (r < 0)
      {
        ++full; // insideDipole's canonical sum
        inside = dipoleInsideOf(K - dipoleExactCanonical(D, p));
        break;
      }
    }
    if (lane == 0 && inside) slab[v] = -slab[v];
  }
  if (full && lane == 0) atomicAdd(counters + 2, full);
}
} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
