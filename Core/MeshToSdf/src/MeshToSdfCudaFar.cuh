// Far blocks of the Normal and PseudoNormal signs on the GPU (included by
// MeshToSdfCuda.cu after MeshToSdfCudaKernels.cuh): the blocks of the slab
// classified as classifyFarCells does on the CPU, by the same functions
// (MeshToSdfFarBlocks.h, docs/MESH_TO_SDF.md "Far blocks") in two launches:
// one thread per block tries it whole and keeps its state (candidate list)
// for its halves, then one thread per half tries the half, its cells and
// their voxels. The distance kernel then writes +-band for the decided voxels
// without a query.
#pragma once

#include "MeshToSdfCudaKernels.cuh"
#include "MeshToSdfFarBlocks.h"

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
namespace
{

/// What both far kernels share: the slab's size in voxels, the box of edge^3
/// voxels at a slab-relative origin, the nearest query of a box's centre
/// (warm-started from the thread's last one) and the record of decided voxels.
struct FarSlab
{
  DevBvh bvh;
  Params P;
  double big;
  long long n[3];
  long long cx, cy;      // cells along x and y
  signed char* sign;     // per cell: the side of its decided voxels
  unsigned char* mask;   // per cell: its decided voxels (bit x + 2 y + 4 z)

  __device__ void boxOf(const long long o[3], long long edge, FarBox& out) const
  {
    long long hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = min(o[a] + edge, n[a]) - 1;
    out = farBox(positionOf(P, P.lo[0] + o[0], P.lo[1] + o[1], P.lo[2] + o[2]),
      positionOf(P, P.lo[0] + hi[0], P.lo[1] + hi[1], P.lo[2] + hi[2]), big);
  }

  __device__ void set(const long long c[3], int s, int m) const
  {
    const long long at = c[0] + cx * (c[1] + cy * c[2]);
    sign[at] = static_cast<signed char>(s);
    mask[at] = static_cast<unsigned char>(mask[at] | m);
  }
};

__device__ FarSlab farSlab(const DevBvh& bvh, const Params& P, double big, signed char* sign, unsigned char* mask)
{
  FarSlab f{ bvh, P, big, { P.hi[0] - P.lo[0] + 1, P.hi[1] - P.lo[1] + 1, P.hi[2] - P.lo[2] + 1 }, 0, 0, sign, mask };
  f.cx = (f.n[0] + FarCell - 1) / FarCell;
  f.cy = (f.n[1] + FarCell - 1) / FarCell;
  return f;
}

/// One thread per FarBlock^3 block of the slab: its own test (farTryBox);
/// its state, for the halves, in states[block]. The cells (sign, mask) are
/// cleared before. At most 128 registers, as farHalfKernel.
__global__ void __launch_bounds__(128, 4) farBlockKernel(DevBvh bvh, const FarCone* cones, Params P, double margin, double big,
  signed char* sign, unsigned char* mask, FarState* states, unsigned long long* decided)
{
  const FarSlab f = farSlab(bvh, P, big, sign, mask);
  const long long mx = (f.n[0] + FarBlock - 1) / FarBlock, my = (f.n[1] + FarBlock - 1) / FarBlock,
                  mz = (f.n[2] + FarBlock - 1) / FarBlock;
  const long long b = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (b >= mx * my * mz) return;
  const long long o[3] = { (b % mx) * FarBlock, ((b / mx) % my) * FarBlock, (b / (mx * my)) * FarBlock };
  const bool pseudo = P.sign == 1;
  auto triAt = [&](int i) -> const Tri& { return bvh.tris[bvh.order[i]]; };
  int slot = -1;
  auto nearest = [&](V3 c) {
    const NearestResult q = nearestDev(bvh, c, slot, 1e300, slot);
    FarQuery r;
    if (q.tri < 0) return r;
    r.tri = &bvh.tris[q.tri];
    r.found = true;
    r.dist = sqrt(q.dist2);
    r.side = farSideAt(bvh.tris[q.tri], q.closest, c, pseudo);
    return r;
  };
  FarState& st = states[b];
  f.boxOf(o, FarBlock, st.box);
  const int s = farTryBox(bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, nullptr, st);
  if (s == 0) return;
  const long long count = farFill(o, FarBlock, f.n, s, [&](const long long c[3], int sd, int m) { f.set(c, sd, m); });
  atomicAdd(decided, static_cast<unsigned long long>(count));
}

/// One thread per half (FarBlock / 2)^3 of a block farBlockKernel left
/// undecided: farClassifyHalf from the block's state. At most 128 registers
/// (4 blocks of 128 threads per SM, as the old per-level kernel had; 166
/// uncapped).
__global__ void __launch_bounds__(128, 4) farHalfKernel(DevBvh bvh, const FarCone* cones, Params P, double margin, double big,
  signed char* sign, unsigned char* mask, const FarState* states, unsigned long long* decided)
{
  constexpr long long Half = FarBlock / 2;
  const FarSlab f = farSlab(bvh, P, big, sign, mask);
  const long long hx = (f.n[0] + Half - 1) / Half, hy = (f.n[1] + Half - 1) / Half, hz = (f.n[2] + Half - 1) / Half;
  const long long h = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (h >= hx * hy * hz) return;
  const long long o[3] = { (h % hx) * Half, ((h / hx) % hy) * Half, (h / (hx * hy)) * Half };
  // decided with its block: the block filled every cell
  if (sign[o[0] / FarCell + f.cx * (o[1] / FarCell + f.cy * (o[2] / FarCell))] != 0) return;
  const long long mx = (f.n[0] + FarBlock - 1) / FarBlock, my = (f.n[1] + FarBlock - 1) / FarBlock;
  const FarState& block = states[o[0] / FarBlock + mx * (o[1] / FarBlock + my * (o[2] / FarBlock))];
  const bool pseudo = P.sign == 1;
  auto triAt = [&](int i) -> const Tri& { return bvh.tris[bvh.order[i]]; };
  int slot = -1;
  auto nearest = [&](V3 c) {
    const NearestResult q = nearestDev(bvh, c, slot, 1e300, slot);
    FarQuery r;
    if (q.tri < 0) return r;
    r.tri = &bvh.tris[q.tri];
    r.found = true;
    r.dist = sqrt(q.dist2);
    r.side = farSideAt(bvh.tris[q.tri], q.closest, c, pseudo);
    return r;
  };
  const long long count = farClassifyHalf(bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, block,
    o, f.n, [&](const long long at[3], long long edge, FarBox& out) { f.boxOf(at, edge, out); },
    [&](const long long c[3], int sd, int m) { f.set(c, sd, m); });
  if (count > 0) atomicAdd(decided, static_cast<unsigned long long>(count));
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
