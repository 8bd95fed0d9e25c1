#include "ToolPanel.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>

#include <cmath>

const ToolInfo& toolInfo(int op)
{
  static const ToolInfo tools[ToolCount] = {
    { "Add", 'A', "Add material: the union with the brush (Ctrl: subtract)" },
    { "Subtract", 'S', "Carve: subtract the brush (Ctrl: add)" },
    { "Paint", 'P', "Paint the surface; soft edges with a falloff" },
    { "Smooth", 'M', "Smooth the surface inside the brush (or hold Shift with any tool)" },
    { "Inflate", 'I', "Push the surface outward (Ctrl: deflate)" },
    { "Grab", 'G', "Drag a region of the surface with the mouse" },
    { "Flatten", 'T', "Pull the surface to the plane tangent under the brush" },
    { "Crease", 'C', "Cut a sharp crease along the stroke (Ctrl: a ridge)" },
    { "Pinch", 'N', "Pull the surface toward the stroke's line: sharpens ridges and creases (Ctrl: spread)" },
  };
  return tools[op >= 0 && op < ToolCount ? op : 0];
}

namespace
{
QButtonGroup* radioGroup(QWidget* parent, QVBoxLayout* into, const QString& title, const QStringList& labels,
  const QList<int>& ids, int checked, int columns = 8)
{
  auto* box = new QGroupBox(title, parent);
  auto* lay = new QGridLayout(box);
  auto* group = new QButtonGroup(parent);
  for (int i = 0; i < labels.size(); ++i)
  {
    auto* b = new QRadioButton(labels[i], box);
    b->setObjectName(title.toLower() + "_" + labels[i].toLower());
    group->addButton(b, ids[i]);
    lay->addWidget(b, i / columns, i % columns);
    b->setChecked(ids[i] == checked);
  }
  into->addWidget(box);
  return group;
}
} // namespace

