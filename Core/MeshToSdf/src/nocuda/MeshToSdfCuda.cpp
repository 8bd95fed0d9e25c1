// Mesh to SDF CUDA entry points for builds without CUDA (never called:
// resolveDevice() returns Cpu there).
#include "../MeshToSdfCuda.h"

namespace lvdif
{
namespace detail::meshtosdf_cuda
{
std::unique_ptr<DeviceMesh> uploadMesh(
  const detail::meshtosdf::PreparedMesh&, const detail::meshtosdf::Bvh&, const detail::meshtosdf::WindingSigner*, bool, bool)
{
  throw Error(ErrorCode::Unsupported, "mesh to SDF: this build has no CUDA");
}

std::unique_ptr<Session> openSession(const DeviceMesh&, const GridGeometry&, const MeshToSdfOptions&, double, double,
  MeshToSdfStats&, std::function<void()>)
{
  throw Error(ErrorCode::Unsupported, "mesh to SDF: this build has no CUDA");
}

void failSharpRegionsOnDevice(bool) {}

std::vector<detail::meshtosdf::SharpVoxel> sharpRegionVoxelsOnDevice(const DeviceMesh&,
  const detail::meshtosdf::SharpFeatures&, const std::vector<detail::meshtosdf::SharpBrick>&, const GridGeometry&,
  const VoxelBox&, double, double)
{
  throw Error(ErrorCode::Unsupported, "mesh to SDF: this build has no CUDA");
}

KeyCopyCounts keyCopyCounts()
{
  return {};
}

void refusePinnedKeys(bool) {}

std::vector<detail::meshtosdf::LeafTri> meshLeavesOnDevice(const detail::meshtosdf::PreparedMesh&, const detail::meshtosdf::Bvh&)
{
  throw Error(ErrorCode::Unsupported, "mesh to SDF: this build has no CUDA");
}

std::vector<std::uint16_t> encodeOnDevice(const SdfDictionary::EncodeConstants&, float, const std::vector<float>&)
{
  throw Error(ErrorCode::Unsupported, "mesh to SDF: this build has no CUDA");
}
} // namespace detail::meshtosdf_cuda
} // namespace lvdif
