#include "lvdif/EditSession.h"

#include "lvdif/Error.h"
#include "lvdif/MarchingCubesWorker.h"

#include <algorithm>
#include <exception>
#include <iterator>
#include <mutex>

namespace lvdif
{

namespace
{
void uniteSorted(std::vector<std::int64_t>& into, const std::vector<std::int64_t>& ids)
{
  std::vector<std::int64_t> all;
  all.reserve(into.size() + ids.size());
  std::set_union(into.begin(), into.end(), ids.begin(), ids.end(), std::back_inserter(all));
  into.swap(all);
}
} // namespace

std::vector<std::int64_t> meshChunksToRemesh(const ChunkedMarchingCubes& mc,
  const std::vector<std::int64_t>& dirtyStorageChunks, const EditResult& edit)
{
  std::vector<std::int64_t> foreign;
  std::set_difference(dirtyStorageChunks.begin(), dirtyStorageChunks.end(), edit.changedChunks.begin(),
    edit.changedChunks.end(), std::back_inserter(foreign));
  std::vector<std::int64_t> ids;
  if (edit.hasChunkBoxes())
  {
    // the union of each changed storage chunk's own box: a moving dab's crescent
    // meets far fewer mesh chunks than its bounding box does
    for (const VoxelBox& b : edit.changedChunkBoxes)
    {
      const std::vector<std::int64_t> more = mc.chunksAffectedBy(b);
      ids.insert(ids.end(), more.begin(), more.end());
    }
  }
  else if (!edit.changedBox.empty())
    ids = mc.chunksAffectedBy(edit.changedBox);
  if (!foreign.empty())
  {
    const std::vector<std::int64_t> more = mc.chunksAffectedByStorageChunks(foreign);
    ids.insert(ids.end(), more.begin(), more.end());
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

EditSession::EditSession(std::shared_ptr<DictionaryVolume> volume, const EditSessionOptions& options)
  : Opts(options)
{
  require(volume != nullptr, "an edit session needs a volume");
  this->build(std::move(volume), nullptr, nullptr);
}

EditSession::~EditSession()
{
  this->teardown();
}

void EditSession::teardown()
{
  // the worker reads through the mesher, which reads the volume; the editor may point at the device volume
  this->Worker.reset();
  this->Mesher.reset();
  this->Ed.reset();
  this->Dev.reset();
  this->DeviceQueue.clear();
  this->Held.clear(); // a new volume is meshed whole
  this->CoarseMark.clear();
  this->CoarseCount = 0;
  this->Refine.clear();
}

void EditSession::build(std::shared_ptr<DictionaryVolume> volume, const BrushSettings* brush, const StrokeSettings* stroke)
{
  // before the teardown: a refused volume leaves the session as it was
  DictionaryVolume::requireCanvasDimensions(volume->dims());
  this->teardown();
  this->Vol = std::move(volume);
  ++this->Generation;
  const bool wantGpu = this->Opts.device != Device::Cpu;
  this->Notice.clear();
  if (wantGpu)
  {
    // the options' own request: Auto in a build without CUDA stays quiet, and
    // the process's one fallback notice is resolveDevice's (notice() still says why)
    if (resolveDevice(this->Opts.device) != Device::Cuda)
      this->Notice = cuda::compiled() ? "no usable CUDA device: editing and meshing run on the CPU"
                                      : "this build has no CUDA: editing and meshing run on the CPU";
    else
    {
      try
      {
        cuda::DeviceVolume::Options o;
        o.maxDeviceBytes = this->Opts.maxDeviceBytes;
        o.historyBytes = this->Opts.undo.maxBytes;
        o.minHistorySteps = this->Opts.undo.minSteps;
        this->Dev = std::make_unique<cuda::DeviceVolume>(*this->Vol, o);
      }
      catch (const Error& e)
      {
        this->Notice = std::string("the volume stays on the host (") + e.what() + "): editing and meshing run on the CPU";
        this->Dev.reset();
      }
    }
  }
  this->Ed = std::make_unique<Editor>(*this->Vol, this->Opts.undo);
  if (brush)
    this->Ed->brush = *brush;
  if (stroke)
    this->Ed->stroke = *stroke;
  if (this->Dev)
    this->Ed->attachDevice(this->Dev.get());
  MarchingCubesOptions mo = this->Opts.meshOptions;
  mo.chunkEdge = this->Opts.meshChunkEdge > 0 ? this->Opts.meshChunkEdge : std::max(16, this->Vol->chunkEdge());
  // the mesher runs on the GPU only when the volume does (it then reads the device volume)
  mo.device = this->Dev && this->Opts.meshing ? Device::Cuda : Device::Cpu;
  this->Mesher = std::make_unique<ChunkedMarchingCubes>(*this->Vol, mo);
  if (this->Opts.meshing && !this->Dev)
  {
    this->Worker = std::make_unique<MarchingCubesWorker>(*this->Mesher);
    this->CoarseMark.assign(static_cast<std::size_t>(this->Mesher->chunkCount()), 0);
  }
  this->Vol->takeDirtyChunks();
  // every mesh chunk changed (consumers drop what they had)
  std::vector<std::int64_t> all(static_cast<std::size_t>(this->Mesher->chunkCount()));
  for (std::size_t i = 0; i < all.size(); ++i)
    all[i] = static_cast<std::int64_t>(i);
  this->Changed.swap(all);
  this->LastRequest.clear();
  ++this->Changes;
}

void EditSession::setVolume(std::shared_ptr<DictionaryVolume> volume)
{
  require(volume != nullptr, "an edit session needs a volume");
  const BrushSettings b = this->Ed->brush;
  const StrokeSettings s = this->Ed->stroke;
  this->build(std::move(volume), &b, &s);
}

std::unique_lock<std::mutex> EditSession::lockSource()
{
  return this->Worker ? std::unique_lock<std::mutex>(this->Worker->sourceMutex()) : std::unique_lock<std::mutex>();
}

void EditSession::sync()
{
  if (!this->Dev)
    return;
  this->Dev->sync();
  // the meshes already show these chunks (meshed from the device): not dirty for meshing
  this->Vol->takeDirtyChunks();
}

std::size_t EditSession::pendingStorageChunks() const
{
  return this->Dev ? this->Dev->pendingChunks() : 0;
}

DictionaryVolume& EditSession::volume()
{
  this->sync();
  return *this->Vol;
}

std::shared_ptr<DictionaryVolume> EditSession::sharedVolume()
{
  this->sync();
  return this->Vol;
}

void EditSession::request(const std::vector<std::int64_t>& ids)
{
  this->LastRequest = ids;
  this->LastRequestAt = Clock::now();
  if (ids.empty())
    return;
  uniteSorted(this->Changed, ids);
  if (!this->Opts.meshing)
    return;
  if (!this->Worker)
    uniteSorted(this->DeviceQueue, ids);
  else if (this->Holding)
    uniteSorted(this->Held, ids);
  else
    this->toWorker(ids);
}

void EditSession::toWorker(const std::vector<std::int64_t>& ids)
{
  const int level = this->CoarseMin > 0 && ids.size() >= this->CoarseMin ? 1 : 0;
  for (std::int64_t id : ids)
  {
    char& m = this->CoarseMark[static_cast<std::size_t>(id)];
    this->CoarseCount += static_cast<std::size_t>(level) - static_cast<std::size_t>(m);
    m = static_cast<char>(level);
  }
  this->Worker->request(ids, level);
}

void EditSession::setCoarseMeshing(std::size_t minChunks)
{
  if (minChunks > 0)
    this->startRefine(); // a new stroke: the last one's refinement first
  this->CoarseMin = minChunks;
}

std::size_t EditSession::refineMeshes()
{
  if (!this->Worker || this->CoarseCount == 0)
    return 0;
  for (std::size_t id = 0; id < this->CoarseMark.size(); ++id)
    if (this->CoarseMark[id])
    {
      this->Refine.push_back(static_cast<std::int64_t>(id));
      this->CoarseMark[id] = 0;
    }
  const std::size_t n = this->CoarseCount;
  this->CoarseCount = 0;
  if (this->Held.empty() && this->Worker->idle())
    this->startRefine();
  return n;
}

void EditSession::startRefine()
{
  if (this->Refine.empty())
    return;
  std::vector<std::int64_t> ids;
  ids.swap(this->Refine);
  // a chunk asked coarsely again since (a new stroke) is refined at that stroke's end
  ids.erase(std::remove_if(ids.begin(), ids.end(), [this](std::int64_t id) { return this->CoarseMark[static_cast<std::size_t>(id)] != 0; }),
    ids.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (!ids.empty())
    this->Worker->request(ids, 0);
}

void EditSession::releaseMeshing()
{
  this->Holding = false;
  if (this->Held.empty())
    return;
  std::vector<std::int64_t> ids;
  ids.swap(this->Held);
  if (this->Worker)
    this->toWorker(ids);
}

void EditSession::afterEdit(const EditResult& edit, bool changed)
{
  // storage chunks changed by this call besides what `edit` names (undo, redo,
  // canvas fills, the earlier edits of a script or recording): the host's dirty
  // flags on the CPU, the editor's record of touched chunks on either
  std::vector<std::int64_t> storage = this->Ed->takeTouchedStorageChunks();
  uniteSorted(storage, this->Vol->takeDirtyChunks());
  this->request(meshChunksToRemesh(*this->Mesher, storage, edit));
  if (changed)
    ++this->Changes;
}

EditResult EditSession::applyDabs(const std::vector<Dab>& dabs, BrushKind kind)
{
  auto lock = this->lockSource();
  const EditResult r = this->Ed->applyDabs(dabs, kind);
  this->afterEdit(this->Ed->lastWrite(), r.changedVoxels > 0);
  return r;
}

EditResult EditSession::dab(const Dab& d)
{
  return this->applyDabs(std::vector<Dab>{ d }, BrushKind::Single);
}

EditResult EditSession::strokeThrough(const std::vector<BrushSample>& samples)
{
  // the editor's stroke (its dab budget, a pinch's stroke directions), not a second copy of it
  auto lock = this->lockSource();
  const EditResult r = this->Ed->strokeThrough(samples);
  this->afterEdit(this->Ed->lastWrite(), r.changedVoxels > 0);
  return r;
}

void EditSession::beginStroke()
{
  auto lock = this->lockSource();
  this->Ed->beginStroke();
}

EditResult EditSession::addSample(const BrushSample& s)
{
  auto lock = this->lockSource();
  const EditResult r = this->Ed->addSample(s);
  this->afterEdit(this->Ed->lastWrite(), r.changedVoxels > 0);
  return r;
}

EditResult EditSession::endStroke()
{
  auto lock = this->lockSource();
  const EditResult r = this->Ed->endStroke();
  // only the stroke's remaining dabs (Drill) or the whole stroke (Basic, Dynamic)
  this->afterEdit(this->Ed->lastWrite(), r.changedVoxels > 0);
  return r;
}

std::size_t EditSession::pump(InputDevice& device, std::size_t maxSamples, int timeoutMs, int maxMillis)
{
  auto lock = this->lockSource();
  const std::uint64_t before = this->Ed->undoCount();
  const std::size_t n = this->Ed->pump(device, maxSamples, timeoutMs, maxMillis);
  // several calls' writes: the touched storage chunks name them all
  this->afterEdit(EditResult(), n > 0 || this->Ed->undoCount() != before);
  return n;
}

bool EditSession::undo()
{
  auto lock = this->lockSource();
  const bool done = this->Ed->undo();
  this->afterEdit(EditResult(), done);
  return done;
}

bool EditSession::redo()
{
  auto lock = this->lockSource();
  const bool done = this->Ed->redo();
  this->afterEdit(EditResult(), done);
  return done;
}

void EditSession::play(const Recording& r, Interrupter& interrupter)
{
  auto lock = this->lockSource();
  // a change only when a record was applied: a refused recording (another
  // canvas) or one cancelled before its first record leaves the document as it was
  std::size_t played = 0;
  try
  {
    this->Ed->play(r, interrupter, &played);
  }
  catch (...)
  {
    this->afterEdit(EditResult(), played > 0);
    throw;
  }
  this->afterEdit(EditResult(), played > 0);
}

void EditSession::runScript(const std::string& source, const ScriptOptions& options)
{
  checkScript(source); // syntax errors before anything changes
  ScriptRunner runner(options);
  std::exception_ptr failure;
  {
    auto lock = this->lockSource();
    runner.attach(*this->Ed);
    try
    {
      runner.run(source);
    }
    catch (...)
    {
      failure = std::current_exception();
    }
    // the edits made on our volume before a `canvas N` or an error
    this->afterEdit(EditResult(), true);
  }
  // a `canvas N` made a new volume: it replaces ours (even when the script failed later),
  // with the brush the script left
  Editor* used = runner.editor(); // before takeVolume(), which ends the runner's editor
  const BrushSettings b = used ? used->brush : this->Ed->brush;
  const StrokeSettings s = used ? used->stroke : this->Ed->stroke;
  std::unique_ptr<DictionaryVolume> made = runner.takeVolume();
  if (made)
    this->build(std::shared_ptr<DictionaryVolume>(std::move(made)), &b, &s);
  if (failure)
    std::rethrow_exception(failure);
}

void EditSession::requestAllMeshes()
{
  if (!this->Opts.meshing)
    return;
  if (this->Worker)
  {
    std::fill(this->CoarseMark.begin(), this->CoarseMark.end(), 0);
    this->CoarseCount = 0;
    this->Worker->requestAll();
    return;
  }
  // on the device: the host ranges are exact after a sync, so empty chunks are skipped here
  this->sync();
  std::vector<std::int64_t> ids;
  for (std::int64_t id = 0; id < this->Mesher->chunkCount(); ++id)
    if (!this->Mesher->chunkIsEmpty(id))
      ids.push_back(id);
  uniteSorted(this->DeviceQueue, ids);
}

std::vector<ChunkMesh> EditSession::collectMeshes(std::vector<Clock::time_point>* gatheredAt)
{
  if (this->Worker)
  {
    // a refinement waits until the stroke's last meshes are done
    if (!this->Refine.empty() && this->Held.empty() && this->Worker->idle())
      this->startRefine();
    return this->Worker->collect(gatheredAt);
  }
  std::vector<ChunkMesh> out;
  if (gatheredAt)
    gatheredAt->clear();
  if (this->DeviceQueue.empty() || !this->Dev)
    return out;
  std::vector<std::int64_t> ids;
  ids.swap(this->DeviceQueue);
  const Clock::time_point at = Clock::now();
  this->Mesher->extractChunksFromDevice(this->Dev->view(), ids, this->Packed);
  out.resize(ids.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (k < this->Packed.chunkCount() && this->Packed.chunkIds[k] == ids[i])
    {
      out[i] = this->Packed.chunk(k++);
      continue;
    }
    out[i].chunkId = ids[i];
    out[i].chunkCoord = this->Mesher->chunkCoord(ids[i]);
    out[i].cells = this->Mesher->chunkCells(ids[i]);
  }
  if (gatheredAt)
    gatheredAt->assign(out.size(), at);
  return out;
}

bool EditSession::meshingIdle() const
{
  return this->Worker ? this->Held.empty() && this->Refine.empty() && this->Worker->idle() : this->DeviceQueue.empty();
}

void EditSession::waitMeshingIdle()
{
  this->releaseMeshing();
  if (this->Worker)
  {
    this->Worker->waitIdle();
    this->startRefine();
    this->Worker->waitIdle();
  }
}

std::vector<std::int64_t> EditSession::takeChangedMeshChunks()
{
  std::vector<std::int64_t> out;
  out.swap(this->Changed);
  return out;
}

} // namespace lvdif
