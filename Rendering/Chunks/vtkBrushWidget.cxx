#include "vtkBrushWidget.h"

#include "vtkBrushRepresentation.h"
#include "vtkCallbackCommand.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkWidgetCallbackMapper.h"
#include "vtkWidgetEvent.h"

vtkStandardNewMacro(vtkBrushWidget);

vtkBrushWidget::vtkBrushWidget()
{
  this->ManagesCursor = 0;
  this->CallbackMapper->SetCallbackMethod(vtkCommand::MouseMoveEvent, vtkWidgetEvent::Move, this, MoveAction);
  this->CallbackMapper->SetCallbackMethod(
    vtkCommand::LeftButtonPressEvent, vtkWidgetEvent::Select, this, PressAction);
  this->CallbackMapper->SetCallbackMethod(
    vtkCommand::LeftButtonReleaseEvent, vtkWidgetEvent::EndSelect, this, ReleaseAction);
  this->CallbackMapper->SetCallbackMethod(
    vtkCommand::MouseWheelForwardEvent, vtkWidgetEvent::Up, this, GrowAction);
  this->CallbackMapper->SetCallbackMethod(
    vtkCommand::MouseWheelBackwardEvent, vtkWidgetEvent::Down, this, ShrinkAction);
}

void vtkBrushWidget::SetRepresentation(vtkBrushRepresentation* r)
{
  this->Superclass::SetWidgetRepresentation(r);
}

vtkBrushRepresentation* vtkBrushWidget::GetBrushRepresentation()
{
  return vtkBrushRepresentation::SafeDownCast(this->WidgetRep);
}

void vtkBrushWidget::CreateDefaultRepresentation()
{
  if (!this->WidgetRep)
  {
    this->WidgetRep = vtkBrushRepresentation::New();
  }
}

void vtkBrushWidget::EmitSample()
{
  vtkBrushRepresentation* rep = this->GetBrushRepresentation();
  double sample[4];
  rep->GetCenter(sample);
  sample[3] = rep->GetRadius();
  ++this->NumberOfSamples;
  this->InvokeEvent(BrushSampleEvent, sample);
}

void vtkBrushWidget::MoveAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBrushWidget*>(w);
  const int X = self->Interactor->GetEventPosition()[0];
  const int Y = self->Interactor->GetEventPosition()[1];
  const int state = self->WidgetRep->ComputeInteractionState(X, Y);
  if (self->WidgetState == Painting)
  {
    if (state == vtkBrushRepresentation::OnSurface)
    {
      self->EmitSample();
    }
    self->EventCallbackCommand->SetAbortFlag(1);
    self->InvokeEvent(vtkCommand::InteractionEvent, nullptr);
  }
  self->Render();
}

void vtkBrushWidget::PressAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBrushWidget*>(w);
  const int X = self->Interactor->GetEventPosition()[0];
  const int Y = self->Interactor->GetEventPosition()[1];
  if (self->WidgetRep->ComputeInteractionState(X, Y) != vtkBrushRepresentation::OnSurface)
  {
    return; // not on the surface: the camera gets the press
  }
  self->WidgetState = Painting;
  self->GrabFocus(self->EventCallbackCommand);
  self->EventCallbackCommand->SetAbortFlag(1);
  self->StartInteraction();
  self->InvokeEvent(vtkCommand::StartInteractionEvent, nullptr);
  self->EmitSample();
  self->Render();
}

void vtkBrushWidget::ReleaseAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBrushWidget*>(w);
  if (self->WidgetState != Painting)
  {
    return;
  }
  self->WidgetState = Idle;
  self->ReleaseFocus();
  self->EventCallbackCommand->SetAbortFlag(1);
  self->EndInteraction();
  self->InvokeEvent(vtkCommand::EndInteractionEvent, nullptr);
  self->Render();
}

void vtkBrushWidget::ChangeRadius(double factor)
{
  vtkBrushRepresentation* rep = this->GetBrushRepresentation();
  const int X = this->Interactor->GetEventPosition()[0];
  const int Y = this->Interactor->GetEventPosition()[1];
  if (this->WidgetState != Painting && rep->ComputeInteractionState(X, Y) != vtkBrushRepresentation::OnSurface)
  {
    return; // off the surface the wheel zooms the camera
  }
  rep->SetRadius(rep->GetRadius() * factor);
  double r = rep->GetRadius();
  this->EventCallbackCommand->SetAbortFlag(1);
  this->InvokeEvent(RadiusChangedEvent, &r);
  this->Render();
}

void vtkBrushWidget::GrowAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBrushWidget*>(w);
  self->ChangeRadius(self->WheelFactor);
}

void vtkBrushWidget::ShrinkAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBrushWidget*>(w);
  self->ChangeRadius(1.0 / self->WheelFactor);
}

void vtkBrushWidget::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WheelFactor: " << this->WheelFactor << "\n";
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
}
