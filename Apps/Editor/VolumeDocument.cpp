#include "VolumeDocument.h"

#include "LVDIFFiles.h"

#include "vtkDictionaryVolumeToImage.h"
#include "LVDIFChunkMesh.h"
#include "LVDIFVolumeBridge.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Error.h"
#include "lvdif/Script.h"
#include "lvdif/VolumeFile.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <QFileInfo>

#include <cmath>
#include <mutex>

namespace
{
std::shared_ptr<lvdif::DictionaryVolume> borrow(lvdif::DictionaryVolume& v)
{
  return std::shared_ptr<lvdif::DictionaryVolume>(&v, [](lvdif::DictionaryVolume*) {});
}
} // namespace

VolumeDocument::VolumeDocument() = default;

VolumeDocument::~VolumeDocument()
{
  // The worker reads through the mesher, which reads the volume.
  this->Worker.reset();
  this->Mesher.reset();
  this->Edit.reset();
  this->Volume.reset();
}

void VolumeDocument::resetPipeline()
{
  ++this->Generation;
  this->Worker.reset();
  this->Mesher.reset();
  this->Edit = std::make_unique<lvdif::Editor>(*this->Volume);
  lvdif::MarchingCubesOptions mo;
  mo.chunkEdge = 32;
  this->Mesher = std::make_unique<lvdif::ChunkedMarchingCubes>(*this->Volume, mo);
  this->Worker = std::make_unique<lvdif::MarchingCubesWorker>(*this->Mesher);
  this->Volume->takeDirtyChunks();
  this->Worker->requestAll();
  this->Modified = false;
  this->EditsSinceAutosave = 0;
}

void VolumeDocument::newCanvas(int nx, int ny, int nz, Fill fill)
{
  lvdif::VolumeOptions o;
  o.dims = { nx, ny, nz };
  o.chunkEdge = 32;
  auto v = std::make_unique<lvdif::DictionaryVolume>(o);
  if (fill == Fill::Full)
  {
    v = std::make_unique<lvdif::DictionaryVolume>(o, v->insideVoxel());
  }
  else if (fill == Fill::Sphere)
  {
    // a starter sphere of at most 64 voxels: its mesh (and so the first frame) stays
    // small on large canvases; the rest of the canvas is uniform and costs nothing
    const double r = std::min(64.0, 0.35 * std::min(nx, std::min(ny, nz)));
    lvdif::fillFromFunction(*v, lvdif::sphereSdf(0.5 * (nx - 1), 0.5 * (ny - 1), 0.5 * (nz - 1), r));
  }
  this->Worker.reset(); // stop reading the old volume before it goes
  this->Mesher.reset();
  this->Volume = std::move(v);
  this->Path.clear();
  this->resetPipeline();
}

void VolumeDocument::adopt(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Worker.reset();
  this->Mesher.reset();
  this->Volume = std::move(volume);
  this->Path.clear();
  this->resetPipeline();
  this->Modified = true;
}

void VolumeDocument::open(const QString& path)
{
  // every volume format, by extension, through the one file registry
  std::shared_ptr<lvdif::DictionaryVolume> v = LVDIFFiles::LoadVolume(path.toStdString());
  this->Worker.reset();
  this->Mesher.reset();
  this->Volume = std::move(v);
  this->Path = path;
  this->resetPipeline();
}

void VolumeDocument::save(const QString& path, bool asCopy)
{
  if (!this->Volume)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "no volume to save");
  }
  {
    std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
    LVDIFFiles::SaveVolume(this->Volume, path.toStdString()); // .lvdv: exact keys, crash-safe
  }
  if (!asCopy)
  {
    this->Path = path;
    this->Modified = false;
  }
}

void VolumeDocument::afterEdit(const lvdif::EditResult& r)
{
  if (r.changedVoxels > 0 || !r.changedChunks.empty())
  {
    this->Modified = true;
    ++this->EditsSinceAutosave;
  }
}

