// Regression image of the sign voxel filters (paper Sect. 3.2): a sphere SDF
// with injected wrong signs (streaks of voxels along x inside and outside,
// isolated voxels, as a mesh-to-SDF sign leak leaves them) rendered before
// (left) and after vtkSignVoxelFilter (right). The broken surface has extra
// pieces (tubes, specks); the repaired one is one closed piece.
#include "ChunkTestData.h"

#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSignVoxelFilter.h"

#include <cstdio>

using namespace lvdiftest;

namespace
{
int regions(vtkPolyData* pd)
{
  vtkNew<vtkPolyDataConnectivityFilter> conn;
  conn->SetInputData(pd);
  conn->SetExtractionModeToAllRegions();
  conn->Update();
  return conn->GetNumberOfExtractedRegions();
}
} // namespace

int TestSVFRepair(int argc, char* argv[])
{
  const int n = 40;
  const double c = 19.3, radius = 12.7;
  auto broken = sdfImage(n, [=](double x, double y, double z) {
    double v = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - radius;
    const int i = int(x), j = int(y), k = int(z);
    const bool streak = (j == 20 && k == 20 && i > 22 && i < 36) || (j == 6 && k == 30 && i > 8 && i < 30) ||
      (j == 14 && k == 16 && i > 12 && i < 26);
    const bool isolated = (i == 7 && j == 9 && k == 11) || (i == 20 && j == 18 && k == 21) || (i == 30 && j == 31 && k == 8);
    return ((streak || isolated) && std::fabs(v) > 2.0) ? -v : v;
  });
  vtkNew<vtkSignVoxelFilter> svf;
  svf->SetInputData(broken);
  svf->Update();
  auto repaired = vtkSmartPointer<vtkImageData>::New();
  repaired->ShallowCopy(svf->GetOutput());
  auto grey = [](int, int, int) { return Rgba{ 200, 200, 205, 255 }; };
  auto meshBroken = contractMesh(broken, grey);
  auto meshRepaired = contractMesh(repaired, grey);
  const int before = regions(meshBroken), after = regions(meshRepaired);
  std::printf("surface pieces: %d before, %d after the sign voxel filters\n", before, after);

  auto rw = makeTestWindow(600, 300);
  vtkNew<vtkChunkActorManager> managers[2];
  vtkNew<vtkRenderer> renderers[2];
  vtkPolyData* meshes[2] = { meshBroken, meshRepaired };
  for (int v = 0; v < 2; ++v)
  {
    renderers[v]->SetViewport(0.5 * v, 0, 0.5 * (v + 1), 1);
    renderers[v]->SetBackground(0.1, 0.1, 0.12);
    rw->AddRenderer(renderers[v]);
    managers[v]->SetRenderer(renderers[v]);
    for (auto& kv : splitChunks(meshes[v], 16, n - 1))
      managers[v]->SetChunk(kv.first, kv.second);
    vtkCamera* cam = renderers[v]->GetActiveCamera();
    cam->SetFocalPoint(c, c, c);
    cam->SetPosition(c + 60, c - 70, c + 45);
    cam->SetViewUp(0, 0, 1);
    renderers[v]->ResetCameraClippingRange();
  }
  const bool r = matchesBaseline(argc, argv, rw);
  return (r && before > 1 && after == 1) ? 0 : 1;
}
