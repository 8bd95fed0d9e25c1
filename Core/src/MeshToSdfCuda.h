// CUDA entry points of mesh to SDF (MeshToSdfCuda.cu; stubs in
// nocuda/MeshToSdfCuda.cpp). Called only when resolveDevice() chose CUDA.
#pragma once

#include "MeshToSdfInternal.h"
#include "lvdif/MeshToSdf.h"

#include <memory>

namespace lvdif
{
namespace cudasdf
{
/// The mesh and its BVHs uploaded once; compute() then fills any extent of
/// the grid with the same contract as the CPU path (distances and signs in
/// output units, band-saturated), one slab of z layers at a time so device
/// memory stays bounded. Always uses the BVH (the accelerators give the same
/// distances); winding is null unless the sign mode is WindingNumber.
class Session
{
public:
  virtual ~Session() = default;
  virtual void compute(const VoxelBox& extent, float* out, MeshToSdfStats& stats, Interrupter& interrupter) = 0;
};

std::unique_ptr<Session> openSession(const sdfdetail::PreparedMesh& mesh, const sdfdetail::Bvh& bvh,
  const sdfdetail::WindingSigner* winding, const GridGeometry& grid, const MeshToSdfOptions& options, double toOut,
  double band, MeshToSdfStats& stats);
} // namespace cudasdf
} // namespace lvdif
