#include "vtkLVDIFEditor.h"

#include "LVDIFFiles.h"
#include "LVDIFVolumeBridge.h"
#include "vtkDictionaryVolumeToImage.h"
#include "vtkIdTypeArray.h"
#include "vtkObjectFactory.h"

#include "lvdif/EditLimits.h"
#include "lvdif/EditSession.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"

#include <cmath>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>

vtkStandardNewMacro(vtkLVDIFEditor);

// Brush and stroke settings while there is no session (they survive volume changes).
struct vtkLVDIFEditor::Settings
{
  lvdif::BrushSettings brush;
  lvdif::StrokeSettings stroke;
  std::string notice;
};

namespace
{
lvdif::BrushSettings& brushOf(lvdif::EditSession* s, lvdif::BrushSettings& fallback)
{
  return s ? s->brush() : fallback;
}
lvdif::StrokeSettings& strokeOf(lvdif::EditSession* s, lvdif::StrokeSettings& fallback)
{
  return s ? s->stroke() : fallback;
}
} // namespace

vtkLVDIFEditor::vtkLVDIFEditor()
  : Brush(new Settings)
  , ImageSource(vtkSmartPointer<vtkDictionaryVolumeToImage>::New())
  , LastChanged(vtkSmartPointer<vtkIdTypeArray>::New())
{
}

vtkLVDIFEditor::~vtkLVDIFEditor() = default;

template <class F>
int vtkLVDIFEditor::Guard(const char* what, F&& fn)
{
  this->LastError.clear();
  this->LastErrorLine = this->LastErrorColumn = 0;
  try
  {
    fn();
    this->ReportChanges();
    return 1;
  }
  catch (const lvdif::ScriptError& e)
  {
    this->LastError = e.what();
    this->LastErrorLine = e.line();
    this->LastErrorColumn = e.column();
  }
  catch (const std::exception& e)
  {
    this->LastError = std::string(what) + ": " + e.what();
  }
  // edits made before the failure (a script's first lines) are kept: report them
  this->ReportChanges();
  vtkErrorMacro(<< this->LastError);
  return 0;
}

bool vtkLVDIFEditor::RequireVolume()
{
  if (this->Session)
    return true;
  this->LastError = "no volume: call NewVolume or LoadVolume first";
  this->LastErrorLine = this->LastErrorColumn = 0;
  vtkErrorMacro(<< this->LastError);
  return false;
}

void vtkLVDIFEditor::ReportChanges()
{
  if (!this->Session)
    return;
  if (this->Session->generation() != this->ImageGeneration)
  {
    // a script's `canvas N` replaced the volume
    this->ImageSource->SetVolume(this->Session->sharedVolume());
    this->ImageGeneration = this->Session->generation();
  }
  const std::vector<std::int64_t> ids = this->Session->takeChangedMeshChunks();
  if (ids.empty())
    return;
  // the image source and GetVolume() read the host copy: bring it up to date
  // (a Python call is not a frame; the interactive path keeps it lazy)
  this->Session->sync();
  this->LastChanged->SetNumberOfValues(static_cast<vtkIdType>(ids.size()));
  for (std::size_t i = 0; i < ids.size(); ++i)
    this->LastChanged->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(ids[i]));
  this->ImageSource->Modified();
  this->InvokeEvent(ChunksModifiedEvent, this->LastChanged.GetPointer());
  this->Modified();
}

void vtkLVDIFEditor::SetDevice(int device)
{
  // the filters' one rule and words (LVDIFVolumeBridge::DeviceOption); refused
  // here, at the call: the editor has no update to refuse it at
  try
  {
    LVDIFVolumeBridge::DeviceOption(device);
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return;
  }
  if (this->Device != device)
  {
    this->Device = device;
    this->Modified();
  }
}

bool vtkLVDIFEditor::IsOnDevice()
{
  return this->Session && this->Session->onDevice();
}

const char* vtkLVDIFEditor::GetNotice()
{
  return this->Brush->notice.c_str();
}

int vtkLVDIFEditor::GetMeshChunkEdge()
{
  return this->Session ? this->Session->meshChunkEdge() : 0;
}

std::shared_ptr<lvdif::DictionaryVolume> vtkLVDIFEditor::GetVolume()
{
  return this->Session ? this->Session->sharedVolume() : nullptr;
}

