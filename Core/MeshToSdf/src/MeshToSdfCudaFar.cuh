// Far blocks of the Normal and PseudoNormal signs on the GPU (included by
// MeshToSdfCuda.cu after MeshToSdfCudaKernels.cuh): one thread per block of
// FarBlock^3 voxels of the slab decides it, or else its FarCell^3 cells, as
// classifyFarCells does on the CPU (MeshToSdfFarBlocks.h, docs/MESH_TO_SDF.md
// "Far blocks"); the distance kernel then writes +-band for their voxels
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

/// farSide of MeshToSdfFarBlocks.cpp on the binary BVH (exact boxes).
__device__ int farSideDev(const DevBvh& b, const FarBox& box, double bandWorld, double margin, int& hintSlot)
{
  int slot = -1;
  const NearestResult r = nearestDev(b, box.centre, hintSlot, 1e300, slot);
  if (r.tri < 0) return 0;
  hintSlot = slot;
  const double dist = sqrt(r.dist2);
  if (!farPastBand(dist, box, bandWorld, margin)) return 0;
  const double reach = farRadius(dist, box, margin);
  const double reach2 = reach * reach;
  int side = 0;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const GpuNode& n = b.nodes[stack[--top]];
    if (pointBoxDist2(box.centre, n.lo, n.hi) > reach2) continue;
    if (n.left < 0)
    {
      for (int i = n.first; i < n.first + n.count; ++i)
      {
        const GpuTri& t = b.leaf[i];
        const int s = farFaceSide(t.v[0], t.v[1], t.v[2], t.n, box, reach, margin);
        if (s == 2) continue;
        if (s == 0 || (side != 0 && s != side)) return 0;
        side = s;
      }
      continue;
    }
    if (top + 2 > 64) return 0; // deeper than the stack: undecided, never wrong
    stack[top++] = n.left;
    stack[top++] = n.right;
  }
  return side;
}

/// The far cells of the slab P.lo..P.hi (box-relative, FarCells layout in
/// `cells`, count[0] x count[1] x count[2]); decided voxels added to *decided.
__global__ void farCellsKernel(DevBvh bvh, Params P, double margin, double big, long long cx, long long cy,
  long long cz, signed char* cells, unsigned long long* decided)
{
  constexpr int Sub = FarBlock / FarCell;
  const long long n[3] = { P.hi[0] - P.lo[0] + 1, P.hi[1] - P.lo[1] + 1, P.hi[2] - P.lo[2] + 1 };
  const long long bx = (n[0] + FarBlock - 1) / FarBlock, by = (n[1] + FarBlock - 1) / FarBlock,
                  bz = (n[2] + FarBlock - 1) / FarBlock;
  const long long b = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (b >= bx * by * bz) return;
  const long long bi[3] = { b % bx, (b / bx) % by, b / (bx * by) };
  auto boxOf = [&](const long long v0[3], long long edge) {
    long long hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = min(v0[a] + edge, n[a]) - 1;
    return farBox(positionOf(P, P.lo[0] + v0[0], P.lo[1] + v0[1], P.lo[2] + v0[2]),
      positionOf(P, P.lo[0] + hi[0], P.lo[1] + hi[1], P.lo[2] + hi[2]), big);
  };
  const long long v0[3] = { bi[0] * FarBlock, bi[1] * FarBlock, bi[2] * FarBlock };
  int hint = -1;
  const int whole = farSideDev(bvh, boxOf(v0, FarBlock), P.bandWorld, margin, hint);
  unsigned long long count = 0;
  for (int d = 0; d < Sub * Sub * Sub; ++d)
  {
    const long long c[3] = { bi[0] * Sub + d % Sub, bi[1] * Sub + (d / Sub) % Sub, bi[2] * Sub + d / (Sub * Sub) };
    if (c[0] >= cx || c[1] >= cy || c[2] >= cz) continue;
    const long long c0[3] = { c[0] * FarCell, c[1] * FarCell, c[2] * FarCell };
    const int s = whole != 0 ? whole : farSideDev(bvh, boxOf(c0, FarCell), P.bandWorld, margin, hint);
    cells[c[0] + cx * (c[1] + cy * c[2])] = static_cast<signed char>(s);
    if (s != 0)
    {
      count += static_cast<unsigned long long>((min(c0[0] + FarCell, n[0]) - c0[0]) *
        (min(c0[1] + FarCell, n[1]) - c0[1]) * (min(c0[2] + FarCell, n[2]) - c0[2]));
    }
  }
  if (count) atomicAdd(decided, count);
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
