#include "lvdif/UndoStack.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cstring>

namespace lvdif
{

UndoStack::UndoStack(DictionaryVolume& volume)
  : UndoStack(volume, Options())
{
}

UndoStack::UndoStack(DictionaryVolume& volume, const Options& options)
  : Volume(volume)
  , Opts(options)
{
}

std::uint64_t UndoStack::snapshotBytes(const Snapshot& s) const
{
  const std::uint64_t e = static_cast<std::uint64_t>(this->Volume.chunkEdge());
  return sizeof(Snapshot) + (s.Data ? e * e * e * sizeof(Voxel) : 0);
}

void UndoStack::beginStep(const std::string& label)
{
  require(!this->Open, "an undo step is already open");
  this->Open = std::make_unique<Step>();
  this->Open->Label = label;
  this->OpenIds.clear();
}

UndoStack::Snapshot UndoStack::capture(std::int64_t id) const
{
  Snapshot s;
  s.Id = id;
  if (const Voxel* d = this->Volume.chunkData(id))
  {
    const std::size_t n = static_cast<std::size_t>(this->Volume.chunkEdge()) * this->Volume.chunkEdge() *
      this->Volume.chunkEdge();
    s.Data.reset(new Voxel[n]);
    std::memcpy(s.Data.get(), d, n * sizeof(Voxel));
  }
  else
  {
    s.Value = this->Volume.uniformValue(id);
  }
  return s;
}

void UndoStack::beforeChunkWrite(const DictionaryVolume& volume, std::int64_t chunkId)
{
  if (&volume != &this->Volume)
    return;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (!this->Open || !this->OpenIds.insert(chunkId).second)
      return;
  }
  // the calling thread owns this chunk during the edit: copy outside the lock
  Snapshot s = this->capture(chunkId);
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Open->Bytes += this->snapshotBytes(s);
  this->Open->Chunks.push_back(std::move(s));
}

bool UndoStack::endStep()
{
  require(this->Open != nullptr, "no undo step is open");
  std::unique_ptr<Step> step = std::move(this->Open);
  this->OpenIds.clear();
  if (step->Chunks.empty())
    return false;
  for (auto& r : this->Redo)
    this->Bytes -= r->Bytes;
  this->Redo.clear();
  this->Bytes += step->Bytes;
  this->Undo.push_back(std::move(step));
  this->enforceCap();
  return true;
}

void UndoStack::enforceCap()
{
  const std::uint64_t hard = memoryLimitBytes();
  while (!this->Undo.empty())
  {
    const bool overCap = this->Bytes > this->Opts.maxBytes && this->Undo.size() > this->Opts.minSteps;
    const bool overMemory = this->Bytes > hard && this->Undo.size() > 1;
    if (!overCap && !overMemory)
      break;
    this->Bytes -= this->Undo.front()->Bytes;
    this->Undo.pop_front();
  }
}

// Exchanges the volume's chunks with the step's snapshots.
void UndoStack::swapIn(Step& step)
{
  const std::size_t n = static_cast<std::size_t>(this->Volume.chunkEdge()) * this->Volume.chunkEdge() *
    this->Volume.chunkEdge();
  std::uint64_t bytes = 0;
  this->LastRestored.clear();
  for (Snapshot& s : step.Chunks)
  {
    this->LastRestored.push_back(s.Id);
    Snapshot now = this->capture(s.Id);
    if (s.Data)
    {
      // fillChunk marks the range stale and the chunk dirty; then the data is copied back
      this->Volume.fillChunk(s.Id, s.Data[0]);
      Voxel* d = this->Volume.expandChunk(s.Id);
      std::memcpy(d, s.Data.get(), n * sizeof(Voxel));
    }
    else
    {
      this->Volume.fillChunk(s.Id, s.Value);
    }
    s = std::move(now);
    bytes += this->snapshotBytes(s);
  }
  this->Bytes = this->Bytes - step.Bytes + bytes;
  step.Bytes = bytes;
  std::sort(this->LastRestored.begin(), this->LastRestored.end());
}

bool UndoStack::undo()
{
  require(!this->Open, "cannot undo while a step is open");
  if (this->Undo.empty())
    return false;
  std::unique_ptr<Step> step = std::move(this->Undo.back());
  this->Undo.pop_back();
  this->swapIn(*step);
  this->Redo.push_back(std::move(step));
  return true;
}

bool UndoStack::redo()
{
  require(!this->Open, "cannot redo while a step is open");
  if (this->Redo.empty())
    return false;
  std::unique_ptr<Step> step = std::move(this->Redo.back());
  this->Redo.pop_back();
  this->swapIn(*step);
  this->Undo.push_back(std::move(step));
  this->enforceCap();
  return true;
}

void UndoStack::clear()
{
  this->Undo.clear();
  this->Redo.clear();
  this->Open.reset();
  this->OpenIds.clear();
  this->Bytes = 0;
}

} // namespace lvdif