void vtkLVDIFEditor::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  lvdif::EditSessionOptions o;
  o.device = this->Device == 1 ? lvdif::Device::Cpu : (this->Device == 2 ? lvdif::Device::Cuda : lvdif::Device::Auto);
  o.meshing = false; // this object hands out no meshes, only which mesh chunks changed
  // A volume the session refuses (EditSession's canvas rule) throws before the
  // current session changes: the editor keeps its volume.
  if (volume && this->Session && this->Session->options().device == o.device)
    this->Session->setVolume(volume); // brush kept; the old volume leaves the GPU before the new one comes
  else
  {
    std::unique_ptr<lvdif::EditSession> next;
    if (volume)
      next = std::make_unique<lvdif::EditSession>(volume, o);
    if (this->Session)
    {
      this->Brush->brush = this->Session->brush();
      this->Brush->stroke = this->Session->stroke();
    }
    this->Session = std::move(next);
    if (this->Session)
    {
      this->Session->brush() = this->Brush->brush;
      this->Session->stroke() = this->Brush->stroke;
    }
  }
  this->Brush->notice = this->Session ? this->Session->notice() : std::string();
  this->ImageSource->SetVolume(volume);
  this->ImageGeneration = this->Session ? this->Session->generation() : 0;
  this->ReportChanges(); // a new session reports every mesh chunk
}

int vtkLVDIFEditor::NewVolume(int nx, int ny, int nz, bool filled)
{
  return this->Guard("NewVolume", [&] {
    lvdif::VolumeOptions o;
    o.dims = { nx, ny, nz };
    o.chunkEdge = this->ChunkEdge;
    o.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    std::shared_ptr<lvdif::DictionaryVolume> v = lvdif::DictionaryVolume::newCanvas(o); // the editors' one canvas rule
    if (filled)
    {
      const lvdif::Rgba c = brushOf(this->Session.get(), this->Brush->brush).color;
      const lvdif::Voxel fill{ v->insideVoxel().sdf, v->colors().add(c) };
      for (std::int64_t id = 0; id < v->chunkCount(); ++id)
        v->fillChunk(id, fill);
    }
    v->takeDirtyChunks();
    this->SetVolume(std::move(v));
  });
}

int vtkLVDIFEditor::LoadVolume(const char* path)
{
  return this->Guard("LoadVolume", [&] {
    lvdif::require(path && *path, "no file name");
    // every volume format, by extension, through the one file registry (as the CLI and the Qt editor)
    this->SetVolume(LVDIFFiles::LoadVolume(path));
  });
}

int vtkLVDIFEditor::SaveVolume(const char* path)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("SaveVolume", [&] {
    lvdif::require(path && *path, "no file name");
    LVDIFFiles::SaveVolume(this->Session->sharedVolume(), path); // sharedVolume() syncs a GPU volume first
  });
}

void vtkLVDIFEditor::GetDimensions(int dims[3])
{
  for (int i = 0; i < 3; ++i)
    dims[i] = this->Session ? static_cast<int>(this->Session->mesher().pointDims()[i]) : 0;
}

int vtkLVDIFEditor::GetNumberOfChunks()
{
  return this->Session ? static_cast<int>(this->Session->mesher().chunkCount()) : 0;
}

// ---- brush settings -----------------------------------------------------------

void vtkLVDIFEditor::SetOperation(int op)
{
  if (op < OperationAdd || op > OperationPaint)
  {
    vtkErrorMacro(<< "operation " << op << " is not 0 (add), 1 (subtract) or 2 (paint)");
    return;
  }
  brushOf(this->Session.get(), this->Brush->brush).op = static_cast<lvdif::BrushOp>(op);
  this->Modified();
}

int vtkLVDIFEditor::GetOperation()
{
  return static_cast<int>(brushOf(this->Session.get(), this->Brush->brush).op);
}

void vtkLVDIFEditor::SetPrimitive(int primitive)
{
  if (primitive != PrimitiveSphere && primitive != PrimitiveCube)
  {
    vtkErrorMacro(<< "primitive " << primitive << " is not 0 (sphere) or 1 (cube)");
    return;
  }
  strokeOf(this->Session.get(), this->Brush->stroke).shape = static_cast<lvdif::BrushShape>(primitive);
  this->Modified();
}

int vtkLVDIFEditor::GetPrimitive()
{
  return static_cast<int>(strokeOf(this->Session.get(), this->Brush->stroke).shape);
}

namespace
{
// The rules every edit input follows (lvdif/EditLimits.h); "" when v passes.
std::string numberProblem(double v, double lo, double hi, const char* what, bool positive)
{
  try
  {
    if (positive && !(v > 0))
      return std::string(what) + " must be > 0";
    lvdif::checkedNumber(v, lo, hi, what);
  }
  catch (const lvdif::Error& e)
  {
    return e.what();
  }
  return std::string();
}
} // namespace

void vtkLVDIFEditor::SetRadius(double r)
{
  const std::string bad = numberProblem(r, 0, lvdif::EditLimits::MaxSize, "radius", true);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  strokeOf(this->Session.get(), this->Brush->stroke).radius = r;
  this->Modified();
}

