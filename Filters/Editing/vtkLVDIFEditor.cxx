#include "vtkLVDIFEditor.h"

#include "vtkDictionaryVolumeToImage.h"
#include "vtkIdTypeArray.h"
#include "vtkObjectFactory.h"

#include "lvdif/EditLimits.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"
#include "lvdif/VolumeFile.h"

#include <cmath>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>

vtkStandardNewMacro(vtkLVDIFEditor);

// Brush and stroke settings while there is no lvdif::Editor (they survive volume changes).
struct vtkLVDIFEditor::Settings
{
  lvdif::BrushSettings brush;
  lvdif::StrokeSettings stroke;
};

namespace
{
lvdif::BrushSettings& brushOf(lvdif::Editor* ed, lvdif::BrushSettings& fallback)
{
  return ed ? ed->brush : fallback;
}
lvdif::StrokeSettings& strokeOf(lvdif::Editor* ed, lvdif::StrokeSettings& fallback)
{
  return ed ? ed->stroke : fallback;
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
  if (this->Ed)
    return true;
  this->LastError = "no volume: call NewVolume or LoadVolume first";
  this->LastErrorLine = this->LastErrorColumn = 0;
  vtkErrorMacro(<< this->LastError);
  return false;
}

void vtkLVDIFEditor::ReportChanges()
{
  if (!this->Ed)
    return;
  const std::vector<std::int64_t> ids = this->Ed->takeTouchedChunks();
  if (ids.empty())
    return;
  this->LastChanged->SetNumberOfValues(static_cast<vtkIdType>(ids.size()));
  for (std::size_t i = 0; i < ids.size(); ++i)
    this->LastChanged->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(ids[i]));
  this->ImageSource->Modified();
  this->InvokeEvent(ChunksModifiedEvent, this->LastChanged.GetPointer());
  this->Modified();
}

void vtkLVDIFEditor::ReportAll()
{
  const vtkIdType n = this->Volume ? static_cast<vtkIdType>(this->Volume->chunkCount()) : 0;
  this->LastChanged->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
    this->LastChanged->SetValue(i, i);
  this->ImageSource->Modified();
  this->InvokeEvent(ChunksModifiedEvent, this->LastChanged.GetPointer());
  this->Modified();
}

void vtkLVDIFEditor::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  if (this->Ed)
  {
    this->Brush->brush = this->Ed->brush;
    this->Brush->stroke = this->Ed->stroke;
  }
  this->Ed.reset();
  this->Volume = std::move(volume);
  if (this->Volume)
  {
    this->Ed = std::make_unique<lvdif::Editor>(*this->Volume);
    this->Ed->brush = this->Brush->brush;
    this->Ed->stroke = this->Brush->stroke;
  }
  this->ImageSource->SetVolume(this->Volume);
  this->ReportAll();
}

int vtkLVDIFEditor::NewVolume(int nx, int ny, int nz, bool filled)
{
  return this->Guard("NewVolume", [&] {
    lvdif::VolumeOptions o;
    o.dims = { nx, ny, nz };
    o.chunkEdge = this->ChunkEdge;
    o.bandWidth = static_cast<float>(this->BandWidth);
    auto v = std::make_shared<lvdif::DictionaryVolume>(o);
    if (filled)
    {
      const lvdif::Rgba c = brushOf(this->Ed.get(), this->Brush->brush).color;
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
    std::shared_ptr<lvdif::DictionaryVolume> v = lvdif::loadVolume(path);
    this->SetVolume(std::move(v));
  });
}

int vtkLVDIFEditor::SaveVolume(const char* path)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("SaveVolume", [&] {
    lvdif::require(path && *path, "no file name");
    lvdif::saveVolume(*this->Volume, path);
  });
}

void vtkLVDIFEditor::GetDimensions(int dims[3])
{
  for (int i = 0; i < 3; ++i)
    dims[i] = this->Volume ? static_cast<int>(this->Volume->dims()[i]) : 0;
}

int vtkLVDIFEditor::GetNumberOfChunks()
{
  return this->Volume ? static_cast<int>(this->Volume->chunkCount()) : 0;
}

// ---- brush settings -----------------------------------------------------------

