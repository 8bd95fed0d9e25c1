// The one harness of the rendering regression tests: a window of a fixed size
// without multisampling (so that baselines do not depend on the GL driver's
// antialiasing), a grab of its pixels, and the comparison with the baseline
// (vtkRegressionTestImage; -I opens the interactor, as in VTK's own tests).
#pragma once

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

namespace lvdiftest
{

inline vtkSmartPointer<vtkRenderWindow> makeTestWindow(int width, int height)
{
  auto rw = vtkSmartPointer<vtkRenderWindow>::New();
  rw->SetSize(width, height);
  rw->SetMultiSamples(0);
  return rw;
}

/// A copy of the window's RGB pixels as they are now (no render: a partial
/// frame's picture stays what it drew).
inline vtkSmartPointer<vtkImageData> windowPixels(vtkRenderWindow* rw)
{
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(rw);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOff();
  w2i->ShouldRerenderOff();
  w2i->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->DeepCopy(w2i->GetOutput());
  return img;
}

/// Renders and returns a copy of the window's RGB pixels.
inline vtkSmartPointer<vtkImageData> grabWindow(vtkRenderWindow* rw)
{
  rw->Render();
  return windowPixels(rw);
}

/// Renders, compares with the test's baseline; true when it matched (or the
/// interactive run ended). Attaches an interactor if the window has none.
inline bool matchesBaseline(int argc, char* argv[], vtkRenderWindow* rw)
{
  vtkSmartPointer<vtkRenderWindowInteractor> iren = rw->GetInteractor();
  if (!iren)
  {
    iren = vtkSmartPointer<vtkRenderWindowInteractor>::New();
    iren->SetRenderWindow(rw);
  }
  rw->Render();
  const int r = vtkRegressionTestImage(rw);
  if (r == vtkRegressionTester::DO_INTERACTOR) iren->Start();
  return r != vtkRegressionTester::FAILED;
}

} // namespace lvdiftest
