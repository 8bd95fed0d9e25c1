// lvdif-editor: the Qt 5 volume editor. See docs/USER_GUIDE.md.
#include "EditorDriver.h"
#include "EditorOptions.h"
#include "MainWindow.h"
#include "VolumeFiles.h" // the CLI's: VolumeOutputIsCubicOnly

#include <QApplication>
#include <QElapsedTimer>
#include <QOpenGLContext>
#include <QScreen>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <algorithm>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace
{
/// Installed while the QApplication starts: without a usable display Qt's
/// platform plugin printed three lines of its own and aborted (status 134);
/// the editor says it once and exits with 1.
void refuseWithoutDisplay(QtMsgType type, const QMessageLogContext& context, const QString& message)
{
  if (type == QtFatalMsg)
  {
    const char* display = std::getenv("DISPLAY");
    std::fprintf(stderr,
      "lvdif-editor: cannot open a window: no usable X display (DISPLAY=%s); run it on a desktop, or headless "
      "as xvfb-run -a lvdif-editor ...\n",
      display && *display ? display : "not set");
    std::_Exit(1);
  }
  // the platform plugin's own lines before that fatal one: the line above says it
  if (context.category && std::strncmp(context.category, "qt.qpa", 6) == 0)
    return;
  std::fprintf(stderr, "%s\n", message.toLocal8Bit().constData());
}
} // namespace

