#include "VolumeDocument.h"

#include "BoxCaps.h"
#include "LVDIFFiles.h"

#include "lvdif/Cuda.h"
#include "lvdif/Error.h"
#include "lvdif/Script.h"
#include "lvdif/StarterCanvas.h"

#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace
{
/// VTK's error text goes nowhere while it lives (its warnings still reach
/// stderr); an algorithm with an ErrorEvent observer still gets its errors.
class DroppedErrors : public vtkOutputWindow
{
public:
  static DroppedErrors* New();
  vtkTypeMacro(DroppedErrors, vtkOutputWindow);
  DroppedErrors() { this->SetDisplayModeToAlwaysStdErr(); } // not through vtkLogger, turned off meanwhile
  void DisplayErrorText(const char*) override {}
};
vtkStandardNewMacro(DroppedErrors);

struct QuietVtkErrors
{
  vtkSmartPointer<vtkOutputWindow> was = vtkOutputWindow::GetInstance();
  const vtkLogger::Verbosity logged = vtkLogger::GetCurrentVerbosityCutoff();
  QuietVtkErrors()
  {
    vtkOutputWindow::SetInstance(vtkSmartPointer<DroppedErrors>::New());
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // it logs each error there too
  }
  ~QuietVtkErrors()
  {
    vtkOutputWindow::SetInstance(this->was);
    vtkLogger::SetStderrVerbosity(this->logged);
  }
};
} // namespace

VolumeDocument::VolumeDocument() = default;

VolumeDocument::~VolumeDocument() = default;

void VolumeDocument::hold(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  if (this->Session)
    this->Session->setVolume(std::move(volume));
  else
  {
    this->Session = std::make_unique<lvdif::EditSession>(std::move(volume));
    // one notice per run: a missing GPU was already told by lvdif's one
    // fallback line (none in a build without CUDA); say only why a volume
    // stays on the host of a machine that has one
    static bool told = false;
    if (!this->Session->notice().empty() && !told && lvdif::cuda::available())
    {
      std::cerr << "lvdif-editor: " << this->Session->notice() << "\n";
      told = true;
    }
  }
  this->Session->requestAllMeshes();
  this->CapsPending = true;
  this->SeenChanges = this->Session->changeCount();
  this->Modified = false;
  this->EditsSinceAutosave = 0;
  this->resetHistory();
  this->RedoDropped = false; // a new history
}

void VolumeDocument::resetHistory()
{
  this->Done.clear();
  this->Undone.clear();
}

void VolumeDocument::noteChanges()
{
  if (this->Session->changeCount() != this->SeenChanges)
  {
    this->SeenChanges = this->Session->changeCount();
    this->Modified = true;
    ++this->EditsSinceAutosave;
  }
}

void VolumeDocument::newCanvas(int nx, int ny, int nz, Fill fill)
{
  // Core's one new canvas and starter shape, as `lvdif play` without --in makes it
  std::shared_ptr<lvdif::DictionaryVolume> v = lvdif::makeCanvas({ nx, ny, nz }, fill);
  this->Path.clear();
  this->hold(std::move(v));
  this->StarterGeneration = fill == Fill::Sphere ? this->Session->generation() : -1;
  this->StarterChanges = this->Session->changeCount();
}

void VolumeDocument::adopt(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Path.clear();
  this->hold(std::move(volume));
  this->Modified = true;
}

void VolumeDocument::open(const QString& path, bool untitled)
{
  std::shared_ptr<lvdif::DictionaryVolume> v;
  {
    // A file that cannot be read is one message, the lvdif::Error the file
    // registry makes of its reader's error: VTK's own text from objects it
    // does not watch (the XML parser under a .vti reader) was a second line
    // on stderr, in VTK's log format. Watched readers still report theirs.
    QuietVtkErrors quiet;
    // every volume format, by extension, through the one file registry
    v = LVDIFFiles::LoadVolume(path.toStdString());
  }
  if (untitled)
  {
    this->adopt(std::move(v));
    return;
  }
  this->Path = path;
  this->hold(std::move(v));
}

void VolumeDocument::save(const QString& path, bool asCopy)
{
  if (!this->Session)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "no volume to save");
  }
  // sharedVolume() syncs a device-resident volume first; the CPU worker only reads
  LVDIFFiles::SaveVolume(this->Session->sharedVolume(), path.toStdString()); // .lvdv: exact keys, crash-safe
  if (!asCopy)
  {
    this->Path = path;
    this->Modified = false;
  }
}

