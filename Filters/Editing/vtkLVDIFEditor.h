/**
 * @class   vtkLVDIFEditor
 * @brief   the editing engine as a VTK object: holds one lvdif::EditSession
 *
 * A thin holder of lvdif::EditSession (the volume, on the host or resident on
 * the GPU; brushes, strokes, undo/redo, recorder and player, scripts; the mesh
 * chunks each edit invalidates) with plain scalar and string arguments, so that
 * Python and ParaView drive the same session as the Qt app (docs/EDITING.md):
 *
 * @code{.py}
 * from lvdif import vtkLVDIFEditor
 * ed = vtkLVDIFEditor()
 * ed.NewVolume(128, 128, 128, False)
 * ed.SetOperationToAdd(); ed.SetRadius(10); ed.SetColor(255, 0, 0, 255)
 * ed.Dab(64, 64, 64)
 * ed.Undo()
 * if not ed.RunScript("sphere 64 64 64 20"): print(ed.GetLastError())
 * image = ed.GetImageSource()   # a vtkImageAlgorithm producing `sdf` and `rgba`
 * @endcode
 *
 * Every method that may fail returns 1 on success and 0 on failure; the
 * message is then in GetLastError() (and, for scripts, the line and column in
 * GetLastErrorLine()/GetLastErrorColumn()). Failures lose nothing: the volume
 * is unchanged by a refused call (a script that fails half way keeps the edits
 * it made before the error, each undoable).
 *
 * Events: after every call that changed voxels the editor invokes
 * ChunksModifiedEvent with call data a vtkIdTypeArray* of the mesh chunks whose
 * meshes the call invalidated (increasing; mesh chunk id = cx + ncx * (cy + ncy
 * * cz) over chunks of GetMeshChunkEdge() cells, the ids of
 * lvdif::ChunkedMarchingCubes / vtkChunkedMarchingCubes' chunk_id), then
 * vtkCommand::ModifiedEvent. The image source is marked modified as well.
 * NewVolume and LoadVolume report every mesh chunk.
 */
#ifndef vtkLVDIFEditor_h
#define vtkLVDIFEditor_h

#include "lvdifFiltersEditingModule.h"
#include "vtkCommand.h"
#include "vtkObject.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <string>

class vtkDictionaryVolumeToImage;
class vtkIdTypeArray;

namespace lvdif
{
class DictionaryVolume;
class Editor;
class EditSession;
}

