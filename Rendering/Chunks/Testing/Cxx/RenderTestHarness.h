// The one harness of the rendering regression tests: a window of a fixed size
// without multisampling (so that baselines do not depend on the GL driver's
// antialiasing), a grab of its pixels, and the comparison with the baseline
// (vtkRegressionTestImage; -I opens the interactor, as in VTK's own tests).
#pragma once

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>
#include <functional>
#include <string>

namespace lvdiftest
{

/// The tests' check: prints "ok: what" or "FAILED: what" and counts the
/// failures into `failures` (the test's exit status).
inline std::function<void(bool, const std::string&)> checkCounter(int& failures)
{
  return [&failures](bool ok, const std::string& what) {
    std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
    failures += ok ? 0 : 1;
  };
}

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

/// The pixels (x, y) whose RGB differs between two grabs of the same size,
/// except those `allowed` excuses (counted in *excused when given); -1 when
/// the grabs are not comparable (no colour bytes, different sizes).
inline long differingPixels(vtkImageData* a, vtkImageData* b,
  const std::function<bool(int, int)>& allowed = nullptr, long* excused = nullptr)
{
  if (excused)
    *excused = 0;
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (!pa || !pb || pa->GetNumberOfComponents() != 3 || pb->GetNumberOfComponents() != 3 ||
    pa->GetNumberOfValues() != pb->GetNumberOfValues() || da[0] != db[0] || da[1] != db[1])
    return -1;
  long n = 0, ok = 0;
  for (vtkIdType t = 0; t < pa->GetNumberOfTuples(); ++t)
    for (int c = 0; c < 3; ++c)
      if (pa->GetValue(3 * t + c) != pb->GetValue(3 * t + c))
      {
        const bool excuse = allowed && allowed(static_cast<int>(t % da[0]), static_cast<int>(t / da[0]));
        (excuse ? ok : n) += 1;
        break;
      }
  if (excused)
    *excused = ok;
  return n;
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
