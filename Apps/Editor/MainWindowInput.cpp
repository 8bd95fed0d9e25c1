// MainWindow: synthetic input for tests and scripted screenshots: a mouse drag
// as interactor events, key presses through Qt's shortcut system.
#include "MainWindow.h"

#include "vtkCommand.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkRenderWindowInteractor.h"

#include <QApplication>
#include <QKeySequence>
#include <QVTKOpenGLNativeWidget.h>
#ifdef LVDIF_EDITOR_HAVE_QTTEST
#include <QTest>
#endif

#include <cctype>
#include <cmath>
#include <cstdio>

void MainWindow::replayDrag(const QVector<QPointF>& points, bool ctrl, bool shift)
{
  vtkRenderWindowInteractor* iren = this->View->interactor();
  // Points with both coordinates in [0, 1] are fractions of the view's size.
  bool fractions = true;
  for (const QPointF& p : points)
    fractions = fractions && p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1;
  const int* size = this->RenderWindow->GetSize();
  const double sx = fractions ? size[0] : 1.0, sy = fractions ? size[1] : 1.0;
  auto send = [iren, sx, sy, ctrl, shift](const QPointF& p, unsigned long event) {
    iren->SetEventInformation(
      static_cast<int>(std::lround(p.x() * sx)), static_cast<int>(std::lround(p.y() * sy)), ctrl, shift);
    iren->InvokeEvent(event, nullptr);
  };
  if (points.isEmpty())
    return;
  send(points.front(), vtkCommand::MouseMoveEvent);
  send(points.front(), vtkCommand::LeftButtonPressEvent);
  for (int i = 1; i < points.size(); ++i)
  {
    send(points[i], vtkCommand::MouseMoveEvent);
    QApplication::processEvents();
  }
  send(points.back(), vtkCommand::LeftButtonReleaseEvent);
  iren->SetEventInformation(iren->GetEventPosition()[0], iren->GetEventPosition()[1], 0, 0);
}

bool MainWindow::typeKeys(const QString& keys)
{
#ifdef LVDIF_EDITOR_HAVE_QTTEST
  for (QString word : keys.split(' ', Qt::SkipEmptyParts))
  {
    // bracket names for callers that cannot pass brackets (CMake lists)
    word.replace("LeftBracket", "[").replace("RightBracket", "]");
    const QKeySequence seq = QKeySequence::fromString(word, QKeySequence::PortableText);
    if (seq.isEmpty() || seq[0] == 0)
    {
      std::fprintf(stderr, "lvdif-editor: --keys: '%s' is not a key\n", word.toLocal8Bit().constData());
      return false;
    }
    const int k = seq[0];
    // without a window manager (Xvfb) nothing activates the window, and window
    // shortcuts only fire in the active window
    QApplication::setActiveWindow(this);
    this->View->setFocus();
    const int key = k & ~Qt::KeyboardModifierMask;
    const Qt::KeyboardModifiers mods(k & Qt::KeyboardModifierMask);
    // printable keys by their character (QTest knows the text of every one of them)
    if (key >= 0x20 && key <= 0x7e)
      QTest::keyClick(this->View, static_cast<char>(std::tolower(key)), mods);
    else
      QTest::keyClick(this->View, Qt::Key(key), mods);
    QApplication::processEvents();
  }
  return true;
#else
  (void)keys;
  std::fprintf(stderr, "lvdif-editor: --keys needs Qt5Test at build time\n");
  return false;
#endif
}