class LVDIFFILTERSEDITING_EXPORT vtkLVDIFEditor : public vtkObject
{
public:
  static vtkLVDIFEditor* New();
  vtkTypeMacro(vtkLVDIFEditor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Invoked with a vtkIdTypeArray* of the invalidated mesh chunk ids.
  enum
  {
    ChunksModifiedEvent = vtkCommand::UserEvent + 7001
  };
  enum Operation
  {
    OperationAdd = 0,
    OperationSubtract = 1,
    OperationPaint = 2
  };
  enum Primitive
  {
    PrimitiveSphere = 0,
    PrimitiveCube = 1
  };
  enum BrushKind
  {
    BrushKindSingle = 0,
    BrushKindBasic = 1,
    BrushKindDynamic = 2,
    BrushKindDrill = 3
  };

  ///@{
  /// A new empty (filled = false: all outside) or solid (filled = true) volume
  /// of nx x ny x nz voxels with ChunkEdge and BandWidth; clears undo/redo.
  int NewVolume(int nx, int ny, int nz, bool filled);
  /// Reads a volume file of any format of the file registry (LVDIFFiles.h,
  /// by extension: .lvdv, .lvdvp, .bv, .vti, .vdb with OpenVDB); clears undo/redo.
  int LoadVolume(const char* path);
  /// Writes the volume by extension through the same registry, crash-safely
  /// (an unknown extension or an unwritable place is refused before any work).
  int SaveVolume(const char* path);
  bool HasVolume() const { return this->Session != nullptr; }
  /// Dimensions of the volume (0 0 0 without one).
  void GetDimensions(int dims[3]);
  int GetNumberOfChunks();
  ///@}

  ///@{
  /// Where volumes live and edits run from the next NewVolume/LoadVolume/SetVolume on:
  /// 0 auto (the GPU when one can be used, the default), 1 CPU, 2 CUDA (the GPU, else
  /// the CPU with a notice). GetNotice() says why a volume stayed on the CPU ("" otherwise).
  void SetDevice(int device);
  vtkGetMacro(Device, int);
  void SetDeviceToAuto() { this->SetDevice(0); }
  void SetDeviceToCpu() { this->SetDevice(1); }
  void SetDeviceToCuda() { this->SetDevice(2); }
  bool IsOnDevice();
  const char* GetNotice();
  /// Cells per mesh chunk edge of the ids in ChunksModifiedEvent (0 without a volume).
  int GetMeshChunkEdge();
  ///@}

  ///@{
  /// Options of volumes made by NewVolume (chunk edge a power of two 4..256, band in voxels).
  vtkSetMacro(ChunkEdge, int); // the one rule (docs/USER_GUIDE.md): refused when used, no clamp
  vtkGetMacro(ChunkEdge, int);
  vtkSetMacro(BandWidth, double); // 0: no band; negative or NaN refused (LVDIFVolumeBridge::BandOption)
  vtkGetMacro(BandWidth, double);
  ///@}

  ///@{
  /// Brush settings (kept across volumes). Out-of-range values are refused
  /// (vtkErrorMacro) and leave the setting as it was.
  void SetOperation(int op);
  int GetOperation();
  void SetOperationToAdd() { this->SetOperation(OperationAdd); }
  void SetOperationToSubtract() { this->SetOperation(OperationSubtract); }
  void SetOperationToPaint() { this->SetOperation(OperationPaint); }
  void SetPrimitive(int primitive);
  int GetPrimitive();
  void SetPrimitiveToSphere() { this->SetPrimitive(PrimitiveSphere); }
  void SetPrimitiveToCube() { this->SetPrimitive(PrimitiveCube); }
  /// Sphere radius or cube half edge, voxels (> 0).
  void SetRadius(double r);
  double GetRadius();
  void SetColor(int r, int g, int b, int a);
  void SetColor(int r, int g, int b) { this->SetColor(r, g, b, 255); }
  /// Component i (0..3) of the brush colour.
  int GetColorComponent(int i);
  /// Smooth blend radius k in voxels (0 = hard CSG).
  void SetBlend(double k);
  double GetBlend();
  void SetBrushKind(int kind);
  int GetBrushKind();
  /// Stroke interpolation interval in voxels (> 0).
  void SetSpacing(double s);
  double GetSpacing();
  /// Radius at the end of a dynamic stroke and floor for pressure (> 0).
  void SetMinRadius(double r);
  double GetMinRadius();
  ///@}

  ///@{
  /// Edits, each one undo step (a stroke from BeginStroke to EndStroke is one).
  /// Coordinates are voxel indices (x fastest). Pressure < 0 means "none".
  int Dab(double x, double y, double z);
  int BeginStroke();
  int AddSample(double x, double y, double z, double pressure);
  int AddSample(double x, double y, double z) { return this->AddSample(x, y, z, -1.0); }
  int EndStroke();
  bool IsStrokeOpen();
  ///@}

  ///@{
  int Undo();
  int Redo();
  bool CanUndo();
  bool CanRedo();
  int GetUndoCount();
  ///@}

  ///@{
  /// Recorder and player (docs/RECORDING.md).
  int StartRecording();
  bool IsRecording();
  /// Stops and writes the recording (path may be empty/null: stop and discard).
  int StopRecording(const char* path);
  int PlayRecording(const char* path);
  /// Imports the original LVDIF CSV recording and plays it. originalSize is
  /// the edge of the volume it was recorded on (0: read it from a
  /// Recording_<N>_... file name); coordinates scale to this volume's x edge.
  int ImportOriginalCsv(const char* path, double originalSize);
  int ImportOriginalCsv(const char* path) { return this->ImportOriginalCsv(path, 0.0); }
  ///@}

  ///@{
  /// Runs a script (docs/SCRIPTING.md) on this volume through this editor
  /// (undoable, recorded when recording). A `canvas` command replaces the
  /// volume. RunScriptFile reads the script from a file.
  int RunScript(const char* text);
  int RunScriptFile(const char* path);
  ///@}

  ///@{
  /// The last failure's message ("" after a success) and, for script errors,
  /// its 1-based line and column (0 otherwise).
  const char* GetLastError() { return this->LastError.c_str(); }
  int GetLastErrorLine() { return this->LastErrorLine; }
  int GetLastErrorColumn() { return this->LastErrorColumn; }
  ///@}

  /// Mesh chunk ids reported by the last ChunksModifiedEvent.
  vtkIdTypeArray* GetLastChangedChunks();

  /// An image source sharing this editor's volume (`sdf` and `rgba`); it
  /// follows NewVolume/LoadVolume and is marked modified by every edit.
  vtkDictionaryVolumeToImage* GetImageSource();

#ifndef __VTK_WRAP__
  /// The volume's host copy (synced from the GPU first when it lives there).
  std::shared_ptr<lvdif::DictionaryVolume> GetVolume();
  /// Adopts a volume (clears undo/redo). Throws lvdif::Error for a volume an
  /// edit session refuses (thinner than a canvas), keeping the current one.
  void SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume);
  /// The session (nullptr without a volume), e.g. for collectMeshes() or pump().
  lvdif::EditSession* GetSession() { return this->Session.get(); }
#endif

protected:
  vtkLVDIFEditor();
  ~vtkLVDIFEditor() override;

  /// Runs fn, turning exceptions into LastError; 1 on success.
  template <class F>
  int Guard(const char* what, F&& fn);
  bool RequireVolume();
  void ReportChanges();

  std::unique_ptr<lvdif::EditSession> Session;
  struct Settings;
  std::unique_ptr<Settings> Brush; // while there is no session
  vtkSmartPointer<vtkDictionaryVolumeToImage> ImageSource;
  vtkSmartPointer<vtkIdTypeArray> LastChanged;
  std::string LastError;
  int LastErrorLine = 0;
  int LastErrorColumn = 0;
  int ChunkEdge = 32;
  double BandWidth = 8.0;
  int Device = 0;
  int ImageGeneration = 0; // the session generation the image source shows

private:
  vtkLVDIFEditor(const vtkLVDIFEditor&) = delete;
  void operator=(const vtkLVDIFEditor&) = delete;
};

#endif
