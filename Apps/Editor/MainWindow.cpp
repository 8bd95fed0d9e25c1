// MainWindow: the window made (the view, its redraw culler and timers, the
// brush widget, the tool panel), the menus, the brush state, the camera's home
// view, the volume's new, open, import, save, undo and redo, and the title.
#include "MainWindow.h"
#include "Matcap.h"
#include "vtkTexture.h"


#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"

#include "LVDIFFiles.h"
#include "ProgressBar.h" // the CLI's (Apps/CLI)
#include "vtkBrushRepresentation.h"
#include "vtkBrushWidget.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCuller.h"
#include "vtkCullerCollection.h"
#include "vtkChunkActorManager.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QImage>
#include <QInputDialog>
#include <QLabel>
#include <QLockFile>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QTabletEvent>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <QVTKOpenGLWindow.h>

#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

MainWindow::MainWindow(const EditorOptions& options)
  : Options(options)
{
  this->Clock.start();
  if (options.nativeView)
  {
    // presented alone: Qt does not compose the whole window after each frame
    this->NativeView = new QVTKOpenGLWindow();
    this->ViewWidget = QWidget::createWindowContainer(this->NativeView, this); // owns it
    this->ViewWidget->setFocusPolicy(Qt::StrongFocus);
  }
  else
  {
    this->View = new QVTKOpenGLNativeWidget(this);
    this->ViewWidget = this->View;
  }
  // Software OpenGL (Mesa llvmpipe) rasterizes a multisampled frame about
  // twice as slowly: --samples 0 trades the edges' smoothing for that.
  if (options.samples >= 0)
    this->RenderWindow->SetMultiSamples(options.samples);
  if (this->NativeView)
    this->NativeView->setRenderWindow(this->RenderWindow);
  else
    this->View->setRenderWindow(this->RenderWindow);
  this->RenderWindow->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.16, 0.17, 0.2);
  this->Renderer->SetBackground2(0.05, 0.05, 0.07);
  this->Renderer->GradientBackgroundOn();
  this->Renderer->SetKeepBackgroundActor(!options.stockBackground);
  // While the camera stands still (a stroke, the cursor moving over the
  // surface) a frame redraws only the screen region that changed, with the
  // chunk actors that cover it: the cost of a stroke's frame follows the
  // brush, not the model's size. The picture equals a full redraw's.
  this->Redraw->SetEnabled(!options.fullRedraw);
  // First, so that the renderer's frustum culler then sees only the props a
  // partial frame draws (each culler asks every prop it is given for its bounds).
  {
    std::vector<vtkSmartPointer<vtkCuller>> others;
    vtkCollectionSimpleIterator it;
    this->Renderer->GetCullers()->InitTraversal(it);
    while (vtkCuller* c = this->Renderer->GetCullers()->GetNextCuller(it))
      others.emplace_back(c);
    this->Renderer->GetCullers()->RemoveAllItems();
    this->Renderer->AddCuller(this->Redraw);
    for (vtkCuller* c : others)
      this->Renderer->AddCuller(c);
  }
  this->RenderWindow->SetPartialRedraw(this->Redraw); // and presents only that region
  this->setCentralWidget(this->ViewWidget);
  // tablet events and keys: those of the widget view; a native view's go to
  // its window (the container gets keys only when it has the focus itself)
  this->ViewWidget->installEventFilter(this);
  if (this->NativeView)
    this->NativeView->installEventFilter(this);
  this->resize(options.width, options.height);

  this->Chunks->SetRenderer(this->Renderer);
  this->Chunks->SetRedrawCuller(this->Redraw); // a re-meshed chunk damages only around its changed triangles
  this->Chunks->SetDrawRangeTriangles(options.drawRangeTriangles); // a partial frame draws only the ranges it reaches
  this->Chunks->GetProperty()->SetSpecular(0.25);
  this->Chunks->GetProperty()->SetSpecularPower(25);
  this->Chunks->SetInterpolationMode(
    options.perVertexColor ? vtkTetrahedralColorMapper::PerVertex : vtkTetrahedralColorMapper::Tetrahedral);
  this->Matcap = matcapTexture(makeClayMatcap());

  this->Brush->SetInteractor(this->viewInteractor());
  this->Brush->SetRepresentation(this->BrushRep);
  auto observe = [this](unsigned long event, auto handler) {
    vtkNew<vtkCallbackCommand> cb;
    cb->SetClientData(new std::function<void(void*)>(handler));
    cb->SetCallback([](vtkObject*, unsigned long, void* cd, void* data) {
      (*static_cast<std::function<void(void*)>*>(cd))(data);
    });
    cb->SetClientDataDeleteCallback([](void* cd) { delete static_cast<std::function<void(void*)>*>(cd); });
    this->Brush->AddObserver(event, cb);
  };
  observe(vtkBrushWidget::BrushSampleEvent, [this](void* d) { this->addBrushSample(static_cast<double*>(d)); });
  observe(vtkCommand::StartInteractionEvent, [this](void*) { this->beginStroke(); });
  observe(vtkCommand::EndInteractionEvent, [this](void*) { this->endStroke(); });
  observe(vtkCommand::InteractionEvent, [this](void*) { this->onGrabMove(); });
  observe(vtkBrushWidget::RadiusChangedEvent, [this](void* d) {
    const double world = *static_cast<double*>(d);
    if (this->Doc.hasVolume())
    {
      this->Tools->setRadius(world / this->Doc.volume().options().spacing[0]);
      this->applyBrushState();
    }
  });

  this->Tools = new ToolPanel(this);
  for (int i = 0; i < ToolCount; ++i)
    if (options.op.compare(toolInfo(i).name, Qt::CaseInsensitive) == 0)
      this->Tools->setOp(i); // with the tool's own strength and falloff
  BrushState s = this->Tools->state();
  s.shape = options.shape == "cube" ? 1 : 0;
  s.kind = options.kind == "dynamic" ? 2 : (options.kind == "drill" ? 3 : 1);
  s.radius = options.radius;
  if (!options.color.isEmpty())
    s.color = QColor(options.color);
  for (int a = 0; a < 3; ++a)
    s.mirror[a] = options.mirror.contains(QChar("xyz"[a]));
  this->Tools->setState(s);
  // --strength and --falloff are the brush's, whatever tool is picked: they set
  // only the --op tool's, so `--keys M --strength 1` smoothed at Smooth's own 0.5
  this->Tools->setEveryTool(options.strength, options.falloff);
  auto* dock = new QDockWidget("Brush", this);
  dock->setObjectName("BrushDock");
  dock->setWidget(this->Tools);
  this->addDockWidget(Qt::RightDockWidgetArea, dock);
  connect(this->Tools, &ToolPanel::changed, this, &MainWindow::applyBrushState);
  connect(this->Tools, &ToolPanel::changed, this, &MainWindow::syncToolActions);
  connect(this->Tools, &ToolPanel::undoRequested, this, &MainWindow::undo);
  connect(this->Tools, &ToolPanel::redoRequested, this, &MainWindow::redo);
  connect(this->Tools, &ToolPanel::recordToggled, this, &MainWindow::toggleRecording);
  connect(this->Tools, &ToolPanel::playRequested, this, &MainWindow::scriptDialog);

  this->Status = new QLabel(this);
  this->Status->setObjectName("meshStatus"); // "N chunks, M triangles"
  this->VolumeStatus = new QLabel(this);
  this->VolumeStatus->setObjectName("volumeStatus");
  this->statusBar()->addWidget(this->VolumeStatus, 1);
  this->statusBar()->addPermanentWidget(this->Status);
  this->buildTools();
  this->buildMenus();

  // Finished chunk meshes are picked up ~60 times a second; the view never waits for them.
  this->MeshTimer = new QTimer(this);
  connect(this->MeshTimer, &QTimer::timeout, this, &MainWindow::showFinishedMeshes);
  this->MeshTimer->start(15);
  this->FrameTimer = new QTimer(this);
  this->FrameTimer->setSingleShot(true);
  // 1 ms, not 0: a zero timer fires only once the window system's event
  // queue is empty (Qt's documentation), which a stream of samples may delay
  this->FrameTimer->setInterval(1);
  this->FrameTimer->setTimerType(Qt::PreciseTimer);
  connect(this->FrameTimer, &QTimer::timeout, this, &MainWindow::frameAfterSamples);
  // With multisampling, Mesa's scissored clear can reach one pixel row or
  // column past the redrawn rectangle, so frames drawn in part are
  // interactive frames: once the stroke or the cursor has been still for a
  // moment, the view is drawn whole (as VTK's interactive and still frames).
  this->StillTimer = new QTimer(this);
  this->StillTimer->setSingleShot(true);
  this->StillTimer->setInterval(250);
  connect(this->StillTimer, &QTimer::timeout, this, [this] {
    if (this->Painting)
    {
      this->StillTimer->start(); // still painting: after the release
      return;
    }
    // the still frame: drawn whole, with the view's multisampling (the
    // stroke's frames may have been drawn with one sample per pixel)
    this->RenderWindow->SetSingleSampleFrames(false);
    this->Redraw->RequestFullRedraw();
    this->RenderWindow->Render();
    this->updateView();
  });
  {
    vtkNew<vtkCallbackCommand> cb;
    cb->SetClientData(this);
    cb->SetCallback([](vtkObject*, unsigned long, void* cd, void*) {
      auto* self = static_cast<MainWindow*>(cd);
      int damage[4];
      if (self->RenderWindow->GetLastFrameSingleSampled() ||
        (self->RenderWindow->GetMultiSamples() > 1 && self->Redraw->GetLastFramePartial(damage)))
        self->StillTimer->start();
    });
    this->RenderWindow->AddObserver(vtkCommand::EndEvent, cb);
  }
  this->AutosaveTimer = new QTimer(this);
  connect(this->AutosaveTimer, &QTimer::timeout, this, &MainWindow::autosave);
  if (options.autosaveSeconds > 0)
    this->AutosaveTimer->start(options.autosaveSeconds * 1000);
  this->updateTitle();
}

