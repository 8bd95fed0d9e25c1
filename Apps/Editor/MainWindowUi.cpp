// MainWindow: the toolbar, the keyboard shortcuts and the Help menu that lists
// them, recent files, the view (camera presets, orthographic, shading), the
// status bar, the tool cursor and the Dynamic brush's live preview.
#include "MainWindow.h"

#include "lvdif/ByteStream.h"

#include "vtkActor.h"
#include "vtkBrushRepresentation.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkChunkActorManager.h"
#include "vtkDoubleArray.h"
#include "vtkMath.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTubeFilter.h"

#include "Matcap.h"
#include "vtkTexture.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QDateTime>
#include <stdexcept>

#include <QFileDialog>
#include <QFileInfo>
#include <QImageReader>
#include <QKeyEvent>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPainter>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QVTKOpenGLNativeWidget.h>
#include <QVTKOpenGLWindow.h>

#include <cmath>
#include <limits>

namespace
{
struct ViewPreset
{
  const char* name;
  Qt::Key key;
  double dir[3]; // from the focal point to the camera
  double up[3];
};
// Y up, as the command line's pictures and the usual mesh files (OBJ, PLY).
const ViewPreset Presets[] = {
  { "Front", Qt::Key_1, { 0, 0, 1 }, { 0, 1, 0 } },
  { "Back", Qt::Key_2, { 0, 0, -1 }, { 0, 1, 0 } },
  { "Right", Qt::Key_3, { 1, 0, 0 }, { 0, 1, 0 } },
  { "Left", Qt::Key_4, { -1, 0, 0 }, { 0, 1, 0 } },
  { "Top", Qt::Key_7, { 0, 1, 0 }, { 0, 0, -1 } },
  { "Bottom", Qt::Key_8, { 0, -1, 0 }, { 0, 0, 1 } },
};
const char* ShadingNames[] = { "Smooth", "Flat", "Wireframe", "Matcap" };

QString keyText(const QKeySequence& k)
{
  return k.toString(QKeySequence::NativeText).toHtmlEscaped();
}
} // namespace

void MainWindow::buildTools()
{
  // VTK's own key bindings ('e'/'q' quit, 'w' wireframe, '3' stereo, ...) would
  // fight the editor's shortcuts: the interactor's character events stop here.
  vtkNew<vtkCallbackCommand> swallow;
  swallow->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    static_cast<vtkCallbackCommand*>(self)->SetAbortFlag(1);
  });
  swallow->SetClientData(swallow.GetPointer());
  this->viewInteractor()->AddObserver(vtkCommand::CharEvent, swallow, 100.0);

  QToolBar* bar = this->addToolBar("Tools");
  bar->setObjectName("ToolsBar");
  this->ToolActions = new QActionGroup(this);
  for (int i = 0; i < ToolCount; ++i)
  {
    const ToolInfo& t = toolInfo(i);
    QAction* a = bar->addAction(t.name);
    a->setCheckable(true);
    a->setShortcut(QKeySequence(QString(QChar(t.key))));
    a->setToolTip(QString("%1 (%2)").arg(t.tip).arg(t.key));
    a->setData(i);
    this->ToolActions->addAction(a);
    connect(a, &QAction::triggered, this, [this, i] { this->Tools->setOp(i); });
  }
  bar->addSeparator();
  auto addAction = [this, bar](const QString& text, const QKeySequence& key, auto slot, bool inBar) {
    QAction* a = new QAction(text, this);
    a->setShortcut(key);
    connect(a, &QAction::triggered, this, slot);
    this->addAction(a); // window-wide, also when the toolbar is hidden
    if (inBar)
      bar->addAction(a);
    this->ShortcutActions.push_back(a);
    return a;
  };
  addAction("Smaller brush", QKeySequence(Qt::Key_BracketLeft), [this] { this->scaleRadius(1 / 1.2); }, false);
  addAction("Larger brush", QKeySequence(Qt::Key_BracketRight), [this] { this->scaleRadius(1.2); }, false);
  addAction("Frame the surface", QKeySequence(Qt::Key_F), [this] { this->frameSurface(); }, true);
  this->syncToolActions();
}

