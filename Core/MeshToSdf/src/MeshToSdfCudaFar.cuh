// Far blocks of the Normal and PseudoNormal signs on the GPU (included by
// MeshToSdfCuda.cu after MeshToSdfCudaKernels.cuh): the blocks of the slab
// classified as classifyFarCells does on the CPU, by the same functions
// (MeshToSdfFarBlocks.h, docs/MESH_TO_SDF.md "Far blocks") in two launches:
// one thread per block tries it whole and keeps its state (candidate list)
// for its halves, listing the blocks it leaves undecided; then one CUDA block
// of 64 threads per listed block: 8 threads try its halves, one thread per
// cell its cells (states in shared memory), 8 threads per cell their voxels. The
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

/// Triangle `tri` of the device copy as the far tests read it.
__device__ inline FarTri farTriDev(const DevBvh& bvh, int tri, bool pseudo)
{
  return { &bvh.tris[tri], pseudo ? &bvh.normals[tri] : nullptr };
}

/// The nearest query of a box's centre for farTryBox (both far kernels),
/// seeded by the thread's previous answer.
struct FarNearestDev
{
  const DevBvh& bvh;
  bool pseudo;
  int slot = -1;

  __device__ FarQuery operator()(V3 c)
  {
    const NearestResult q = nearestDev(bvh, c, this->slot, 1e300, this->slot);
    FarQuery r;
    if (q.tri < 0) return r;
    r.tri = &bvh.tris[q.tri];
    r.found = true;
    r.dist = sqrt(q.dist2);
    r.side = farSideAt(farTriDev(bvh, q.tri, this->pseudo), q.closest, c, this->pseudo);
    return r;
  }
};

/// A warp of farBlockKernel takes a tile of 4 x 4 x 2 blocks (lane bits 0-1:
/// x, 2-3: y, 4: z), so that its threads' queries and walks follow similar
/// paths down the tree (a row of 32 blocks along x spans 256 voxels).
constexpr long long FarTileX = 4, FarTileY = 4, FarTileZ = 2;
static_assert(FarTileX * FarTileY * FarTileZ == 32, "a tile per warp");

/// The tiles of farBlockKernel along each axis of m blocks.
__host__ __device__ inline void farTiles(const long long m[3], long long t[3])
{
  t[0] = (m[0] + FarTileX - 1) / FarTileX;
  t[1] = (m[1] + FarTileY - 1) / FarTileY;
  t[2] = (m[2] + FarTileZ - 1) / FarTileZ;
}