ToolPanel::ToolPanel(QWidget* parent)
  : QWidget(parent)
{
  // CSG tools start at the paper's hard rule; the shaping tools with a soft edge
  const double strengths[ToolCount] = { 1, 1, 1, 0.5, 0.3, 1, 0.5, 0.5, 0.5 };
  const int falloffs[ToolCount] = { 0, 0, 0, 2, 2, 2, 2, 1, 2 };
  for (int i = 0; i < ToolCount; ++i)
  {
    this->ToolStrength[i] = strengths[i];
    this->ToolFalloff[i] = falloffs[i];
  }
  auto* lay = new QVBoxLayout(this);
  QStringList tools;
  QList<int> ids;
  for (int i = 0; i < ToolCount; ++i)
  {
    tools << toolInfo(i).name;
    ids << i;
  }
  this->Ops = radioGroup(this, lay, "Operation", tools, ids, this->State.op, 4);
  for (int i = 0; i < ToolCount; ++i)
    this->Ops->button(i)->setToolTip(QString("%1 (%2)").arg(toolInfo(i).tip).arg(toolInfo(i).key));
  this->Shapes = radioGroup(this, lay, "Shape", { "Sphere", "Cube" }, { 0, 1 }, this->State.shape);
  this->Kinds = radioGroup(this, lay, "Brush", { "Basic", "Dynamic", "Drill" }, { 1, 2, 3 }, this->State.kind);
  for (QButtonGroup* g : { this->Ops, this->Shapes, this->Kinds })
  {
    connect(g, QOverload<int>::of(&QButtonGroup::buttonClicked), this, [this](int) {
      this->switchTool(this->Ops->checkedId());
      this->State.shape = this->Shapes->checkedId();
      this->State.kind = this->Kinds->checkedId();
      Q_EMIT changed();
    });
  }

  this->RadiusLabel = new QLabel(this);
  this->Radius = new QSlider(Qt::Horizontal, this);
  this->Radius->setObjectName("radius");
  this->Radius->setRange(1, 200); // half voxels: 0.5 .. 100
  this->Radius->setToolTip("Brush radius in voxels (the mouse wheel over the surface changes it too)");
  lay->addWidget(this->RadiusLabel);
  lay->addWidget(this->Radius);
  connect(this->Radius, &QSlider::valueChanged, this, [this](int v) {
    this->State.radius = 0.5 * v;
    this->RadiusLabel->setText(QString("Radius: %1 voxels").arg(this->State.radius, 0, 'f', 1));
    Q_EMIT changed();
  });

  this->BlendLabel = new QLabel(this);
  this->Blend = new QSlider(Qt::Horizontal, this);
  this->Blend->setObjectName("blend");
  this->Blend->setRange(0, 40);
  this->Blend->setToolTip("Smooth blend radius in voxels (0: hard CSG)");
  lay->addWidget(this->BlendLabel);
  lay->addWidget(this->Blend);
  connect(this->Blend, &QSlider::valueChanged, this, [this](int v) {
    this->State.blend = 0.5 * v;
    this->BlendLabel->setText(QString("Smooth blend: %1 voxels").arg(this->State.blend, 0, 'f', 1));
    Q_EMIT changed();
  });

  this->StrengthLabel = new QLabel(this);
  this->Strength = new QSlider(Qt::Horizontal, this);
  this->Strength->setObjectName("strength");
  this->Strength->setRange(1, 20); // twentieths: 0.05 .. 1
  this->Strength->setToolTip("How far each dab moves the surface toward the tool's result (1: all the way)");
  lay->addWidget(this->StrengthLabel);
  lay->addWidget(this->Strength);
  connect(this->Strength, &QSlider::valueChanged, this, [this](int v) {
    this->State.strength = v / 20.0;
    this->StrengthLabel->setText(QString("Strength: %1").arg(this->State.strength, 0, 'f', 2));
    Q_EMIT changed();
  });
  auto* falloffRow = new QHBoxLayout;
  falloffRow->addWidget(new QLabel("Falloff", this));
  this->Falloff = new QComboBox(this);
  this->Falloff->setObjectName("falloff");
  this->Falloff->addItems({ "Constant", "Linear", "Smooth", "Sharp" });
  this->Falloff->setToolTip("How the brush's weight falls from its centre to its rim");
  falloffRow->addWidget(this->Falloff, 1);
  lay->addLayout(falloffRow);
  connect(this->Falloff, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int i) {
    this->State.falloff = i;
    Q_EMIT changed();
  });
  auto* mirrorRow = new QHBoxLayout;
  mirrorRow->addWidget(new QLabel("Symmetry", this));
  for (int a = 0; a < 3; ++a)
  {
    this->Mirror[a] = new QCheckBox(QString("XYZ"[a]), this);
    this->Mirror[a]->setObjectName(QString("mirror_") + "xyz"[a]);
    this->Mirror[a]->setToolTip("Mirror every dab about the volume's centre plane across this axis");
    mirrorRow->addWidget(this->Mirror[a]);
    connect(this->Mirror[a], &QCheckBox::toggled, this, [this, a](bool on) {
      this->State.mirror[a] = on;
      Q_EMIT changed();
    });
  }
  lay->addLayout(mirrorRow);

  this->ColorButton = new QPushButton(this);
  this->ColorButton->setObjectName("color");
  connect(this->ColorButton, &QPushButton::clicked, this, &ToolPanel::pickColor);
  lay->addWidget(this->ColorButton);

  auto* row = new QHBoxLayout;
  auto* undo = new QPushButton("Undo", this);
  auto* redo = new QPushButton("Redo", this);
  connect(undo, &QPushButton::clicked, this, &ToolPanel::undoRequested);
  connect(redo, &QPushButton::clicked, this, &ToolPanel::redoRequested);
  row->addWidget(undo);
  row->addWidget(redo);
  lay->addLayout(row);
  auto* row2 = new QHBoxLayout;
  this->RecordButton = new QPushButton("Record", this);
  this->RecordButton->setCheckable(true);
  auto* play = new QPushButton("Play...", this);
  connect(this->RecordButton, &QPushButton::toggled, this, &ToolPanel::recordToggled);
  connect(play, &QPushButton::clicked, this, &ToolPanel::playRequested);
  row2->addWidget(this->RecordButton);
  row2->addWidget(play);
  lay->addLayout(row2);
  lay->addStretch(1);
  this->setState(this->State);
}