void MainWindow::buildViewMenu(QMenu* view)
{
  view->addSeparator();
  QMenu* presets = view->addMenu("Camera &presets");
  presets->addAction("Home (as the command line's pictures)", this, [this] { this->setViewPreset(-1); },
    QKeySequence(Qt::Key_0));
  for (int i = 0; i < int(sizeof(Presets) / sizeof(Presets[0])); ++i)
    presets->addAction(Presets[i].name, this, [this, i] { this->setViewPreset(i); }, QKeySequence(Presets[i].key));
  this->OrthoAction = view->addAction("&Orthographic", this, [this](bool on) { this->setOrthographic(on); });
  this->OrthoAction->setCheckable(true);
  this->OrthoAction->setShortcut(QKeySequence(Qt::Key_5));
  QMenu* shading = view->addMenu("&Shading");
  this->ShadingActions = new QActionGroup(this);
  for (int i = 0; i < 4; ++i)
  {
    QAction* a = shading->addAction(ShadingNames[i], this, [this, i] { this->setShading(i); });
    a->setCheckable(true);
    a->setChecked(i == 0);
    a->setShortcut(QKeySequence(QString("Alt+%1").arg(i + 1)));
    a->setData(i);
    this->ShadingActions->addAction(a);
  }
  shading->addSeparator();
  shading->addAction("&Load matcap image...", this, [this] { this->loadMatcapDialog(); });
  view->addAction("&Frame the surface", this, [this] { this->frameSurface(); });
}

void MainWindow::buildHelpMenu()
{
  QMenu* help = this->menuBar()->addMenu("&Help");
  help->addAction("&Keyboard shortcuts", this, [this] {
    QMessageBox box(this);
    box.setWindowTitle("Keyboard shortcuts");
    box.setTextFormat(Qt::RichText);
    box.setText(this->shortcutHelp());
    box.exec();
  }, QKeySequence::HelpContents);
  help->addAction("&About", this, [this] {
    QMessageBox::about(this, "LVDIF editor",
      "Sculpting on large signed distance volumes (LVDIF-VTK). The user guide is docs/USER_GUIDE.md.");
  });
}

QString MainWindow::shortcutHelp() const
{
  QString rows;
  auto row = [&rows](const QString& keys, const QString& what) {
    rows += "<tr><td><b>" + keys + "</b></td><td>" + what.toHtmlEscaped() + "</td></tr>";
  };
  for (QAction* a : this->ToolActions->actions())
    row(keyText(a->shortcut()), a->toolTip());
  row("Ctrl + drag", "Invert the tool: add <-> subtract, inflate -> deflate, crease -> ridge, pinch -> spread");
  row("Shift + drag", "Smooth, whatever the tool");
  row("Mouse wheel over the surface", "Brush radius");
  for (QAction* a : this->ShortcutActions)
    row(keyText(a->shortcut()), a->text());
  for (QMenu* m : this->menuBar()->findChildren<QMenu*>())
    for (QAction* a : m->actions())
      if (!a->shortcut().isEmpty() && !a->menu())
        row(keyText(a->shortcut()), QString(a->text()).remove('&'));
  return "<table cellspacing=4>" + rows + "</table>";
}

void MainWindow::syncToolActions()
{
  const int op = this->Tools->state().op;
  for (QAction* a : this->ToolActions->actions())
    a->setChecked(a->data().toInt() == op);
  this->updateCursor();
}

void MainWindow::scaleRadius(double factor)
{
  // [ and ] step within the panel's range, 0.5..100 voxels, but never the wrong
  // way: ] on a radius above it (--radius 150, the wheel) made it 100, [ on one
  // below it 0.5
  const double r0 = this->Tools->state().radius;
  const double r = std::min(std::max(100.0, r0), std::max(std::min(0.5, r0), r0 * factor));
  this->Tools->setRadius(r);
  this->applyBrushState();
  this->RenderWindow->Render();
}

// ---- view ------------------------------------------------------------------

void MainWindow::volumeBounds(double b[6])
{
  const auto& o = this->Doc.volume().options();
  const auto& d = this->Doc.volume().dims();
  for (int a = 0; a < 3; ++a)
  {
    b[2 * a] = o.origin[a];
    b[2 * a + 1] = o.origin[a] + o.spacing[a] * (d[a] - 1);
  }
}

