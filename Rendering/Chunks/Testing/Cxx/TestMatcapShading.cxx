// Matcap shading against an independent oracle: a finely tessellated unit
// sphere seen by a parallel camera down -z, so that the view-space normal at
// pixel (x, y) inside its disc is (x, y, sqrt(1 - x^2 - y^2)) exactly. The
// matcap image is a ramp (red = u, green = v, blue constant), so every pixel
// must show (255 u, 255 v, 60) times the surface colour, u,v = n.xy/2 + 1/2.
// The picture must not change when the scene's lights do, and without the
// matcap the sphere is lit as before (the picture differs).
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTetrahedralColorMapper.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
#include "RenderTestHarness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace
{
const int N = 200;          // window edge in pixels
const double Scale = 1.05;  // parallel scale: half the view height in world units
const int T = 64;           // matcap edge in texels
const double Surface[3] = { 255, 200, 150 };

vtkSmartPointer<vtkTexture> rampTexture()
{
  vtkNew<vtkImageData> img;
  img->SetDimensions(T, T, 1);
  img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int j = 0; j < T; ++j)
    for (int i = 0; i < T; ++i)
    {
      auto* p = static_cast<unsigned char*>(img->GetScalarPointer(i, j, 0));
      p[0] = static_cast<unsigned char>(std::lround(255.0 * (i + 0.5) / T));
      p[1] = static_cast<unsigned char>(std::lround(255.0 * (j + 0.5) / T));
      p[2] = 60;
    }
  auto tex = vtkSmartPointer<vtkTexture>::New();
  tex->SetInputData(img);
  tex->InterpolateOn();
  tex->RepeatOff();
  tex->EdgeClampOn();
  return tex;
}

vtkSmartPointer<vtkPolyData> sphere()
{
  vtkNew<vtkSphereSource> s;
  s->SetRadius(1.0);
  s->SetThetaResolution(256);
  s->SetPhiResolution(256);
  s->Update();
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(s->GetOutput());
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(pd->GetNumberOfPoints());
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    rgba->SetTuple4(i, Surface[0], Surface[1], Surface[2], 255);
  pd->GetPointData()->AddArray(rgba);
  return pd;
}

double maxDifference(vtkImageData* a, vtkImageData* b)
{
  double m = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const auto* p = static_cast<unsigned char*>(a->GetScalarPointer(i, j, 0));
      const auto* q = static_cast<unsigned char*>(b->GetScalarPointer(i, j, 0));
      for (int c = 0; c < 3; ++c)
        m = std::max(m, std::fabs(double(p[c]) - double(q[c])));
    }
  return m;
}
} // namespace

using namespace lvdiftest;

int TestMatcapShading(int, char*[])
{
  vtkNew<vtkRenderer> ren;
  auto rw = makeTestWindow(N, N);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  mgr->GetProperty()->SetAmbient(0.0);
  mgr->GetProperty()->SetDiffuse(1.0);
  mgr->GetProperty()->SetSpecular(0.0);
  mgr->SetChunk(0, sphere());
  vtkCamera* cam = ren->GetActiveCamera();
  cam->ParallelProjectionOn();
  cam->SetFocalPoint(0, 0, 0);
  cam->SetPosition(0, 0, 5);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(Scale);
  ren->ResetCameraClippingRange();

  auto lit = grabWindow(rw);
  mgr->SetMatcapTexture(rampTexture());
  auto matcap = grabWindow(rw);

  double maxErr = 0;
  int checked = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const double x = (i + 0.5 - N / 2.0) / (N / 2.0) * Scale, y = (j + 0.5 - N / 2.0) / (N / 2.0) * Scale;
      if (x * x + y * y > 0.9 * 0.9)
        continue; // away from the silhouette's pixels
      const double u = x * 0.5 + 0.5, v = y * 0.5 + 0.5;
      const double expect[3] = { 255 * u * Surface[0] / 255, 255 * v * Surface[1] / 255, 60 * Surface[2] / 255 };
      const auto* px = static_cast<unsigned char*>(matcap->GetScalarPointer(i, j, 0));
      for (int c = 0; c < 3; ++c)
        maxErr = std::max(maxErr, std::fabs(px[c] - expect[c]));
      ++checked;
    }
  std::printf("matcap: %d pixels, max |error| %.2f (8-bit levels)\n", checked, maxErr);

  // the scene's lights play no part
  vtkNew<vtkLight> red;
  red->SetColor(1, 0, 0);
  red->SetPosition(3, -2, 4);
  red->SetIntensity(0.8);
  ren->AddLight(red);
  auto relit = grabWindow(rw);
  const double lightDiff = maxDifference(matcap, relit);
  ren->RemoveLight(red);
  std::printf("matcap with another light differs by %.1f levels\n", lightDiff);

  // off again: lit as before
  mgr->SetMatcapTexture(nullptr);
  auto litAgain = grabWindow(rw);
  const double offDiff = maxDifference(lit, litAgain), litVsMatcap = maxDifference(lit, matcap);
  std::printf("off again differs from the first lit picture by %.1f; lit vs matcap %.1f\n", offDiff, litVsMatcap);
  const bool ok = checked > 10000 && maxErr <= 4.0 && lightDiff == 0 && offDiff == 0 && litVsMatcap > 40;
  return ok ? 0 : 1;
}