vtkRenderWindowInteractor* MainWindow::viewInteractor() const
{
  return this->NativeView ? this->NativeView->interactor() : this->View->interactor();
}

QObject* MainWindow::viewInputTarget()
{
  return this->NativeView ? static_cast<QObject*>(this->NativeView) : this->View;
}

void MainWindow::updateView()
{
  if (this->NativeView)
    this->NativeView->update();
  else
    this->View->update();
}

QImage MainWindow::grabView()
{
  // QVTKOpenGLNativeWidget renders in its paintGL: a render requested from
  // outside is deferred, so reading the render window's buffer could give the
  // previous frame. Its grabFramebuffer() paints now and returns that frame.
  if (!this->NativeView)
    return this->View->grabFramebuffer();
  // QOpenGLWindow::grabFramebuffer() reads the window's back buffer, which
  // holds no frame after a swap; the render window's display framebuffer
  // holds the last Render()'s frame (the caller's).
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(this->RenderWindow);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOn();
  w2i->ShouldRerenderOff();
  w2i->Update();
  vtkImageData* pixels = w2i->GetOutput();
  const int* dims = pixels->GetDimensions();
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(pixels->GetPointData()->GetScalars());
  if (!rgb || dims[0] <= 0 || dims[1] <= 0)
    return QImage();
  QImage image(dims[0], dims[1], QImage::Format_RGB888);
  for (int y = 0; y < dims[1]; ++y) // VTK's rows go up, QImage's down
    std::memcpy(image.scanLine(dims[1] - 1 - y), rgb->GetPointer(3 * dims[0] * y), 3 * static_cast<size_t>(dims[0]));
  return image;
}

