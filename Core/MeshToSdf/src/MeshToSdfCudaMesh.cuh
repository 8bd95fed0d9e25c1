// The prepared mesh's copy on the GPU (MeshToSdfCudaMesh.cu): compact leaf
// records and the mesh tree, the pseudo-normals and node cones of the
// Normal/PseudoNormal signs, and the winding structures, which may be added
// while a session's distance kernel runs (into buffers reserved beforehand, on
// a non-blocking stream). Read by the sessions (MeshToSdfCuda.cu).
#pragma once

#include "MeshToSdfCuda.h"
#include "MeshToSdfCudaLayout.cuh"
#include "MeshToSdfCudaMemory.cuh"
#include "MeshToSdfFarBlocks.h"

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

class CudaMesh : public DeviceMesh
{
public:
  /// windingLater: reserve (allocate now) the buffers of the winding
  /// structures, so that addWinding only copies (a cudaMalloc could wait for
  /// the distance kernel it is meant to overlap). Their sizes are bounded by
  /// the mesh: closed chain <= triangles + boundary edges, nodes <= 2 x that.
  CudaMesh(const PreparedMesh& mesh, const Bvh& bvh, const WindingSigner* winding, bool normals, bool windingLater);
  // addNormals/addWinding run under the prepared mesh's lock while sessions
  // of other threads may be launching kernels: the parts they add are
  // published by release stores, and a session reads them only after an
  // acquire load saw them (or after taking that lock itself).
  bool hasNormals() const override { return this->Full.load(std::memory_order_acquire) != nullptr; }
  void addNormals() override;
  /// The node cones (valid once hasNormals()).
  const FarCone* cones() const { return this->hasNormals() ? this->Cones : nullptr; }
  /// The mesh BVH as the distance kernel takes it (full records if uploaded).
  DevBvh meshBvh() const;
  void addWinding(const WindingSigner& winding, bool reoriented) override;
  bool hasWinding(bool reoriented) const override
  {
    return this->Winding[reoriented ? 1 : 0].load(std::memory_order_acquire);
  }
  const PreparedMesh& prepared() const { return this->Mesh; }
  std::uint64_t bytes() const override { return this->Arena.bytes(); }
  DevBvh Dbvh;     // immutable once constructed (tris: see meshBvh)
  WindingDev W[2]; // [0]: M as given, [1]: M+ (reorientFaces); each written once by addWinding, before Winding[i] is set
  DipoleDev D[2];  // the correction s (count 0: none, or the cone closure); as W

private:
  const PreparedMesh& Mesh; // owned by the prepared mesh, which owns this copy
  const Bvh& MeshBvh;
  DeviceArena Arena;
  Stream Upload;
  std::atomic<bool> Winding[2] = { false, false };
  const int* Slot = nullptr; // each mesh triangle's slot in the tree's leaf order (both winding variants)
  std::atomic<const Tri*> Full{ nullptr }; // the triangle records by index (Normal/PseudoNormal)
  const FarCone* Cones = nullptr;          // the node cones, written before Full
  const TriNormals* Normals = nullptr;     // the records' pseudo-normals, written before Full
  const CornerNormals* Corners = nullptr;  // the mesh's vertex normals at the corners (if any), written before Full
  DevBvh Reserved; // windingLater buffers
  std::size_t ClosedCap = 0, EdgeCap = 0;
  int* ReservedSlot = nullptr;
  GpuTri* ReservedCone = nullptr;
  WindingSigner::Cluster* ReservedClusters = nullptr;
  WeightedTri* ReservedDipoleTris = nullptr;
  DipoleNode* ReservedDipoleNodes = nullptr;
};

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
