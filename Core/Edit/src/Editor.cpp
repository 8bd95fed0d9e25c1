#include "lvdif/Editor.h"

#include "lvdif/Error.h"

#include <algorithm>
#include <chrono>

namespace lvdif
{

namespace
{
void merge(EditResult& into, const EditResult& r)
{
  into.changedVoxels += r.changedVoxels;
  into.changedBox = into.changedBox.unite(r.changedBox);
  // per-chunk boxes survive only when both sides have them (or a side changed nothing)
  const bool boxes = (into.changedChunks.empty() || into.hasChunkBoxes()) && (r.changedChunks.empty() || r.hasChunkBoxes());
  std::vector<std::int64_t> all;
  std::vector<VoxelBox> allBoxes;
  std::size_t i = 0, j = 0;
  const std::size_t n = into.changedChunks.size(), m = r.changedChunks.size();
  while (i < n || j < m)
  {
    const bool takeA = j == m || (i < n && into.changedChunks[i] <= r.changedChunks[j]);
    const bool takeB = i == n || (j < m && r.changedChunks[j] <= into.changedChunks[i]);
    VoxelBox b;
    if (takeA)
    {
      all.push_back(into.changedChunks[i]);
      if (boxes && into.hasChunkBoxes())
        b = b.unite(into.changedChunkBoxes[i]);
      ++i;
    }
    if (takeB)
    {
      if (!takeA)
        all.push_back(r.changedChunks[j]);
      if (boxes && r.hasChunkBoxes())
        b = b.unite(r.changedChunkBoxes[j]);
      ++j;
    }
    if (boxes)
      allBoxes.push_back(b);
  }
  into.changedChunks.swap(all);
  into.changedChunkBoxes.swap(allBoxes);
}
} // namespace

namespace
{
// Pinch pulls toward the stroke's centre line: each dab gets the direction
// from the stroke's previous dab (the first one: toward the next; a lone dab
// keeps none and pulls radially).
void orientPinch(std::vector<Dab>& dabs, const Dab* previous)
{
  for (std::size_t i = 0; i < dabs.size(); ++i)
  {
    const Dab* from = i > 0 ? &dabs[i - 1] : previous;
    const Dab* to = &dabs[i];
    if (!from && dabs.size() > 1)
      from = &dabs[0], to = &dabs[1];
    if (from)
      for (int a = 0; a < 3; ++a)
        dabs[i].vec[a] = to->center[a] - from->center[a];
  }
}
} // namespace

Editor::Editor(DictionaryVolume& volume, const UndoStack::Options& undo)
  : Volume(volume)
  , Undo(volume, undo)
{
}

EditResult Editor::applyNow(const std::vector<Dab>& dabs)
{
  if (!this->Device)
    return lvdif::applyDabs(this->Volume, dabs, this->brush, &this->Undo, this->interrupter);
  if (!cuda::appliesOnDevice(this->brush))
  {
    // smooth, grab and pinch read neighbours, flatten and soft paint measure the host
    // volume: they run on the CPU, on the synced host copy, and the changed
    // storage chunks are handed to the device as part of its open step
    this->Device->sync();
    const EditResult r = lvdif::applyDabs(this->Volume, dabs, this->brush, nullptr, this->interrupter);
    this->Device->adoptHostChunks(r.changedChunks);
    return r;
  }
  return this->Device->applyDabs(dabs, this->brush);
}

void Editor::beginStep(const char* label)
{
  if (this->Device)
    this->Device->beginStep();
  else
    this->Undo.beginStep(label);
}

void Editor::endStep()
{
  if (this->Device)
    this->Device->endStep();
  else
    this->Undo.endStep();
}

void Editor::attachDevice(cuda::DeviceVolume* device)
{
  require(!this->Builder, "finish the open stroke first");
  require(!device || &device->volume() == &this->Volume, "the device volume mirrors another volume");
  this->Undo.clear();
  if (this->Device)
    this->Device->clearHistory();
  this->Device = device;
  if (this->Device)
    this->Device->clearHistory();
}

bool Editor::canUndo() const
{
  return this->Device ? this->Device->canUndo() : this->Undo.canUndo();
}

bool Editor::canRedo() const
{
  return this->Device ? this->Device->canRedo() : this->Undo.canRedo();
}

std::size_t Editor::undoCount() const
{
  return this->Device ? this->Device->undoCount() : this->Undo.undoCount();
}

void Editor::clearHistory()
{
  require(!this->Builder, "finish the open stroke first");
  this->Undo.clear();
  if (this->Device)
    this->Device->clearHistory();
}

void Editor::fillVolume(Voxel fill)
{
  require(!this->Builder, "finish the open stroke first");
  DictionaryVolume& v = this->Volume;
  std::vector<std::int64_t> all(static_cast<std::size_t>(v.chunkCount()));
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    v.fillChunk(id, fill);
    all[static_cast<std::size_t>(id)] = id;
  }
  this->Undo.clear(); // the history no longer matches the volume
  if (this->Device)
    this->Device->reload(); // drops the device's pending edits and history too
  this->touchStorageChunks(all);
  // recorded as the values, not the keys: a player's dictionaries may number them otherwise
  EditRecord e;
  e.type = EditRecord::Type::Fill;
  e.sdf = v.decode(fill.sdf);
  e.brush.color = v.colors().color(fill.color);
  this->record(e);
}