double vtkLVDIFEditor::GetRadius()
{
  return strokeOf(this->Session.get(), this->Brush->stroke).radius;
}

void vtkLVDIFEditor::SetColor(int r, int g, int b, int a)
{
  const int c[4] = { r, g, b, a };
  for (int v : c)
    if (v < 0 || v > 255)
    {
      vtkErrorMacro(<< "colour components must be in 0..255, got " << v);
      return;
    }
  brushOf(this->Session.get(), this->Brush->brush).color = lvdif::Rgba{ static_cast<std::uint8_t>(r),
    static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(b), static_cast<std::uint8_t>(a) };
  this->Modified();
}

int vtkLVDIFEditor::GetColorComponent(int i)
{
  if (i < 0 || i > 3)
    return -1;
  const lvdif::Rgba& c = brushOf(this->Session.get(), this->Brush->brush).color;
  const std::uint8_t v[4] = { c.r, c.g, c.b, c.a };
  return v[i];
}

void vtkLVDIFEditor::SetBlend(double k)
{
  const std::string bad = numberProblem(k, 0, lvdif::EditLimits::MaxSize, "blend", false);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  brushOf(this->Session.get(), this->Brush->brush).blend = k;
  this->Modified();
}

double vtkLVDIFEditor::GetBlend()
{
  return brushOf(this->Session.get(), this->Brush->brush).blend;
}

void vtkLVDIFEditor::SetBrushKind(int kind)
{
  if (kind < BrushKindSingle || kind > BrushKindDrill)
  {
    vtkErrorMacro(<< "brush kind " << kind << " is not 0 (single), 1 (basic), 2 (dynamic) or 3 (drill)");
    return;
  }
  strokeOf(this->Session.get(), this->Brush->stroke).kind = static_cast<lvdif::BrushKind>(kind);
  this->Modified();
}

int vtkLVDIFEditor::GetBrushKind()
{
  return static_cast<int>(strokeOf(this->Session.get(), this->Brush->stroke).kind);
}

void vtkLVDIFEditor::SetSpacing(double s)
{
  const std::string bad = numberProblem(s, lvdif::EditLimits::MinSpacing, lvdif::EditLimits::MaxSize, "spacing", false);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  strokeOf(this->Session.get(), this->Brush->stroke).spacing = s;
  this->Modified();
}

double vtkLVDIFEditor::GetSpacing()
{
  return strokeOf(this->Session.get(), this->Brush->stroke).spacing;
}

void vtkLVDIFEditor::SetMinRadius(double r)
{
  const std::string bad = numberProblem(r, 0, lvdif::EditLimits::MaxSize, "minimum radius", true);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  strokeOf(this->Session.get(), this->Brush->stroke).minRadius = r;
  this->Modified();
}

double vtkLVDIFEditor::GetMinRadius()
{
  return strokeOf(this->Session.get(), this->Brush->stroke).minRadius;
}

// ---- edits ----------------------------------------------------------------------

int vtkLVDIFEditor::Dab(double x, double y, double z)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("Dab", [&] {
    lvdif::Dab d;
    d.shape = this->Session->stroke().shape;
    d.center = { x, y, z };
    d.radius = this->Session->stroke().radius;
    this->Session->dab(d);
  });
}

int vtkLVDIFEditor::BeginStroke()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("BeginStroke", [&] { this->Session->beginStroke(); });
}

int vtkLVDIFEditor::AddSample(double x, double y, double z, double pressure)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("AddSample", [&] {
    lvdif::BrushSample s;
    s.position = { x, y, z };
    s.pressure = pressure;
    s.buttons = 1;
    for (double v : s.position)
      lvdif::require(std::isfinite(v), "sample position must be finite");
    this->Session->addSample(s);
  });
}

int vtkLVDIFEditor::EndStroke()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("EndStroke", [&] { this->Session->endStroke(); });
}

bool vtkLVDIFEditor::IsStrokeOpen()
{
  return this->Session && this->Session->strokeOpen();
}

int vtkLVDIFEditor::Undo()
{
  if (!this->RequireVolume())
    return 0;
  bool done = false;
  const int ok = this->Guard("Undo", [&] { done = this->Session->undo(); });
  return ok && done ? 1 : 0;
}

int vtkLVDIFEditor::Redo()
{
  if (!this->RequireVolume())
    return 0;
  bool done = false;
  const int ok = this->Guard("Redo", [&] { done = this->Session->redo(); });
  return ok && done ? 1 : 0;
}

bool vtkLVDIFEditor::CanUndo()
{
  return this->Session && this->Session->canUndo();
}

bool vtkLVDIFEditor::CanRedo()
{
  return this->Session && this->Session->canRedo();
}

int vtkLVDIFEditor::GetUndoCount()
{
  return this->Session ? static_cast<int>(this->Session->undoCount()) : 0;
}

