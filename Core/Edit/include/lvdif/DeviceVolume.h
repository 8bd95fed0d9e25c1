// Device-resident editing: the CUDA brush of
// BrushCuda.h copies every touched chunk to the device and back per call, so
// a dab costs ~1.5 ms of transfers. A DeviceVolume instead mirrors the chunk
// table on the GPU once:
//   * expanded chunks live in a device pool of chunkEdge^3 slots (a fixed
//     capacity, bounded by Options::maxDeviceBytes and by free device memory,
//     checked before allocating);
//   * uniform chunks are only their value (kept on the host: the kernel gets
//     it with the launch), and get a slot the first time an edit reaches them
//     (freed again when the edit left them unchanged);
// and applies dabs entirely on the device with the same per-voxel rule and
// encoder as the CPU (BrushKernel.h; DeviceVolume.cu is compiled with
// --fmad=false like Brush.cu), so the bits are the CPU's.
//
// The host DictionaryVolume stays the reference for everything else (meshing,
// saving, undo): chunks changed on the device are *pending* until sync()
// writes their changed voxels back through DictionaryVolume::set (dirty
// flags, ranges, the ChunkWriteObserver's copy-on-write, collapse to uniform
// exactly as a CPU edit of those voxels). Call sync() before reading the host
// volume; after changing the host volume some other way (undo, a CPU edit,
// loading), call refresh() with the chunks it changed. sync() reports net
// changes: a voxel edited and edited back between two syncs is not written.
#pragma once

#include "lvdif/Brush.h"
#include "lvdif/Cuda.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace lvdif
{
namespace cuda
{

class DeviceVolume
{
public:
  struct Options
  {
    /// Device bytes the pool may use; 0 means half of the free device memory.
    std::uint64_t maxDeviceBytes = 0;
    /// Slots kept beyond the expanded chunks at upload, for chunks that edits
    /// expand (the pool is allocated once with expanded + headroom slots, at most the bound).
    std::uint64_t headroomSlots = 4096;
  };

  /// Uploads the volume's chunks. Error(Unsupported) without a CUDA device,
  /// Error(OutOfMemory) when the expanded chunks do not fit the bound.
  explicit DeviceVolume(DictionaryVolume& volume);
  DeviceVolume(DictionaryVolume& volume, const Options& options);
  ~DeviceVolume();
  DeviceVolume(const DeviceVolume&) = delete;
  DeviceVolume& operator=(const DeviceVolume&) = delete;

  DictionaryVolume& volume() { return this->Volume; }

  /// Applies the dabs on the device (lvdif::applyDabs's semantics and bits).
  /// The host voxels are not written: the changed chunks become pending.
  /// Error(OutOfMemory) (nothing changed) when the pool has too few free slots
  /// for the uniform chunks the dabs reach; Error(InvalidArgument) for bad dabs.
  EditResult applyDabs(const std::vector<Dab>& dabs, const BrushSettings& settings);

  /// Writes every pending chunk back to the host volume; returns the ids of the
  /// chunks whose voxels changed (increasing). The observer is told before the
  /// first write into each chunk (UndoStack snapshots it).
  EditResult sync(ChunkWriteObserver* observer = nullptr);

  /// Re-reads these chunks from the host after it changed them (Error
  /// InvalidArgument if one is pending: sync first).
  void refresh(const std::vector<std::int64_t>& ids);

  std::size_t pendingChunks() const;
  std::size_t slotsUsed() const;
  std::size_t slotCapacity() const;
  /// Device bytes held (pool and launch buffers).
  std::uint64_t deviceBytes() const;

  struct Impl;

private:
  DictionaryVolume& Volume;
  std::unique_ptr<Impl> P;
};

} // namespace cuda
} // namespace lvdif
