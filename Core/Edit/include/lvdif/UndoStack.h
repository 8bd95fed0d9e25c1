// Undo/redo of whole strokes, storing only the chunks a stroke touched.
//
// Copy-on-write: the undo stack observes the brush (ChunkWriteObserver); before
// the first write into a chunk during a step it snapshots that chunk (its
// uniform value, or a copy of its chunkEdge^3 voxels). Undo swaps the stored
// chunks with the volume's (so the same step can be redone), marking them
// dirty. Volumes restored this way are bit-identical to the volume before the
// step (every voxel; the colour dictionary only grows, keys stay valid).
//
// Memory: each step costs ~16 bytes per uniform chunk and chunkEdge^3 * 4
// bytes per expanded chunk it touched (128 KiB at edge 32), independent of
// the volume's size. A radius-15 dab on a surface touches at most 27 chunks of
// edge 32 (its 46-voxel influence box), typically 8..12 expanded ones, so
// ~1.5 MiB; 100 such strokes fit the default 256 MiB cap at 1024^3 (the test
// measures the per-dab cost at a smaller size; it does not depend on the size).
// When the total exceeds maxBytes the oldest steps are dropped first, but the
// newest minSteps steps are kept as long as they fit the process memory limit.
#pragma once

#include "lvdif/Brush.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_set>
#include <vector>

namespace lvdif
{

class UndoStack : public ChunkWriteObserver
{
public:
  struct Options
  {
    std::uint64_t maxBytes = 256ull << 20;
    std::size_t minSteps = 1;
  };

  explicit UndoStack(DictionaryVolume& volume);
  UndoStack(DictionaryVolume& volume, const Options& options);

  /// Starts a step (a stroke); Error(InvalidArgument) if one is open.
  void beginStep(const std::string& label);
  /// Closes the step. A step that touched nothing is discarded (returns false);
  /// otherwise the redo steps are dropped and the cap enforced.
  bool endStep();
  bool inStep() const { return this->Open != nullptr; }

  /// Snapshots the chunk on its first write in the open step (thread-safe).
  void beforeChunkWrite(const DictionaryVolume& volume, std::int64_t chunkId) override;

  bool canUndo() const { return !this->Undo.empty(); }
  bool canRedo() const { return !this->Redo.empty(); }
  /// Reverts the newest step; false if there is none. Refused while a step is open.
  bool undo();
  bool redo();
  std::size_t undoCount() const { return this->Undo.size(); }
  std::size_t redoCount() const { return this->Redo.size(); }
  std::string undoLabel() const { return this->Undo.empty() ? std::string() : this->Undo.back()->Label; }
  /// Bytes held by all undo and redo steps.
  std::uint64_t bytes() const { return this->Bytes; }
  /// The chunk ids restored by the last undo() or redo(), increasing.
  const std::vector<std::int64_t>& lastRestoredChunks() const { return this->LastRestored; }
  const Options& options() const { return this->Opts; }
  void clear();

private:
  struct Snapshot
  {
    std::int64_t Id = 0;
    Voxel Value;                    // when uniform
    std::unique_ptr<Voxel[]> Data;  // when expanded
  };
  struct Step
  {
    std::string Label;
    std::vector<Snapshot> Chunks;
    std::uint64_t Bytes = 0;
  };

  Snapshot capture(std::int64_t id) const;
  void swapIn(Step& step);
  void enforceCap();
  std::uint64_t snapshotBytes(const Snapshot& s) const;

  DictionaryVolume& Volume;
  Options Opts;
  std::deque<std::unique_ptr<Step>> Undo, Redo;
  std::unique_ptr<Step> Open;
  std::unordered_set<std::int64_t> OpenIds;
  std::mutex Mutex;
  std::uint64_t Bytes = 0;
  std::vector<std::int64_t> LastRestored;
};

} // namespace lvdif