void ToolPanel::setState(const BrushState& s)
{
  this->State = s;
  const QSignalBlocker b1(this->Radius), b2(this->Blend), b3(this->Strength), b4(this->Falloff);
  this->Strength->setValue(static_cast<int>(std::lround(20 * s.strength)));
  this->StrengthLabel->setText(QString("Strength: %1").arg(s.strength, 0, 'f', 2));
  this->Falloff->setCurrentIndex(s.falloff);
  for (int a = 0; a < 3; ++a)
  {
    const QSignalBlocker b(this->Mirror[a]);
    this->Mirror[a]->setChecked(s.mirror[a]);
  }
  this->Ops->button(s.op)->setChecked(true);
  this->Shapes->button(s.shape)->setChecked(true);
  this->Kinds->button(s.kind)->setChecked(true);
  this->Radius->setValue(static_cast<int>(std::lround(2 * s.radius)));
  this->RadiusLabel->setText(QString("Radius: %1 voxels").arg(s.radius, 0, 'f', 1));
  this->Blend->setValue(static_cast<int>(std::lround(2 * s.blend)));
  this->BlendLabel->setText(QString("Smooth blend: %1 voxels").arg(s.blend, 0, 'f', 1));
  this->updateColorButton();
}

void ToolPanel::setRadius(double voxels)
{
  this->State.radius = voxels;
  const QSignalBlocker block(this->Radius);
  this->Radius->setValue(static_cast<int>(std::lround(2 * voxels)));
  this->RadiusLabel->setText(QString("Radius: %1 voxels").arg(voxels, 0, 'f', 1));
}

void ToolPanel::switchTool(int op)
{
  if (op == this->State.op)
    return;
  this->ToolStrength[this->State.op] = this->State.strength;
  this->ToolFalloff[this->State.op] = this->State.falloff;
  BrushState s = this->State;
  s.op = op;
  s.strength = this->ToolStrength[op];
  s.falloff = this->ToolFalloff[op];
  this->setState(s);
}

void ToolPanel::setOp(int op)
{
  if (op < 0 || op >= ToolCount || op == this->State.op)
    return;
  this->switchTool(op);
  Q_EMIT changed();
}

void ToolPanel::setEveryTool(double strength, int falloff)
{
  BrushState s = this->State;
  for (int i = 0; i < ToolCount; ++i)
  {
    if (strength > 0)
      this->ToolStrength[i] = strength;
    if (falloff >= 0)
      this->ToolFalloff[i] = falloff;
  }
  s.strength = this->ToolStrength[s.op];
  s.falloff = this->ToolFalloff[s.op];
  this->setState(s);
}

void ToolPanel::setRecording(bool on)
{
  const QSignalBlocker block(this->RecordButton);
  this->RecordButton->setChecked(on);
  this->RecordButton->setText(on ? "Stop" : "Record");
}

void ToolPanel::toggleRecording()
{
  this->RecordButton->toggle(); // toggled: recordToggled
}

void ToolPanel::pickColor()
{
  const QColor c = QColorDialog::getColor(this->State.color, this, "Brush colour", QColorDialog::ShowAlphaChannel);
  if (c.isValid())
  {
    this->State.color = c;
    this->updateColorButton();
    Q_EMIT changed();
  }
}

void ToolPanel::updateColorButton()
{
  this->ColorButton->setText("Colour " + this->State.color.name());
  this->ColorButton->setStyleSheet(QString("background-color: %1; color: %2")
                                     .arg(this->State.color.name())
                                     .arg(this->State.color.lightness() > 128 ? "black" : "white"));
}
