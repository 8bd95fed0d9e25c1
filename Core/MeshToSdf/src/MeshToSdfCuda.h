// CUDA entry points of mesh to SDF (MeshToSdfCuda.cu; stubs in
// nocuda/MeshToSdfCuda.cpp). Called only when resolveDevice() chose CUDA.
#pragma once

#include "MeshToSdfInternal.h"
#include "MeshToSdfSharpFeatures.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/SdfDictionary.h"

#include <functional>
#include <memory>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
/// The mesh and its BVH (and, when uploaded with a winding signer, the
/// closed chain's BVH, cone and clusters) on the GPU; freed on destruction.
/// Owned by MeshToSdfPrepared::Impl, so it lives as long as the prepared mesh.
class DeviceMesh
{
public:
  virtual ~DeviceMesh() = default;
  /// The winding structures of M as given, or of M+ (reoriented:
  /// MeshToSdfOptions::reorientFaces); a copy may hold both.
  virtual bool hasWinding(bool reoriented) const = 0;
  virtual std::uint64_t bytes() const = 0;
  /// Uploads one variant of the winding structures to a copy made without it
  /// (called once per variant, under the prepared mesh's lock). reoriented
  /// requires winding.gpuTakesCpuClosure(true).
  virtual void addWinding(const detail::meshtosdf::WindingSigner& winding, bool reoriented) = 0;
  /// The full triangle records (normals), which only the Normal and
  /// PseudoNormal modes read: uploaded on first need, like addWinding.
  virtual bool hasNormals() const = 0;
  virtual void addNormals() = 0;
};

/// windingLater (winding null): reserve device memory for an addWinding to come.
std::unique_ptr<DeviceMesh> uploadMesh(const detail::meshtosdf::PreparedMesh& mesh, const detail::meshtosdf::Bvh& bvh,
  const detail::meshtosdf::WindingSigner* winding, bool normals, bool windingLater);

/// The chunks of one group of chunk layers, encoded on the GPU.
struct ChunkKeys
{
  static constexpr std::uint32_t NotUniform = 0xffffffffu;
  std::vector<std::uint32_t> uniform; // per chunk (cx + ccx * (cy + ccy * czLocal)): its key or NotUniform
  std::vector<std::int64_t> listed;   // the NotUniform chunks, in order (their keys: Session::takeKeys)
  std::vector<float> floats;          // options.cudaVerifyKeys: the slab's floats (box layout)
};

/// takeKeys' callback: listed chunks [first, last), chunk i's chunkEdge^3 keys
/// at keys + (i - first) * chunkEdge^3 (localIndex layout; outside the grid:
/// junk). The keys are valid during the call only.
using KeyPieceFn = std::function<void(std::size_t first, std::size_t last, const std::uint16_t* keys)>;

/// compute() fills any extent of the grid with the same contract as the CPU
/// path (distances and signs in output units, band-saturated), one slab of z
/// layers at a time so device memory stays bounded. Always uses the BVH (the
/// accelerators give the same distances). launchKeys/fetchKeys/takeKeys: the
/// dictionary-volume path, where the chunks are encoded on the GPU and only
/// their keys come back, while the GPU computes the next group.
class Session
{
public:
  virtual ~Session() = default;
  virtual void compute(const VoxelBox& extent, float* out, MeshToSdfStats& stats, Interrupter& interrupter) = 0;
  /// Queues (does not wait for) the kernels of `box`: whole chunk layers
  /// over the full x and y extent of the grid, chunks of `edge` voxels.
  virtual void launchKeys(const VoxelBox& box, int edge, const SdfDictionary::EncodeConstants& encode, float band,
    MeshToSdfStats& stats) = 0;
  /// Waits for the last launchKeys, lists its uniform and non-uniform chunks
  /// into `out`, queues the keys of the non-uniform ones and starts copying
  /// them back (the next launchKeys may follow at once). Their keys come
  /// through takeKeys, which must be called before the next fetchKeys.
  virtual void fetchKeys(ChunkKeys& out, MeshToSdfStats& stats) = 0;
  /// The keys of the last fetchKeys' listed chunks, in order, a piece at a
  /// time (MeshToSdfOptions::cudaKeyPieceBytes) through pinned host memory:
  /// `store` runs on piece k while piece k + 1 is copied. Returns the seconds
  /// spent waiting for copies.
  virtual double takeKeys(const KeyPieceFn& store) = 0;
};
/// ensureWinding: when the sign mode is WindingNumber and `mesh` has no
/// winding structures yet, called right after the first distance kernel is
/// queued (so the host builds and uploads them while the GPU computes
/// distances); it must leave them on `mesh`.
std::unique_ptr<Session> openSession(const DeviceMesh& mesh, const GridGeometry& grid,
  const MeshToSdfOptions& options, double toOut, double band, MeshToSdfStats& stats,
  std::function<void()> ensureWinding);

/// Step 2 of the sharp features' regions (meshtosdf::sharpRegionVoxels' twin:
/// the same voxels and floats; ordered by brick, then voxel) on the GPU, on a stream of
/// its own and stream-ordered memory, so that it runs beside a session's
/// kernels without waiting for them (MeshToSdfCudaSharp.cu).
std::vector<detail::meshtosdf::SharpVoxel> sharpRegionVoxelsOnDevice(const DeviceMesh& mesh,
  const detail::meshtosdf::SharpFeatures& sharp, const std::vector<detail::meshtosdf::SharpBrick>& bricks,
  const GridGeometry& grid, const VoxelBox& extent, double toOut, double band);

/// Tests: the pieces the keys came back in since the process started, and
/// how many of them through pageable memory (pinned memory was refused).
struct KeyCopyCounts
{
  std::int64_t pieces = 0, pageable = 0;
};
KeyCopyCounts keyCopyCounts();
/// Tests: true makes the sessions opened afterwards take the pageable
/// fallback, as if pinned host memory were refused.
void refusePinnedKeys(bool refuse);

/// Tests: true makes sharpRegionVoxelsOnDevice fail (a DeviceFailure, as
/// a CUDA call that failed), so that the CPU's fallback can be tested.
void failSharpRegionsOnDevice(bool fail);

/// Tests: the mesh tree's leaf copies as the device copy gathers them from
/// the welded mesh (they must equal leafCopies(bvh)).
std::vector<detail::meshtosdf::LeafTri> meshLeavesOnDevice(
  const detail::meshtosdf::PreparedMesh& mesh, const detail::meshtosdf::Bvh& bvh);

/// Tests: SdfDictionary::encodeWith (band-clamped as DictionaryVolume::encode) run on the GPU.
std::vector<std::uint16_t> encodeOnDevice(
  const SdfDictionary::EncodeConstants& encode, float band, const std::vector<float>& values);
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
