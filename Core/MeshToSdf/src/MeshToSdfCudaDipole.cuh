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

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
namespace
{
using DipoleNode = DipoleTree::Node;
using DipoleDev = DipoleView;

/// The corners of block (ix, iy, iz) of edge voxels of the slab (clipped to it).
__device__ void dipoleBlockCorners(const Params& P, int edge, long long ix, long long iy, long long iz, V3& p0, V3& p1)
{
  const long long x0 = P.lo[0] + edge * ix, y0 = P.lo[1] + edge * iy, z0 = P.lo[2] + edge * iz;
  p0 = positionOf(P, x0, y0, z0);
  p1 = positionOf(P, min(x0 + edge - 1, P.hi[0]), min(y0 + edge - 1, P.hi[1]), min(z0 + edge - 1, P.hi[2]));
}

/// One thread per block of edge voxels (one level of DipoleEdges) of the
/// slab. The coarsest level (parent null): dipoleBlockBound, and a block
/// without a bound is listed (list, listCount) for the level below. The
/// others take their parent's bound, none or one (a parent's bound holds
/// over the block too; its edge is ratio x edge, bx / ratio rounded up per
/// row); dipoleListedBlockKernel then bounds the blocks of listed parents.
__global__ void dipoleBlockKernel(DipoleDev D, Params P, int edge, long long bx, long long by, long long blocks,
  const double* parent, int ratio, double* bounds, long long* list, unsigned long long* listCount)
{
  const long long b = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (b >= blocks) return;
  const long long ix = b % bx, iy = (b / bx) % by, iz = b / (bx * by);
  double lo = 1, hi = 0;
  if (parent)
  {
    const long long cx = (bx + ratio - 1) / ratio, cy = (by + ratio - 1) / ratio;
    const long long c = ix / ratio + cx * (iy / ratio + cy * (iz / ratio));
    lo = parent[2 * c];
    hi = parent[2 * c + 1];
  }
  else
  {
    V3 p0, p1;
    dipoleBlockCorners(P, edge, ix, iy, iz, p0, p1);
    dipoleBlockBound(D, p0, p1, lo, hi);
    if (!(lo <= hi) && list) list[atomicAdd(listCount, 1ull)] = b;
  }
  bounds[2 * b] = lo;
  bounds[2 * b + 1] = hi;
}

/// The blocks of edge voxels inside the listed blocks of the level above
/// (parents, parentCount of them; edge ratio x edge, pbx x pby per layer), one
/// per thread of a grid-stride loop, so that full warps bound blocks:
/// dipoleBlockBound, and a block without a bound listed for the level below
/// (list null: the finest level).
__global__ void dipoleListedBlockKernel(DipoleDev D, Params P, int edge, long long bx, long long by, long long bz,
  long long pbx, long long pby, int ratio, const long long* parents, const unsigned long long* parentCount,
  double* bounds, long long* list, unsigned long long* listCount)
{
  const long long r3 = static_cast<long long>(ratio) * ratio * ratio;
  const long long total = static_cast<long long>(*parentCount) * r3;
  const long long stride = static_cast<long long>(gridDim.x) * blockDim.x;
  for (long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x; t < total; t += stride)
  {
    const long long b = dipoleChildBlock(parents[t / r3], t % r3, ratio, pbx, pby, bx, by, bz);
    if (b < 0) continue;
    V3 p0, p1;
    dipoleBlockCorners(P, edge, b % bx, (b / bx) % by, b / (bx * by), p0, p1);
    double lo = 1, hi = 0;
    dipoleBlockBound(D, p0, p1, lo, hi);
    bounds[2 * b] = lo;
    bounds[2 * b + 1] = hi;
    if (!(lo <= hi) && list) list[atomicAdd(listCount, 1ull)] = b;
  }
}

/// WindingSigner::signRow with the correction s (closure without a cone):
/// one warp per scan line as signKernel; the lanes walk the crossings
/// together, then each lane takes its voxel: decided by the block's bound of
/// s if that decides it, else listed (queue; dipoleRefineKernel refines the
/// listed voxels with full warps), or refined here (insideDipole) when the
/// list is full. A row whose +x ray is ambiguous takes an oblique ray per
/// voxel (WindingSigner::insideAt), and a voxel whose oblique ray is
/// ambiguous too the sum over all of M.
__global__ void signDipoleKernel(WindingDev W, DipoleDev D, Params P, long long rowBegin, long long rowEnd,
  const double* bounds, long long bx, long long by, float* out, unsigned long long* counters, unsigned long long* queue,
  unsigned long long* queueCount, long long queueCap)
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
  const RowRay ray = castRowRay(W, start, h, hits, lane);
  const int ok = ray.ok, count = ray.count, sum = ray.sum;
  unsigned long long ev = 0, full = 0, fallback = 0;
  const double* blockRow = bounds + 2 * bx * ((j - P.lo[1]) / DipoleBlock + by * ((k - P.lo[2]) / DipoleBlock));
  int ahead = sum, next = 0;
  for (long long base = 0; base < nx; base += 32)
  {
    const long long mine = base + lane;
    const long long end = base + 32 < nx ? base + 32 : nx;
    int myK = 0;
    bool myRay = true, myInside = false;
    for (long long i = base; i < end; ++i)
    {
      if (ok)
      {
        const double ti = 0.5 * h + static_cast<double>(i) * h;
        while (next < count && hits[next].t <= ti) ahead -= hits[next++].sign;
        if (i - base == lane) myK = ahead;
        continue;
      }
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
}

/// The voxels signDipoleKernel listed (queue, min(queueCount, queueCap) of
/// them), one per thread of a grid-stride loop: insideDipole at the
/// position the row computes (pos(i) of signDipoleKernel, the same
/// operations), the sign flipped when inside.
__global__ void dipoleRefineKernel(DipoleDev D, Params P, const unsigned long long* queue,
  const unsigned long long* queueCount, long long queueCap, float* out, unsigned long long* counters)
{
  const long long n = min(static_cast<long long>(*queueCount), queueCap);
  const long long nx = P.hi[0] - P.lo[0] + 1, ny = P.hi[1] - P.lo[1] + 1;
  const long long stride = static_cast<long long>(gridDim.x) * blockDim.x;
  const double h = P.spacing[0];
  unsigned long long full = 0;
  for (long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x; t < n; t += stride)
  {
    long long v = 0;
    int K = 0;
    dipoleListedVoxel(queue[t], v, K);
    const long long row = v / nx, i = v % nx;
    const V3 start = positionOf(P, P.lo[0], P.lo[1] + row % ny, P.lo[2] + row / ny);
    if (insideDipole(D, K, start + V3{ static_cast<double>(i) * h, 0, 0 }, full)) out[v] = -out[v];
  }
  if (full) atomicAdd(counters + 2, full);
}
} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
