// DeviceVolume for builds without CUDA: construction refuses with Error(Unsupported).
#include "lvdif/DeviceVolume.h"

#include "lvdif/Error.h"

namespace lvdif
{
namespace cuda
{
struct DeviceVolume::Impl
{
};

DeviceVolume::DeviceVolume(DictionaryVolume& volume)
  : DeviceVolume(volume, Options())
{
}

DeviceVolume::DeviceVolume(DictionaryVolume& volume, const Options&)
  : Volume(volume)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA: no device-resident volume");
}

DeviceVolume::~DeviceVolume() = default;

EditResult DeviceVolume::applyDabs(const std::vector<Dab>&, const BrushSettings&)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

EditResult DeviceVolume::sync(ChunkWriteObserver*)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

void DeviceVolume::refresh(const std::vector<std::int64_t>&)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

void DeviceVolume::adoptHostChunks(const std::vector<std::int64_t>&)
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

void DeviceVolume::reload()
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

void DeviceVolume::beginStep()
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

bool DeviceVolume::endStep() { return false; }
bool DeviceVolume::inStep() const { return false; }
bool DeviceVolume::canUndo() const { return false; }
bool DeviceVolume::canRedo() const { return false; }
std::size_t DeviceVolume::undoCount() const { return 0; }
std::size_t DeviceVolume::redoCount() const { return 0; }
bool DeviceVolume::undo() { return false; }
bool DeviceVolume::redo() { return false; }
void DeviceVolume::clearHistory() {}
std::uint64_t DeviceVolume::historyDeviceBytes() const { return 0; }

const std::vector<std::int64_t>& DeviceVolume::lastRestoredChunks() const
{
  static const std::vector<std::int64_t> none;
  return none;
}

DeviceVolumeView DeviceVolume::view()
{
  throw Error(ErrorCode::Unsupported, "this build has no CUDA");
}

std::size_t DeviceVolume::pendingChunks() const { return 0; }
std::size_t DeviceVolume::slotsUsed() const { return 0; }
std::size_t DeviceVolume::slotCapacity() const { return 0; }
std::uint64_t DeviceVolume::deviceBytes() const { return 0; }

} // namespace cuda
} // namespace lvdif
