// Regression image: a bunny-like blob (smooth union of spheres, Quilez's
// polynomial smin) with a smooth colour field and a painted band, rendered
// from 4^3 = 64-cell chunks with the tetrahedral shader.
#include "ChunkTestData.h"

#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkProperty.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

using namespace lvdiftest;

namespace
{
double sph(double x, double y, double z, double cx, double cy, double cz, double r)
{
  return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r;
}
double smin(double a, double b, double k)
{
  const double h = std::max(k - std::fabs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}
double blob(double x, double y, double z)
{
  double d = sph(x, y, z, 24, 20, 22, 12);          // body
  d = smin(d, sph(x, y, z, 34, 30, 22, 7), 5);      // head
  d = smin(d, sph(x, y, z, 36, 40, 19, 2.5), 3);    // ear
  d = smin(d, sph(x, y, z, 33, 41, 25, 2.5), 3);    // ear
  d = smin(d, sph(x, y, z, 12, 14, 22, 4), 4);      // tail
  return d;
}
Rgba color(int i, int j, int k)
{
  if (std::abs(k - 22) <= 1)
    return Rgba{ 250, 200, 30, 255 }; // a painted band, 3 voxels thick
  return Rgba{ static_cast<unsigned char>(120 + 2 * i), static_cast<unsigned char>(90 + 2 * j),
    static_cast<unsigned char>(200 - 2 * k), 255 };
}
} // namespace

int TestColoredSurface(int argc, char* argv[])
{
  auto img = sdfImage(48, blob);
  auto mesh = contractMesh(img, color);
  auto chunks = splitChunks(mesh, 16, 47);

  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.15, 0.15, 0.18);
  auto rw = makeTestWindow(400, 400);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  mgr->GetProperty()->SetSpecular(0.3);
  mgr->GetProperty()->SetSpecularPower(20);
  for (auto& kv : chunks)
    mgr->SetChunk(kv.first, kv.second);
  ren->ResetCamera();
  ren->GetActiveCamera()->Elevation(-60);
  ren->GetActiveCamera()->OrthogonalizeViewUp();
  ren->GetActiveCamera()->Azimuth(25);
  ren->GetActiveCamera()->Zoom(1.3);
  ren->ResetCameraClippingRange();
  const bool r = matchesBaseline(argc, argv, rw);
  return r ? 0 : 1;
}