void vtkLVDIFEditor::SetOperation(int op)
{
  if (op < OperationAdd || op > OperationPaint)
  {
    vtkErrorMacro(<< "operation " << op << " is not 0 (add), 1 (subtract) or 2 (paint)");
    return;
  }
  brushOf(this->Ed.get(), this->Brush->brush).op = static_cast<lvdif::BrushOp>(op);
  this->Modified();
}

int vtkLVDIFEditor::GetOperation()
{
  return static_cast<int>(brushOf(this->Ed.get(), this->Brush->brush).op);
}

void vtkLVDIFEditor::SetPrimitive(int primitive)
{
  if (primitive != PrimitiveSphere && primitive != PrimitiveCube)
  {
    vtkErrorMacro(<< "primitive " << primitive << " is not 0 (sphere) or 1 (cube)");
    return;
  }
  strokeOf(this->Ed.get(), this->Brush->stroke).shape = static_cast<lvdif::BrushShape>(primitive);
  this->Modified();
}

int vtkLVDIFEditor::GetPrimitive()
{
  return static_cast<int>(strokeOf(this->Ed.get(), this->Brush->stroke).shape);
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
  strokeOf(this->Ed.get(), this->Brush->stroke).radius = r;
  this->Modified();
}

double vtkLVDIFEditor::GetRadius()
{
  return strokeOf(this->Ed.get(), this->Brush->stroke).radius;
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
  brushOf(this->Ed.get(), this->Brush->brush).color = lvdif::Rgba{ static_cast<std::uint8_t>(r),
    static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(b), static_cast<std::uint8_t>(a) };
  this->Modified();
}

int vtkLVDIFEditor::GetColorComponent(int i)
{
  if (i < 0 || i > 3)
    return -1;
  const lvdif::Rgba& c = brushOf(this->Ed.get(), this->Brush->brush).color;
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
  brushOf(this->Ed.get(), this->Brush->brush).blend = k;
  this->Modified();
}

double vtkLVDIFEditor::GetBlend()
{
  return brushOf(this->Ed.get(), this->Brush->brush).blend;
}

void vtkLVDIFEditor::SetBrushKind(int kind)
{
  if (kind < BrushKindSingle || kind > BrushKindDrill)
  {
    vtkErrorMacro(<< "brush kind " << kind << " is not 0 (single), 1 (basic), 2 (dynamic) or 3 (drill)");
    return;
  }
  strokeOf(this->Ed.get(), this->Brush->stroke).kind = static_cast<lvdif::BrushKind>(kind);
  this->Modified();
}

int vtkLVDIFEditor::GetBrushKind()
{
  return static_cast<int>(strokeOf(this->Ed.get(), this->Brush->stroke).kind);
}

void vtkLVDIFEditor::SetSpacing(double s)
{
  const std::string bad = numberProblem(s, lvdif::EditLimits::MinSpacing, lvdif::EditLimits::MaxSize, "spacing", false);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  strokeOf(this->Ed.get(), this->Brush->stroke).spacing = s;
  this->Modified();
}

double vtkLVDIFEditor::GetSpacing()
{
  return strokeOf(this->Ed.get(), this->Brush->stroke).spacing;
}

void vtkLVDIFEditor::SetMinRadius(double r)
{
  const std::string bad = numberProblem(r, 0, lvdif::EditLimits::MaxSize, "minimum radius", true);
  if (!bad.empty())
  {
    vtkErrorMacro(<< bad);
    return;
  }
  strokeOf(this->Ed.get(), this->Brush->stroke).minRadius = r;
  this->Modified();
}

double vtkLVDIFEditor::GetMinRadius()
{
  return strokeOf(this->Ed.get(), this->Brush->stroke).minRadius;
}

// ---- edits ----------------------------------------------------------------------

int vtkLVDIFEditor::Dab(double x, double y, double z)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("Dab", [&] {
    lvdif::Dab d;
    d.shape = this->Ed->stroke.shape;
    d.center = { x, y, z };
    d.radius = this->Ed->stroke.radius;
    this->Ed->dab(d);
  });
}

