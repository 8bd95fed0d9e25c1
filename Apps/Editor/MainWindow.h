// The editor window: the VTK view (chunk actors + brush widget), the tool
// panel, menus, the mesh polling timer, autosave and recovery.
#pragma once

#include "EditorBrush.h"
#include "EditorOptions.h"
#include "EditorRenderWindow.h"
#include "vtkGradientBackgroundRenderer.h"
#include "MeshImport.h"
#include "ToolPanel.h"
#include "VolumeDocument.h"

#include <QDateTime>
#include <QElapsedTimer>
#include <QMainWindow>

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

class QLockFile;

#include "vtkNew.h"
#include "vtkSmartPointer.h"

class vtkTexture;

class QAction;
class QImage;
class QActionGroup;
class QMenu;
class vtkActor;
class QLabel;
class QTimer;
class QVTKOpenGLNativeWidget;
class QVTKOpenGLWindow;
class vtkRenderWindowInteractor;
class vtkBrushRepresentation;
class vtkBrushWidget;
class vtkChunkActorManager;
class vtkGenericOpenGLRenderWindow;
class vtkPartialRedrawCuller;
class vtkRenderer;

/// What one frame that showed newly finished chunk meshes installed (the
/// meshesShown signal): the chunks in the order their meshes were collected (a
/// chunk may come twice, the later mesh shown), when each mesh's input was read
/// (it shows every edit made before that time and none after;
/// lvdif::EditSession::collectMeshes), and when the install began.
struct ShownMeshes
{
  using TimePoint = std::chrono::steady_clock::time_point;
  std::vector<std::int64_t> chunks;
  std::vector<TimePoint> gatheredAt;
  std::vector<int> levels; // per mesh: 0 full resolution, 1 coarse (a stroke's level of detail)
  TimePoint installStart; // the first install since the last frame (brush samples share a frame)
  TimePoint renderStart;  // the frame's Render() call
  /// Whether the frame was drawn: false when every mesh equalled the one its
  /// chunk showed (vtkChunkActorManager left them as they were), so the view
  /// already showed them and nothing was rendered.
  bool drawn = true;
};

/// Where the UI thread's time went during brush input (summed since
/// resetStrokeProfile; --benchmark-stroke prints it): milliseconds and counts.
struct StrokeProfile
{
  double brushMs = 0;    // applying samples (Core editor: dabs, undo step, re-mesh request)
  double settleMs = 0;   // waiting for the worker after a sample
  double convertMs = 0;  // chunk meshes to vtkPolyData
  double setChunkMs = 0; // actor updates (corner colours, mapper input, damage)
  double renderMs = 0;   // Render() of frames with new meshes (without glFinish)
  int samples = 0;
  int meshes = 0;        // chunk meshes installed
  int unchangedMeshes = 0; // of those, equal to the chunk's shown mesh: left as shown
  int undrawnFrames = 0;   // frames whose meshes were all unchanged: not rendered
  int frames = 0;
  int settleTimeouts = 0; // frames whose settle wait ended before the worker was idle
};

/// Whether a text is a recording (its first line that is no comment is
/// LVDIF-RECORDING), and whether a file --script / Run script gets is a script
/// to run (false: a recording to play, by extension or first line).
bool isRecordingText(const std::string& source);
bool isScriptFile(const QString& path);

class MainWindow : public QMainWindow
{
  Q_OBJECT
public:
  explicit MainWindow(const EditorOptions& options);
  ~MainWindow() override;

  VolumeDocument& document() { return this->Doc; }
  /// The chunk actors of the view.
  vtkChunkActorManager* chunkActors() { return this->Chunks; }
  /// The view's render window and interactor.
  EditorRenderWindow* renderWindow() { return this->RenderWindow; }
  vtkRenderWindowInteractor* viewInteractor() const;
  /// The view's widget in the window's layout (the QVTKOpenGLNativeWidget, or
  /// by default the container of its QVTKOpenGLWindow) and the object
  /// that takes its mouse events (the widget, or that window).
  QWidget* viewWidget() { return this->ViewWidget; }
  QObject* viewInputTarget();