/// One thread per FarBlock^3 block of the slab (a warp per tile, FarTileX):
/// its own test (farTryBox); its state, for the halves, in states[block],
/// and the block appended to undecided (work[0]: their count) when the test
/// leaves it so. The cells (sign, mask) and work are cleared before. At most
/// 128 registers.
__global__ void __launch_bounds__(128, 4) farBlockKernel(DevBvh bvh, const FarCone* cones, Params P, double margin, double big,
  signed char* sign, unsigned char* mask, FarState* states, long long* undecided, unsigned long long* work,
  unsigned long long* decided)
{
  const FarSlab f = farSlab(bvh, P, big, sign, mask);
  const long long m[3] = { (f.n[0] + FarBlock - 1) / FarBlock, (f.n[1] + FarBlock - 1) / FarBlock,
    (f.n[2] + FarBlock - 1) / FarBlock };
  long long tiles[3];
  farTiles(m, tiles);
  const long long thread = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  const long long tile = thread / 32;
  const int lane = static_cast<int>(thread % 32);
  if (tile >= tiles[0] * tiles[1] * tiles[2]) return;
  const long long at[3] = { (tile % tiles[0]) * FarTileX + (lane & 3), ((tile / tiles[0]) % tiles[1]) * FarTileY + ((lane >> 2) & 3),
    (tile / (tiles[0] * tiles[1])) * FarTileZ + (lane >> 4) };
  if (at[0] >= m[0] || at[1] >= m[1] || at[2] >= m[2]) return;
  const long long b = at[0] + m[0] * (at[1] + m[1] * at[2]);
  const long long o[3] = { at[0] * FarBlock, at[1] * FarBlock, at[2] * FarBlock };
  const bool pseudo = P.sign == 1;
  auto triAt = [&](int i) { return farTriDev(bvh, bvh.order[i], pseudo); };
  FarNearestDev nearest{ bvh, pseudo };
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
/// that a grid sized to the GPU needs no count on the host. Three steps, the
/// states in shared memory: threads 0-7 try half t from the block's state;
/// thread t tries cell t % 8 of half t / 8 (if that half is undecided); then
/// the voxels of the cells left undecided by their lists, 8 threads per cell
/// (one per voxel) and 8 cells at a time, so that a warp's threads loop over
/// lists of the same cell (a thread per cell looped over its 8 voxels, the
/// warp as long as its longest list 8 times). The same functions as the CPU's
/// farClassifyHalf. At most 128 registers, as farBlockKernel.
__global__ void __launch_bounds__(FarCellThreads, 8) farCellKernel(DevBvh bvh, const FarCone* cones, Params P, double margin,
  double big, signed char* sign, unsigned char* mask, const FarState* states, const long long* undecided,
  unsigned long long* work, unsigned long long* decided)
{
  constexpr long long Half = FarBlock / 2;
  // FarState has default initialisers, which __shared__ forbids: raw storage,
  // every field read below written by boxOf and farTryBox first
  __shared__ alignas(FarState) unsigned char rawHalves[8 * sizeof(FarState)];
  __shared__ alignas(FarState) unsigned char rawCells[FarCellThreads * sizeof(FarState)];
  __shared__ int halfSide[8];
  __shared__ unsigned char cellVoxels[FarCellThreads]; // 1: the cell's voxels are tried by its list
  __shared__ long long current;
  FarState* halves = reinterpret_cast<FarState*>(rawHalves);
  FarState* cells = reinterpret_cast<FarState*>(rawCells);
  const FarSlab f = farSlab(bvh, P, big, sign, mask);
  const long long mx = (f.n[0] + FarBlock - 1) / FarBlock, my = (f.n[1] + FarBlock - 1) / FarBlock;
  const bool pseudo = P.sign == 1;
  auto triAt = [&](int i) { return farTriDev(bvh, bvh.order[i], pseudo); };
  FarNearestDev nearest{ bvh, pseudo };
  auto boxOf = [&](const long long at[3], long long edge, FarBox& out) { f.boxOf(at, edge, out); };
  auto set = [&](const long long c[3], int sd, int m) { f.set(c, sd, m); };
  const int t = static_cast<int>(threadIdx.x), lane = t & 31;
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
    // the origin of cell q of half h (q < 0: of the half); whether it lies in the slab
    auto originOf = [&](int h, int q, long long at[3]) {
      const long long o1[3] = { o[0] + Half * (h & 1), o[1] + Half * ((h >> 1) & 1), o[2] + Half * (h >> 2) };
      if (q < 0)
        for (int a = 0; a < 3; ++a) at[a] = o1[a];
      else
        farCellOrigin(o1, q, at);
      return at[0] < f.n[0] && at[1] < f.n[1] && at[2] < f.n[2];
    };
    long long at[3];
    if (t < 8)
    {
      halfSide[t] = 0;
      if (originOf(t, -1, at))
      {
        FarState& s1 = halves[t];
        boxOf(at, Half, s1.box);
        const int r1 = farTryBox(bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, &states[b], s1);
        if (r1 != 0) mine += static_cast<unsigned long long>(farFill(at, Half, f.n, r1, set));
        halfSide[t] = r1;
      }
    }
    __syncthreads();
    // a half outside the slab has halfSide 0, but its cells are outside too
    cellVoxels[t] = 0;
    if (halfSide[t >> 3] == 0 && originOf(t >> 3, t & 7, at))
    {
      FarState& s2 = cells[t];
      boxOf(at, static_cast<long long>(FarCell), s2.box);
      const int r2 =
        farTryBox(bvh.nodes, cones, triAt, nearest, pseudo, P.bandWorld, margin, big, &halves[t >> 3], s2);
      if (r2 != 0)
        mine += static_cast<unsigned long long>(farFill(at, static_cast<long long>(FarCell), f.n, r2, set));
      else if (s2.past && s2.count >= 0)
        cellVoxels[t] = 1;
    }
    __syncthreads();
    // cell c = 8 i + t / 8 (the cells of half i), voxel t % 8; the 8 lanes of
    // a cell combine their bits by a ballot, its first lane records them
    for (int i = 0; i < 8; ++i)
    {
      const int c = 8 * i + (t >> 3);
      int side = 0;
      if (cellVoxels[c] && originOf(i, c & 7, at))
        side = farCellVoxel(triAt, pseudo, margin, big, cells[c], at, t & 7, f.n, boxOf);
      const unsigned bits = (__ballot_sync(FullMask, side != 0) >> (lane & 24)) & 0xffu;
      if ((lane & 7) == 0 && bits != 0)
      {
        const long long cell[3] = { at[0] / FarCell, at[1] / FarCell, at[2] / FarCell };
        set(cell, cells[c].side, static_cast<int>(bits));
        mine += static_cast<unsigned long long>(__popc(bits));
      }
    }
    __syncthreads(); // current and the states are rewritten for the next block
  }
  if (mine > 0) atomicAdd(decided, mine);
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