MainWindow::~MainWindow()
{
  this->Brush->Off();
  this->Chunks->RemoveAllChunks();
}

void MainWindow::buildMenus()
{
  QMenu* file = this->menuBar()->addMenu("&File");
  file->addAction("&New canvas...", this, &MainWindow::newDialog, QKeySequence::New);
  file->addAction("&Open volume...", this, &MainWindow::openDialog, QKeySequence::Open);
  this->OpenMeshAction = file->addAction("Open &mesh...", this, &MainWindow::openMeshDialog);
  this->OpenMeshAction->setToolTip("Convert an OBJ, OFF, STL or PLY mesh to a volume (signed distance field)");
  this->OpenMeshAction->setStatusTip(this->OpenMeshAction->toolTip());
  file->setToolTipsVisible(true);
  file->addSeparator();
  file->addAction("&Save", this, [this] {
    if (this->Doc.path().isEmpty())
      this->saveAsDialog();
    else
      this->saveVolume(this->Doc.path());
  }, QKeySequence::Save);
  // explicit: QKeySequence::SaveAs is empty on platforms without a desktop theme (Xvfb, bare X11)
  file->addAction("Save &as...", this, &MainWindow::saveAsDialog, QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
  file->addAction("&Export mesh...", this, &MainWindow::exportDialog);
  file->addAction("Screens&hot...", this, &MainWindow::screenshotDialog);
  file->addSeparator();
  file->addAction("&Run script (recording)...", this, &MainWindow::scriptDialog, QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_R));
  file->addSeparator();
  file->addAction("&Quit", this, &QWidget::close, QKeySequence::Quit);

  QMenu* edit = this->menuBar()->addMenu("&Edit");
  edit->addAction("&Undo", this, &MainWindow::undo, QKeySequence(Qt::CTRL | Qt::Key_Z));
  edit->addAction("&Redo", this, &MainWindow::redo, QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z));
  edit->addAction("Redo (alternative)", this, &MainWindow::redo, QKeySequence(Qt::CTRL | Qt::Key_Y));
  edit->addSeparator();
  edit->addAction("Record / stop recording", this, [this] { this->Tools->toggleRecording(); },
    QKeySequence(Qt::CTRL | Qt::Key_R));

  QMenu* view = this->menuBar()->addMenu("&View");
  QAction* tetra = view->addAction("&Tetrahedral colour interpolation");
  tetra->setCheckable(true);
  tetra->setChecked(!this->Options.perVertexColor);
  connect(tetra, &QAction::toggled, this, [this](bool on) {
    this->Chunks->SetInterpolationMode(
      on ? vtkTetrahedralColorMapper::Tetrahedral : vtkTetrahedralColorMapper::PerVertex);
    this->RenderWindow->Render();
  });
  // the same three modes as --stroke-lod
  QMenu* lod = view->addMenu("Stroke &level of detail");
  this->StrokeLodActions = new QActionGroup(this);
  for (const auto& m : { std::make_pair("auto", "&Auto (coarse while a large brush drags)"),
         std::make_pair("on", "&On (coarse while dragging)"), std::make_pair("off", "O&ff (full resolution)") })
  {
    QAction* a = lod->addAction(m.second);
    a->setCheckable(true);
    a->setData(QString(m.first));
    a->setChecked(this->Options.strokeLod == m.first);
    this->StrokeLodActions->addAction(a);
    connect(a, &QAction::triggered, this, [this, mode = QString(m.first)] { this->setStrokeLod(mode); });
  }
  view->addAction("&Reset camera", this, &MainWindow::resetView);
  this->buildViewMenu(view);
  this->buildHelpMenu();
}