int main(int argc, char* argv[])
{
  // Every option is checked before the QApplication, which cannot start
  // without a display: --help is answered and a bad option refused (status 2)
  // without one; Qt's own options (-platform, -display, ...) are left to it.
  // The environment's locale first, as the QApplication sets it: the
  // arguments' file names are decoded in its encoding.
  std::setlocale(LC_ALL, "");
  const EditorOptions options = parseEditorOptions(editorArguments(argc, argv));
  // Before the QApplication (build-notes 2d).
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  const QtMessageHandler qtMessages = qInstallMessageHandler(refuseWithoutDisplay);
  QApplication app(argc, argv);
  qInstallMessageHandler(qtMessages);
  {
    // A platform without OpenGL (-platform offscreen, QT_QPA_PLATFORM=minimal):
    // the view's first frame crashed the editor (segmentation fault).
    QOpenGLContext gl;
    // the plugin's own complaint ("does not support createPlatformOpenGLContext!"): the line below says it
    const QtMessageHandler before = qInstallMessageHandler([](QtMsgType, const QMessageLogContext&, const QString&) {});
    const bool haveGl = gl.create();
    qInstallMessageHandler(before);
    if (!haveGl)
    {
      std::fprintf(stderr,
        "lvdif-editor: cannot draw the view: Qt's platform '%s' gives no OpenGL context; run it on a desktop, or "
        "headless as xvfb-run -a lvdif-editor ...\n",
        QGuiApplication::platformName().toLocal8Bit().constData());
      return 1;
    }
  }
  // QApplication takes the C library's locale from the environment; under a
  // comma-decimal one (de_DE) strtod read a mesh's or script's "0.5" as 0 or
  // refused it, and printf wrote recordings with "0,5". Numbers in files are C
  // text; Qt's own number display follows QLocale, which this leaves alone.
  std::setlocale(LC_NUMERIC, "C");
  QApplication::setApplicationName("lvdif-editor");
  QApplication::setOrganizationName("LVDIF");

  // A --size larger than the screen (the whole desktop) is refused before the
  // window is made: 16384x16384 under Xvfb's 1280x1024 screen ran for many
  // minutes and tens of GB (the view's framebuffers; 8192x8192 took 52 s and
  // 4 GB), and no screen could show it.
  if (options.sizeGiven)
  {
    const QScreen* screen = QGuiApplication::primaryScreen();
    const QSize desktop = screen ? screen->virtualSize() : QSize();
    if (desktop.isValid() && (options.width > desktop.width() || options.height > desktop.height()))
    {
      std::fprintf(stderr,
        "lvdif-editor: --size %dx%d is larger than the screen, %dx%d: give at most that (headless, give Xvfb a larger "
        "screen: xvfb-run -a -s \"-screen 0 %dx%dx24\" lvdif-editor ...)\n",
        options.width, options.height, desktop.width(), desktop.height(), std::max(options.width, desktop.width()),
        std::max(options.height, desktop.height()));
      return 2;
    }
  }
  QElapsedTimer sinceWindow;
  sinceWindow.start();
  MainWindow window(options);
  // A --size below the least size of the window (the Brush panel's height, the
  // menus' width) was silently enlarged, and the screenshots came out another
  // size than asked: refused, naming the least size (the default grows to it).
  const QSize least = window.minimumSizeHint().expandedTo(window.minimumSize());
  if (options.sizeGiven && (options.width < least.width() || options.height < least.height()))
  {
    std::fprintf(stderr,
      "lvdif-editor: --size %dx%d is smaller than this window can be, %dx%d (the Brush panel and the menus): give at "
      "least that\n",
      options.width, options.height, std::max(options.width, least.width()), std::max(options.height, least.height()));
    return 2;
  }
  // the command line's work (batch, keys, drag, benchmark) drives the window from outside
  EditorDriver driver(window, options, sinceWindow);
  window.show();
  bool loaded = false;
  const bool benchmark = !options.benchmarkStroke.isEmpty();
  if ((!options.batch() || !options.recoveryAnswer.isEmpty()) && !benchmark)
    loaded = window.offerRecovery();
  if (!loaded)
  {
    if (!options.openMesh.isEmpty())
    {
      MeshImportSettings settings;
      settings.resolution = options.meshResolution;
      settings.signMode = meshSignModeFromName(options.meshSign);
      settings.reorientFaces = options.meshReorient;
      // a .bv output holds cubic volumes only: the grid made cubic, as the CLI's
      settings.cubic = options.batch() && VolumeOutputIsCubicOnly(options.save.toStdString());
      loaded = window.openMesh(options.openMesh, settings);
    }
    else if (!options.open.isEmpty())
      loaded = window.openVolume(options.open);
    else
    {
      const std::array<int, 3> d = options.canvasDims();
      const int nx = d[0], ny = d[1], nz = d[2];
      // A script starts from an empty canvas unless --fill says otherwise, as
      // `lvdif script` does (and Run script with no volume): the same script
      // gave another model in the editor, the starter sphere in it. A
      // recording keeps the editor's start canvas, on which it was recorded.
      const QString fillName =
        options.fillGiven || options.script.isEmpty() || !isScriptFile(options.script) ? options.fill : "empty";
      const VolumeDocument::Fill fill = lvdif::canvasFillFromName(fillName.toStdString(), "--fill"); // checked by the parser
      loaded = window.newCanvas(nx, ny, nz, fill);
    }
  }
  if (benchmark)
  {
    if (!loaded)
      return 1;
    // Once the window is up and the first surface is shown, replay the stroke;
    // StrokeBenchmark quits the application with its status.
    QTimer::singleShot(0, &window, [&] {
      if (!driver.startStrokeBenchmark(options.benchmarkStroke))
        QApplication::exit(1);
    });
    return app.exec();
  }
  if (!options.batch() && options.drag.isEmpty() && options.script.isEmpty() && options.keys.isEmpty() &&
    options.keysAfter.isEmpty() && options.matcap.isEmpty())
    return app.exec();

  int status = loaded ? 0 : 1;
  QTimer::singleShot(0, &window, [&] {
    if (status == 0)
      status = driver.runBatch();
    if (options.batch())
      window.close();
  });
  const int rc = app.exec();
  // Ctrl-C in a batch run's mesh conversion: 130, as the CLI (it was 1, a failure)
  if (window.cancelled() && (status != 0 || rc != 0))
    return 130;
  return status != 0 ? status : rc;
}
