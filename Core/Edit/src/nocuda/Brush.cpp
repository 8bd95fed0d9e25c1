// Stub of the CUDA brush entry point for builds without CUDA (never reached:
// callers go through resolveDevice, which falls back to the CPU).
#include "lvdif/BrushCuda.h"

#include "lvdif/Error.h"

namespace lvdif
{
namespace cuda
{
EditResult applyDabs(DictionaryVolume&, const std::vector<Dab>&, const BrushSettings&, ChunkWriteObserver*)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA brush kernels");
}
} // namespace cuda
} // namespace lvdif
