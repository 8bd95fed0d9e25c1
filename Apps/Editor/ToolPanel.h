// The brush controls (a dock): operation, shape, brush kind, radius, colour,
// smooth blend, and the undo / record buttons. It only edits a BrushState
// and says so; MainWindow applies it to the Core editor.
#pragma once

#include <QColor>
#include <QWidget>

class QButtonGroup;
class QLabel;
class QPushButton;
class QSlider;

struct BrushState
{
  int op = 0;    // 0 add, 1 subtract, 2 paint (lvdif::BrushOp)
  int shape = 0; // 0 sphere, 1 cube (lvdif::BrushShape)
  int kind = 1;  // 1 basic, 2 dynamic, 3 drill (lvdif::BrushKind)
  double radius = 4.0; // voxels
  double blend = 0.0;  // voxels
  QColor color = QColor(230, 90, 60);
};

class ToolPanel : public QWidget
{
  Q_OBJECT
public:
  explicit ToolPanel(QWidget* parent = nullptr);
  const BrushState& state() const { return this->State; }
  void setRadius(double voxels); // from the wheel: updates the slider quietly
  void setState(const BrushState& s);
  void setRecording(bool on);

Q_SIGNALS:
  void changed();
  void undoRequested();
  void redoRequested();
  void recordToggled(bool on);
  void playRequested();

private:
  void pickColor();
  void updateColorButton();

  BrushState State;
  QButtonGroup* Ops;
  QButtonGroup* Shapes;
  QButtonGroup* Kinds;
  QSlider* Radius;
  QLabel* RadiusLabel;
  QSlider* Blend;
  QLabel* BlendLabel;
  QPushButton* ColorButton;
  QPushButton* RecordButton;
};
