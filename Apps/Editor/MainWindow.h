// The editor window: the VTK view (chunk actors + brush widget), the tool
// panel, menus, the mesh polling timer, autosave and recovery.
#pragma once

#include "EditorOptions.h"
#include "MeshImport.h"
#include "ToolPanel.h"
#include "VolumeDocument.h"

#include <QElapsedTimer>
#include <QMainWindow>

#include "vtkNew.h"
#include "vtkSmartPointer.h"

class QAction;
class StrokeBenchmark;
class QLabel;
class QTimer;
class QVTKOpenGLNativeWidget;
class vtkBrushRepresentation;
class vtkBrushWidget;
class vtkChunkActorManager;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

class MainWindow : public QMainWindow
{
  Q_OBJECT
public:
  explicit MainWindow(const EditorOptions& options);
  ~MainWindow() override;

  VolumeDocument& document() { return this->Doc; }

  // ---- the command-line / test entry points ------------------------------
  bool newCanvas(int nx, int ny, int nz, VolumeDocument::Fill fill);
  bool openVolume(const QString& path);
  /// Converts a mesh file to a volume (vtkMeshToSDF on a worker thread, with a
  /// progress dialog and Cancel); false on error or cancel.
  bool openMesh(const QString& path, const MeshImportSettings& settings);
  bool saveVolume(const QString& path);
  bool exportMesh(const QString& path);
  bool saveScreenshot(const QString& path);
  bool playRecording(const QString& path);
  /// Runs a script (.lvs) or plays a recording (.lvr; .lvrec is accepted too), by extension.
  bool runScript(const QString& path);
  /// A left-drag through display points (VTK display coordinates, origin
  /// bottom-left) sent as interactor events, as a user's mouse would.
  void replayDrag(const QVector<QPointF>& points);
  /// Blocks until every requested chunk is meshed and shown (tests only: the
  /// interactive view never waits).
  void finishMeshing();
  void undo();
  void redo();
  /// The recovery file (autosave target).
  QString recoveryPath() const;
  /// Offers to recover an autosaved volume if one exists; true if recovered.
  bool offerRecovery();
  /// --benchmark-stroke: replays the samples of `path` at their recorded times
  /// through the UI, prints the latency and quits (StrokeBenchmark.h); false
  /// (with a message) if the file cannot be read.
  bool startStrokeBenchmark(const QString& path);

protected:
  void closeEvent(QCloseEvent* event) override;
  /// Tablet pressure: the view's tablet events carry it; the mouse events Qt
  /// synthesises from them then drive the brush as usual.
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  void buildMenus();
  void applyBrushState();
  void pollMeshes();
  /// After a brush sample: waits a few ms for its chunks, then installs them.
  void settleMeshes();
  void autosave();
  void resetView();
  void volumeReplaced();
  void updateTitle();
  bool maybeSave();
  void onBrushSample(const double* sample);
  void onStrokeStart();
  void onStrokeEnd();
  void newDialog();
  void openDialog();
  void openMeshDialog();
  bool saveAsDialog();
  void exportDialog();
  void screenshotDialog();
  void scriptDialog();
  void toggleRecording(bool on);
  void showError(const QString& what, const std::exception& e);

  EditorOptions Options;
  VolumeDocument Doc;
  ToolPanel* Tools = nullptr;
  QVTKOpenGLNativeWidget* View = nullptr;
  QLabel* Status = nullptr;
  QTimer* MeshTimer = nullptr;
  QTimer* AutosaveTimer = nullptr;
  QAction* OpenMeshAction = nullptr;
  MeshImportSettings MeshSettings;
  QElapsedTimer Clock;
  vtkNew<vtkGenericOpenGLRenderWindow> RenderWindow;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkChunkActorManager> Chunks;
  vtkNew<vtkBrushRepresentation> BrushRep;
  vtkNew<vtkBrushWidget> Brush;
  bool ViewInitialized = false;
  bool Painting = false;
  double Pressure = -1; // last tablet pressure in [0, 1]; -1: no tablet in use
  StrokeBenchmark* Bench = nullptr; // set while --benchmark-stroke runs
  friend class StrokeBenchmark;
};
