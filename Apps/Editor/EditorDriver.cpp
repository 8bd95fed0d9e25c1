#include "EditorDriver.h"
#include "VolumeFiles.h" // the CLI's rule of an output on the volume's grid

#include "EditorOptions.h"
#include "MainWindow.h"
#include "StrokeBenchmark.h"

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkRenderWindowInteractor.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QKeyEvent>
#include <QKeySequence>
#include <QLabel>
#include <QMouseEvent>
#include <QProgressDialog>
#include <QTimer>
#include <QWheelEvent>
#include <QWindow>
#ifdef LVDIF_EDITOR_HAVE_QTTEST
#include <QTest>
#endif

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>

EditorDriver::EditorDriver(MainWindow& window, const EditorOptions& options, QElapsedTimer sinceWindow)
  : Window(window)
  , Options(options)
  , SinceWindow(sinceWindow)
{
}


int EditorDriver::runBatch()
{
  const EditorOptions& o = this->Options;
  bool ok = true;
  this->waitForLayout(); // a native view draws (and so gives screenshots) only once its window is exposed
  // A batch run answers every dialog: with the answers given, else it is
  // cancelled and the run fails naming the option to give (a key's Save As, a
  // recording's Stop or a question waited forever for nobody).
  if (o.batch() || !o.saveAsAnswer.isEmpty() || !o.openAnswer.isEmpty() || o.cancelDialogs > 0)
    this->answerSaveDialogs(o.saveAsAnswer, o.openAnswer, o.cancelDialogs);
  // --save's rule on the grid of the volume opened (a .bv's cube, a .vdb's one
  // spacing), before the work: `--open long.lvdv --replay-drag ... --screenshot
  // s.png --save x.bv` did the drag and wrote the screenshot, then failed to
  // save. A script may make its own canvas: its rule stands at its `canvas`.
  if (!o.save.isEmpty() && this->Window.document().hasVolume() && (o.script.isEmpty() || !isScriptFile(o.script)))
  {
    const lvdif::DictionaryVolume& v = this->Window.document().volume();
    const std::string refused = VolumeOutputDimsProblem(o.save.toStdString(), v.dims(), v.options().spacing.data());
    if (!refused.empty())
    {
      std::fprintf(stderr, "lvdif-editor: --save %s: %s (nothing was done)\n", o.save.toLocal8Bit().constData(),
        refused.c_str());
      return 1;
    }
  }
  // a script first: it sets the scene the keys and the drag then work on
  if (!o.script.isEmpty())
    ok = this->Window.runScript(o.script) && ok;
  if (!o.matcap.isEmpty())
    ok = this->Window.loadMatcap(o.matcap) && ok;
  if (!o.keys.isEmpty())
    ok = this->typeKeys(o.keys) && ok;
  if (!o.drag.isEmpty())
  {
    this->waitForSurface(); // the surface must be there to be picked
    this->drag(o.drag, o.dragCtrl, o.dragShift, o.dragShot, o.wheel);
  }
  if (!o.keysAfter.isEmpty())
    ok = this->typeKeys(o.keysAfter) && ok;
  // one --undo too many is an error, as a script's or a recording's `undo`
  // with nothing to undo (it did nothing without a word: --undo 5 after one
  // stroke undid one and the run succeeded)
  for (int i = 0; i < o.undo; ++i)
    if (!this->Window.undo())
    {
      std::fprintf(stderr, "lvdif-editor: --undo %d: there %s only %d step%s to undo\n", o.undo, i == 1 ? "was" : "were", i,
        i == 1 ? "" : "s");
      ok = false;
      break;
    }
  // an error reported by what a key or the drag did (Ctrl+S onto a file that
  // cannot be written, a brush that failed) fails the run too: it exited 0
  ok = ok && this->Window.errorCount() == 0 && this->Unanswered == 0;
  if (!ok)
  {
    // as in the command line: after a failure nothing is written, so a script
    // that fails midway never replaces the --save file with its half-done model;
    // the failed step said why, once (a second line, "an earlier step failed:
    // no output written", followed every such message)
    return 1;
  }
  this->waitForSurface();
  if (o.printStatus)
  {
    // the status bar's volume text, as a user reads it
    // and the shown surface's, "N chunks, M triangles" (the status bar's right end)
    auto* status = this->Window.findChild<QLabel*>("volumeStatus");
    auto* mesh = this->Window.findChild<QLabel*>("meshStatus");
    if (status)
      std::printf("lvdif-editor: status: %s | %s\n", status->text().toLocal8Bit().constData(),
        mesh && !mesh->text().isEmpty() ? mesh->text().toLocal8Bit().constData() : "no surface shown");
  }
  if (!o.screenshot.isEmpty())
    ok = this->Window.saveScreenshot(o.screenshot) && ok;
  if (!o.windowShot.isEmpty())
    ok = this->Window.saveWindowShot(o.windowShot) && ok;
  if (!o.save.isEmpty())
    ok = this->Window.saveVolume(o.save) && ok;
  if (!o.exportMesh.isEmpty())
    ok = this->Window.exportMesh(o.exportMesh) && ok;
  return ok && this->Window.errorCount() == 0 && this->Unanswered == 0 ? 0 : 1;
}

