// The brush controls (a dock): tool (operation), shape, brush kind, radius,
// strength, falloff, symmetry, colour, smooth blend, and the undo / record buttons. It only edits a BrushState
// and says so; MainWindow applies it to the Core editor.
#pragma once

#include "lvdif/Stroke.h"

#include <QColor>
#include <QWidget>

class QButtonGroup;
class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;
class QSlider;

struct BrushState
{
  int op = 0;    // lvdif::BrushOp: 0 add, 1 subtract, 2 paint, 3 smooth, 4 inflate, 5 grab, 6 flatten, 7 crease, 8 pinch
  int shape = 0; // 0 sphere, 1 cube (lvdif::BrushShape)
  int kind = 1;  // 1 basic, 2 dynamic, 3 drill (lvdif::BrushKind)
  double radius = lvdif::StrokeSettings{}.radius; // voxels: Core's default, as every front end
  double blend = 0.0;  // voxels
  double strength = 1.0; // (0, 1]
  int falloff = 0;       // lvdif::Falloff: 0 constant, 1 linear, 2 smooth, 3 sharp
  bool mirror[3] = { false, false, false }; // symmetry about the volume's centre planes
  // Core's default, as every front end (the editor had its own, scripts and the CLI white)
  QColor color = QColor(lvdif::DefaultBrushColor.r, lvdif::DefaultBrushColor.g, lvdif::DefaultBrushColor.b,
    lvdif::DefaultBrushColor.a);
};

/// The tools in lvdif::BrushOp order: name, shortcut key, tool tip.
struct ToolInfo
{
  const char* name;
  char key;
  const char* tip;
};
const ToolInfo& toolInfo(int op);
constexpr int ToolCount = 9;

class ToolPanel : public QWidget
{
  Q_OBJECT
public:
  explicit ToolPanel(QWidget* parent = nullptr);
  const BrushState& state() const { return this->State; }
  void setRadius(double voxels); // from the wheel: updates the slider quietly
  void setState(const BrushState& s);
  void setRecording(bool on);
  /// Presses the Record / Stop button (Edit > Record, Ctrl+R).
  void toggleRecording();
  /// Selects a tool (lvdif::BrushOp) and says so.
  void setOp(int op);
  /// Every tool's strength (if > 0) and falloff (if >= 0), as the command
  /// line gives them: the tool shown now and those picked later.
  void setEveryTool(double strength, int falloff);

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
  /// Each tool's own strength and falloff, restored when it is picked again.
  double ToolStrength[ToolCount];
  int ToolFalloff[ToolCount];
  void switchTool(int op);
  QButtonGroup* Ops;
  QButtonGroup* Shapes;
  QButtonGroup* Kinds;
  QSlider* Radius;
  QLabel* RadiusLabel;
  QSlider* Blend;
  QLabel* BlendLabel;
  QSlider* Strength;
  QLabel* StrengthLabel;
  QComboBox* Falloff;
  QCheckBox* Mirror[3];
  QPushButton* ColorButton;
  QPushButton* RecordButton;
};
