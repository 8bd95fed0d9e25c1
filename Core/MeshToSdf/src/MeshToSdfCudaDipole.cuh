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

/// One thread per block of edge voxels (one level of DipoleEdges) of the
/// slab: dipoleBlockBound. parent (every level but the coarsest): the bounds
/// of the level above, whose edge is ratio x edge (bx / ratio rounded up per
/// row); a parent's bound is taken as it is (it holds over the block too).
__global__ void dipoleBlockKernel(DipoleDev D, Params P, int edge, long long bx, long long by, long long blocks,
  const double* parent, int ratio, double* bounds)
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
  if (!(lo <= hi))
  {
    const long long x0 = P.lo[0] + edge * ix, y0 = P.lo[1] + edge * iy, z0 = P.lo[2] + edge * iz;
    const V3 p0 = positionOf(P, x0, y0, z0);
    const V3 p1 = positionOf(P, min(x0 + edge - 1, P.hi[0]), min(y0 + edge - 1, P.hi[1]), min(z0 + edge - 1, P.hi[2]));
    dipoleBlockBound(D, p0, p1, lo, hi);
  }
  bounds[2 * b] = lo;
  bounds[2 * b + 1] = hi;
}

/// WindingSigner::signRow with the correction s (closure without a cone):
/// one warp per scan line as signKernel; the lanes walk the crossings
/// together, then each lane decides its voxel: the block's bound of s if it
/// decides, else insideDipole. A row whose +x ray is ambiguous takes an
/// oblique ray per voxel (WindingSigner::insideAt), and a voxel whose oblique
/// ray is ambiguous too the sum over all of M.
// Blocks of the sign kernel that must fit on an SM at once (registers capped
// to allow it; 1: no cap, 110 registers, 4 blocks). A build-time tuning knob
// for scripts/gpu-write.sh's A/B (6: 80 registers with some spills); the
// values are the same either way.
#ifndef LVDIF_SIGN_MIN_BLOCKS
#define LVDIF_SIGN_MIN_BLOCKS 1
#endif
__global__ void __launch_bounds__(32 * SignWarps, LVDIF_SIGN_MIN_BLOCKS) signDipoleKernel(WindingDev W,
  DipoleDev D, Params P, long long rowBegin, long long rowEnd,
  const int4* rayMeta, const Hit* rayHits, const double* bounds, long long bx, long long by, float* out,
  unsigned long long* counters)
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
  unsigned long long ev = 0, full = 0, fallback = 0;
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
    if (mine >= nx) continue;
    if (!ok) ++fallback;
    if (myRay)
    {
      // ambiguous rows use no block bounds (WindingSigner::insideAt)
      const double lo = ok ? blockRow[2 * (mine / DipoleBlock)] : 1.0, hi = ok ? blockRow[2 * (mine / DipoleBlock) + 1] : 0.0;
      myInside = insideWithBlock(D, myK, pos(mine), lo, hi, ev, full);
    }
    if (myInside) rowOut[mine] = -rowOut[mine];
  }
  if (ev) atomicAdd(counters, ev);
  if (fallback) atomicAdd(counters + 1, fallback);
  if (full) atomicAdd(counters + 2, full);
}
} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
