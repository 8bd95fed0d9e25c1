#include "EditorOptions.h"

#include "Arguments.h" // the CLI's guard of a number's text
#include "EditorDriver.h" // the words of --keys
#include "LVDIFFiles.h"
#include "MainWindow.h" // isScriptFile
#include "MeshImport.h"
#include "VolumeFiles.h" // the CLI's rule of an output on the volume's dimensions
#include "lvdif/DictionaryVolume.h"
#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/StarterCanvas.h"

#include <QColor>
#include <QCoreApplication>
#include <QCommandLineParser>
#include <QFileInfo>
#include <QPointF>
#include <QRegularExpression>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

std::size_t strokeLodMinChunks(const QString& mode)
{
  // auto: measured on the 2-core VM at 512^3 (docs/BENCHMARKS.md, session 24)
  constexpr std::size_t AutoMinChunks = 24;
  return mode == "on" ? 1 : (mode == "off" ? 0 : AutoMinChunks);
}

namespace
{
[[noreturn]] void fail(const QString& message)
{
  std::fprintf(stderr, "lvdif-editor: %s\n", message.toLocal8Bit().constData());
  std::exit(2);
}

/// The one guard of the editor's whole-number options: the text must be an
/// integer in [lo, hi] (QString::toInt gave 0 for "99999999999999999999" or
/// "12x", so "--new 99999999999999999999" became a 0 x 0 x 0 canvas).
int integerOption(const QString& text, const QString& name, qint64 lo, qint64 hi)
{
  bool ok = false;
  // the CLI's guard of the text first (" 32" was taken as 32, where the CLI refuses it)
  const qint64 v = plainNumberText(text.toStdString()) ? text.toLongLong(&ok) : 0;
  if (!ok || v < lo || v > hi)
    fail(name + " expects an integer in [" + QString::number(lo) + ", " + QString::number(hi) + "], got '" + text + "'" +
      QString::fromStdString(numberTextHint(text.toStdString())));
  return static_cast<int>(v);
}

/// The one guard of the editor's real number options: the whole text a finite
/// number (QString::toDouble gave 0 for "abc", so "--radius abc" said "must be
/// positive"), then in (0, hi] by the one rule of every edit input
/// (lvdif::checkedPositive; --strength had a check of its own in other words).
double positiveOption(const QString& text, const QString& name, double hi)
{
  bool ok = false;
  const double v = plainNumberText(text.toStdString()) ? text.toDouble(&ok) : 0;
  if (!ok || !std::isfinite(v))
    fail(name + " expects a number, got '" + text + "'" + QString::fromStdString(numberTextHint(text.toStdString())));
  try
  {
    lvdif::checkedPositive(v, hi, name.toStdString());
  }
  catch (const lvdif::Error& e)
  {
    fail(e.what());
  }
  return v;
}

/// ".lvdv, .vti, ..." : the extensions of a kind the editor reads or writes,
/// from the one file registry (the help listed two volume formats of five).
QString extensions(LVDIFFiles::Kind kind, bool forSaving)
{
  QStringList list;
  for (const LVDIFFiles::Format& f : LVDIFFiles::Formats())
    if (f.kind == kind && !(forSaving ? f.writerClass : f.readerClass).empty())
      list << "." + QString::fromStdString(f.extension);
  return list.join(", ");
}

/// A batch output checked before any work, as the CLI does: a format the
/// editor writes there and a folder it can write to (it converted a mesh or
/// ran a script first and then failed on a missing folder or an unknown
/// extension; a screenshot into a missing folder said "no frame to save").
void checkOutput(const char* option, const QString& path, const LVDIFFiles::Kind* kind)
{
  if (path.isEmpty())
    return;
  const std::string p = path.toStdString();
  try
  {
    // the registry's words, as the CLI's (a Qt dialog filter, "Volumes (*.lvdv
    // ...);;LVDIF ...", was the list)
    if (kind)
      LVDIFFiles::RequireFormat(p, *kind, true);
    else if (LVDIFFiles::Extension(p) != "png")
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "a picture must be a .png file, not " + p);
    LVDIFFiles::RequireWritable(p);
  }
  catch (const lvdif::Error& e)
  {
    fail(QString("--%1 %2: %3").arg(option, path, e.what()));
  }
}
} // namespace

