// The editor's command-line automation: --script, --keys, --replay-drag,
// --keys-after, --undo, --screenshot*, --save, --export, --save-as-answer and
// --benchmark-stroke (docs/USER_GUIDE.md, "Command line"). The app tests and
// the user guide's pictures are made this way.
//
// It drives a MainWindow only from outside, as a user or a device would: its
// public operations (the ones its menus call), its brush-input slots and
// meshesShown signal, the document it shows, and synthetic Qt events on the
// view (mouse drags, key clicks through Qt's shortcut system, answers to file
// dialogs). MainWindow knows nothing of it.
#pragma once

#include <QElapsedTimer>
#include <QObject>
#include <QPointF>
#include <QString>
#include <QVector>

struct EditorOptions;
class MainWindow;

/// The key combination of one word of --keys (QKeySequence's portable text, "Ctrl+Z";
/// LeftBracket/RightBracket for [ and ]) as Qt's key code with its modifiers; 0 when the
/// word is not one key. The option parser checks every word with it before the window opens.
int editorKeyOfWord(QString word);

class EditorDriver : public QObject
{
  Q_OBJECT
public:
  /// `sinceWindow` was started when the window was made (--timing).
  EditorDriver(MainWindow& window, const EditorOptions& options, QElapsedTimer sinceWindow);

  /// The work of the command line (script, keys, drag, keys after, undo, then
  /// screenshots, save, export); 0 if every step succeeded, else 1.
  int runBatch();

  /// Blocks until every requested chunk is meshed and shown (the interactive
  /// view never waits: the batch's screenshots and the drag's picking need the
  /// whole surface).
  void waitForSurface();
  /// Processes events until the window is exposed and the view's render
  /// window has the widget's size, the same on two turns in a row (at most
  /// 10 s): batch steps start on the event loop's first turn, and a drag given
  /// in fractions of the view must not map them through a size still changing.
  void waitForLayout();
  /// waitForSurface without the --timing report (between a drag's samples).
  void showAllMeshes();

  /// A left-drag through display points (VTK display coordinates, origin
  /// bottom-left; fractions of the view if every coordinate is in [0, 1]) as Qt
  /// mouse events on the view, with Ctrl and/or Shift held as a user would.
  /// With `shotBeforeRelease`, a screenshot of the view before the release.
  /// With `wheelSteps`, the wheel turns that many steps (negative: backward)
  /// over the first point before the press, as a user sizes the brush.
  void drag(const QVector<QPointF>& points, bool ctrl, bool shift, const QString& shotBeforeRelease = QString(),
    int wheelSteps = 0);

  /// Types key combinations ("G ] Ctrl+Z", QKeySequence's portable text, one per
  /// word; LeftBracket/RightBracket for [ and ]) into the window through Qt's
  /// shortcut system, as a keyboard would; false if a word is not a key or Qt5Test
  /// was missing at build time.
  bool typeKeys(const QString& keys);

  /// From now on, a Save file dialog that opens is answered with `path`, an
  /// Open file dialog with `openPath` (if not empty); in a batch run any other
  /// dialog (or a file dialog without its answer) is cancelled, and the run fails.
  /// The first `cancels` file dialogs are cancelled, as a user's Cancel.
  void answerSaveDialogs(const QString& path, const QString& openPath = QString(), int cancels = 0);

  /// --benchmark-stroke: once the surface is shown, replays the samples of
  /// `path` through the brush input (StrokeBenchmark.h), prints the latency and
  /// quits the application; false (with a message) if the file cannot be read.
  bool startStrokeBenchmark(const QString& path);

private:
  void answerShownSaveDialog();

  MainWindow& Window;
  const EditorOptions& Options;
  QElapsedTimer SinceWindow;
  QString SaveAnswer, OpenAnswer;
  int CancelsLeft = 0;
  int Unanswered = 0; // dialogs a batch run cancelled for want of an answer
  bool Answering = false;
};