  // ---- file and edit operations: the menus call these, so does the command line
  bool newCanvas(int nx, int ny, int nz, VolumeDocument::Fill fill);
  /// `untitled`: a recovered autosave, opened as a volume with no file yet.
  bool openVolume(const QString& path, bool untitled = false);
  /// Converts a mesh file to a volume (vtkMeshToSDF on a worker thread, with a
  /// progress dialog and Cancel); false on error or cancel.
  bool openMesh(const QString& path, const MeshImportSettings& settings);
  bool saveVolume(const QString& path);
  /// Waits for every requested chunk mesh, then writes the merged surface.
  bool exportMesh(const QString& path);
  /// The view as a PNG (the frame shown now: chunks still being meshed are missing).
  bool saveScreenshot(const QString& path);
  /// The whole window as a PNG (the user guide's pictures).
  bool saveWindowShot(const QString& path);
  bool playRecording(const QString& path);
  /// Runs a script (.lvs) or plays a recording (.lvr, .lvrec, or any file whose
  /// first line is LVDIF-RECORDING).
  bool runScript(const QString& path);
  /// Reads a matcap image (PNG, JPG, ...) and shows the surface with it
  /// (Matcap shading); an unreadable file is reported and changes nothing.
  bool loadMatcap(const QString& path);
  /// The shortcut table of Help > Keyboard shortcuts (HTML).
  QString shortcutHelp() const;
  /// Undoes the last step; false when there was none.
  bool undo();
  void redo();
  /// This editor's recovery file (autosave target): its slot in the recovery
  /// folder, claimed on first use (claimRecoverySlot).
  QString recoveryPath();
  /// Offers to recover an autosaved volume if one exists; true if recovered.
  bool offerRecovery();
  /// How many errors were reported so far (message boxes, or lines of a batch
  /// run): a batch run that reported one exits non-zero, whatever step (a
  /// key's save, a drag's brush) it came from.
  int errorCount() const { return this->Errors; }
  /// Whether one of them was a cancel (lvdif::ErrorCode::Cancelled: Ctrl-C in
  /// a batch run's mesh conversion): the run then exits with 130, as the CLI's.
  bool cancelled() const { return this->Cancelled; }

public slots:
  // ---- brush input --------------------------------------------------------
  // The view's brush widget calls these for a left-drag on the surface; any
  // other source of 3D samples (a recorded stroke: --benchmark-stroke) drives
  // the window the same way. The tool is the tool panel's, with Ctrl/Shift as
  // the view's interactor saw them at the start.
  /// Starts a stroke; false if none could start (no volume, or an error shown).
  bool beginStroke();
  /// One sample, double[4]: world x, y, z and the brush radius in world units.
  /// Applies it, waits a few ms at most for its meshes, and shows them in the
  /// next frame (drawn when the event loop is free).
  void addBrushSample(const double* sample);
  void endStroke();
  /// The level of detail of strokes (--stroke-lod, View > Stroke level of
  /// detail): auto, on or off; from the next stroke on.
  void setStrokeLod(const QString& mode);
  const QString& strokeLod() const { return this->Options.strokeLod; }
  /// When the last stroke ended and its coarse meshes were asked for again at
  /// full resolution, and how many (0: none were coarse).
  std::chrono::steady_clock::time_point refineRequestedAt() const { return this->RefineAt; }
  std::size_t refinedChunks() const { return this->Refined; }

  // ---- the view -------------------------------------------------------------
  /// Installs the chunk meshes finished since the last call as actors and
  /// renders (the 15 ms mesh timer calls it); never waits for the meshing.
  void showFinishedMeshes();

  const StrokeProfile& strokeProfile() const { return this->Profile; }
  void resetStrokeProfile() { this->Profile = StrokeProfile(); }

signals:
  /// After the render of a frame that installed newly finished chunk meshes
  /// (before Qt composes the widget): for latency measurements (--benchmark-stroke).
  void meshesShown(const ShownMeshes& shown);

protected:
  void closeEvent(QCloseEvent* event) override;
  /// Tablet pressure: the view's tablet events carry it; the mouse events Qt
  /// synthesises from them then drive the brush as usual.
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  /// Recovery slots: recovery.lvdv, recovery-2.lvdv, ... each guarded by a
  /// lock file that the editor using it holds while it runs, so that two
  /// editors never autosave into, offer or delete each other's file.
  /// skip: a slot not to take (an autosave the user chose to keep).
  void claimRecoverySlot(const QString& skip = QString());
  QString RecoveryFile;
  std::unique_ptr<QLockFile> RecoveryLock;
  /// The recovery file is this session's (it autosaved, or recovered the
  /// file): a normal end deletes it, and only then.
  bool RecoveryOwned = false;