void VolumeDocument::beginStroke()
{
  this->StrokeUndoCount = this->Session->undoCount();
  this->StrokeChanges = this->Session->changeCount();
  this->Session->beginStroke();
}

void VolumeDocument::addSample(const lvdif::BrushSample& s)
{
  try
  {
    this->Session->addSample(s);
  }
  catch (...)
  {
    // The stroke ends at its failure (an edit over the memory limit): what it
    // applied before stays, one undo step. Left open, it refused every later
    // stroke ("a stroke is already open"), and Ctrl+Z threw "finish the open
    // stroke first" out of the event loop: the editor aborted, the work unsaved.
    try
    {
      this->endStroke();
    }
    catch (...)
    {
      // the stroke's own failure is the one reported
    }
    this->noteChanges();
    throw;
  }
  this->noteChanges();
}

void VolumeDocument::endStroke()
{
  if (!this->Session->strokeOpen())
    return;
  // One step of ours whatever it changed (the script runner's rule, one for
  // every front end): the session holds it when it wrote a chunk (a device's
  // history may keep one more). The session closes its step even when the
  // stroke fails; then whether it holds one is told by its counts.
  bool held = true;
  try
  {
    const lvdif::EditResult r = this->Session->endStroke();
    held = r.changedVoxels > 0 || !r.changedChunks.empty() || this->Session->undoCount() > this->StrokeUndoCount;
  }
  catch (...)
  {
    this->Done.push_back(this->Session->changeCount() != this->StrokeChanges ||
      this->Session->undoCount() != this->StrokeUndoCount);
    this->Undone.clear();
    this->RedoDropped = true;
    this->noteChanges();
    throw;
  }
  this->Done.push_back(held);
  this->Undone.clear();
  this->RedoDropped = true;
  this->noteChanges();
}

bool VolumeDocument::undo()
{
  const bool held = this->Done.empty() || this->Done.back();
  if (held && !this->Session->undo())
  {
    // the session's cap dropped the oldest steps: nothing of ours is left below
    this->Done.clear();
    return false;
  }
  if (!this->Done.empty())
    this->Done.pop_back();
  this->Undone.push_back(held);
  this->noteChanges();
  return true;
}

bool VolumeDocument::redo()
{
  const bool held = this->Undone.empty() || this->Undone.back();
  // a stroke since the last undo dropped what was undone, also one that changed nothing
  if (held && ((this->Undone.empty() && this->RedoDropped) || !this->Session->redo()))
    return false;
  if (!this->Undone.empty())
    this->Undone.pop_back();
  this->Done.push_back(held);
  this->noteChanges();
  return true;
}

void VolumeDocument::startRecording()
{
  this->Session->startRecording();
}

lvdif::Recording VolumeDocument::stopRecording()
{
  return this->Session->stopRecording();
}

void VolumeDocument::play(const lvdif::Recording& r)
{
  // On the untouched starter canvas a recording starts from the starter it was made on, where
  // its version says (Core's rule, as `lvdif play` without --in).
  const lvdif::Index3 d = this->volume().dims();
  if (this->StarterGeneration == this->Session->generation() && this->StarterChanges == this->Session->changeCount() &&
    (r.canvas[0] == 0 || r.canvas == d) && lvdif::recordedStarter(r, d, "File > Open") == Fill::Dot)
    this->newCanvas(int(d[0]), int(d[1]), int(d[2]), Fill::Dot);
  // as runScript: the edits played before an error stay, so they count as changes
  // (and are the session's steps: the strokes' history goes on from its)
  const std::uint64_t before = this->Session->changeCount();
  auto after = [&] {
    if (this->Session->changeCount() != before)
      this->resetHistory();
    this->noteChanges();
  };
  try
  {
    this->Session->play(r);
  }
  catch (...)
  {
    after();
    throw;
  }
  after();
}

