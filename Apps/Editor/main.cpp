// lvdif-editor: the Qt 5 volume editor. See docs/USER_GUIDE.md.
#include "EditorOptions.h"
#include "MainWindow.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <cstdio>

namespace
{
// The command-line work, run once the window is shown.
int runBatch(MainWindow& w, const EditorOptions& o)
{
  bool ok = true;
  // a script first: it sets the scene the keys and the drag then work on
  if (!o.script.isEmpty())
    ok = w.runScript(o.script) && ok;
  if (!o.keys.isEmpty())
    ok = w.typeKeys(o.keys) && ok;
  if (!o.drag.isEmpty())
  {
    w.finishMeshing(); // the surface must be there to be picked
    w.replayDrag(o.drag, o.dragCtrl, o.dragShift);
  }
  if (!o.keysAfter.isEmpty())
    ok = w.typeKeys(o.keysAfter) && ok;
  for (int i = 0; i < o.undo; ++i)
    w.undo();
  w.finishMeshing();
  if (!o.screenshot.isEmpty())
    ok = w.saveScreenshot(o.screenshot) && ok;
  if (!o.windowShot.isEmpty())
    ok = w.saveWindowShot(o.windowShot) && ok;
  if (!o.save.isEmpty())
    ok = w.saveVolume(o.save) && ok;
  if (!o.exportMesh.isEmpty())
    ok = w.exportMesh(o.exportMesh) && ok;
  return ok ? 0 : 1;
}
} // namespace

int main(int argc, char* argv[])
{
  // Before the QApplication (build-notes 2d).
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("lvdif-editor");
  QApplication::setOrganizationName("LVDIF");
  const EditorOptions options = parseEditorOptions(app.arguments());

  MainWindow window(options);
  window.show();
  bool loaded = false;
  const bool benchmark = !options.benchmarkStroke.isEmpty();
  if (!options.batch() && !benchmark)
    loaded = window.offerRecovery();
  if (!loaded)
  {
    if (!options.openMesh.isEmpty())
    {
      MeshImportSettings settings;
      settings.resolution = options.meshResolution;
      settings.signMode = meshSignModeFromName(options.meshSign);
      loaded = window.openMesh(options.openMesh, settings);
    }
    else if (!options.open.isEmpty())
      loaded = window.openVolume(options.open);
    else
    {
      const auto& d = options.newDims;
      const int nx = d[0] > 0 ? d[0] : 128, ny = d[1] > 0 ? d[1] : 128, nz = d[2] > 0 ? d[2] : 128;
      const VolumeDocument::Fill fill = options.fill == "empty"
        ? VolumeDocument::Fill::Empty
        : (options.fill == "full" ? VolumeDocument::Fill::Full : VolumeDocument::Fill::Sphere);
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
      window.finishMeshing();
      if (!window.startStrokeBenchmark(options.benchmarkStroke))
        QApplication::exit(1);
    });
    return app.exec();
  }
  if (!options.batch() && options.drag.isEmpty() && options.script.isEmpty() && options.keys.isEmpty() &&
    options.keysAfter.isEmpty())
    return app.exec();

  int status = loaded ? 0 : 1;
  QTimer::singleShot(0, &window, [&] {
    if (status == 0)
      status = runBatch(window, options);
    if (options.batch())
      window.close();
  });
  const int rc = app.exec();
  return status != 0 ? status : rc;
}