void EditorDriver::showAllMeshes()
{
  if (this->Window.document().hasVolume())
    this->Window.document().waitMeshingIdle();
  this->Window.showFinishedMeshes();
  this->Window.renderWindow()->Render();
}

void EditorDriver::waitForSurface()
{
  this->showAllMeshes();
  if (this->Options.timing)
    std::fprintf(stderr, "lvdif-editor: every chunk meshed and shown %lld ms after the window was made\n",
      static_cast<long long>(this->SinceWindow.elapsed()));
}

void EditorDriver::waitForLayout()
{
  QWidget* v = this->Window.viewWidget();
  QElapsedTimer waited;
  waited.start();
  int last[2] = { -1, -1 };
  while (waited.elapsed() < 10000)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    const int* size = this->Window.renderWindow()->GetSize();
    const double ratio = v->devicePixelRatioF();
    auto* nativeView = qobject_cast<QWindow*>(this->Window.viewInputTarget()); // the native view's own window
    const bool exposed = v->window()->windowHandle() && v->window()->windowHandle()->isExposed() &&
      (!nativeView || nativeView->isExposed());
    const bool fits = size[0] == std::lround(v->width() * ratio) && size[1] == std::lround(v->height() * ratio);
    if (exposed && fits && size[0] == last[0] && size[1] == last[1])
      return;
    last[0] = size[0];
    last[1] = size[1];
  }
  std::fprintf(stderr, "lvdif-editor: the window was not laid out after 10 s; going on\n");
}