  void buildMenus();
  // MainWindowUi.cpp: toolbar, shortcuts, help, view, recent files, status, cursor, preview
  void buildTools();
  void buildViewMenu(QMenu* view);
  void buildHelpMenu();
  void syncToolActions();
  void scaleRadius(double factor);
  void volumeBounds(double b[6]);
  /// What the home view and the view presets show whole: the shown surface's
  /// bounds, or the volume's box while none is shown.
  void homeTarget(double b[6]);
  /// -1: home (the command line's camera, Y up); else Front, Back, Right, Left, Top, Bottom.
  void setViewPreset(int preset);
  void frameSurface();
  void setOrthographic(bool on);
  /// 0 smooth, 1 flat, 2 wireframe, 3 matcap (the image in Matcap; clay by default).
  void setShading(int mode);
  void loadMatcapDialog();
  void addRecentFile(const QString& path);
  void rebuildRecentMenu();
  void updateStatus();
  /// The tool a stroke started now would use (Shift: smooth; Ctrl: add <-> subtract).
  int effectiveOp() const;
  void updateCursor();
  /// Dynamic strokes: the tapered tube the stroke would make (reset: remove it).
  void updatePreview(const double* world, bool reset = false);
  bool keyFilter(QEvent* event);
  void onGrabMove();
  void applyBrushState();
  /// The frame after brush samples (when the event loop is free: one for all
  /// samples applied by then): hands their chunks to the worker at once, waits
  /// a little for the meshes, installs them and renders.
  void frameAfterSamples();
  /// Installs the chunk meshes finished since the last call as actors (no render).
  void installFinishedMeshes();
  /// Renders if meshes were installed since the last frame; emits meshesShown.
  void drawFrame();
  void autosave();
  void resetView();
  /// While a new volume's first meshes come in: the home view again as the
  /// surface grows, unless the camera was moved or a stroke began.
  void settleHome();
  void volumeReplaced();
  void updateTitle();
  bool maybeSave();
  void newDialog();
  void openDialog();
  void openMeshDialog();
  bool saveAsDialog();
  void exportDialog();
  void screenshotDialog();
  void scriptDialog();
  void toggleRecording(bool on);
  /// Stop: asks for the recording's file, then stops and saves it; Cancel
  /// (or a file that cannot be written) keeps it recording. True if stopped.
  bool stopAndSaveRecording();
  /// Before another volume replaces this one, or the window closes: a
  /// recording in progress is stopped and saved as Stop does (the new session
  /// would end it unsaved); false if that was cancelled (the caller stops).
  bool finishRecording();
  void showError(const QString& what, const std::exception& e);

  EditorOptions Options;
  VolumeDocument Doc;
  ToolPanel* Tools = nullptr;
  // The view: a native window of its own (QVTKOpenGLWindow, in ViewWidget, a
  // window container) that presents only itself after a frame, or with
  // --widget-view a widget that Qt composes into the whole window after each
  // frame (QVTKOpenGLNativeWidget: under Xvfb about 5 ms more between a
  // frame's render and the next brush sample); exactly one of them is set.
  QVTKOpenGLNativeWidget* View = nullptr;
  QVTKOpenGLWindow* NativeView = nullptr;
  QWidget* ViewWidget = nullptr;
  void updateView();
  QImage grabView();
  QLabel* Status = nullptr;
  QTimer* MeshTimer = nullptr;
  QTimer* FrameTimer = nullptr; // the frame after brush samples (coalesces a backlog of samples)
  ShownMeshes Pending;          // installed since the last frame
  bool PendingChanged = false;  // some chunk actor or the camera changed since the last frame
  StrokeProfile Profile;
  double LastRenderMs = 0; // Render() of the last frame with new meshes
  QTimer* AutosaveTimer = nullptr;
  QTimer* StillTimer = nullptr; // the full redraw after interactive (partial, multisampled) frames
  QAction* OpenMeshAction = nullptr;
  MeshImportSettings MeshSettings;
  QElapsedTimer Clock;
  vtkNew<EditorRenderWindow> RenderWindow;
  vtkNew<vtkGradientBackgroundRenderer> Renderer; // its gradient background's quad kept between frames
  vtkNew<vtkChunkActorManager> Chunks;
  vtkNew<vtkPartialRedrawCuller> Redraw; // partial redraws while the camera stands still
  vtkNew<EditorBrushRepresentation> BrushRep; // on the surface, or on the solid's box (EditorBrush.h)
  vtkNew<vtkBrushWidget> Brush;
  bool ViewInitialized = false;
  // The home view of a new volume settles as its meshes come (settleHome):
  // the target it fitted and the camera it left.
  bool HomeSettling = false;
  double HomeBounds[6] = { 0, 0, 0, 0, 0, 0 };
  double HomeCamera[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  bool Painting = false;
  /// After a stroke (or its failure): its held requests to the worker, then
  /// full resolution for the chunks it meshed coarsely.
  void finishStrokeMeshing();
  std::chrono::steady_clock::time_point RefineAt;
  std::size_t Refined = 0;
  QActionGroup* StrokeLodActions = nullptr;
  double Pressure = -1; // last tablet pressure in [0, 1]; -1: no tablet in use
  QActionGroup* ToolActions = nullptr;
  std::vector<QAction*> ShortcutActions;
  QAction* OrthoAction = nullptr;
  QMenu* RecentMenu = nullptr;
  QLabel* VolumeStatus = nullptr;
  QDateTime LastEdit;
  vtkSmartPointer<vtkActor> Preview;
  std::vector<std::array<double, 3>> PreviewPoints;
  int Shading = 0;
  QActionGroup* ShadingActions = nullptr;
  vtkSmartPointer<vtkTexture> Matcap; // the matcap image: clay (made at start) or the user's
  int CursorOp = -1;
  int Errors = 0;           // showError calls
  bool Cancelled = false;   // one of them was lvdif::ErrorCode::Cancelled
  bool Grabbing = false;    // a Grab stroke: samples on the view plane through its start
  double GrabDepth = 0;     // display depth of the grab's start point
};
