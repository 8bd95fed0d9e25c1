// vtkChunkedMarchingCubes (LVDIF::FiltersMeshing) feeding the chunk actors:
// its partitioned output (one poly data per chunk, with the tetrahedral
// contract arrays) goes through vtkChunkActorManager::SetPartitions, and the
// picture must equal the filter's merged output shown as one chunk (the same
// triangles with boundary vertices merged). Setting the same partitions again
// re-uploads nothing. Then a regression image.
#include "ChunkTestData.h"

#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkChunkedMarchingCubes.h"
#include "vtkImageDifference.h"
#include "vtkPartitionedDataSet.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>

using namespace lvdiftest;

namespace
{
} // namespace

int TestChunkedMCRender(int argc, char* argv[])
{
  const int n = 50;
  auto img = sdfImage(n, [](double x, double y, double z) {
    const double a = std::sqrt((x - 20.3) * (x - 20.3) + (y - 24.6) * (y - 24.6) + (z - 24.1) * (z - 24.1)) - 13.2;
    const double b = std::sqrt((x - 32.1) * (x - 32.1) + (y - 25.2) * (y - 25.2) + (z - 26.3) * (z - 26.3)) - 9.4;
    return std::min(a, b);
  });
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const Rgba c = checkerColor(i, j, k);
        rgba->SetTypedTuple(id++, c.data());
      }
  img->GetPointData()->AddArray(rgba);

  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(img);
  mc->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  mc->SetChunkEdge(16);
  mc->SetOutputModeToPartitioned();
  mc->Update();
  auto* parts = vtkPartitionedDataSet::SafeDownCast(mc->GetOutputDataObject(0));
  if (!parts || parts->GetNumberOfPartitions() < 2)
  {
    std::printf("ERROR: expected a partitioned output with several chunks\n");
    return 1;
  }

  auto rw = makeTestWindow(400, 400);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.1, 0.1, 0.12);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> chunks;
  chunks->SetRenderer(ren);
  chunks->SetPartitions(parts);
  const vtkIdType uploads = chunks->GetNumberOfChunkUpdates();
  chunks->SetPartitions(parts); // nothing changed: no update
  int failures = 0;
  if (chunks->GetNumberOfChunkUpdates() != uploads || chunks->GetNumberOfChunks() != static_cast<int>(parts->GetNumberOfPartitions()))
  {
    std::printf("ERROR: setting unchanged partitions updated chunks\n");
    ++failures;
  }
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(26, 25, 25);
  cam->SetPosition(26 + 40, 25 - 80, 25 + 50);
  cam->SetViewUp(0, 0, 1);
  ren->ResetCameraClippingRange();
  auto partitioned = grabWindow(rw);

  vtkNew<vtkChunkedMarchingCubes> merged;
  merged->SetInputData(img);
  merged->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  merged->SetChunkEdge(16);
  merged->SetOutputModeToMerged();
  merged->Update();
  chunks->SetVisibility(false);
  vtkNew<vtkChunkActorManager> one;
  one->SetRenderer(ren);
  one->SetChunk(0, vtkPolyData::SafeDownCast(merged->GetOutputDataObject(0)));
  auto whole = grabWindow(rw);
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(partitioned);
  diff->SetImageData(whole);
  diff->AllowShiftOff();
  diff->SetThreshold(0);
  diff->Update();
  std::printf("%u chunks; partitioned vs merged image error: %g\n", parts->GetNumberOfPartitions(), diff->GetError());
  if (diff->GetError() > 1.0)
  {
    std::printf("ERROR: the chunk actors differ from the merged surface\n");
    ++failures;
  }
  one->SetVisibility(false);
  chunks->SetVisibility(true);

  const bool r = matchesBaseline(argc, argv, rw);
  return (r && failures == 0) ? 0 : 1;
}