namespace
{
/// The largest zoom (vtkCamera::Zoom) at which every corner of `bounds` stays
/// in the view of `cam`, of width / height `aspect`, in width and in height,
/// with a margin of 4 % (infinity when no corner limits it).
double fittingZoom(vtkCamera* cam, double aspect, const double bounds[6])
{
  const double* eye = cam->GetPosition();
  double dop[3], up[3], right[3];
  cam->GetDirectionOfProjection(dop);
  cam->GetViewUp(up);
  vtkMath::Normalize(dop);
  vtkMath::Cross(dop, up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, dop, up);
  double reach = 0; // the corners' largest half extent the view needs, as a tangent (perspective) or a length
  for (int c = 0; c < 8; ++c)
  {
    const double p[3] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)], bounds[4 + ((c >> 2) & 1)] };
    const double v[3] = { p[0] - eye[0], p[1] - eye[1], p[2] - eye[2] };
    const double x = std::fabs(vtkMath::Dot(v, right)) / std::max(aspect, 1e-6), y = std::fabs(vtkMath::Dot(v, up));
    const double depth = vtkMath::Dot(v, dop);
    if (cam->GetParallelProjection())
      reach = std::max(reach, std::max(x, y));
    else if (depth > 0)
      reach = std::max(reach, std::max(x, y) / depth);
  }
  reach *= 1.04;
  if (!(reach > 0))
    return std::numeric_limits<double>::infinity();
  if (cam->GetParallelProjection())
    return cam->GetParallelScale() / reach;
  // Zoom divides the view angle
  return cam->GetViewAngle() / vtkMath::DegreesFromRadians(2 * std::atan(reach));
}
} // namespace

void MainWindow::homeTarget(double b[6])
{
  this->Chunks->GetBounds(b);
  if (!(b[1] >= b[0]))
    this->volumeBounds(b);
}

void MainWindow::setViewPreset(int preset)
{
  vtkCamera* cam = this->Renderer->GetActiveCamera();
  cam->SetFocalPoint(0, 0, 0);
  if (preset < 0)
  {
    // the command line's camera (Apps/CLI): VTK's default view, azimuth 35, elevation 25
    cam->SetPosition(0, 0, 1);
    cam->SetViewUp(0, 1, 0);
  }
  else
  {
    const ViewPreset& p = Presets[preset];
    cam->SetPosition(p.dir[0], p.dir[1], p.dir[2]);
    cam->SetViewUp(p.up[0], p.up[1], p.up[2]);
  }
  if (this->Doc.hasVolume())
  {
    double b[6];
    this->volumeBounds(b);
    this->Renderer->ResetCamera(b);
  }
  if (preset < 0)
  {
    cam->Azimuth(35);
    cam->Elevation(25);
    cam->OrthogonalizeViewUp();
  }
  // The volume's box is mostly empty around the surface: 1.4 times closer,
  // but no closer than shows the whole surface (the box while none is shown)
  // in width and in height. A Full canvas's surface is its box, which a narrow
  // window cut off (--size 300x800 showed a third of its width).
  double zoom = 1.4;
  if (this->Doc.hasVolume())
  {
    double target[6];
    this->homeTarget(target);
    zoom = std::min(zoom, fittingZoom(cam, this->Renderer->GetTiledAspectRatio(), target));
  }
  cam->Zoom(zoom);
  this->Renderer->ResetCameraClippingRange();
  this->RenderWindow->Render();
}

void MainWindow::frameSurface()
{
  double b[6];
  this->Chunks->GetBounds(b);
  if (!(b[1] >= b[0]))
  {
    if (!this->Doc.hasVolume())
      return;
    this->volumeBounds(b);
  }
  this->Renderer->ResetCamera(b);
  this->Renderer->ResetCameraClippingRange();
  this->RenderWindow->Render();
}

void MainWindow::setOrthographic(bool on)
{
  this->Renderer->GetActiveCamera()->SetParallelProjection(on);
  if (this->OrthoAction && this->OrthoAction->isChecked() != on)
    this->OrthoAction->setChecked(on);
  this->frameSurface();
}

void MainWindow::setShading(int mode)
{
  vtkProperty* p = this->Chunks->GetProperty();
  p->SetRepresentationToSurface();
  p->SetInterpolationToGouraud();
  p->SetAmbient(0.0);
  p->SetDiffuse(1.0);
  p->SetSpecular(0.25);
  p->SetSpecularPower(25);
  if (mode == 1)
    p->SetInterpolationToFlat();
  else if (mode == 2)
    p->SetRepresentationToWireframe();
  else if (mode == 3)
  {
    // the matcap's colour times the surface colour (the diffuse colour at
    // diffuse 1), no scene lights: vtkTetrahedralColorMapper's Matcap
    p->SetDiffuse(1.0);
    p->SetSpecular(0.0);
  }
  this->Chunks->SetMatcapTexture(mode == 3 ? this->Matcap.Get() : nullptr);
  if (this->ShadingActions)
    for (QAction* a : this->ShadingActions->actions())
      if (a->data().toInt() == mode && !a->isChecked())
        a->setChecked(true);
  this->Shading = mode;
  this->RenderWindow->Render();
}

