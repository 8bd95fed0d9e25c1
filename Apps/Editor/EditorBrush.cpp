#include "EditorBrush.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

vtkStandardNewMacro(EditorBrushRepresentation);

EditorBrushRepresentation::EditorBrushRepresentation()
{
  // not in the camera's clipping range (the representation is the renderer's
  // prop, the actor its part): a huge cursor hid the model from the picker
  this->UseBoundsOff();
  this->Actor->UseBoundsOff();
}

void EditorBrushRepresentation::SetVolume(const double bounds[6], std::function<bool(const double world[3])> inside,
  std::function<bool()> showsSurface)
{
  for (int i = 0; i < 6; ++i)
    this->Box[i] = bounds[i];
  this->Inside = std::move(inside);
  this->ShowsSurface = std::move(showsSurface);
  this->HaveVolume = true;
}

void EditorBrushRepresentation::ClearVolume()
{
  this->HaveVolume = false;
  this->Inside = nullptr;
  this->ShowsSurface = nullptr;
}

void EditorBrushRepresentation::SetAxisScale(double sx, double sy, double sz)
{
  if (sx == this->AxisScale[0] && sy == this->AxisScale[1] && sz == this->AxisScale[2])
    return;
  this->AxisScale[0] = sx;
  this->AxisScale[1] = sy;
  this->AxisScale[2] = sz;
  this->BuildRepresentation();
  this->Modified();
}

void EditorBrushRepresentation::BuildRepresentation()
{
  this->Superclass::BuildRepresentation();
  // the cursor scaled about its centre: an ellipsoid (or box) of r * spacing[a]
  this->Actor->SetOrigin(this->Center);
  this->Actor->SetScale(this->AxisScale);
}

bool EditorBrushRepresentation::RayThroughBox(int X, int Y, double entry[3], double exit[3], double normal[3])
{
  double ends[2][3];
  for (int e = 0; e < 2; ++e)
  {
    this->Renderer->SetDisplayPoint(X, Y, e);
    this->Renderer->DisplayToWorld();
    const double* w = this->Renderer->GetWorldPoint();
    if (w[3] == 0)
      return false;
    for (int a = 0; a < 3; ++a)
      ends[e][a] = w[a] / w[3];
  }
  // The line through the pixel, p(t) = near + t (far - near), from the camera's
  // plane on: the clipping planes are no bound (with nothing drawn, or inside
  // the box, they do not reach the box's faces).
  double d[3], dd = 0, back = 0;
  const double* eye = this->Renderer->GetActiveCamera()->GetPosition();
  for (int a = 0; a < 3; ++a)
  {
    d[a] = ends[1][a] - ends[0][a];
    dd += d[a] * d[a];
    back += (eye[a] - ends[0][a]) * d[a];
  }
  if (!(dd > 0))
    return false;
  // the slab method: the line's parameter in [t0, t1] inside the box
  double t0 = back / dd, t1 = std::numeric_limits<double>::infinity();
  int entryAxis = -1;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = this->Box[2 * a], hi = this->Box[2 * a + 1];
    if (d[a] == 0)
    {
      if (ends[0][a] < lo || ends[0][a] > hi)
        return false;
      continue;
    }
    double ta = (lo - ends[0][a]) / d[a], tb = (hi - ends[0][a]) / d[a];
    if (ta > tb)
      std::swap(ta, tb);
    if (ta > t0)
    {
      t0 = ta;
      entryAxis = a;
    }
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1) || entryAxis < 0)
    return false; // missed, or the camera is inside the box (no face to stand on)
  for (int a = 0; a < 3; ++a)
  {
    entry[a] = ends[0][a] + t0 * d[a];
    exit[a] = ends[0][a] + t1 * d[a];
    normal[a] = 0;
  }
  entry[entryAxis] = d[entryAxis] > 0 ? this->Box[2 * entryAxis] : this->Box[2 * entryAxis + 1]; // exactly on the face
  normal[entryAxis] = d[entryAxis] > 0 ? -1 : 1;
  return true;
}

int EditorBrushRepresentation::ComputeInteractionState(int X, int Y, int modify)
{
  this->LastHit = NoHit;
  if (this->Superclass::ComputeInteractionState(X, Y, modify) == OnSurface)
  {
    this->LastHit = SurfaceHit;
    return this->InteractionState;
  }
  double entry[3], exit[3], normal[3];
  if (!this->HaveVolume || !this->Renderer || !this->RayThroughBox(X, Y, entry, exit, normal))
    return this->InteractionState;
  // No surface along the ray: the whole way through the box is inside, or outside.
  double middle[3];
  for (int a = 0; a < 3; ++a)
    middle[a] = 0.5 * (entry[a] + exit[a]);
  if (this->Inside && this->Inside(middle))
  {
    this->LastHit = BoxHit;
    this->SetCenter(entry);
  }
  else if (this->ShowsSurface && !this->ShowsSurface())
  {
    this->LastHit = EmptyVolumeHit;
    this->SetCenter(middle);
    double toCamera = 0;
    for (int a = 0; a < 3; ++a)
      toCamera += (entry[a] - exit[a]) * (entry[a] - exit[a]);
    toCamera = std::sqrt(toCamera);
    for (int a = 0; a < 3; ++a)
      normal[a] = toCamera > 0 ? (entry[a] - exit[a]) / toCamera : 0;
  }
  else
    return this->InteractionState;
  for (int a = 0; a < 3; ++a)
    this->PickedNormal[a] = normal[a];
  this->Actor->VisibilityOn();
  this->InteractionState = OnSurface;
  return this->InteractionState;
}
