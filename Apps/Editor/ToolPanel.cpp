#include "ToolPanel.h"

#include <QButtonGroup>
#include <QColorDialog>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>

#include <cmath>

namespace
{
QButtonGroup* radioGroup(QWidget* parent, QVBoxLayout* into, const QString& title, const QStringList& labels,
  const QList<int>& ids, int checked)
{
  auto* box = new QGroupBox(title, parent);
  auto* lay = new QHBoxLayout(box);
  auto* group = new QButtonGroup(parent);
  for (int i = 0; i < labels.size(); ++i)
  {
    auto* b = new QRadioButton(labels[i], box);
    b->setObjectName(title.toLower() + "_" + labels[i].toLower());
    group->addButton(b, ids[i]);
    lay->addWidget(b);
    b->setChecked(ids[i] == checked);
  }
  into->addWidget(box);
  return group;
}
} // namespace

ToolPanel::ToolPanel(QWidget* parent)
  : QWidget(parent)
{
  auto* lay = new QVBoxLayout(this);
  this->Ops = radioGroup(this, lay, "Operation", { "Add", "Subtract", "Paint" }, { 0, 1, 2 }, this->State.op);
  this->Shapes = radioGroup(this, lay, "Shape", { "Sphere", "Cube" }, { 0, 1 }, this->State.shape);
  this->Kinds = radioGroup(this, lay, "Brush", { "Basic", "Dynamic", "Drill" }, { 1, 2, 3 }, this->State.kind);
  for (QButtonGroup* g : { this->Ops, this->Shapes, this->Kinds })
  {
    connect(g, QOverload<int>::of(&QButtonGroup::buttonClicked), this, [this](int) {
      this->State.op = this->Ops->checkedId();
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
  const QSignalBlocker b1(this->Radius), b2(this->Blend);
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

void ToolPanel::setRecording(bool on)
{
  const QSignalBlocker block(this->RecordButton);
  this->RecordButton->setChecked(on);
  this->RecordButton->setText(on ? "Stop" : "Record");
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
