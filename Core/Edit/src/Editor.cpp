#include "lvdif/Editor.h"

#include "lvdif/Error.h"

#include <algorithm>

namespace lvdif
{

namespace
{
void merge(EditResult& into, const EditResult& r)
{
  into.changedVoxels += r.changedVoxels;
  into.changedBox = into.changedBox.unite(r.changedBox);
  std::vector<std::int64_t> all;
  std::set_union(into.changedChunks.begin(), into.changedChunks.end(), r.changedChunks.begin(),
    r.changedChunks.end(), std::back_inserter(all));
  into.changedChunks.swap(all);
}
} // namespace

Editor::Editor(DictionaryVolume& volume, const UndoStack::Options& undo)
  : Volume(volume)
  , Undo(volume, undo)
{
}

EditResult Editor::applyNow(const std::vector<Dab>& dabs)
{
  return this->Device ? this->Device->applyDabs(dabs, this->brush)
                      : lvdif::applyDabs(this->Volume, dabs, this->brush, &this->Undo);
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
}

void Editor::record(const EditRecord& e)
{
  if (!this->Rec)
    return;
  EditRecord r = e;
  r.time = this->Time >= 0 ? this->Time : static_cast<double>(this->Rec->records.size());
  this->Rec->records.push_back(std::move(r));
}

EditResult Editor::applyDabs(const std::vector<Dab>& dabs, BrushKind kind)
{
  require(!this->Builder, "finish the open stroke first");
  this->beginStep(kind == BrushKind::Single ? "dab" : "stroke");
  EditResult r;
  this->LastWrite = EditResult();
  try
  {
    r = this->applyNow(dabs);
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
  return this->applyDabs(strokeDabs(samples, this->stroke), this->stroke.kind);
}

void Editor::beginStroke()
{
  require(!this->Builder, "a stroke is already open");
  this->Builder = std::make_unique<StrokeBuilder>(this->stroke);
  this->StrokeDabs.clear();
  this->StrokeResult = EditResult();
  this->beginStep("stroke");
}

EditResult Editor::addSample(const BrushSample& s)
{
  require(this->Builder != nullptr, "no stroke is open");
  this->Builder->add(s);
  const std::vector<Dab> ready = this->Builder->takeReady();
  EditResult r;
  this->LastWrite = EditResult();
  if (!ready.empty())
  {
    r = this->applyNow(ready);
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
  const std::vector<Dab> rest = this->Builder->finish();
  EditResult r;
  this->LastWrite = EditResult();
  try
  {
    r = this->applyNow(rest);
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

std::size_t Editor::pump(InputDevice& device, std::size_t maxSamples, int timeoutMs)
{
  std::size_t n = 0;
  BrushSample s;
  while (n < maxSamples && device.poll(s, n == 0 ? timeoutMs : 0))
  {
    ++n;
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
}

Recording Editor::stopRecording()
{
  require(this->Rec != nullptr, "not recording");
  Recording r = std::move(*this->Rec);
  this->Rec.reset();
  return r;
}

void Editor::play(const Recording& r, Interrupter& interrupter)
{
  interrupter.start("play recording");
  const BrushSettings saved = this->brush;
  std::size_t i = 0;
  for (const EditRecord& e : r.records)
  {
    interrupter.checkInterrupt();
    if (e.type == EditRecord::Type::Undo)
      this->undo();
    else if (e.type == EditRecord::Type::Redo)
      this->redo();
    else
    {
      this->brush = e.brush;
      this->applyDabs(e.dabs, e.kind);
    }
    interrupter.progress(static_cast<double>(++i) / static_cast<double>(std::max<std::size_t>(1, r.records.size())));
  }
  this->brush = saved;
  interrupter.end();
}

} // namespace lvdif