void MainWindow::applyBrushState()
{
  const BrushState& s = this->Tools->state();
  if (this->Doc.hasVolume())
  {
    lvdif::Editor& e = this->Doc.editor();
    e.brush.op = static_cast<lvdif::BrushOp>(s.op);
    e.brush.invert = false;
    e.brush.blend = s.blend;
    e.brush.strength = s.strength;
    e.brush.falloff = static_cast<lvdif::Falloff>(s.falloff);
    const auto& dims = this->Doc.volume().dims();
    for (int a = 0; a < 3; ++a)
    {
      e.brush.symmetry.mirror[a] = s.mirror[a];
      e.brush.symmetry.plane[a] = 0.5 * double(dims[a] - 1); // the volume's centre: voxel i mirrors to n-1-i
    }
    e.brush.color = lvdif::Rgba{ static_cast<std::uint8_t>(s.color.red()), static_cast<std::uint8_t>(s.color.green()),
      static_cast<std::uint8_t>(s.color.blue()), static_cast<std::uint8_t>(s.color.alpha()) };
    e.stroke.shape = static_cast<lvdif::BrushShape>(s.shape);
    e.stroke.radius = s.radius;
    // Basic strokes are applied as they go (as the Core's Drill, here with
    // the cursor on the surface) so the user sees the surface change under
    // the mouse; Dynamic needs the whole stroke for its taper and is applied
    // on release. The kind is the one chosen, so a recording names it (a
    // Basic stroke was recorded as kind=drill).
    e.stroke.kind = s.kind == 2 ? lvdif::BrushKind::Dynamic
      : s.kind == 3             ? lvdif::BrushKind::Drill
                                : lvdif::BrushKind::Basic;
    e.stroke.applyAsItGoes = true;
    // The cursor in world units of the x axis, scaled per axis to the dab's
    // true extent (r * spacing[a]); the wheel's range is every edit input's,
    // (0, EditLimits::MaxSize] voxels (the cursor capped it at 1e6 world units).
    const auto& h = this->Doc.volume().options().spacing;
    this->BrushRep->SetMaximumRadius(lvdif::EditLimits::MaxSize * h[0]);
    this->BrushRep->SetMinimumRadius(1e-3 * h[0]);
    this->BrushRep->SetAxisScale(1.0, h[1] / h[0], h[2] / h[0]);
    this->BrushRep->SetRadius(s.radius * h[0]);
  }
  this->BrushRep->SetShape(s.shape == 1 ? vtkBrushRepresentation::Cube : vtkBrushRepresentation::Sphere);
  this->BrushRep->GetCursorProperty()->SetColor(s.color.redF(), s.color.greenF(), s.color.blueF());
}