void Editor::record(const EditRecord& e)
{
  if (!this->Rec)
    return;
  EditRecord r = e;
  r.time = this->Time >= 0 ? this->Time : static_cast<double>(this->Rec->records.size());
  this->Rec->records.push_back(std::move(r));
}

void Editor::throwIfInterrupted(const EditResult& r)
{
  if (!r.interrupted)
    return;
  // a dab stopped part way: its written chunks are in the open undo step; they
  // are reported before the cancel propagates, so views re-mesh them
  this->touchStorageChunks(r.changedChunks);
  throw Error(ErrorCode::Cancelled, "operation cancelled");
}

EditResult Editor::applyChecked(const std::vector<Dab>& dabs)
{
  if (dabs.size() > this->limits.maxDabsPerEdit)
    throw Error(ErrorCode::InvalidArgument, "an edit of " + std::to_string(dabs.size()) +
        " dabs is more than the limit of " + std::to_string(this->limits.maxDabsPerEdit));
  if (this->DabsApplied + dabs.size() > this->limits.maxTotalDabs)
    throw Error(ErrorCode::InvalidArgument, "the edits would apply more than " +
        std::to_string(this->limits.maxTotalDabs) + " dabs in all (the editor's limit)");
  for (std::size_t i = 0; i < dabs.size(); ++i)
    validate(dabs[i], i);
  // the chunk-visit budget holds for the whole edit, not per batch
  requireChunkVisitBudget(this->Volume, dabs, this->brush);
  // Batches are bit-identical to one call (dabs apply per voxel in list order).
  // A batch ends after 4096 dabs or about 2^23 voxels of dab boxes, whichever
  // comes first, so a cancel is seen within a fraction of a second even for
  // large dabs (a radius-40 dab alone covers ~10^6 voxels).
  constexpr std::size_t MaxBatch = 4096;
  constexpr double MaxBatchVoxels = double(1 << 23);
  const double reach = this->brush.op == BrushOp::Paint
    ? 0.0
    : std::max<double>(this->Volume.bandWidth(), this->brush.colorOffset) + this->brush.blend;
  const double volumeVoxels =
    double(this->Volume.dims()[0]) * double(this->Volume.dims()[1]) * double(this->Volume.dims()[2]);
  auto batchEnd = [&](std::size_t at) {
    double work = 0;
    std::size_t end = at;
    while (end < dabs.size() && end - at < MaxBatch && (end == at || work < MaxBatchVoxels))
    {
      const double side = 2 * (std::max(0.0, dabs[end].radius) + reach) + 1;
      work += std::min(side * side * side, volumeVoxels);
      ++end;
    }
    return end;
  };
  if (batchEnd(0) == dabs.size())
  {
    if (this->interrupter)
      this->interrupter->checkInterrupt();
    EditResult r = this->applyNow(dabs);
    this->DabsApplied += dabs.size();
    this->throwIfInterrupted(r);
    return r;
  }
  EditResult all;
  for (std::size_t at = 0, end = 0; at < dabs.size(); at = end)
  {
    end = batchEnd(at);
    if (this->interrupter)
      this->interrupter->checkInterrupt();
    const std::vector<Dab> part(dabs.begin() + static_cast<std::ptrdiff_t>(at),
      dabs.begin() + static_cast<std::ptrdiff_t>(end));
    const EditResult r = this->applyNow(part);
    this->DabsApplied += part.size();
    this->touchStorageChunks(r.changedChunks); // a cancelled edit still reports what it changed
    merge(all, r);
    this->throwIfInterrupted(r);
  }
  return all;
}

