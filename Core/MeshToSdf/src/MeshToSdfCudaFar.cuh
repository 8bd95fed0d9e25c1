// Far blocks of the Normal and PseudoNormal signs on the GPU (included by
// MeshToSdfCuda.cu after MeshToSdfCudaKernels.cuh): the boxes of the slab
// decided level by level as classifyFarCells does on the CPU
// (MeshToSdfFarBlocks.h, docs/MESH_TO_SDF.md "Far blocks"); the distance
// kernel then writes +-band for their voxels without a query.
#pragma once

#include "MeshToSdfCudaKernels.cuh"
#include "MeshToSdfFarBlocks.h"

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
namespace
{

/// One level of the far cells of the slab P.lo..P.hi (box-relative,
/// FarCells layout in `cells`, cx x cy x cz, cleared before the first
/// level): one thread per box of edge^3 voxels whose enclosing box of the
/// level before (2 edge) was not decided. Launched for edge = FarBlock, then
/// FarBlock / 2, then FarCell, this tries the boxes farClassifyBlock tries on
/// the CPU (each with its own nearest query and farBoxSide on the same BVH
/// and cones), with 8 and 64 times more threads than one per block; decided
/// voxels added to *decided. parentDist: the level before's distances (or
/// bounds), by which a box certainly within the band is skipped without a
/// query, as on the CPU; ownDist: this level's, for the next (null at the
/// first level and the last).
__global__ void farLevelKernel(DevBvh bvh, const FarCone* cones, Params P, double margin, double big, int edge,
  long long cx, long long cy, long long cz, signed char* cells, const double* parentDist, double* ownDist,
  unsigned long long* decided)
{
  const long long n[3] = { P.hi[0] - P.lo[0] + 1, P.hi[1] - P.lo[1] + 1, P.hi[2] - P.lo[2] + 1 };
  const long long mx = (n[0] + edge - 1) / edge, my = (n[1] + edge - 1) / edge, mz = (n[2] + edge - 1) / edge;
  const long long b = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (b >= mx * my * mz) return;
  const long long o[3] = { (b % mx) * edge, ((b / mx) % my) * edge, (b / (mx * my)) * edge };
  signed char* first = cells + (o[0] / FarCell + cx * (o[1] / FarCell + cy * (o[2] / FarCell)));
  if (edge != FarBlock && *first != 0) return; // inside a box decided at the level before
  long long hi[3];
  for (int a = 0; a < 3; ++a) hi[a] = min(o[a] + edge, n[a]) - 1;
  const FarBox box = farBox(positionOf(P, P.lo[0] + o[0], P.lo[1] + o[1], P.lo[2] + o[2]),
    positionOf(P, P.lo[0] + hi[0], P.lo[1] + hi[1], P.lo[2] + hi[2]), big);
  if (parentDist)
  {
    // the enclosing box (edge 2 edge) and its distance or bound: a box
    // certainly within the band is left undecided without a query, as on the CPU
    const long long pe = 2 * edge, pmx = (n[0] + pe - 1) / pe, pmy = (n[1] + pe - 1) / pe;
    long long po[3], phi[3];
    for (int a = 0; a < 3; ++a)
    {
      po[a] = o[a] - o[a] % pe;
      phi[a] = min(po[a] + pe, n[a]) - 1;
    }
    const FarBox parent = farBox(positionOf(P, P.lo[0] + po[0], P.lo[1] + po[1], P.lo[2] + po[2]),
      positionOf(P, P.lo[0] + phi[0], P.lo[1] + phi[1], P.lo[2] + phi[2]), big);
    const double bound = farChildBound(parentDist[po[0] / pe + pmx * (po[1] / pe + pmy * (po[2] / pe))], box, parent, big);
    if (bound - box.radius <= P.bandWorld)
    {
      if (ownDist) ownDist[b] = bound; // for this box's own cells
      return;
    }
  }
  int slot = -1;
  const NearestResult q = nearestDev(bvh, box.centre, -1, 1e300, slot);
  if (q.tri < 0)
  {
    if (ownDist) ownDist[b] = 0; // no triangle: nothing is decided below either
    return;
  }
  const bool pseudo = P.sign == 1;
  auto triAt = [&](int i) -> const Tri& { return bvh.tris[bvh.order[i]]; };
  const double dq = sqrt(q.dist2);
  if (ownDist) ownDist[b] = dq;
  const int s = farBoxSide(bvh.nodes, cones, triAt, pseudo, box, dq, dq, P.bandWorld, margin,
    farSideAt(bvh.tris[q.tri], q.closest, box.centre, pseudo));
  if (s == 0) return;
  for (long long z = o[2]; z <= hi[2]; z += FarCell)
    for (long long y = o[1]; y <= hi[1]; y += FarCell)
      for (long long x = o[0]; x <= hi[0]; x += FarCell)
        cells[x / FarCell + cx * (y / FarCell + cy * (z / FarCell))] = static_cast<signed char>(s);
  atomicAdd(decided, static_cast<unsigned long long>((hi[0] - o[0] + 1) * (hi[1] - o[1] + 1) * (hi[2] - o[2] + 1)));
  (void)cz;
}

} // namespace
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
