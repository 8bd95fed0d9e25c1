// Command-line options of the editor (for users and for the tests).
#pragma once

#include <QPointF>
#include <QString>
#include <QVector>

#include "lvdif/Stroke.h"

#include <array>
#include <cstddef>

struct EditorOptions
{
  QString open;               // --open FILE (.vti)
  QString openMesh;           // --open-mesh FILE (.obj .off .stl .ply), converted to a volume
  int meshResolution = 128;   // --mesh-resolution N (points along the mesh's longest axis)
  QString meshSign = "winding"; // --mesh-sign winding|pseudo|normal
  bool meshReorient = false;  // --mesh-reorient (winding sign: the faces re-oriented consistently)
  std::array<int, 3> newDims{ 0, 0, 0 }; // --new N or NXxNYxNZ
  QString fill = "sphere";    // --fill empty|full|sphere
  bool fillGiven = false;     // --fill given (without it a --script, not a recording, starts from an empty canvas)
  QString script;             // --script FILE (a recording to play)
  QVector<QPointF> drag;      // --replay-drag "x,y;x,y;..." (display pixels, origin bottom-left; or fractions of the view if all in [0,1])
  int undo = 0;               // --undo N after the drag
  QString screenshot;         // --screenshot FILE.png (the view)
  QString windowShot;         // --screenshot-window FILE.png (the whole window)
  QString dragShot;           // --screenshot-during-drag FILE.png (the view before the button is released)
  QString save;               // --save FILE.vti
  QString exportMesh;         // --export FILE.ply|obj|stl
  QString op = "add", shape = "sphere", kind = "basic"; // --op (a tool name) --shape --brush
  double strength = -1;       // --strength (0, 1] of every tool; < 0: each tool's own
  int falloff = -1;           // --falloff constant|linear|smooth|sharp of every tool; < 0: each tool's own
  QString mirror;             // --mirror: letters of the mirrored axes, e.g. "x" or "xz"
  QString keys, keysAfter;    // --keys / --keys-after: key presses before / after the drag ("G ] Ctrl+Z")
  bool dragCtrl = false, dragShift = false; // --drag-modifiers ctrl,shift
  int cancelDialogs = 0;      // --cancel-dialogs N: the first N file dialogs are cancelled (tests)
  bool printStatus = false;   // --print-status: print the status bar's text when the work is done (tests)
  int wheel = 0;              // --wheel N: wheel steps over the first --replay-drag point before the press (< 0: backward) (tests)
  QString saveAsAnswer;       // --save-as-answer FILE: what the Save As dialog answers (tests)
  QString openAnswer;         // --open-answer FILE: what an Open file dialog answers (tests)
  QString recoveryAnswer;     // --recovery-answer yes|no|discard: what the recovery question answers (tests)
  double radius = lvdif::StrokeSettings{}.radius; // --radius voxels (Core's default, as the CLI, scripts and ParaView)
  QString color;              // --color #rrggbb
  int width = 900, height = 700; // --size WxH of the window
  bool sizeGiven = false;     // --size given: below the window's least size it is refused (main.cpp)
  bool quit = false;          // --quit when done (implied by --screenshot/--save/--export)
  bool noRecovery = false;    // --no-recovery: never offer to recover
  QString recoveryDir;        // --recovery-dir DIR (default: the app data folder)
  int autosaveSeconds = 60;   // --autosave S
  bool perVertexColor = false; // --per-vertex-color
  QString matcap;             // --matcap FILE: matcap shading with this image
  QString benchmarkStroke;    // --benchmark-stroke FILE: replay a recorded stroke, print latency and FPS, quit
  bool timing = false;        // --timing: print when the first surface and the whole surface were shown
  bool fullRedraw = false;    // --full-redraw: draw every frame whole (no partial redraw of what changed)
  int samples = -1;           // --samples N: multisamples per pixel of the view (-1: VTK's default)
  bool multisampledDrag = false; // --multisampled-drag: a stroke's frames with the view's multisampling (as before)
  bool nativeView = true;     // the view in a native window of its own (QVTKOpenGLWindow), presented alone; --widget-view: false
  bool stockBackground = false; // --stock-background: VTK's gradient background, a new quad per frame (comparisons)
  int drawRangeTriangles = 32; // --draw-ranges N: triangles per draw range of a chunk (0: one draw per chunk)
  QString strokeLod = "auto"; // --stroke-lod auto|on|off: a stroke's frames meshed coarsely, refined at its end (View menu too)
  /// The size of the canvas made when no file is opened: --new (or, without it, a
  /// --script or --benchmark-stroke recording's canvas), or 128^3.
  std::array<int, 3> canvasDims() const
  {
    return { newDims[0] > 0 ? newDims[0] : 128, newDims[1] > 0 ? newDims[1] : 128, newDims[2] > 0 ? newDims[2] : 128 };
  }
  bool batch() const { return this->quit || !this->screenshot.isEmpty() || !this->windowShot.isEmpty() || !this->save.isEmpty() || !this->exportMesh.isEmpty(); }
};

/// The mesh chunks a frame of a stroke must invalidate for its meshes to be
/// made coarsely (lvdif::EditSession::setCoarseMeshing) under a --stroke-lod
/// mode (auto, on, off); one rule for the option and the View menu.
std::size_t strokeLodMinChunks(const QString& mode);

/// The command line without Qt's own options (-platform, -display, -style,
/// -geometry, ...), which the QApplication takes: the editor's options are
/// checked before it starts, so a bad one is refused with status 2 even
/// without a display.
QStringList editorArguments(int argc, char* argv[]);

/// Parses the arguments in one pass: --help prints the options and exits 0, a
/// bad option is one line on stderr and exit status 2. Needs no QApplication.
EditorOptions parseEditorOptions(const QStringList& arguments);
