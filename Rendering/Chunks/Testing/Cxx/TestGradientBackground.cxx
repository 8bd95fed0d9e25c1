// vtkGradientBackgroundRenderer against VTK's own renderer as the oracle: two
// windows of the same size show the same scene (a gradient background, a large
// sphere and a small one that moves, each renderer with a partial-redraw
// culler as in the editor); one renderer is VTK's (its gradient quad made anew
// each frame), the other keeps its quad between frames. After a full frame,
// after groups of frames drawn in part (the small sphere moving: the scissored
// clear and the kept quad drawn under the scissor), after a change of the
// background colours and after a resize (the quad refilled), the two pictures
// must be equal pixel for pixel, with 0 and 8 samples per pixel. Negative
// control: VTK's renderer with Background2 one level (1/255) brighter must
// give a different picture, or this comparison could not fail.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkGradientBackgroundRenderer.h"
#include "vtkImageData.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "RenderTestHarness.h"

#include <cstdio>
#include <functional>
#include <cstdlib>
#include <string>

using namespace lvdiftest;

namespace
{
struct Scene
{
  vtkSmartPointer<vtkRenderer> Ren;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkPartialRedrawCuller> Culler;
  vtkNew<vtkSphereSource> Small;
  vtkNew<vtkActor> Mover;

  Scene(vtkRenderer* ren, int samples)
    : Ren(ren)
  {
    this->Window = makeTestWindow(300, 260);
    this->Window->SetMultiSamples(samples);
    this->Window->AddRenderer(this->Ren);
    this->Ren->SetBackground(0.16, 0.17, 0.2);
    this->Ren->SetBackground2(0.05, 0.05, 0.07);
    this->Ren->GradientBackgroundOn();
    vtkNew<vtkSphereSource> big;
    big->SetRadius(1.0);
    big->SetThetaResolution(48);
    big->SetPhiResolution(48);
    vtkNew<vtkPolyDataMapper> bigMapper;
    bigMapper->SetInputConnection(big->GetOutputPort());
    vtkNew<vtkActor> bigActor;
    bigActor->SetMapper(bigMapper);
    bigActor->GetProperty()->SetColor(0.9, 0.55, 0.3);
    this->Ren->AddActor(bigActor);
    this->Small->SetRadius(0.12);
    vtkNew<vtkPolyDataMapper> smallMapper;
    smallMapper->SetInputConnection(this->Small->GetOutputPort());
    this->Mover->SetMapper(smallMapper);
    this->Mover->GetProperty()->SetColor(0.3, 0.6, 0.9);
    this->Ren->AddActor(this->Mover);
    this->Ren->GetActiveCamera()->SetPosition(0, 0, 6);
    this->Ren->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    this->Ren->GetActiveCamera()->SetClippingRange(1, 20);
    this->Culler->SetEnabled(true);
    this->Ren->AddCuller(this->Culler);
  }
  void Place(double x, double y) { this->Mover->SetPosition(x, y, 1.3); }
};
} // namespace

int TestGradientBackground(int, char*[])
{
  int failures = 0;
  const auto check = checkCounter(failures);

  for (int samples : { 0, 8 })
  {
    std::printf("---- %d samples per pixel\n", samples);
    vtkNew<vtkGradientBackgroundRenderer> keptRen;
    Scene stock(vtkSmartPointer<vtkRenderer>::New(), samples), kept(keptRen, samples);
    check(!vtkGradientBackgroundRenderer::SafeDownCast(stock.Ren), "the oracle is VTK's renderer");
    auto both = [&](const std::function<void(Scene&)>& f) {
      for (Scene* s : { &stock, &kept })
      {
        f(*s);
      }
    };
    auto compare = [&](const std::string& what, bool expectEqual = true) {
      const long diff = differingPixels(windowPixels(stock.Window), windowPixels(kept.Window));
      std::printf("  %s: %ld pixels differ\n", what.c_str(), diff);
      if (expectEqual)
        check(diff == 0, what + ": the kept quad's picture equals VTK's");
      else
        check(diff > 0, what + ": negative control, the comparison sees a background one level brighter");
      both([](Scene& s) { s.Window->Render(); }); // whole: the grab set the camera, which the culler cannot tell from a change
    };
    auto full = [&] {
      both([](Scene& s) {
        s.Culler->RequestFullRedraw();
        s.Window->Render();
        s.Window->Render(); // the first frame creates the light; then the culler has a valid frame
      });
    };

    both([](Scene& s) { s.Place(0.2, 0.1); });
    full();
    compare("full frame");
    const int updates = keptRen->GetNumberOfBackgroundUpdates();
    check(updates == 1, "the quad was filled once (" + std::to_string(updates) + ")");

    const int partialBefore = kept.Culler->GetNumberOfPartialRedraws();
    for (int f = 0; f < 5; ++f)
      both([f](Scene& s) {
        s.Place(0.2 + 0.07 * f, 0.1 - 0.05 * f);
        s.Window->Render();
      });
    check(kept.Culler->GetNumberOfPartialRedraws() == partialBefore + 5 &&
        stock.Culler->GetNumberOfPartialRedraws() == partialBefore + 5,
      "the moving sphere's frames were drawn in part");
    compare("frames drawn in part");
    check(keptRen->GetNumberOfBackgroundUpdates() == updates, "the quad was kept (no refill)");

    // another gradient: a full frame (the renderer changed), the quad refilled
    both([](Scene& s) {
      s.Ren->SetBackground(0.3, 0.1, 0.12);
      s.Ren->SetBackground2(0.02, 0.2, 0.25);
    });
    full();
    compare("new background colours");
    check(keptRen->GetNumberOfBackgroundUpdates() == updates + 1, "the quad was refilled for the colours");
    for (int f = 0; f < 3; ++f)
      both([f](Scene& s) {
        s.Place(-0.3 + 0.1 * f, -0.4);
        s.Window->Render();
      });
    compare("new colours, frames drawn in part");

    both([](Scene& s) { s.Window->SetSize(340, 220); });
    full();
    compare("resized window");
    check(keptRen->GetNumberOfBackgroundUpdates() == updates + 2, "the quad was refilled for the size");
    for (int f = 0; f < 3; ++f)
      both([f](Scene& s) {
        s.Place(0.4, -0.2 + 0.1 * f);
        s.Window->Render();
      });
    compare("resized, frames drawn in part");

    // Negative control: the oracle's Background2 one level brighter.
    const double* b2 = stock.Ren->GetBackground2();
    stock.Ren->SetBackground2(b2[0], b2[1] + 1.0 / 255, b2[2]);
    full();
    compare("Background2 + 1/255 in VTK's renderer (negative control)", false);
  }
  std::printf("%s\n", failures ? "FAILED" : "passed");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