void MainWindow::resetView()
{
  // The camera fits the surface to the view's aspect. A native view sizes its
  // render window when its window is first exposed, which may come after the
  // first surface: take the size from the layout now, as the widget view has it.
  if (this->NativeView)
  {
    const double ratio = this->ViewWidget->devicePixelRatioF();
    const int w = static_cast<int>(std::lround(this->ViewWidget->width() * ratio));
    const int h = static_cast<int>(std::lround(this->ViewWidget->height() * ratio));
    const int* size = this->RenderWindow->GetSize();
    if (w > 0 && h > 0 && (size[0] != w || size[1] != h))
      this->RenderWindow->SetSize(w, h);
  }
  this->setViewPreset(-1);
  // the first meshes may be a part of the surface: the view fits it again as the rest comes
  this->HomeSettling = this->Doc.hasVolume();
  this->homeTarget(this->HomeBounds);
  vtkCamera* cam = this->Renderer->GetActiveCamera();
  cam->GetPosition(this->HomeCamera);
  cam->GetFocalPoint(this->HomeCamera + 3);
  cam->GetViewUp(this->HomeCamera + 6);
  this->HomeCamera[9] = cam->GetParallelProjection() ? cam->GetParallelScale() : cam->GetViewAngle();
}

void MainWindow::settleHome()
{
  if (!this->HomeSettling)
    return;
  vtkCamera* cam = this->Renderer->GetActiveCamera();
  double now[10];
  cam->GetPosition(now);
  cam->GetFocalPoint(now + 3);
  cam->GetViewUp(now + 6);
  now[9] = cam->GetParallelProjection() ? cam->GetParallelScale() : cam->GetViewAngle();
  if (this->Painting || !std::equal(now, now + 10, this->HomeCamera))
  {
    this->HomeSettling = false; // the user's view from now on
    return;
  }
  double target[6];
  this->homeTarget(target);
  const bool idle = this->Doc.meshingIdle();
  if (!std::equal(target, target + 6, this->HomeBounds))
    this->resetView();
  this->HomeSettling = !idle;
}

bool MainWindow::newCanvas(int nx, int ny, int nz, VolumeDocument::Fill fill)
{
  if (!this->finishRecording())
    return false; // the recording's Save was cancelled: the volume stays
  try
  {
    this->Chunks->RemoveAllChunks();
    this->Doc.newCanvas(nx, ny, nz, fill);
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot create the canvas", e);
    return false;
  }
  this->volumeReplaced();
  if (fill != VolumeDocument::Fill::Sphere)
    this->resetView();
  return true;
}

bool MainWindow::openVolume(const QString& path, bool untitled)
{
  if (!this->finishRecording())
    return false; // the recording's Save was cancelled: the volume stays
  try
  {
    this->Chunks->RemoveAllChunks();
    this->Doc.open(path, untitled);
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot open " + path, e);
    return false;
  }
  this->volumeReplaced();
  if (!untitled)
    this->addRecentFile(path);
  return true;
}