void VolumeDocument::requestDirty()
{
  // Called with the source mutex held.
  const std::vector<std::int64_t> dirty = this->Volume->takeDirtyChunks();
  if (!dirty.empty())
  {
    this->Worker->request(LVDIFChunkMesh::ChunksToRemesh(*this->Mesher, dirty));
  }
}

void VolumeDocument::requestChanged(const lvdif::EditResult& r)
{
  // Called with the source mutex held.
  const std::vector<std::int64_t> dirty = this->Volume->takeDirtyChunks();
  const std::vector<std::int64_t> ids = LVDIFChunkMesh::ChunksToRemesh(*this->Mesher, dirty, r);
  this->LastRequest = ids;
  this->LastRequestAt = std::chrono::steady_clock::now();
  if (!ids.empty())
  {
    this->Worker->request(ids);
  }
}

void VolumeDocument::beginStroke()
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  this->Edit->beginStroke();
}

void VolumeDocument::addSample(const lvdif::BrushSample& s)
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  this->afterEdit(this->Edit->addSample(s));
  // Only Drill-style (live) strokes write here (Dynamic applies at the end):
  // re-mesh exactly the chunks around the voxels this sample changed.
  this->requestChanged(this->Edit->lastWrite());
}

void VolumeDocument::endStroke()
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  if (this->Edit->strokeOpen())
  {
    this->afterEdit(this->Edit->endStroke());
    // The stroke's remaining dabs only (Drill) or the whole stroke (Dynamic).
    this->requestChanged(this->Edit->lastWrite());
  }
  else
  {
    this->requestDirty();
  }
}

bool VolumeDocument::undo()
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  const bool done = this->Edit->undo();
  if (done)
  {
    this->Modified = true;
    ++this->EditsSinceAutosave;
  }
  this->requestDirty();
  return done;
}

bool VolumeDocument::redo()
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  const bool done = this->Edit->redo();
  if (done)
  {
    this->Modified = true;
    ++this->EditsSinceAutosave;
  }
  this->requestDirty();
  return done;
}

void VolumeDocument::startRecording()
{
  this->Edit->startRecording();
}

lvdif::Recording VolumeDocument::stopRecording()
{
  return this->Edit->stopRecording();
}

void VolumeDocument::play(const lvdif::Recording& r)
{
  std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
  this->Edit->play(r);
  this->Modified = true;
  ++this->EditsSinceAutosave;
  this->requestDirty();
}

void VolumeDocument::runScript(const std::string& source)
{
  lvdif::checkScript(source); // syntax errors before anything changes
  std::unique_ptr<lvdif::DictionaryVolume> made;
  {
    std::lock_guard<std::mutex> lock(this->Worker->sourceMutex());
    lvdif::ScriptRunner runner;
    runner.attach(*this->Volume);
    try
    {
      runner.run(source);
    }
    catch (...)
    {
      // Edits made before the error stay (and are shown); the history no longer matches them.
      this->Edit->undoStack().clear();
      this->Modified = true;
      this->requestDirty();
      throw;
    }
    made = runner.takeVolume();
    if (!made)
    {
      this->Edit->undoStack().clear();
      this->Modified = true;
      ++this->EditsSinceAutosave;
      this->requestDirty();
      return;
    }
  }
  this->Worker.reset();
  this->Mesher.reset();
  this->Volume = std::move(made);
  this->Path.clear();
  this->resetPipeline();
  this->Modified = true;
  ++this->EditsSinceAutosave;
}

std::vector<lvdif::ChunkMesh> VolumeDocument::collectMeshes(std::vector<std::chrono::steady_clock::time_point>* gatheredAt)
{
  return this->Worker ? this->Worker->collect(gatheredAt) : std::vector<lvdif::ChunkMesh>();
}

bool VolumeDocument::meshingIdle() const
{
  return !this->Worker || this->Worker->idle();
}

void VolumeDocument::waitMeshingIdle()
{
  if (this->Worker)
  {
    this->Worker->waitIdle();
  }
}