void VolumeDocument::runScript(const std::string& source, const lvdif::ScriptOptions& options)
{
  const int generation = this->Session->generation();
  // whether the script succeeded or failed later: edits made before an error
  // stay (each undoable), and a `canvas N` volume is kept (the session adopts it)
  bool ran = true;
  auto after = [&] {
    // its edits are the session's steps (the runner kept its own no-op steps for the run only)
    if (ran)
      this->resetHistory();
    this->noteChanges();
    if (this->Session->generation() != generation)
    {
      this->RedoDropped = false; // a new volume's history
      // a new volume: no file yet (Save must not write it over the file that was open)
      this->Path.clear();
      this->Session->requestAllMeshes();
      this->CapsPending = true;
      this->Modified = true;
    }
  };
  try
  {
    this->Session->runScript(source, options);
  }
  catch (const lvdif::ScriptError& e)
  {
    // refused before any statement ran (a `canvas N` where the caller fixed
    // the canvas): the document is as it was, not modified
    if (!options.canvasSizeGivenBy.empty() && e.detail().find(options.canvasSizeGivenBy) != std::string::npos)
    {
      this->SeenChanges = this->Session->changeCount();
      ran = false;
    }
    if (e.code() == lvdif::ErrorCode::ParseError)
      ran = false; // refused before it ran
    after();
    throw;
  }
  catch (...)
  {
    after();
    throw;
  }
  after();
}

std::vector<lvdif::ChunkMesh> VolumeDocument::collectMeshes(std::vector<std::chrono::steady_clock::time_point>* gatheredAt)
{
  if (!this->Session)
    return std::vector<lvdif::ChunkMesh>();
  std::vector<lvdif::ChunkMesh> meshes = this->Session->collectMeshes(gatheredAt);
  // The solid closed at the box's faces (BoxCaps.h): a Full canvas showed
  // nothing until carved. The caps of a chunk come with each of its meshes.
  const lvdif::ChunkedMarchingCubes& mesher = this->Session->mesher();
  const float iso = mesher.options().isoValue;
  const lvdif::DictionaryVolume* v = nullptr; // synced from the device only when a cap is needed
  auto volume = [&]() -> const lvdif::DictionaryVolume& {
    if (!v)
      v = &this->Session->volume();
    return *v;
  };
  const lvdif::Index3 dims = this->Session->hostVolume().dims();
  for (lvdif::ChunkMesh& m : meshes)
    if (BoxCaps::touchesBox(m.cells, dims))
      BoxCaps::append(m, volume(), iso);
  // On the device a new volume's meshing skips the chunks without a surface
  // (EditSession::requestAllMeshes), which a cap may need: their caps come once.
  if (this->CapsPending && this->Session->onDevice())
  {
    std::vector<bool> have(static_cast<std::size_t>(mesher.chunkCount()), false);
    for (const lvdif::ChunkMesh& m : meshes)
      if (m.chunkId >= 0 && m.chunkId < mesher.chunkCount())
        have[static_cast<std::size_t>(m.chunkId)] = true;
    const auto now = std::chrono::steady_clock::now();
    for (std::int64_t id = 0; id < mesher.chunkCount(); ++id)
    {
      lvdif::ChunkMesh m;
      m.cells = mesher.chunkCells(id);
      if (have[static_cast<std::size_t>(id)] || !BoxCaps::touchesBox(m.cells, dims))
        continue;
      m.chunkId = id;
      m.chunkCoord = mesher.chunkCoord(id);
      if (BoxCaps::append(m, volume(), iso))
      {
        meshes.push_back(std::move(m));
        if (gatheredAt)
          gatheredAt->push_back(now);
      }
    }
  }
  this->CapsPending = false;
  return meshes;
}

const std::vector<std::int64_t>& VolumeDocument::lastRequest() const
{
  static const std::vector<std::int64_t> none;
  return this->Session ? this->Session->lastRequest() : none;
}

std::chrono::steady_clock::time_point VolumeDocument::lastRequestTime() const
{
  return this->Session ? this->Session->lastRequestTime() : std::chrono::steady_clock::time_point();
}

bool VolumeDocument::meshingIdle() const
{
  return !this->Session || this->Session->meshingIdle();
}

void VolumeDocument::waitMeshingIdle()
{
  if (this->Session)
  {
    this->Session->waitMeshingIdle();
  }
}

bool VolumeDocument::insideAt(const double world[3])
{
  const lvdif::DictionaryVolume& v = this->Session->volume(); // synced: the brushes may run on the GPU
  const auto& o = v.options();
  std::int64_t i[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::round((world[a] - o.origin[a]) / o.spacing[a]);
    i[a] = static_cast<std::int64_t>(std::max(0.0, std::min(double(v.dims()[a] - 1), std::isfinite(x) ? x : 0.0)));
  }
  return v.sdf(i[0], i[1], i[2]) < 0;
}