bool MainWindow::loadMatcap(const QString& path)
{
  try
  {
    // a file, as every reader of the project requires (lvdif::FileSource): a
    // FIFO hung the editor for good in Qt's reader, and a folder was "File not found"
    lvdif::FileSource file(path.toLocal8Bit().toStdString());
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot read the matcap image " + path, e);
    return false;
  }
  QImageReader reader(path);
  const QImage image = reader.read();
  if (image.isNull())
  {
    this->showError("Cannot read the matcap image " + path, std::runtime_error(reader.errorString().toStdString()));
    return false;
  }
  this->Matcap = matcapTexture(image);
  this->setShading(3);
  return true;
}

void MainWindow::loadMatcapDialog()
{
  const QString path =
    QFileDialog::getOpenFileName(this, "Load matcap image", QString(), "Images (*.png *.jpg *.jpeg);;All files (*)");
  if (!path.isEmpty())
    this->loadMatcap(path);
}

// ---- recent files ------------------------------------------------------------

void MainWindow::addRecentFile(const QString& path)
{
  if (this->Options.batch())
    return; // tests and scripts leave the user's list alone
  QSettings settings;
  QStringList files = settings.value("recentFiles").toStringList();
  const QString abs = QFileInfo(path).absoluteFilePath();
  files.removeAll(abs);
  files.prepend(abs);
  while (files.size() > 8)
    files.removeLast();
  settings.setValue("recentFiles", files);
  this->rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu()
{
  if (!this->RecentMenu)
    return;
  this->RecentMenu->clear();
  const QStringList files = QSettings().value("recentFiles").toStringList();
  for (const QString& f : files)
    this->RecentMenu->addAction(QFileInfo(f).fileName(), this, [this, f] {
      if (!this->maybeSave())
        return;
      const QString ext = QFileInfo(f).suffix().toLower();
      if (ext == "obj" || ext == "off" || ext == "stl" || ext == "ply")
        this->openMesh(f, this->MeshSettings);
      else
        this->openVolume(f); // every volume format of the file registry
    })->setToolTip(f);
  this->RecentMenu->setEnabled(!files.isEmpty());
}

// ---- status, cursor, preview -------------------------------------------------------

void MainWindow::updateStatus()
{
  if (!this->VolumeStatus)
    return;
  if (!this->Doc.hasVolume())
  {
    this->VolumeStatus->setText("no volume");
    return;
  }
  const auto& v = this->Doc.volume();
  const auto& d = v.dims();
  const auto& s = v.options().spacing;
  const double mib = double(v.memoryBytes()) / (1024.0 * 1024.0);
  // the voxel's size on every axis where they differ (a grid of spacing 1, 2, 1
  // said "voxel 1")
  QString voxel = QString::number(s[0], 'g', 4);
  if (s[1] != s[0] || s[2] != s[0])
    voxel += QString(" x %1 x %2").arg(s[1], 0, 'g', 4).arg(s[2], 0, 'g', 4);
  QString text = QString("%1 x %2 x %3 voxels | voxel %4 | %5 MiB | %6")
                   .arg(d[0])
                   .arg(d[1])
                   .arg(d[2])
                   .arg(voxel)
                   .arg(mib, 0, 'f', 1)
                   .arg(this->Doc.modified() ? "modified" : (this->Doc.path().isEmpty() ? "not saved" : "saved"));
  if (this->LastEdit.isValid())
    text += " | last edit " + this->LastEdit.toString("HH:mm:ss");
  this->VolumeStatus->setText(text);
}

int MainWindow::effectiveOp() const
{
  const Qt::KeyboardModifiers m = QApplication::queryKeyboardModifiers();
  vtkRenderWindowInteractor* iren = this->viewInteractor();
  const bool ctrl = (m & Qt::ControlModifier) || iren->GetControlKey();
  const bool shift = (m & Qt::ShiftModifier) || iren->GetShiftKey();
  const int op = this->Tools->state().op;
  if (shift)
    return 3; // smooth
  if (ctrl && op == 0)
    return 1;
  if (ctrl && op == 1)
    return 0;
  return op;
}

void MainWindow::updateCursor()
{
  const int op = this->effectiveOp();
  const bool ctrl = (QApplication::queryKeyboardModifiers() & Qt::ControlModifier) != 0;
  QPixmap pix(32, 32);
  pix.fill(Qt::transparent);
  QPainter p(&pix);
  p.setRenderHint(QPainter::Antialiasing);
  const QColor ink = op == 1 ? QColor(230, 70, 60) : (op == 2 ? this->Tools->state().color : QColor(90, 220, 120));
  p.setPen(QPen(Qt::black, 4));
  p.drawEllipse(QPointF(16, 16), 7, 7);
  p.setPen(QPen(ink, 2));
  p.drawEllipse(QPointF(16, 16), 7, 7);
  // the sign beside the ring: + add, - subtract, a drop for paint, the tool's letter otherwise
  p.setPen(QPen(Qt::white, 2));
  const QRectF corner(19, 19, 12, 12);
  if (op == 0 || (op == 4 && !ctrl))
  {
    p.drawLine(QPointF(25, 20), QPointF(25, 30));
    p.drawLine(QPointF(20, 25), QPointF(30, 25));
  }
  else if (op == 1 || (op == 4 && ctrl))
    p.drawLine(QPointF(20, 25), QPointF(30, 25));
  else if (op == 2)
  {
    p.setBrush(ink);
    p.drawEllipse(corner.adjusted(2, 2, -2, -2));
  }
  else
  {
    QFont f = p.font();
    f.setPixelSize(11);
    f.setBold(true);
    p.setFont(f);
    p.drawText(corner, Qt::AlignCenter, QString(QChar(toolInfo(op).key)));
  }
  p.end();
  if (this->NativeView)
    this->NativeView->setCursor(QCursor(pix, 16, 16));
  else
    this->View->setCursor(QCursor(pix, 16, 16));
  this->CursorOp = op;
}

void MainWindow::updatePreview(const double* world, bool reset)
{
  if (reset)
  {
    this->PreviewPoints.clear();
    if (this->Preview)
      this->Renderer->RemoveActor(this->Preview);
    this->Preview = nullptr;
    return;
  }
  this->PreviewPoints.push_back({ world[0], world[1], world[2] });
  const std::size_t n = this->PreviewPoints.size();
  if (n < 2)
    return;
  // The tapered tube the Dynamic stroke will make if released now: radius from
  // the full one at the start to the stroke's end radius (Core's minRadius),
  // linear in arc length. Built in voxel coordinates, where the stroke is, and
  // placed by the actor's scale and position: on a grid of spacing (1, 2, 1)
  // its section is the dabs' (r * spacing per axis; it was a round tube of
  // the x spacing).
  const auto& o = this->Doc.volume().options();
  std::vector<std::array<double, 3>> voxels(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      voxels[i][a] = (this->PreviewPoints[i][a] - o.origin[a]) / o.spacing[a];
  std::vector<double> arc(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
  {
    double l = 0;
    for (int a = 0; a < 3; ++a)
      l += std::pow(voxels[i][a] - voxels[i - 1][a], 2);
    arc[i] = arc[i - 1] + std::sqrt(l);
  }
  const double r0 = this->Tools->state().radius, r1 = std::min(r0, this->Doc.editor().stroke.minRadius);
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> radii;
  radii->SetName("radius");
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    pts->InsertNextPoint(voxels[i].data());
    radii->InsertNextValue(arc.back() > 0 ? r0 + (r1 - r0) * arc[i] / arc.back() : r0);
    line->InsertCellPoint(static_cast<vtkIdType>(i));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->SetLines(line);
  poly->GetPointData()->SetScalars(radii);
  vtkNew<vtkTubeFilter> tube;
  tube->SetInputData(poly);
  tube->SetNumberOfSides(16);
  tube->SetVaryRadiusToVaryRadiusByAbsoluteScalar();
  tube->CappingOn();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(tube->GetOutputPort());
  mapper->ScalarVisibilityOff();
  if (!this->Preview)
  {
    this->Preview = vtkSmartPointer<vtkActor>::New();
    this->Preview->PickableOff();
    this->Preview->GetProperty()->SetOpacity(0.45);
    this->Renderer->AddActor(this->Preview);
  }
  const QColor c = this->effectiveOp() == 1 ? QColor(230, 70, 60) : this->Tools->state().color;
  this->Preview->GetProperty()->SetColor(c.redF(), c.greenF(), c.blueF());
  this->Preview->SetMapper(mapper);
  this->Preview->SetScale(o.spacing[0], o.spacing[1], o.spacing[2]); // voxels to world
  this->Preview->SetPosition(o.origin[0], o.origin[1], o.origin[2]);
  this->RenderWindow->Render();
}

bool MainWindow::keyFilter(QEvent* event)
{
  if (event->type() == QEvent::KeyPress || event->type() == QEvent::KeyRelease)
  {
    const int k = static_cast<QKeyEvent*>(event)->key();
    if (k == Qt::Key_Control || k == Qt::Key_Shift)
      QTimer::singleShot(0, this, [this] { this->updateCursor(); });
  }
  return false;
}