QStringList editorArguments(int argc, char* argv[])
{
  // Qt's own options (QGuiApplication, the xcb platform, QApplication), which
  // the QApplication takes out of argv: with a value, or a flag. Qt reads
  // them with one dash or two.
  static const QStringList valued{ "platform", "platformpluginpath", "platformtheme", "plugin", "qwindowgeometry",
    "geometry", "qwindowtitle", "title", "qwindowicon", "icon", "session", "display", "name", "visual", "style",
    "stylesheet", "qmljsdebugger" };
  static const QStringList flags{ "reverse", "testability", "sync", "nograb", "dograb", "widgetcount" };
  QStringList arguments;
  for (int i = 0; i < argc; ++i)
  {
    const QString a = QString::fromLocal8Bit(argv[i]);
    if (i == 0 || !a.startsWith('-') || a == "-" || a == "--")
    {
      arguments << a;
      continue;
    }
    QString name = a.mid(a.startsWith("--") ? 2 : 1);
    if (name.contains('='))
      name = name.left(name.indexOf('=')); // -style=fusion
    if (valued.contains(name) && !a.contains('='))
      ++i; // its value too
    else if (!valued.contains(name) && !flags.contains(name))
      arguments << a;
  }
  return arguments;
}

EditorOptions parseEditorOptions(const QStringList& arguments)
{
  QCommandLineParser p;
  // the exit status rule, as every `lvdif` command's --help gives it (the editor's gave none)
  p.setApplicationDescription("LVDIF volume editor\n\nexit status: 0 done, 1 failed while running (an input that "
                              "cannot be read, a failed step of a batch run; nothing is written after it), 2 "
                              "command line refused (nothing read or written), 130 cancelled (Ctrl-C)");
  p.addHelpOption();
  const LVDIFFiles::Kind volumeKind = LVDIFFiles::Kind::Volume, meshKind = LVDIFFiles::Kind::Mesh;
  const QCommandLineOption open("open", "Open a volume (" + extensions(volumeKind, false) + ").", "file");
  const QCommandLineOption openMesh("open-mesh", "Convert a mesh (" + extensions(meshKind, false) + ") to a volume and open it.", "file");
  // the range said (it was not), the dialog's, as the default: one constant each
  const QString defaultMeshRes = QString::number(MeshImportSettings().resolution);
  const QCommandLineOption meshRes("mesh-resolution",
    "Voxels along the mesh's longest axis, " + QString::number(MeshImportSettings().leastResolution()) + " to " +
      QString::number(lvdif::DictionaryVolume::MaxDimension) + " (at least 2 x its " +
      QString::number(MeshImportSettings().padding) + " voxels of padding + 2, as lvdif mesh-to-sdf --dims; --open-mesh; "
      "default " + defaultMeshRes + "). A volume that cannot fit the memory limit (LVDIF_MEMORY_LIMIT) is refused before "
      "converting.",
    "n", defaultMeshRes);
  const QCommandLineOption meshSign("mesh-sign", "Sign of --open-mesh: winding, pseudo or normal (default winding).", "mode", "winding");
  const QCommandLineOption meshReorient("mesh-reorient",
    "--open-mesh with the winding sign: re-orient the faces consistently (the CLI's --reorient).");
  const QCommandLineOption create("new", "New canvas of N^3 or NXxNYxNZ voxels, " +
    QString::number(lvdif::DictionaryVolume::MinCanvasDimension) + " to " + QString::number(lvdif::DictionaryVolume::MaxDimension) +
    " a side, as memory allows (without --open or --open-mesh: the canvas a --script recording was made on, else 128^3).", "size");
  const QCommandLineOption fill("fill",
    "Fill of a new canvas: empty, full or sphere (default sphere; with a --script, empty, as the start canvas of "
    "`lvdif script`; a recording keeps sphere).", "fill", "sphere");
  const QCommandLineOption script("script", "Run a script (.lvs) or play a recording (.lvr) after loading.", "file");
  const QCommandLineOption drag("replay-drag", "Synthetic left-drag through display points 'x,y;x,y;...' (or / between points).", "points");
  const QCommandLineOption undo("undo", "Undo N steps after the drag (default 0); more steps than there are fail the run.", "n", "0");
  const QCommandLineOption shot("screenshot", "Save a screenshot (PNG) and quit.", "file");
  const QCommandLineOption dragShot("screenshot-during-drag",
    "Save a screenshot of the view during --replay-drag, before the button is released.", "file");
  const QCommandLineOption windowShot("screenshot-window", "Save a picture of the whole window (PNG) and quit.", "file");
  const QCommandLineOption save("save", "Save the volume (" + extensions(volumeKind, true) + ") and quit.", "file");
  const QCommandLineOption exp("export", "Export the mesh (" + extensions(meshKind, true) + ") and quit.", "file");
  const QCommandLineOption op("op",
    "Tool: add, subtract, paint, smooth, inflate, grab, flatten, crease, pinch (default add).", "op", "add");
  const QCommandLineOption strength("strength",
    "Brush strength in (0, 1], of every tool (default: each tool's own).", "s");
  const QCommandLineOption falloff("falloff",
    "Brush falloff: constant, linear, smooth, sharp, of every tool (default: each tool's own).", "curve");
  const QCommandLineOption mirror("mirror", "Symmetry: the mirrored axes, e.g. x or xz.", "axes");
  const QCommandLineOption keys("keys", "Key presses before the drag, e.g. \"G ] Ctrl+Z\" (RightBracket/LeftBracket name ] and [) (tests).", "keys");
  const QCommandLineOption keysAfter("keys-after", "Key presses after the drag (tests).", "keys");
  const QCommandLineOption dragMods("drag-modifiers", "Keys held during --replay-drag: ctrl, shift or ctrl,shift.", "keys");
  const QCommandLineOption saveAsAnswer("save-as-answer", "The file the Save As dialog answers (tests).", "file");
  const QCommandLineOption openAnswer("open-answer", "The file an Open dialog answers (tests).", "file");
  const QCommandLineOption cancelDialogs("cancel-dialogs",
    "Cancel the first N dialogs that open; later ones get the answers above (tests).", "n");
  const QCommandLineOption printStatus("print-status", "Print the status bar's text when the work is done (tests).");
  const QCommandLineOption wheel("wheel",
    "Turn the mouse wheel N steps over the first --replay-drag point before the press (negative: backward) (tests).",
    "n");
  const QCommandLineOption recoveryAnswer("recovery-answer",
    "What the question to recover an autosaved volume answers: yes, no or discard; asked in a batch run too (tests).",
    "answer");
  const QCommandLineOption shape("shape", "Brush shape: sphere or cube (default sphere).", "shape", "sphere");
  const QCommandLineOption kind("brush", "Brush kind: basic, dynamic or drill (default basic).", "kind", "basic");
  // the range and the default are Core's, one constant each (the editor said 4 where every other front end uses 3)
  const QString maxRadius = QString::number(lvdif::EditLimits::MaxSize); // 1e+07
  const QString defaultRadius = QString::number(EditorOptions().radius, 'g', 17);
  const QCommandLineOption radius("radius",
    "Brush radius in voxels, in (0, " + maxRadius + "] (default " + defaultRadius + ").", "r", defaultRadius);
  const QCommandLineOption color("color", "Brush colour, #rrggbb or an SVG colour name (default: the panel's).", "color");
  const QCommandLineOption size("size",
    "Window size WxH in pixels (default 900x700); at least the window's least size (the Brush panel's height), at "
    "most the screen's.",
    "size", "900x700");
  const QCommandLineOption quit("quit", "Quit when the command-line work is done.");
  const QCommandLineOption noRecovery("no-recovery", "Do not offer to recover an autosaved volume.");
  const QCommandLineOption recoveryDir("recovery-dir", "Folder of the autosave file (default: the application's data folder).", "dir");
  const QCommandLineOption autosave("autosave", "Autosave interval in seconds (0: off; default 60).", "s", "60");
  const QCommandLineOption matcap("matcap", "Matcap shading with this image (PNG, JPG).", "file");
  const QCommandLineOption perVertex("per-vertex-color", "Per-vertex colours instead of tetrahedral interpolation.");
  const QCommandLineOption benchmark("benchmark-stroke",
    "Replay a recorded stroke (JSON-lines samples or .lvr) at its speed, print the latency and FPS, quit.", "file");
  const QCommandLineOption timing("timing",
    "Print (stderr) when the first surface was shown and when every chunk was meshed and shown, in ms after the window was made.");
  const QCommandLineOption fullRedraw("full-redraw",
    "Draw every frame whole (by default a frame in which the camera stands still redraws only the screen region that changed).");
  const QCommandLineOption samples("samples",
    "Samples per pixel of the view (multisampling; 0: none). Default: VTK's (up to 8; Mesa llvmpipe gives 4).", "n");
  const QCommandLineOption drawRanges("draw-ranges",
    "Triangles per draw range of a chunk (default 32; 0: each chunk in one draw call): a frame drawn in part draws only "
    "the ranges of a chunk that reach into the redrawn region.", "n");
  const QCommandLineOption stockBackground("stock-background",
    "Draw the gradient background as VTK does, with a new quad each frame (by default the quad is kept between frames; "
    "the same picture). For comparisons.");
  const QCommandLineOption widgetView("widget-view",
    "Show the view as a widget that Qt composes into the window after each frame (QVTKOpenGLNativeWidget), as before; "
    "by default it is a native window of its own (QVTKOpenGLWindow in a window container), presented alone. For "
    "comparisons.");
  const QCommandLineOption strokeLod("stroke-lod",
    "Level of detail of a stroke's frames: auto (default), on or off. While you drag, the mesh chunks a frame changed "
    "are meshed on every 2nd voxel (about 1/4 of the triangles; on: always, auto: when the frame changed " +
      QString::number(strokeLodMinChunks("auto")) +
      " or more chunks, as a large brush does) and shown at once; when the stroke ends they are meshed again at full "
      "resolution, so the surface at rest is exactly the one without it. Also in the View menu.",
    "mode", "auto");
  const QCommandLineOption multisampledDrag("multisampled-drag",
    "Draw a stroke's frames with the view's multisampling (by default they have one sample per pixel and the view is "
    "drawn whole, multisampled, once the stroke is still). For comparisons.");
  // What a user reaches for first; the options for tests and comparisons last.
  p.addOptions({ open, openMesh, meshRes, meshSign, meshReorient, create, fill, script, save, exp, shot, windowShot,
    op, shape, kind, radius, color, strength, falloff, mirror, size, samples, perVertex, matcap, strokeLod, autosave, noRecovery,
    recoveryDir, quit, drag, dragShot, undo, dragMods, keys, keysAfter, saveAsAnswer, openAnswer, cancelDialogs, wheel, printStatus, recoveryAnswer, benchmark, timing, fullRedraw,
    drawRanges, multisampledDrag, stockBackground, widgetView });
  // an unknown option or a missing value: one line and status 2, as every
  // other refused option (Qt's process() exits with 1)
  if (!p.parse(arguments))
    fail(p.errorText());
  if (p.isSet("help") || p.isSet("help-all"))
  {
    // the help's usage line names the program through the application
    // object: a QCoreApplication, which needs no display
    int argc = 1;
    QByteArray program = arguments.value(0, "lvdif-editor").toLocal8Bit();
    char* argv[] = { program.data(), nullptr };
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName("lvdif-editor");
    p.process(arguments); // prints the help and exits 0
  }
  // `lvdif-editor model.lvdv` opened a 128^3 sphere canvas and ignored the file
  if (!p.positionalArguments().isEmpty())
    fail("unexpected argument '" + p.positionalArguments().first() +
      "': the editor takes options only (a volume: --open FILE, a mesh: --open-mesh FILE, a script: --script FILE)");
  // as the CLI: an option given twice is refused (Qt's parser silently took the last)
  const QStringList given = p.optionNames();
  for (const QString& name : given)
    if (given.count(name) > 1)
      fail("--" + name + " is given twice");

  EditorOptions o;
  o.open = p.value(open);
  o.openMesh = p.value(openMesh);
  // every fitted grid's range, as `lvdif mesh-to-sdf --dims` (it was 8 to 4096 here, 2 to 1048576 there) ...
  o.meshResolution = integerOption(p.value(meshRes), "--mesh-resolution", lvdif::DictionaryVolume::MinCanvasDimension,
    lvdif::DictionaryVolume::MaxDimension);
  // ... and the padding's least, said why, as the CLI's --dims below 2 x padding + 2
  if (o.meshResolution < MeshImportSettings().leastResolution())
    fail("--mesh-resolution " + QString::number(o.meshResolution) + " leaves no voxel for the mesh inside the " +
      QString::number(MeshImportSettings().padding) + " voxels of padding on every side: use at least " +
      QString::number(MeshImportSettings().leastResolution()) + " (2 x padding + 2)");
  o.meshSign = p.value(meshSign);
  try
  {
    meshSignModeFromName(o.meshSign);
  }
  catch (const lvdif::Error& e)
  {
    fail(e.what());
  }
  o.meshReorient = p.isSet(meshReorient);
  if (o.meshReorient && o.meshSign != "winding")
    fail("--mesh-reorient needs --mesh-sign winding");
  if (p.isSet(create))
  {
    const QStringList parts = p.value(create).split('x');
    if (parts.size() != 1 && parts.size() != 3)
      fail("--new expects N or NXxNYxNZ, got '" + p.value(create) + "'");
    // whole numbers first (any int: the canvas rule below names the range)
    int n[3];
    for (int a = 0; a < 3; ++a)
    {
      bool ok = false;
      const QString& part = parts[parts.size() == 1 ? 0 : a];
      const qint64 v = plainNumberText(part.toStdString()) ? part.toLongLong(&ok) : 0;
      if (!ok || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        fail("--new expects N or NXxNYxNZ in whole numbers of voxels, got '" + p.value(create) + "'" +
          QString::fromStdString(numberTextHint(part.toStdString())));
      n[a] = static_cast<int>(v);
    }
    o.newDims = { n[0], n[1], n[2] };
    // the editors' one smallest and largest canvas
    const std::string tooThin = lvdif::DictionaryVolume::checkCanvasDimensions({ o.newDims[0], o.newDims[1], o.newDims[2] });
    if (!tooThin.empty())
      fail("--new " + p.value(create) + ": " + QString::fromStdString(tooThin));
    // the chunk table of the canvas (what making it allocates first) against the memory limit,
    // in the CLI's words for its --size: it was the canvas's own error after Qt had started,
    // naming no option, status 1 (and without a display, the display's error)
    try
    {
      RequireChunkTable({ o.newDims[0], o.newDims[1], o.newDims[2] }, "--new " + p.value(create).toStdString() + " makes a canvas", "use a smaller --new");
    }
    catch (const lvdif::Error& e)
    {
      fail(e.what());
    }
  }
  o.fill = p.value(fill);
  o.fillGiven = p.isSet(fill);
  try
  {
    lvdif::canvasFillFromName(o.fill.toStdString(), "--fill"); // Core's words, as `lvdif play --fill`
  }
  catch (const lvdif::Error& e)
  {
    fail(e.what());
  }
  o.script = p.value(script);
  if (p.isSet(drag))
  {
    for (const QString& pt : p.value(drag).split(QRegularExpression("[;/ ]"), Qt::SkipEmptyParts))
    {
      const QStringList xy = pt.split(',');
      bool ok1 = false, ok2 = false;
      double x = 0, y = 0;
      if (xy.size() == 2)
      {
        x = xy[0].toDouble(&ok1);
        y = xy[1].toDouble(&ok2);
      }
      // finite numbers: "nan,0.5" or "inf,1" were taken, and the drag went nowhere without a word
      if (!ok1 || !ok2 || !std::isfinite(x) || !std::isfinite(y) || std::fabs(x) > 1e9 || std::fabs(y) > 1e9)
        fail("--replay-drag expects 'x,y;x,y;...' (pixels, or fractions of the view), got '" + pt + "'");
      o.drag.push_back(QPointF(x, y));
    }
  }
  o.undo = integerOption(p.value(undo), "--undo", 0, std::numeric_limits<int>::max());
  o.screenshot = p.value(shot);
  o.windowShot = p.value(windowShot);
  o.dragShot = p.value(dragShot);
  o.save = p.value(save);
  o.exportMesh = p.value(exp);
  o.op = p.value(op).toLower();
  if (!QStringList{ "add", "subtract", "paint", "smooth", "inflate", "grab", "flatten", "crease", "pinch" }.contains(o.op))
    fail("--op expects add, subtract, paint, smooth, inflate, grab, flatten, crease or pinch, got '" + o.op + "'");
  if (p.isSet(strength))
    o.strength = positiveOption(p.value(strength), "--strength", 1);
  const QStringList curves{ "constant", "linear", "smooth", "sharp" };
  if (p.isSet(falloff))
  {
    o.falloff = curves.indexOf(p.value(falloff).toLower());
    if (o.falloff < 0)
      fail("--falloff expects constant, linear, smooth or sharp, got '" + p.value(falloff) + "'");
  }
  o.mirror = p.value(mirror).toLower();
  if (o.mirror.contains(QRegularExpression("[^xyz]")))
    fail("--mirror expects axis letters x, y, z, got '" + o.mirror + "'");
  o.keys = p.value(keys);
  o.keysAfter = p.value(keysAfter);
  // every word a key, before the window and the work (a misspelt key failed the run after the
  // volume was loaded, a mesh converted or a script run, status 1)
  for (const QCommandLineOption* option : { &keys, &keysAfter })
    for (const QString& word : p.value(*option).split(' ', Qt::SkipEmptyParts))
      if (editorKeyOfWord(word) == 0)
        fail("--" + option->names().first() + ": '" + word + "' is not a key (Qt's key names, as \"G ] Ctrl+Z\"; "
          "LeftBracket and RightBracket for [ and ])");
  for (const QString& m : p.value(dragMods).toLower().split(',', Qt::SkipEmptyParts))
  {
    if (m == "ctrl")
      o.dragCtrl = true;
    else if (m == "shift")
      o.dragShift = true;
    else
      fail("--drag-modifiers expects ctrl and/or shift, got '" + m + "'");
  }
  o.saveAsAnswer = p.value(saveAsAnswer);
  o.openAnswer = p.value(openAnswer);
  if (p.isSet(cancelDialogs))
    o.cancelDialogs = integerOption(p.value(cancelDialogs), "--cancel-dialogs", 0, 1000);
  o.printStatus = p.isSet(printStatus);
  if (p.isSet(wheel))
    o.wheel = integerOption(p.value(wheel), "--wheel", -1000, 1000);
  o.recoveryAnswer = p.value(recoveryAnswer).toLower();
  if (p.isSet(recoveryAnswer) && !QStringList{ "yes", "no", "discard" }.contains(o.recoveryAnswer))
    fail("--recovery-answer expects yes, no or discard, got '" + p.value(recoveryAnswer) + "'");
  if (p.isSet(recoveryAnswer) && p.isSet(noRecovery))
    fail("--recovery-answer answers the offer to recover, which --no-recovery turns off: use one of them");
  o.shape = p.value(shape).toLower();
  if (o.shape != "sphere" && o.shape != "cube")
    fail("--shape expects sphere or cube, got '" + p.value(shape) + "'");
  o.kind = p.value(kind).toLower();
  if (o.kind != "basic" && o.kind != "dynamic" && o.kind != "drill")
    fail("--brush expects basic, dynamic or drill, got '" + p.value(kind) + "'");
  // the one radius rule of every edit input (scripts, recordings, the API)
  o.radius = positiveOption(p.value(radius), "--radius", lvdif::EditLimits::MaxSize);
  o.color = p.value(color);
  if (p.isSet(color) && !QColor(o.color).isValid())
    fail("--color expects #rrggbb or a colour name, got '" + o.color + "'");
  const QStringList wh = p.value(size).split('x');
  if (wh.size() != 2) fail("--size expects WxH, got '" + p.value(size) + "'");
  {
    o.width = integerOption(wh[0], "--size", 1, 16384);
    o.height = integerOption(wh[1], "--size", 1, 16384);
  }
  o.sizeGiven = p.isSet(size);
  o.quit = p.isSet(quit);
  o.noRecovery = p.isSet(noRecovery);
  o.recoveryDir = p.value(recoveryDir);
  // A folder the autosave can write to, or one that can be made there: a file
  // or an unwritable place was taken without a word, and every autosave then
  // failed (a status bar line for 5 s), the work unguarded.
  if (!o.recoveryDir.isEmpty())
  {
    QFileInfo at(o.recoveryDir);
    while (!at.exists() && !at.isRoot() && at.absoluteFilePath() != at.absolutePath())
      at = QFileInfo(at.absolutePath()); // the nearest part of the path that exists
    if (at.exists() && !at.isDir())
      fail("--recovery-dir " + o.recoveryDir + ": '" + at.filePath() + "' is a file, not a folder");
    if (!at.exists() || !at.isWritable())
      fail("--recovery-dir " + o.recoveryDir + ": the folder '" + at.filePath() + "' is not writable");
  }
  o.autosaveSeconds = integerOption(p.value(autosave), "--autosave", 0, std::numeric_limits<int>::max() / 1000); // a QTimer takes ms
  o.perVertexColor = p.isSet(perVertex);
  o.matcap = p.value(matcap);
  o.benchmarkStroke = p.value(benchmark);
  o.timing = p.isSet(timing);
  o.fullRedraw = p.isSet(fullRedraw);
  o.stockBackground = p.isSet(stockBackground);
  o.nativeView = !p.isSet(widgetView);
  o.multisampledDrag = p.isSet(multisampledDrag);
  o.strokeLod = p.value(strokeLod);
  if (o.strokeLod != "auto" && o.strokeLod != "on" && o.strokeLod != "off")
    fail("--stroke-lod expects auto, on or off, got '" + o.strokeLod + "'");
  if (p.isSet(drawRanges))
    o.drawRangeTriangles = integerOption(p.value(drawRanges), "--draw-ranges", 0, std::numeric_limits<int>::max());
  if (p.isSet(samples))
    o.samples = integerOption(p.value(samples), "--samples", 0, 16);
  // One source of the volume: the editor opened the first of --open-mesh,
  // --open and --new and silently ignored the others, and the options of a
  // source not given (--fill with --open, --mesh-sign without --open-mesh).
  if (p.isSet(open) + p.isSet(openMesh) + p.isSet(create) > 1)
    fail("--open, --open-mesh and --new each give the volume: use one of them");
  if (p.isSet(fill) && (p.isSet(open) || p.isSet(openMesh)))
    fail("--fill fills a new canvas (--new): not with --open or --open-mesh");
  if ((p.isSet(meshRes) || p.isSet(meshSign) || p.isSet(meshReorient)) && !p.isSet(openMesh))
    fail("--mesh-resolution, --mesh-sign and --mesh-reorient are options of --open-mesh, which is not given");
  // without a drag they did nothing: --screenshot-during-drag wrote no picture
  // (and, being no batch output, left the window open for good)
  if ((p.isSet(dragShot) || p.isSet(dragMods)) && !p.isSet(drag))
    fail("--screenshot-during-drag and --drag-modifiers are options of --replay-drag, which is not given");
  if (p.isSet(wheel) && !p.isSet(drag))
    fail("--wheel turns the wheel over the first point of --replay-drag, which is not given");
  // the benchmark replays its stroke and quits: the command line's other work
  // was silently skipped (--benchmark-stroke S --save out.lvdv saved nothing)
  if (p.isSet(benchmark))
    for (const QCommandLineOption* work : { &script, &matcap, &keys, &drag, &keysAfter, &undo, &shot, &windowShot,
           &save, &exp, &quit })
      if (p.isSet(*work))
        fail("--benchmark-stroke replays its stroke, prints the latency and quits: not with --" + work->names().first() +
          " (it was skipped)");
  // A recording given without a volume to play it on (no --new, --open or
  // --open-mesh) starts from the starter canvas of its own size, the one it was
  // recorded on: `lvdif-editor --script strokes.lvr` played on the 128^3 canvas
  // and was refused ("the recording was made on a 64 x 16 x 24 canvas; this
  // volume is 128 x 128 x 128"). So does --benchmark-stroke's recording. A size
  // the canvas rule refuses is left to the playback's refusal.
  if (!p.isSet(create) && !p.isSet(open) && !p.isSet(openMesh))
    for (const QString& file : { o.script, o.benchmarkStroke })
      if (!file.isEmpty() && !isScriptFile(file))
      {
        lvdif::Index3 c{ 0, 0, 0 };
        try
        {
          c = lvdif::loadRecording(file.toLocal8Bit().toStdString()).canvas;
        }
        catch (const std::exception&)
        {
          // the playback names what is wrong with it
        }
        bool fits = c[0] > 0 && lvdif::DictionaryVolume::checkCanvasDimensions(c).empty();
        try
        {
          if (fits)
            RequireChunkTable(c, "the canvas", "");
        }
        catch (const lvdif::Error&)
        {
          fits = false;
        }
        if (fits)
          o.newDims = { int(c[0]), int(c[1]), int(c[2]) };
        break;
      }
  checkOutput("save", o.save, &volumeKind);
  checkOutput("export", o.exportMesh, &meshKind);
  checkOutput("screenshot", o.screenshot, nullptr);
  checkOutput("screenshot-window", o.windowShot, nullptr);
  checkOutput("screenshot-during-drag", o.dragShot, nullptr);
  // The new canvas's size against --save's rule on it (a .bv holds cubic
  // volumes only), before any work, as the CLI's: --new 32x32x16 --save x.bv
  // made the canvas and did the drag and the screenshots, then failed to save.
  // A script may make its own canvas: its `canvas N` is checked where it
  // stands (MainWindow::runScript); a recording plays on this canvas.
  if (!o.save.isEmpty() && o.open.isEmpty() && o.openMesh.isEmpty() && (o.script.isEmpty() || !isScriptFile(o.script)))
  {
    const std::array<int, 3> d = o.canvasDims();
    const std::string refused = VolumeOutputDimsProblem(o.save.toStdString(), { d[0], d[1], d[2] });
    if (!refused.empty())
      fail("--save " + o.save + ": " + QString::fromStdString(refused));
  }
  return o;
}