EditResult Editor::applyDabs(const std::vector<Dab>& dabs, BrushKind kind)
{
  require(!this->Builder, "finish the open stroke first");
  this->beginStep(kind == BrushKind::Single ? "dab" : "stroke");
  EditResult r;
  this->LastWrite = EditResult();
  try
  {
    r = this->applyChecked(dabs);
  }
  catch (...)
  {
    this->endStep();
    throw;
  }
  this->touchStorageChunks(r.changedChunks);
  this->LastWrite = r;
  this->endStep();
  EditRecord e;
  e.brush = this->brush;
  e.kind = kind;
  e.spacing = this->stroke.spacing;
  e.dabs = dabs;
  this->record(e);
  return r;
}

EditResult Editor::dab(const Dab& d)
{
  return this->applyDabs(std::vector<Dab>{ d }, BrushKind::Single);
}

EditResult Editor::strokeThrough(const std::vector<BrushSample>& samples)
{
  std::vector<Dab> dabs = strokeDabs(samples, this->stroke, this->strokeBudget());
  if (this->brush.op == BrushOp::Pinch)
    orientPinch(dabs, nullptr);
  return this->applyDabs(dabs, this->stroke.kind);
}

std::uint64_t Editor::strokeBudget() const
{
  const std::uint64_t left = this->limits.maxTotalDabs - std::min(this->limits.maxTotalDabs, this->DabsApplied);
  return std::min(this->limits.maxDabsPerEdit, left);
}

void Editor::beginStroke()
{
  require(!this->Builder, "a stroke is already open");
  this->Builder = std::make_unique<StrokeBuilder>(this->stroke, this->strokeBudget());
  this->StrokeDabs.clear();
  this->StrokeResult = EditResult();
  this->GrabStarted = false;
  this->beginStep("stroke");
}

EditResult Editor::addSample(const BrushSample& s)
{
  require(this->Builder != nullptr, "no stroke is open");
  this->Builder->add(s);
  std::vector<Dab> ready = this->Builder->takeReady();
  if (this->brush.op == BrushOp::Grab)
  {
    ready.clear();
    if (this->GrabStarted && s.position != this->GrabFrom)
    {
      Dab d;
      d.center = this->GrabFrom;
      d.radius = this->stroke.radius;
      for (int a = 0; a < 3; ++a)
        d.vec[a] = s.position[a] - this->GrabFrom[a];
      ready.push_back(d);
    }
    this->GrabFrom = s.position;
    this->GrabStarted = true;
  }
  if (this->brush.op == BrushOp::Pinch)
    orientPinch(ready, this->StrokeDabs.empty() ? nullptr : &this->StrokeDabs.back());
  EditResult r;
  this->LastWrite = EditResult();
  if (!ready.empty())
  {
    r = this->applyChecked(ready);
    this->StrokeDabs.insert(this->StrokeDabs.end(), ready.begin(), ready.end());
    merge(this->StrokeResult, r);
    this->touchStorageChunks(r.changedChunks);
    this->LastWrite = r;
  }
  return r;
}

EditResult Editor::endStroke()
{
  require(this->Builder != nullptr, "no stroke is open");
  std::vector<Dab> rest = this->Builder->finish();
  if (this->brush.op == BrushOp::Grab)
    rest.clear(); // applied sample by sample
  if (this->brush.op == BrushOp::Pinch)
    orientPinch(rest, this->StrokeDabs.empty() ? nullptr : &this->StrokeDabs.back());
  EditResult r;
  this->LastWrite = EditResult();
  try
  {
    r = this->applyChecked(rest);
  }
  catch (...)
  {
    this->Builder.reset();
    this->endStep();
    throw;
  }
  this->StrokeDabs.insert(this->StrokeDabs.end(), rest.begin(), rest.end());
  merge(this->StrokeResult, r);
  this->touchStorageChunks(r.changedChunks);
  this->LastWrite = r;
  this->endStep();
  EditRecord e;
  e.brush = this->brush;
  e.kind = this->stroke.kind;
  e.spacing = this->stroke.spacing;
  e.dabs = this->StrokeDabs;
  this->record(e);
  this->Builder.reset();
  return this->StrokeResult;
}

std::size_t Editor::pump(InputDevice& device, std::size_t maxSamples, int timeoutMs, int maxMillis)
{
  std::size_t n = 0;
  BrushSample s;
  const auto t0 = std::chrono::steady_clock::now();
  while (n < maxSamples && device.poll(s, n == 0 ? timeoutMs : 0))
  {
    ++n;
    if (maxMillis >= 0 && std::chrono::steady_clock::now() - t0 > std::chrono::milliseconds(maxMillis))
      maxSamples = n; // this sample is the last of this call
    const bool down = (s.buttons & 1u) != 0;
    if (down && !this->Builder)
      this->beginStroke();
    if (this->Builder)
      this->addSample(s);
    if (!down && this->Builder)
      this->endStroke();
  }
  if (device.finished() && this->Builder)
    this->endStroke();
  return n;
}

