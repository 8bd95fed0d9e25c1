// The brush widget driven by a recorded event stream (as VTK's BoxWidget2
// test): the cursor follows the surface, two wheel steps grow the radius,
// a left-drag emits samples that all lie on the analytic sphere the surface
// was extracted from, the camera does not move while painting, and a press
// beside the surface emits nothing. Ends with a regression image showing the
// cursor on the surface.
#include "ChunkTestData.h"

#include "vtkBrushRepresentation.h"
#include "vtkBrushWidget.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkInteractorEventRecorder.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include <cstdio>
#include <vector>

using namespace lvdiftest;

namespace
{
const double C[3] = { 12.3, 12.6, 12.1 };
const double R = 9.7;

const char* EventLog = "# StreamVersion 1\n"
                       "MouseMoveEvent 140 140 0 0 0 0 0\n"
                       "MouseMoveEvent 150 150 0 0 0 0 0\n"
                       "MouseWheelForwardEvent 150 150 0 0 0 0 0\n"
                       "MouseWheelForwardEvent 150 150 0 0 0 0 0\n"
                       "LeftButtonPressEvent 150 150 0 0 0 0 0\n"
                       "MouseMoveEvent 154 151 0 0 0 0 0\n"
                       "MouseMoveEvent 158 153 0 0 0 0 0\n"
                       "MouseMoveEvent 163 155 0 0 0 0 0\n"
                       "MouseMoveEvent 168 158 0 0 0 0 0\n"
                       "MouseMoveEvent 173 161 0 0 0 0 0\n"
                       "MouseMoveEvent 178 165 0 0 0 0 0\n"
                       "MouseMoveEvent 183 170 0 0 0 0 0\n"
                       "MouseMoveEvent 188 176 0 0 0 0 0\n"
                       "MouseMoveEvent 192 182 0 0 0 0 0\n"
                       "LeftButtonReleaseEvent 192 182 0 0 0 0 0\n"
                       "MouseMoveEvent 5 5 0 0 0 0 0\n"
                       "LeftButtonPressEvent 5 5 0 0 0 0 0\n"
                       "LeftButtonReleaseEvent 5 5 0 0 0 0 0\n"
                       "MouseMoveEvent 120 130 0 0 0 0 0\n";

struct Log
{
  std::vector<std::array<double, 4>> samples;
  int starts = 0, ends = 0;
  double lastRadius = 0;
};
} // namespace

int TestBrushWidget(int argc, char* argv[])
{
  auto img = sdfImage(26, [](double x, double y, double z) {
    return std::sqrt((x - C[0]) * (x - C[0]) + (y - C[1]) * (y - C[1]) + (z - C[2]) * (z - C[2])) - R;
  });
  auto mesh = contractMesh(img, [](int, int, int) { return Rgba{ 180, 180, 190, 255 }; });

  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.1, 0.1, 0.12);
  auto rw = makeTestWindow(300, 300);
  rw->AddRenderer(ren);
  vtkNew<vtkRenderWindowInteractor> iren;
  iren->SetRenderWindow(rw);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  iren->SetInteractorStyle(style);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  for (auto& kv : splitChunks(mesh, 8, 25))
    mgr->SetChunk(kv.first, kv.second);

  vtkNew<vtkBrushRepresentation> rep;
  rep->SetRadius(2.0);
  vtkNew<vtkBrushWidget> widget;
  widget->SetInteractor(iren);
  widget->SetRepresentation(rep);
  Log log;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&log);
  cb->SetCallback([](vtkObject*, unsigned long event, void* cd, void* data) {
    auto* l = static_cast<Log*>(cd);
    if (event == vtkBrushWidget::BrushSampleEvent)
    {
      const auto* s = static_cast<double*>(data);
      l->samples.push_back({ s[0], s[1], s[2], s[3] });
    }
    else if (event == vtkCommand::StartInteractionEvent)
      ++l->starts;
    else if (event == vtkCommand::EndInteractionEvent)
      ++l->ends;
    else if (event == vtkBrushWidget::RadiusChangedEvent)
      l->lastRadius = *static_cast<double*>(data);
  });
  widget->AddObserver(vtkBrushWidget::BrushSampleEvent, cb);
  widget->AddObserver(vtkBrushWidget::RadiusChangedEvent, cb);
  widget->AddObserver(vtkCommand::StartInteractionEvent, cb);
  widget->AddObserver(vtkCommand::EndInteractionEvent, cb);

  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(20);
  ren->GetActiveCamera()->Elevation(15);
  ren->ResetCameraClippingRange();
  iren->Initialize();
  rw->Render();
  widget->On();
  double camBefore[3];
  ren->GetActiveCamera()->GetPosition(camBefore);

  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(iren);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString(EventLog);
  recorder->Play();
  recorder->Off();

  int failures = 0;
  const auto check = checkCounter(failures);
  const double expectRadius = 2.0 * 1.1 * 1.1;
  check(std::fabs(log.lastRadius - expectRadius) < 1e-9, "two wheel steps grow the radius by 1.1^2");
  check(log.starts == 1 && log.ends == 1, "one stroke (the press beside the surface is not one)");
  check(log.samples.size() == 10, "a sample at the press and at each of the 9 moves");
  double worst = 0;
  for (auto& s : log.samples)
  {
    const double d = std::sqrt((s[0] - C[0]) * (s[0] - C[0]) + (s[1] - C[1]) * (s[1] - C[1]) +
      (s[2] - C[2]) * (s[2] - C[2]));
    worst = std::max(worst, std::fabs(d - R));
    if (std::fabs(s[3] - expectRadius) > 1e-9)
      worst = 1e9;
  }
  std::printf("samples: %zu, worst |distance to analytic sphere| %.4f voxels\n", log.samples.size(), worst);
  check(worst < 0.15, "every sample lies on the sphere and carries the radius");
  if (log.samples.size() >= 2)
  {
    const auto& a = log.samples.front();
    const auto& b = log.samples.back();
    check(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) > 3.0, "the stroke moves across the surface");
  }
  double camAfter[3];
  ren->GetActiveCamera()->GetPosition(camAfter);
  check(std::hypot(camAfter[0] - camBefore[0], camAfter[1] - camBefore[1], camAfter[2] - camBefore[2]) < 1e-9,
    "the camera stays put while painting");
  check(!widget->IsPainting(), "the widget is idle after the release");

  const bool r = matchesBaseline(argc, argv, rw);
  return (failures == 0 && r) ? 0 : 1;
}
