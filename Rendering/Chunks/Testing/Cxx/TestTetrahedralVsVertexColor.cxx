// Regression image: the same chunked, checker-coloured sphere with
// tetrahedral colour interpolation (left) and per-vertex colours (right).
// Tetrahedral shows the voxel colour boundaries inside the cells; per-vertex
// smears them over whole triangles.
#include "ChunkTestData.h"

#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"

using namespace lvdiftest;

int TestTetrahedralVsVertexColor(int argc, char* argv[])
{
  const int n = 26;
  auto img = sdfImage(n, [](double x, double y, double z) {
    return std::sqrt((x - 12.3) * (x - 12.3) + (y - 12.6) * (y - 12.6) + (z - 12.1) * (z - 12.1)) - 9.7;
  });
  auto mesh = contractMesh(img, checkerColor);
  auto chunks = splitChunks(mesh, 8, n - 1);

  auto rw = makeTestWindow(600, 300);
  vtkNew<vtkChunkActorManager> managers[2];
  vtkNew<vtkRenderer> renderers[2];
  for (int v = 0; v < 2; ++v)
  {
    renderers[v]->SetViewport(0.5 * v, 0, 0.5 * (v + 1), 1);
    renderers[v]->SetBackground(0.1, 0.1, 0.12);
    rw->AddRenderer(renderers[v]);
    managers[v]->SetRenderer(renderers[v]);
    managers[v]->SetInterpolationMode(
      v == 0 ? vtkTetrahedralColorMapper::Tetrahedral : vtkTetrahedralColorMapper::PerVertex);
    for (auto& kv : chunks)
      managers[v]->SetChunk(kv.first, kv.second);
    renderers[v]->ResetCamera();
    renderers[v]->GetActiveCamera()->Azimuth(30);
    renderers[v]->GetActiveCamera()->Elevation(20);
    renderers[v]->GetActiveCamera()->Zoom(1.4);
    renderers[v]->ResetCameraClippingRange();
  }
  const bool r = matchesBaseline(argc, argv, rw);
  return r ? 0 : 1;
}
