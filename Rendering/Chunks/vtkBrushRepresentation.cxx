#include "vtkBrushRepresentation.h"

#include "vtkActor.h"
#include "vtkCellPicker.h"
#include "vtkCubeSource.h"
#include "vtkObjectFactory.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <algorithm>

vtkStandardNewMacro(vtkBrushRepresentation);

vtkBrushRepresentation::vtkBrushRepresentation()
{
  this->SphereSource = vtkSphereSource::New();
  this->SphereSource->SetThetaResolution(16);
  this->SphereSource->SetPhiResolution(10);
  this->CubeSource = vtkCubeSource::New();
  this->Mapper = vtkPolyDataMapper::New();
  this->Mapper->SetInputConnection(this->SphereSource->GetOutputPort());
  this->Actor = vtkActor::New();
  this->Actor->SetMapper(this->Mapper);
  this->Actor->PickableOff();
  this->Actor->GetProperty()->SetColor(1.0, 0.85, 0.2);
  // An opaque wireframe: translucent cursors need order-independent
  // transparency, which streaks on Mesa's llvmpipe under Xvfb.
  this->Actor->GetProperty()->SetRepresentationToWireframe();
  this->Actor->GetProperty()->SetLineWidth(1.5);
  this->Actor->GetProperty()->LightingOff();
  this->Actor->VisibilityOff(); // until the first pick
  this->Picker = vtkCellPicker::New();
  this->Picker->SetTolerance(0.0005);
  this->Picker->PickFromListOff();
  this->InteractionState = Outside;
  this->BuildRepresentation();
}

vtkBrushRepresentation::~vtkBrushRepresentation()
{
  this->SphereSource->Delete();
  this->CubeSource->Delete();
  this->Mapper->Delete();
  this->Actor->Delete();
  this->Picker->Delete();
}

void vtkBrushRepresentation::SetShape(int shape)
{
  shape = shape == Cube ? Cube : Sphere;
  if (shape == this->Shape)
  {
    return;
  }
  this->Shape = shape;
  this->Mapper->SetInputConnection(
    shape == Cube ? this->CubeSource->GetOutputPort() : this->SphereSource->GetOutputPort());
  this->BuildRepresentation();
  this->Modified();
}

void vtkBrushRepresentation::SetRadius(double r)
{
  r = std::max(this->MinimumRadius, std::min(this->MaximumRadius, r));
  if (r == this->Radius)
  {
    return;
  }
  this->Radius = r;
  this->BuildRepresentation();
  this->Modified();
}

void vtkBrushRepresentation::SetCenter(double x, double y, double z)
{
  this->Center[0] = x;
  this->Center[1] = y;
  this->Center[2] = z;
  this->BuildRepresentation();
  this->Modified();
}

vtkProperty* vtkBrushRepresentation::GetCursorProperty()
{
  return this->Actor->GetProperty();
}

bool vtkBrushRepresentation::PickSurface(int X, int Y)
{
  if (!this->Renderer || !this->Picker->Pick(X, Y, 0.0, this->Renderer))
  {
    return false;
  }
  double p[3];
  this->Picker->GetPickPosition(p);
  this->Picker->GetPickNormal(this->PickedNormal);
  this->SetCenter(p);
  this->Actor->VisibilityOn();
  return true;
}

void vtkBrushRepresentation::PlaceWidget(double bounds[6])
{
  this->SetCenter(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]));
}

void vtkBrushRepresentation::BuildRepresentation()
{
  this->SphereSource->SetCenter(this->Center);
  this->SphereSource->SetRadius(this->Radius);
  this->CubeSource->SetCenter(this->Center);
  this->CubeSource->SetXLength(2 * this->Radius);
  this->CubeSource->SetYLength(2 * this->Radius);
  this->CubeSource->SetZLength(2 * this->Radius);
  this->BuildTime.Modified();
}

int vtkBrushRepresentation::ComputeInteractionState(int X, int Y, int)
{
  this->InteractionState = this->PickSurface(X, Y) ? OnSurface : Outside;
  if (this->InteractionState == Outside)
  {
    this->Actor->VisibilityOff();
  }
  return this->InteractionState;
}

double* vtkBrushRepresentation::GetBounds()
{
  return this->Actor->GetBounds();
}

void vtkBrushRepresentation::GetActors(vtkPropCollection* pc)
{
  pc->AddItem(this->Actor);
}

void vtkBrushRepresentation::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Actor->ReleaseGraphicsResources(w);
}

int vtkBrushRepresentation::RenderOpaqueGeometry(vtkViewport* v)
{
  return this->Actor->GetVisibility() ? this->Actor->RenderOpaqueGeometry(v) : 0;
}

int vtkBrushRepresentation::RenderTranslucentPolygonalGeometry(vtkViewport* v)
{
  return this->Actor->GetVisibility() ? this->Actor->RenderTranslucentPolygonalGeometry(v) : 0;
}

vtkTypeBool vtkBrushRepresentation::HasTranslucentPolygonalGeometry()
{
  return this->Actor->GetVisibility() ? this->Actor->HasTranslucentPolygonalGeometry() : 0;
}

void vtkBrushRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << (this->Shape == Cube ? "Cube" : "Sphere") << "\n";
  os << indent << "Radius: " << this->Radius << " [" << this->MinimumRadius << ", " << this->MaximumRadius
     << "]\n";
  os << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2] << "\n";
}