// ---- recorder and player ------------------------------------------------------------

int vtkLVDIFEditor::StartRecording()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("StartRecording", [&] { this->Session->startRecording(); });
}

bool vtkLVDIFEditor::IsRecording()
{
  return this->Session && this->Session->recording();
}

int vtkLVDIFEditor::StopRecording(const char* path)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("StopRecording", [&] {
    const lvdif::Recording r = this->Session->stopRecording();
    if (path && *path)
      lvdif::saveRecording(path, r);
  });
}

int vtkLVDIFEditor::PlayRecording(const char* path)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("PlayRecording", [&] {
    lvdif::require(path && *path, "no file name");
    const lvdif::Recording r = lvdif::loadRecording(path);
    if (!r.warning.empty()) vtkWarningMacro(<< r.warning); // a version 1 file: no end record
    this->Session->play(r);
  });
}

int vtkLVDIFEditor::ImportOriginalCsv(const char* path, double originalSize)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("ImportOriginalCsv", [&] {
    lvdif::require(path && *path, "no file name");
    lvdif::CsvImportOptions o;
    o.originalSize = originalSize;
    if (!(originalSize > 0))
    {
      // the original names its files Recording_<N>_<date>.csv
      std::smatch m;
      const std::string name(path);
      static const std::regex re("Recording_([0-9]+)_[^/\\\\]*$");
      lvdif::require(std::regex_search(name, m, re),
        "give the original volume size: the file name does not say it (Recording_<N>_...)");
      o.originalSize = std::stod(m[1].str());
    }
    o.targetSize = static_cast<double>(this->Session->mesher().pointDims()[0]);
    std::ifstream in(path);
    if (!in)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, std::string("cannot open '") + path + "'");
    const lvdif::CsvImportResult r = lvdif::importOriginalCsv(in, o);
    if (r.skippedRows)
      vtkWarningMacro(<< r.skippedRows << " broken rows skipped; first: " << r.firstProblem);
    this->Session->play(r.recording);
  });
}

// ---- scripts -------------------------------------------------------------------------------

int vtkLVDIFEditor::RunScript(const char* text)
{
  const std::string source = text ? text : "";
  return this->Guard("RunScript", [&] {
    lvdif::ScriptOptions o;
    o.canvas.chunkEdge = this->ChunkEdge;
    o.canvas.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    if (this->Session)
    {
      this->Session->runScript(source, o); // the session adopts a `canvas N` volume itself
      return;
    }
    // no volume yet: the script must make one (`canvas N`); a session then holds it
    lvdif::ScriptRunner runner(o);
    struct Adopt // a `canvas` volume is kept even when the script fails later
    {
      vtkLVDIFEditor* Self;
      lvdif::ScriptRunner& Runner;
      ~Adopt()
      {
        if (lvdif::Editor* used = this->Runner.editor())
        {
          this->Self->Brush->brush = used->brush;
          this->Self->Brush->stroke = used->stroke;
        }
        std::unique_ptr<lvdif::DictionaryVolume> made = this->Runner.takeVolume();
        if (made)
          this->Self->SetVolume(std::shared_ptr<lvdif::DictionaryVolume>(std::move(made)));
      }
    } adopt{ this, runner };
    runner.run(source);
  });
}

int vtkLVDIFEditor::RunScriptFile(const char* path)
{
  // the one script reader: a directory read as an empty script (success) and a FIFO blocked before
  std::string text;
  if (!this->Guard("RunScriptFile", [&] {
        lvdif::require(path && *path, "no file name");
        text = lvdif::readScriptFile(path);
      }))
    return 0;
  return this->RunScript(text.c_str());
}

vtkDictionaryVolumeToImage* vtkLVDIFEditor::GetImageSource()
{
  return this->ImageSource;
}

void vtkLVDIFEditor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  int d[3];
  this->GetDimensions(d);
  os << indent << "Dimensions: " << d[0] << " " << d[1] << " " << d[2] << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "Device: " << this->Device << (this->IsOnDevice() ? " (on the GPU)" : "") << "\n";
  os << indent << "Operation: " << this->GetOperation() << "\n";
  os << indent << "Primitive: " << this->GetPrimitive() << "\n";
  os << indent << "Radius: " << this->GetRadius() << "\n";
  os << indent << "Blend: " << this->GetBlend() << "\n";
  os << indent << "BrushKind: " << this->GetBrushKind() << "\n";
  os << indent << "Spacing: " << this->GetSpacing() << "\n";
  os << indent << "UndoCount: " << this->GetUndoCount() << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}

vtkIdTypeArray* vtkLVDIFEditor::GetLastChangedChunks()
{
  return this->LastChanged;
}
