// CUDA entry points of mesh to SDF (MeshToSdfCuda.cu; stubs in
// nocuda/MeshToSdfCuda.cpp). Called only when resolveDevice() chose CUDA.
#pragma once

#include "MeshToSdfInternal.h"
#include "lvdif/MeshToSdf.h"

namespace lvdif
{
namespace cudasdf
{
/// Same contract as the CPU path of meshToSdf for one extent of the grid:
/// distances (and signs) in output units, band-saturated, into out, one
/// slab of z layers at a time. Always uses the BVH (the accelerators give the
/// same distances); winding is null unless the sign mode is WindingNumber.
void computeExtent(const sdfdetail::PreparedMesh& mesh, const sdfdetail::Bvh& bvh,
  const sdfdetail::WindingSigner* winding, const GridGeometry& grid,
  const VoxelBox& extent, float* out, const MeshToSdfOptions& options, double toOut, double band,
  MeshToSdfStats& stats, Interrupter& interrupter);
} // namespace cudasdf
} // namespace lvdif
