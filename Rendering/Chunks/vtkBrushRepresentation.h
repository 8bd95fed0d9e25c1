/**
 * @class   vtkBrushRepresentation
 * @brief   the brush cursor: a wireframe sphere or cube that sits on the
 *          picked surface point
 *
 * The representation picks the surface under the mouse with a vtkCellPicker
 * (every pickable prop of the renderer; the cursor itself is not pickable),
 * places the cursor there and draws it. Radius is in world units (for a cube
 * it is the half edge, as the Core's cube brush). Used by vtkBrushWidget.
 */
#ifndef vtkBrushRepresentation_h
#define vtkBrushRepresentation_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkWidgetRepresentation.h"

class vtkActor;
class vtkCellPicker;
class vtkCubeSource;
class vtkPolyDataMapper;
class vtkProperty;
class vtkSphereSource;

class LVDIFRENDERINGCHUNKS_EXPORT vtkBrushRepresentation : public vtkWidgetRepresentation
{
public:
  static vtkBrushRepresentation* New();
  vtkTypeMacro(vtkBrushRepresentation, vtkWidgetRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Shapes
  {
    Sphere = 0,
    Cube = 1
  };
  enum InteractionStates
  {
    Outside = 0,
    OnSurface = 1
  };

  ///@{
  /// Cursor shape (Sphere or Cube).
  void SetShape(int shape);
  vtkGetMacro(Shape, int);
  ///@}

  ///@{
  /// Brush radius in world units, clamped to [MinimumRadius, MaximumRadius].
  void SetRadius(double r);
  vtkGetMacro(Radius, double);
  vtkSetMacro(MinimumRadius, double);
  vtkGetMacro(MinimumRadius, double);
  vtkSetMacro(MaximumRadius, double);
  vtkGetMacro(MaximumRadius, double);
  ///@}

  ///@{
  /// The cursor centre (the last picked surface point).
  void SetCenter(double x, double y, double z);
  void SetCenter(const double c[3]) { this->SetCenter(c[0], c[1], c[2]); }
  vtkGetVector3Macro(Center, double);
  ///@}

  /// Surface normal at the last pick (unit, world coordinates).
  vtkGetVector3Macro(PickedNormal, double);

  /// Picks the surface at display (X, Y); on a hit moves the cursor there.
  bool PickSurface(int X, int Y);

  /// The cursor's look.
  vtkProperty* GetCursorProperty();

  // vtkWidgetRepresentation
  void PlaceWidget(double bounds[6]) override;
  void BuildRepresentation() override;
  int ComputeInteractionState(int X, int Y, int modify = 0) override;
  double* GetBounds() override;
  void GetActors(vtkPropCollection* pc) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;
  int RenderOpaqueGeometry(vtkViewport* v) override;
  int RenderTranslucentPolygonalGeometry(vtkViewport* v) override;
  vtkTypeBool HasTranslucentPolygonalGeometry() override;

protected:
  vtkBrushRepresentation();
  ~vtkBrushRepresentation() override;

  int Shape = Sphere;
  double Radius = 1.0;
  double MinimumRadius = 1e-3;
  double MaximumRadius = 1e6;
  double Center[3] = { 0, 0, 0 };
  double PickedNormal[3] = { 0, 0, 1 };

  vtkSphereSource* SphereSource;
  vtkCubeSource* CubeSource;
  vtkPolyDataMapper* Mapper;
  vtkActor* Actor;
  vtkCellPicker* Picker;

private:
  vtkBrushRepresentation(const vtkBrushRepresentation&) = delete;
  void operator=(const vtkBrushRepresentation&) = delete;
};

#endif