void EditorDriver::drag(
  const QVector<QPointF>& points, bool ctrl, bool shift, const QString& shotBeforeRelease, int wheelSteps)
{
  if (points.isEmpty())
    return;
  this->waitForLayout();
  QWidget* v = this->Window.viewWidget();
  QObject* target = this->Window.viewInputTarget(); // the widget, or the native view's window
  vtkRenderWindowInteractor* iren = this->Window.viewInteractor();
  // Points with both coordinates in [0, 1] are fractions of the view's size.
  bool fractions = true;
  for (const QPointF& p : points)
    fractions = fractions && p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1;
  const int* size = this->Window.renderWindow()->GetSize();
  const double sx = fractions ? size[0] : 1.0, sy = fractions ? size[1] : 1.0;
  // VTK display pixels (origin bottom-left) to the widget's Qt coordinates
  // (origin top-left, device-independent pixels): the inverse of what the
  // view's interactor adapter does with a mouse event, so the interactor sees
  // exactly the pixel asked for.
  const double ratio = v->devicePixelRatioF();
  auto widgetPoint = [&](const QPointF& p) {
    const long x = std::lround(p.x() * sx), y = std::lround(p.y() * sy);
    return QPointF(static_cast<double>(x) / ratio, static_cast<double>(iren->GetSize()[1] - 1 - y) / ratio);
  };
  Qt::KeyboardModifiers mods;
  if (ctrl)
    mods |= Qt::ControlModifier;
  if (shift)
    mods |= Qt::ShiftModifier;
  auto mouse = [&](QEvent::Type type, const QPointF& p, Qt::MouseButton button, Qt::MouseButtons buttons) {
    const QPointF local = widgetPoint(p);
    QMouseEvent event(type, local, local, local + v->mapToGlobal(QPoint(0, 0)), button, buttons, mods);
    QApplication::sendEvent(target, &event);
  };
  // the modifier keys go down before the press and up after the release
  auto modifierKeys = [&](QEvent::Type type) {
    const Qt::Key keys[2] = { Qt::Key_Control, Qt::Key_Shift };
    const bool held[2] = { ctrl, shift };
    for (int i = 0; i < 2; ++i)
      if (held[i])
      {
        QKeyEvent event(type, keys[i], type == QEvent::KeyPress ? mods : Qt::KeyboardModifiers());
        QApplication::sendEvent(target, &event);
      }
  };
  modifierKeys(QEvent::KeyPress);
  mouse(QEvent::MouseMove, points.front(), Qt::NoButton, Qt::NoButton);
  for (int i = 0; i < std::abs(wheelSteps); ++i)
  {
    const QPointF local = widgetPoint(points.front());
    QWheelEvent event(local, local + v->mapToGlobal(QPoint(0, 0)), QPoint(), QPoint(0, wheelSteps > 0 ? 120 : -120),
      Qt::NoButton, mods, Qt::NoScrollPhase, false);
    QApplication::sendEvent(target, &event);
    QApplication::processEvents();
  }
  mouse(QEvent::MouseButtonPress, points.front(), Qt::LeftButton, Qt::LeftButton);
  QApplication::processEvents();
  this->showAllMeshes(); // the press's sample too: the first move picks on its result
  for (int i = 1; i < points.size(); ++i)
  {
    mouse(QEvent::MouseMove, points[i], Qt::NoButton, Qt::LeftButton);
    QApplication::processEvents();
    // Each sample picks the surface shown: wait until the previous samples'
    // chunks are re-meshed and shown, so a replay picks the same points
    // however loaded the machine is (a user's pace, not the mouse's).
    this->showAllMeshes();
  }
  if (!shotBeforeRelease.isEmpty())
    this->Window.saveScreenshot(shotBeforeRelease); // e.g. the Dynamic brush's preview
  mouse(QEvent::MouseButtonRelease, points.back(), Qt::LeftButton, Qt::NoButton);
  mods = Qt::KeyboardModifiers();
  modifierKeys(QEvent::KeyRelease);
}

int editorKeyOfWord(QString word)
{
  // bracket names for callers that cannot pass brackets (CMake lists)
  word.replace("LeftBracket", "[").replace("RightBracket", "]");
  const QKeySequence seq = QKeySequence::fromString(word, QKeySequence::PortableText);
  // an unknown name parses as Key_unknown, which QTest cannot type (it asserts); one key a word
  if (seq.count() != 1 || seq[0] == 0 || (seq[0] & ~Qt::KeyboardModifierMask) == Qt::Key_unknown)
    return 0;
  return seq[0];
}

