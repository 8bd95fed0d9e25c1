// Sign voxel filter CUDA entry points for builds without CUDA (never called:
// the dispatcher only picks CUDA when lvdif::cuda::available()).
#include "../SignVoxelFilterImpl.h"

#include "lvdif/Error.h"

namespace lvdif
{
namespace detail::svf
{
std::uint64_t signVoxelFilterCudaBytes(const GridGeometry&)
{
  return 0;
}

SignVoxelFilterStats signVoxelFilterCuda(const FloatGridView&, const SvfSetup&, Interrupter&)
{
  throw Error(ErrorCode::Unsupported, "signVoxelFilter: this build has no CUDA");
}
} // namespace detail::svf
} // namespace lvdif