bool MainWindow::openMesh(const QString& path, const MeshImportSettings& settings)
{
  QString error, warning;
  std::shared_ptr<lvdif::DictionaryVolume> volume;
  bool interrupted = false;
  if (this->Options.batch())
  {
    // a batch run shows the conversion's progress as the CLI does (it was
    // silent for minutes), and Ctrl-C cancels it
    ProgressBar console;
    volume = importMesh(this, path, settings, error, &warning, &console);
    interrupted = console.wasInterrupted();
  }
  else
    volume = importMesh(this, path, settings, error, &warning);
  if (!volume)
  {
    if (!error.isEmpty() || interrupted)
    {
      if (interrupted)
        this->showError("Cannot convert " + path, lvdif::Error(lvdif::ErrorCode::Cancelled, "cancelled (Ctrl-C)"));
      else
        this->showError("Cannot convert " + path, std::runtime_error(error.toStdString()));
    }
    return false;
  }
  if (!warning.isEmpty())
  {
    // a batch run has nobody to close a message box
    if (this->Options.batch())
      std::fprintf(stderr, "lvdif-editor: warning: %s\n", warning.toLocal8Bit().constData());
    else
      QMessageBox::warning(this, "Open mesh", warning);
  }
  if (!this->finishRecording())
    return false; // the recording's Save was cancelled: the volume stays
  try
  {
    this->Chunks->RemoveAllChunks();
    this->Doc.adopt(std::move(volume));
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot open " + path, e);
    return false;
  }
  this->volumeReplaced();
  this->addRecentFile(path);
  return true;
}

bool MainWindow::saveVolume(const QString& path)
{
  try
  {
    this->Doc.save(path);
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot save " + path, e);
    return false;
  }
  this->addRecentFile(path);
  this->updateTitle();
  return true;
}

bool MainWindow::undo()
{
  // an error is said, never thrown out of the event loop (that aborted the editor)
  bool done = false;
  try
  {
    done = this->Doc.hasVolume() && !this->Painting && this->Doc.undo();
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot undo", e);
  }
  this->updateTitle();
  return done;
}

void MainWindow::redo()
{
  try
  {
    if (this->Doc.hasVolume() && !this->Painting)
      this->Doc.redo();
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot redo", e);
  }
  this->updateTitle();
}

void MainWindow::volumeReplaced()
{
  this->Tools->setRecording(this->Doc.session().recording()); // a script's `canvas N` ended it
  this->Chunks->RemoveAllChunks();
  const auto& o = this->Doc.volume().options();
  this->Chunks->SetOrigin(o.origin[0], o.origin[1], o.origin[2]);
  this->Chunks->SetSpacing(o.spacing[0], o.spacing[1], o.spacing[2]);
  // where no surface is under the mouse, the brush may stand on the solid's box
  double box[6];
  this->volumeBounds(box);
  this->BrushRep->SetVolume(box, [this](const double* world) { return this->Doc.insideAt(world); },
    [this] { return this->Chunks->GetNumberOfChunks() > 0 || !this->Doc.meshingIdle(); });
  this->applyBrushState();
  this->ViewInitialized = false;
  this->Brush->On();
  this->updateTitle();
}

bool MainWindow::eventFilter(QObject* watched, QEvent* event)
{
  switch (event->type())
  {
    case QEvent::TabletPress:
    case QEvent::TabletMove:
      this->Pressure = static_cast<QTabletEvent*>(event)->pressure();
      break;
    case QEvent::TabletRelease:
      this->Pressure = -1;
      break;
    default:
      break;
  }
  this->keyFilter(event);
  // Not consumed: Qt turns unaccepted tablet events into mouse events.
  return QMainWindow::eventFilter(watched, event);
}

void MainWindow::updateTitle()
{
  QString name = this->Doc.path().isEmpty() ? QString("untitled") : QFileInfo(this->Doc.path()).fileName();
  if (this->Doc.hasVolume())
  {
    const auto& d = this->Doc.volume().dims();
    name += QString(" (%1x%2x%3)").arg(d[0]).arg(d[1]).arg(d[2]);
  }
  this->setWindowTitle(name + (this->Doc.modified() ? " *" : "") + " - LVDIF editor");
  this->updateStatus();
}

void MainWindow::showError(const QString& what, const std::exception& e)
{
  ++this->Errors;
  // the CLI's one rule of a cancel: the error's code (its main exits with 130)
  const auto* error = dynamic_cast<const lvdif::Error*>(&e);
  if (error && error->code() == lvdif::ErrorCode::Cancelled)
    this->Cancelled = true;
  const QString text = what + ": " + QString::fromLocal8Bit(e.what());
  if (this->Options.batch())
    std::fprintf(stderr, "lvdif-editor: %s\n", text.toLocal8Bit().constData());
  else
    QMessageBox::critical(this, "LVDIF editor", text);
}