bool EditorDriver::typeKeys(const QString& keys)
{
#ifdef LVDIF_EDITOR_HAVE_QTTEST
  QWidget* v = this->Window.viewWidget();
  for (const QString& word : keys.split(' ', Qt::SkipEmptyParts))
  {
    const int k = editorKeyOfWord(word);
    if (k == 0)
    {
      std::fprintf(stderr, "lvdif-editor: --keys: '%s' is not a key\n", word.toLocal8Bit().constData());
      return false;
    }
    // without a window manager (Xvfb) nothing activates the window, and window
    // shortcuts only fire in the active window
    QApplication::setActiveWindow(&this->Window);
    v->setFocus();
    const int key = k & ~Qt::KeyboardModifierMask;
    const Qt::KeyboardModifiers mods(k & Qt::KeyboardModifierMask);
    // A native view's keys come to its own window, the focus window once the
    // view is clicked: typed there, through Qt's window-system path (shortcut
    // matching included), as a keyboard would.
    if (auto* nativeView = qobject_cast<QWindow*>(this->Window.viewInputTarget()))
    {
      nativeView->requestActivate();
      QApplication::processEvents();
      if (key >= 0x20 && key <= 0x7e)
        QTest::keyClick(nativeView, static_cast<char>(std::tolower(key)), mods);
      else
        QTest::keyClick(nativeView, Qt::Key(key), mods);
    }
    // printable keys by their character (QTest knows the text of every one of them)
    else if (key >= 0x20 && key <= 0x7e)
      QTest::keyClick(v, static_cast<char>(std::tolower(key)), mods);
    else
      QTest::keyClick(v, Qt::Key(key), mods);
    QApplication::processEvents();
  }
  return true;
#else
  (void)keys;
  std::fprintf(stderr, "lvdif-editor: --keys needs Qt5Test at build time\n");
  return false;
#endif
}

void EditorDriver::answerSaveDialogs(const QString& path, const QString& openPath, int cancels)
{
  if (!this->Answering)
  {
    // A file dialog runs its own event loop (exec): a timer of ours still fires in it.
    auto* timer = new QTimer(this);
    connect(timer, &QTimer::timeout, this, &EditorDriver::answerShownSaveDialog);
    timer->start(10);
    this->Answering = true;
  }
  this->SaveAnswer = path;
  this->OpenAnswer = openPath;
  this->CancelsLeft = cancels;
}

void EditorDriver::answerShownSaveDialog()
{
  for (QWidget* w : QApplication::topLevelWidgets())
  {
    auto* dialog = qobject_cast<QDialog*>(w);
    // a progress dialog needs no answer (it closes when the work is done)
    if (!dialog || !dialog->isVisible() || qobject_cast<QProgressDialog*>(dialog))
      continue;
    if (this->CancelsLeft > 0)
    {
      --this->CancelsLeft;
      dialog->reject(); // as its Cancel button
      continue;
    }
    auto* files = qobject_cast<QFileDialog*>(dialog);
    const bool opening = files && files->acceptMode() == QFileDialog::AcceptOpen;
    const QString& answer = opening ? this->OpenAnswer : this->SaveAnswer;
    if (!files || answer.isEmpty())
    {
      if (!this->Options.batch())
        continue; // a user is there to answer it
      // nobody is: the run waited for good
      ++this->Unanswered;
      std::fprintf(stderr, "lvdif-editor: the dialog '%s' opened in a batch run and was cancelled%s\n",
        dialog->windowTitle().toLocal8Bit().constData(),
        files ? (opening ? ": answer it with --open-answer FILE" : ": answer it with --save-as-answer FILE") : "");
      dialog->reject();
      continue;
    }
    if (!opening)
      files->setOption(QFileDialog::DontConfirmOverwrite); // a test's file may be there from an earlier run
    files->selectFile(QFileInfo(answer).absoluteFilePath());
    static_cast<QDialog*>(files)->accept(); // QFileDialog's accept, as its Open or Save button calls it
  }
}

bool EditorDriver::startStrokeBenchmark(const QString& path)
{
  try
  {
    const lvdif::Index3 dims = this->Window.document().volume().dims();
    auto* bench =
      new StrokeBenchmark(this->Window, StrokeBenchmark::loadSamples(path, &dims), QFileInfo(path).fileName());
    this->waitForLayout(); // a native view renders nothing before its window is exposed
    this->waitForSurface();
    bench->start();
    return true;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "benchmark-stroke: %s\n", e.what());
    return false;
  }
}
