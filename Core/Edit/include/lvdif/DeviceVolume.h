// Device-resident editing: the CUDA brush of BrushCuda.h copies every touched
// chunk to the device and back per call (~1.5 ms of transfers a dab). A
// DeviceVolume instead mirrors the storage-chunk table on the GPU once:
//   * expanded storage chunks live in a device pool of chunkEdge^3 slots (a
//     fixed capacity, bounded by Options::maxDeviceBytes and by free device
//     memory, checked before allocating);
//   * uniform chunks are only their value, and get a slot the first time an
//     edit reaches them (freed again when the edit left them unchanged);
// and applies dabs entirely on the device with the same per-voxel rule and
// encoder as the CPU (BrushKernel.h; DeviceVolume.cu is compiled with
// --fmad=false like Brush.cu), so the bits are the CPU's.
//
// History on the device (copy on write): inside beginStep()/endStep() the
// first write into a storage chunk goes to a fresh slot and the old slot (or
// uniform value) becomes the step's snapshot, so undo and redo swap slot
// numbers and copy no voxels; the snapshots never leave the device. The
// history's slots count against Options::historyBytes (oldest steps dropped
// first, the newest minHistorySteps kept while the pool has room).
//
// The host DictionaryVolume is a lazily synced copy: chunks changed on the
// device (edits, undo, redo) are *pending* until sync() writes their changed
// voxels back through DictionaryVolume::set (dirty flags, ranges, collapse to
// uniform exactly as a CPU edit of those voxels). Call sync() before reading
// the host volume (saving, CPU-only consumers); after changing the host volume
// some other way, call refresh() with the chunks it changed, or reload().
// view() hands the resident volume to other device code (marching cubes).
#pragma once

#include "lvdif/Brush.h"
#include "lvdif/Cuda.h"
#include "lvdif/DeviceVolumeView.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace lvdif
{
namespace cuda
{

/// Whether DeviceVolume::applyDabs takes this brush. Smooth, Grab and Pinch read
/// neighbouring voxels; Flatten measures its plane and soft paint its colours
/// on the host volume: those run on the synced host copy (Editor does this).
inline bool appliesOnDevice(const BrushSettings& s)
{
  if (readsNeighbours(s.op) || s.op == BrushOp::Flatten)
    return false;
  return !(s.op == BrushOp::Paint && !(s.strength == 1 && s.falloff == Falloff::Constant));
}

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
    /// Device bytes the undo/redo history may hold (its slots are reserved in the pool on top).
    std::uint64_t historyBytes = 256ull << 20;
    /// Steps kept even past historyBytes while the pool has free slots.
    std::size_t minHistorySteps = 1;
  };

  /// Uploads the volume's chunks. Error(Unsupported) without a CUDA device,
  /// Error(OutOfMemory) when the expanded chunks do not fit the bound.
  explicit DeviceVolume(DictionaryVolume& volume);
  DeviceVolume(DictionaryVolume& volume, const Options& options);
  ~DeviceVolume();
  DeviceVolume(const DeviceVolume&) = delete;
  DeviceVolume& operator=(const DeviceVolume&) = delete;

  DictionaryVolume& volume() { return this->Volume; }

  /// Applies the dabs on the device (lvdif::applyDabs's semantics and bits;
  /// changedBox is the exact bounding box of the changed voxels). The host
  /// voxels are not written: the changed chunks become pending. Error(OutOfMemory)
  /// (nothing changed) when the pool has too few free slots even after dropping
  /// old history; Error(InvalidArgument) for bad dabs.
  EditResult applyDabs(const std::vector<Dab>& dabs, const BrushSettings& settings);

  // ---- history (copy on write in the pool) ----------------------------------
  /// Opens a step (Error InvalidArgument if one is open).
  void beginStep();
  /// Closes the step; a step that changed nothing is discarded (false).
  bool endStep();
  bool inStep() const;
  bool canUndo() const;
  bool canRedo() const;
  std::size_t undoCount() const;
  std::size_t redoCount() const;
  /// Swaps the newest step's snapshots in; false if none (refused inside a step).
  bool undo();
  bool redo();
  /// Storage chunks the last undo()/redo() restored, increasing.
  const std::vector<std::int64_t>& lastRestoredChunks() const;
  void clearHistory();
  /// Device bytes held by the history's snapshots.
  std::uint64_t historyDeviceBytes() const;

  /// The resident volume for other device code (tables uploaded if they changed).
  DeviceVolumeView view();

  /// Writes every pending chunk back to the host volume; returns the ids of the
  /// chunks whose voxels changed (increasing). The observer is told before the
  /// first write into each chunk (UndoStack snapshots it).
  EditResult sync(ChunkWriteObserver* observer = nullptr);

  /// Re-reads these chunks from the host after it changed them (Error
  /// InvalidArgument if one is pending: sync first).
  void refresh(const std::vector<std::int64_t>& ids);
  /// Takes these chunks from the host after a host-side edit (Smooth, Grab) of
  /// the synced volume: inside a step, copy on write (the device's state is the
  /// snapshot). The chunks must not be pending.
  void adoptHostChunks(const std::vector<std::int64_t>& ids);
  /// Drops pending device changes and the history and re-reads every chunk
  /// from the host (after the host volume was rewritten as a whole).
  void reload();

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
