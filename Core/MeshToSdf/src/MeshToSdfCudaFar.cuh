// Far blocks of the Normal and PseudoNormal signs on the GPU (included by
// MeshToSdfCuda.cu after MeshToSdfCudaKernels.cuh): the blocks of the slab
// classified as classifyFarCells does on the CPU, by the same functions
// (MeshToSdfFarBlocks.h, docs/MESH_TO_SDF.md "Far blocks") in two launches:
// one thread per block tries it whole and keeps its state (candidate list)
// for its halves, listing the blocks it leaves undecided; then one CUDA block
// of 64 threads per listed block: 8 threads try its halves (states in shared
// memory), then one thread per cell tries the cell and its voxels. The
// distance kernel then writes +-band for the decided voxels without a query.
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
/// its state, for the halves, in states[block], and the block appended to
/// undecided (work[0]: their count) when the test leaves it so. The cells
/// (sign, mask) and work are cleared before. At most 128 registers.
__global__ void __launch_bounds__(128, 4) farBlockKernel(DevBvh bvh, const FarCone* cones, Params P, double margin, double big,
  signed char* sign, unsigned char* mask, FarState* states, long long* undecided, unsigned long long* work,
  unsigned long long* decided)
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
  if (s == 0)
  {
    undecided[atomicAdd(work, 1ull)] = b;
    return;
  }
  const long long count = farFill(o, FarBlock, f.n, s, [&](const long long c[3], int sd, int m) { f.set(c, sd, m); });
  atomicAdd(decided, static_cast<unsigned long long>(count));
}

/// Threads per CUDA block of farCellKernel: one per cell of a FarBlock^3 block.
constexpr int FarCellThreads = 64;
static_assert(FarCellThreads == 8 * 8 && FarBlock == 4 * FarCell, "8 halves of 8 cells each");

/// The blocks farBlockKernel left undecided (undecided[0, work[0])), one per
/// CUDA block of 64 threads at a time, taken in turn (work[1]: the next) so
/// that a grid sized to the GPU needs no count on the host: threads 0-7 try
/// half t from the block's state, keeping the half's state in shared memory;
/// then thread t takes cell t % 8 of half t / 8 left undecided, with its
/// voxels (farClassifyCell). The same functions as the CPU's farClassifyHalf,
/// spread over threads (a thread per half did 8 cells and 64 voxels one after
/// the other, beside threads of decided blocks with nothing to do). At most
/// 128 registers, as farBlockKernel.
__global__ void __launch_bounds__(FarCellThreads, 8) farCellKernel(DevBvh bvh, const FarCone* cones, Params P, double margin,
  double big, signed char* sign, unsigned char* mask, const FarState* states, const long long* undecided,
  unsigned long long* work, unsigned long long* decided)
{
  constexpr long long Half = FarBlock / 2;
  // FarState has default initialisers, which __shared__ forbids: raw storage,
  // every field read below written by boxOf and farTryBox first
  __shared__ alignas(FarState) unsigned char raw[8 * sizeof(FarState)];
  __shared__ int halfSide[8];
  __shared__ long long current;
  FarState* halves = reinterpret_cast<FarState*>(raw);
  const FarSlab f = farSlab(bvh, P, big, sign, mask);
  const long long mx = (f.n[0] + FarBlock - 1) / FarBlock, my = (f.n[1] + FarBlock - 1) / FarBlock;
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
  auto boxOf = [&](const long long at[3], long long edge, FarBox& out) { f.boxOf(at, edge, out); };
  auto set = [&](const long long c[3], int sd, int m) { f.set(c, sd, m); };
  const int t = static_cast<int>(threadIdx.x);
  unsigned long long mine = 0;
  for (;;)
  {
    if (t == 0)
    {
      const unsigned long long k = atomicAdd(work + 1, 1ull);
      current = k < work[0] ? undecided[k] : -1;
    }
    __syncthreads();
    const long long b = current;
    if (b < 0) break; // the same for every thread of the CUDA block
    const long long o[3] = { (b % mx) * FarBlock, ((b / mx) % my) * FarBlock, (b / (mx * my)) * FarBlock };
    // half h's origin; whether it lies in the slab
    auto halfAt = [&](int h, long long o1[3]) {
      o1[0] = o[0] + Half * (h & 1);
      o1[1] = o[1] + Half * ((h >> 1) & 1);
      o1[2] = o[2] + Half * (h >> 2);
      return o1[0] < f.n[0] && o1[1] < f.n[1] && o1[2] < f.n[2];
    };
    long long o1[3];
    if (t < 8)
    {
      halfSide[t] = 0;
      if (halfAt(t, o1))
      {
        FarState& s1 = halves[t];
        boxOf(o1, Half, s1.box);
        const int r1 = farTryBox(bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, &states[b], s1);
        if (r1 != 0) mine += static_cast<unsigned long long>(farFill(o1, Half, f.n, r1, set));
        halfSide[t] = r1;
      }
    }
    __syncthreads();
    const int h = t >> 3;
    if (halfAt(h, o1) && halfSide[h] == 0)
    {
      long long o2[3];
      farCellOrigin(o1, t & 7, o2);
      mine += static_cast<unsigned long long>(farClassifyCell(
        bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, halves[h], o2, f.n, boxOf, set));
    }
    __syncthreads(); // current and the halves' states are rewritten for the next block
  }
  if (mine > 0) atomicAdd(decided, mine);
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
