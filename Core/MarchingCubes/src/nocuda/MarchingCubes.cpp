// CUDA marching cubes entry points for builds without CUDA (never reached:
// resolveDevice() never answers Cuda in such a build).
#include "../MarchingCubesImpl.h"

#include "lvdif/Error.h"

namespace lvdif
{
std::shared_ptr<MarchingCubesCudaState> makeMarchingCubesCudaState(const MarchingCubesTables&)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA");
}

ChunkMesh meshChunkCuda(const ChunkedMarchingCubes::Impl&, const ChunkedMarchingCubes::ChunkInput&)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA");
}
std::vector<ChunkMesh> meshChunksCuda(const ChunkedMarchingCubes::Impl&, const std::vector<std::int64_t>&, Interrupter&)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA");
}

void packChunksCuda(const ChunkedMarchingCubes::Impl&, const std::vector<std::int64_t>&, PackedChunkMeshes&, Interrupter&)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA");
}

std::shared_ptr<std::uint8_t> allocatePageLocked(std::size_t)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA (page-locked memory)");
}

void packChunksFromDeviceVolumeCuda(const ChunkedMarchingCubes::Impl&, const DeviceVolumeView&,
  const std::vector<std::int64_t>&, PackedChunkMeshes&)
{
  throw Error(ErrorCode::DeviceFailure, "marching cubes: this build has no CUDA");
}

void dropMarchingCubesCudaGrid(MarchingCubesCudaState&) {}
} // namespace lvdif
