/**
 * @class   vtkBrushWidget
 * @brief   brush input: a cursor on the surface under the mouse, wheel to
 *          change the radius, left-drag to emit brush samples
 *
 * Events (observe them on the widget):
 * - BrushSampleEvent while dragging with the left button over the surface;
 *   call data is a double[4] {x, y, z, radius} in world coordinates. The
 *   first sample comes with the press (after StartInteractionEvent), the
 *   last before EndInteractionEvent.
 * - RadiusChangedEvent after a wheel step (call data: double* radius).
 *
 * A press that does not hit the surface is left to the interactor style
 * (camera rotation); a press on the surface is consumed, so the camera
 * stays put while painting. The wheel changes the radius by WheelFactor per
 * step (the camera does not zoom while the cursor is on the surface).
 */
#ifndef vtkBrushWidget_h
#define vtkBrushWidget_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkAbstractWidget.h"
#include "vtkCommand.h" // for UserEvent

class vtkBrushRepresentation;

class LVDIFRENDERINGCHUNKS_EXPORT vtkBrushWidget : public vtkAbstractWidget
{
public:
  static vtkBrushWidget* New();
  vtkTypeMacro(vtkBrushWidget, vtkAbstractWidget);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Events
  {
    BrushSampleEvent = vtkCommand::UserEvent + 801,
    RadiusChangedEvent = vtkCommand::UserEvent + 802
  };

  void SetRepresentation(vtkBrushRepresentation* r);
  vtkBrushRepresentation* GetBrushRepresentation();
  void CreateDefaultRepresentation() override;

  ///@{
  /// Radius factor per wheel step (> 1).
  vtkSetClampMacro(WheelFactor, double, 1.001, 10.0);
  vtkGetMacro(WheelFactor, double);
  ///@}

  /// True between a press on the surface and the release.
  bool IsPainting() const { return this->WidgetState == Painting; }
  /// Samples emitted since the widget was created.
  vtkGetMacro(NumberOfSamples, vtkIdType);

protected:
  vtkBrushWidget();
  ~vtkBrushWidget() override = default;

  enum WidgetStates
  {
    Idle = 0,
    Painting = 1
  };
  int WidgetState = Idle;
  double WheelFactor = 1.1;
  vtkIdType NumberOfSamples = 0;

  static void MoveAction(vtkAbstractWidget* w);
  static void PressAction(vtkAbstractWidget* w);
  static void ReleaseAction(vtkAbstractWidget* w);
  static void GrowAction(vtkAbstractWidget* w);
  static void ShrinkAction(vtkAbstractWidget* w);

  void EmitSample();
  void ChangeRadius(double factor);

private:
  vtkBrushWidget(const vtkBrushWidget&) = delete;
  void operator=(const vtkBrushWidget&) = delete;
};

#endif