bool Editor::undo()
{
  require(!this->Builder, "finish the open stroke first");
  const bool done = this->Device ? this->Device->undo() : this->Undo.undo();
  if (done)
  {
    this->touchStorageChunks(this->Device ? this->Device->lastRestoredChunks() : this->Undo.lastRestoredChunks());
    EditRecord e;
    e.type = EditRecord::Type::Undo;
    this->record(e);
  }
  return done;
}

bool Editor::redo()
{
  require(!this->Builder, "finish the open stroke first");
  const bool done = this->Device ? this->Device->redo() : this->Undo.redo();
  if (done)
  {
    this->touchStorageChunks(this->Device ? this->Device->lastRestoredChunks() : this->Undo.lastRestoredChunks());
    EditRecord e;
    e.type = EditRecord::Type::Redo;
    this->record(e);
  }
  return done;
}

void Editor::touchStorageChunks(const std::vector<std::int64_t>& ids)
{
  std::vector<std::int64_t> all;
  all.reserve(this->Touched.size() + ids.size());
  std::set_union(this->Touched.begin(), this->Touched.end(), ids.begin(), ids.end(), std::back_inserter(all));
  this->Touched.swap(all);
}

std::vector<std::int64_t> Editor::takeTouchedStorageChunks()
{
  std::vector<std::int64_t> out;
  out.swap(this->Touched);
  return out;
}

void Editor::startRecording()
{
  this->Rec = std::make_unique<Recording>();
  this->Rec->canvas = this->Volume.dims(); // so a player can refuse another canvas
}

Recording Editor::stopRecording()
{
  require(this->Rec != nullptr, "not recording");
  Recording r = std::move(*this->Rec);
  this->Rec.reset();
  return r;
}

void Editor::play(const Recording& r, Interrupter& interrupter, std::size_t* played)
{
  if (played)
    *played = 0;
  // positions are voxels of the recorded canvas: on another one the dabs land
  // elsewhere (or outside) and the model silently differs, so refuse up front
  const Index3& d = this->Volume.dims();
  if (r.canvas[0] > 0 && r.canvas != d)
    throw Error(ErrorCode::InvalidArgument,
      "the recording was made on a " + std::to_string(r.canvas[0]) + " x " + std::to_string(r.canvas[1]) + " x " +
        std::to_string(r.canvas[2]) + " canvas; this volume is " + std::to_string(d[0]) + " x " +
        std::to_string(d[1]) + " x " + std::to_string(d[2]) + " (nothing was played)");
  interrupter.start("play recording");
  const BrushSettings saved = this->brush;
  // long edits inside the recording check the same interrupter between batches
  struct Restore
  {
    Editor& E;
    Interrupter* Old;
    BrushSettings Brush;
    ~Restore()
    {
      this->E.interrupter = this->Old;
      this->E.brush = this->Brush;
    }
  } restore{ *this, this->interrupter, saved };
  this->interrupter = &interrupter;
  std::size_t i = 0;
  for (const EditRecord& e : r.records)
  {
    interrupter.checkInterrupt();
    if (e.type == EditRecord::Type::Undo || e.type == EditRecord::Type::Redo)
    {
      // The recorder writes only undos and redos that happened: one with nothing
      // to act on means another start (an undo of an edit made before the recording
      // began, another volume or history): going on would silently give another model.
      const bool undo = e.type == EditRecord::Type::Undo;
      if (!(undo ? this->undo() : this->redo()))
        throw Error(ErrorCode::InvalidArgument,
          "record " + std::to_string(i + 1) + " of " + std::to_string(r.records.size()) + " ('" +
            (undo ? "undo" : "redo") + "') has nothing to " + (undo ? "undo" : "redo") +
            ": the recording does not start from this volume and history, so it cannot be played back exactly");
    }
    else if (e.type == EditRecord::Type::Fill)
      this->fillVolume(Voxel{ this->Volume.encode(static_cast<float>(e.sdf)), this->Volume.colors().add(e.brush.color) });
    else
    {
      this->brush = e.brush;
      this->applyDabs(e.dabs, e.kind);
    }
    if (played)
      ++*played;
    interrupter.progress(static_cast<double>(++i) / static_cast<double>(std::max<std::size_t>(1, r.records.size())));
  }
  this->brush = saved;
  interrupter.end();
}

} // namespace lvdif