int vtkLVDIFEditor::BeginStroke()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("BeginStroke", [&] { this->Ed->beginStroke(); });
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
    this->Ed->addSample(s);
  });
}

int vtkLVDIFEditor::EndStroke()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("EndStroke", [&] { this->Ed->endStroke(); });
}

bool vtkLVDIFEditor::IsStrokeOpen()
{
  return this->Ed && this->Ed->strokeOpen();
}

int vtkLVDIFEditor::Undo()
{
  if (!this->RequireVolume())
    return 0;
  bool done = false;
  const int ok = this->Guard("Undo", [&] { done = this->Ed->undo(); });
  return ok && done ? 1 : 0;
}

int vtkLVDIFEditor::Redo()
{
  if (!this->RequireVolume())
    return 0;
  bool done = false;
  const int ok = this->Guard("Redo", [&] { done = this->Ed->redo(); });
  return ok && done ? 1 : 0;
}

bool vtkLVDIFEditor::CanUndo()
{
  return this->Ed && !this->Ed->strokeOpen() && this->Ed->undoStack().canUndo();
}

bool vtkLVDIFEditor::CanRedo()
{
  return this->Ed && !this->Ed->strokeOpen() && this->Ed->undoStack().canRedo();
}

int vtkLVDIFEditor::GetUndoCount()
{
  return this->Ed ? static_cast<int>(this->Ed->undoStack().undoCount()) : 0;
}

// ---- recorder and player ------------------------------------------------------------

int vtkLVDIFEditor::StartRecording()
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("StartRecording", [&] { this->Ed->startRecording(); });
}

bool vtkLVDIFEditor::IsRecording()
{
  return this->Ed && this->Ed->recording();
}

int vtkLVDIFEditor::StopRecording(const char* path)
{
  if (!this->RequireVolume())
    return 0;
  return this->Guard("StopRecording", [&] {
    const lvdif::Recording r = this->Ed->stopRecording();
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
    this->Ed->play(r);
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
    o.targetSize = static_cast<double>(this->Volume->dims()[0]);
    std::ifstream in(path);
    if (!in)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, std::string("cannot open '") + path + "'");
    const lvdif::CsvImportResult r = lvdif::importOriginalCsv(in, o);
    if (r.skippedRows)
      vtkWarningMacro(<< r.skippedRows << " broken rows skipped; first: " << r.firstProblem);
    this->Ed->play(r.recording);
  });
}

// ---- scripts -------------------------------------------------------------------------------

int vtkLVDIFEditor::RunScript(const char* text)
{
  const std::string source = text ? text : "";
  return this->Guard("RunScript", [&] {
    lvdif::ScriptOptions o;
    o.canvas.chunkEdge = this->ChunkEdge;
    o.canvas.bandWidth = static_cast<float>(this->BandWidth);
    lvdif::ScriptRunner runner(o);
    if (this->Ed)
      runner.attach(*this->Ed);
    struct Adopt // a `canvas` volume replaces ours even when the script fails later
    {
      vtkLVDIFEditor* Self;
      lvdif::ScriptRunner& Runner;
      ~Adopt()
      {
        std::unique_ptr<lvdif::DictionaryVolume> made;
        lvdif::Editor* used = this->Runner.editor();
        lvdif::BrushSettings b;
        lvdif::StrokeSettings s;
        if (used)
        {
          b = used->brush;
          s = used->stroke;
        }
        made = this->Runner.takeVolume();
        if (made)
        {
          made->takeDirtyChunks();
          this->Self->Brush->brush = b;
          this->Self->Brush->stroke = s;
          this->Self->Ed.reset(); // SetVolume must not copy the old editor's settings over
          this->Self->SetVolume(std::shared_ptr<lvdif::DictionaryVolume>(std::move(made)));
        }
      }
    } adopt{ this, runner };
    runner.run(source);
  });
}

int vtkLVDIFEditor::RunScriptFile(const char* path)
{
  std::ifstream in(path ? path : "");
  if (!in)
  {
    this->LastError = std::string("RunScriptFile: cannot open '") + (path ? path : "") + "'";
    this->LastErrorLine = this->LastErrorColumn = 0;
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return this->RunScript(text.str().c_str());
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
