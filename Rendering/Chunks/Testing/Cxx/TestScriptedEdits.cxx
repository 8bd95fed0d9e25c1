// A surface after a few scripted edits (an LVDIF script run by the Core's
// interpreter: two coloured unions, a cube cut, a painted stroke) on a
// dictionary volume, meshed by the Core's chunked
// marching cubes and shown through vtkChunkActorManager. The manager is fed
// incrementally (only the chunks the edits dirtied are re-meshed and
// replaced); the oracle is a second manager fed with a full re-mesh of the
// final volume: both images must be identical. Then a regression image.
#include "vtkChunkActorManager.h"
#include "LVDIFChunkedMarchingCubesOutput.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Script.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "RenderTestHarness.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace
{
void show(vtkChunkActorManager* mgr, const std::vector<lvdif::ChunkMesh>& meshes, const lvdif::DictionaryVolume& v)
{
  for (const auto& m : meshes)
  {
    if (m.empty())
      mgr->RemoveChunk(m.chunkId);
    else
      mgr->SetChunk(m.chunkId, LVDIFChunkedMarchingCubesOutput::VolumeChunkToPolyData(m, v));
  }
}

void setCamera(vtkRenderer* ren)
{
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(32, 32, 32);
  cam->SetPosition(32 + 55, 32 - 120, 32 + 75);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(30);
  ren->ResetCameraClippingRange();
}

} // namespace

using namespace lvdiftest;

int TestScriptedEdits(int argc, char* argv[])
{
  lvdif::VolumeOptions o;
  o.dims = { 64, 64, 64 };
  o.chunkEdge = 16;
  lvdif::DictionaryVolume volume(o);
  lvdif::fillFromFunction(volume, lvdif::sphereSdf(32.2, 31.7, 32.1, 20.3), volume.colors().add({ 190, 190, 200, 255 }));
  volume.takeDirtyChunks();
  lvdif::MarchingCubesOptions mo;
  mo.chunkEdge = 16;
  lvdif::ChunkedMarchingCubes mc(volume, mo);

  auto rw = makeTestWindow(400, 400);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.12, 0.12, 0.15);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> incremental;
  incremental->SetRenderer(ren);
  show(incremental, mc.extractAll(), volume);
  const int initialChunks = incremental->GetNumberOfChunks();
  setCamera(ren);
  rw->Render();

  // The script (docs/SCRIPTING.md), run by the Core's interpreter on this volume.
  const char* script = R"(
color 230 70 40
sphere 44, 16, 44, 8            # a red bump
color 60 200 90
sphere 16, 18, 20, 6.5          # a green bump
op subtract
cube 32, 16, 50, 6              # a cube cut into the top
op paint
color 250 210 40
radius 4
line 17.4, 23.1, 43, 29.2, 14.9, 43   # a painted stroke on the surface
)";
  lvdif::ScriptRunner runner;
  runner.attach(volume);
  runner.run(script);
  const std::vector<std::int64_t> ids = mc.chunksAffectedByStorageChunks(volume.takeDirtyChunks());
  const vtkIdType before = incremental->GetNumberOfChunkUpdates();
  show(incremental, mc.extractChunks(ids), volume);
  std::printf("%d chunks shown, %zu re-meshed after the edits, %lld actor updates\n", initialChunks, ids.size(),
    static_cast<long long>(incremental->GetNumberOfChunkUpdates() - before));
  int failures = 0;
  if (ids.empty() || static_cast<int>(ids.size()) >= mc.chunkCount())
  {
    std::printf("ERROR: expected a strict subset of the chunks to be re-meshed\n");
    ++failures;
  }
  auto incrementalImage = grabWindow(rw);

  // Oracle: everything re-meshed from scratch.
  incremental->SetVisibility(false);
  vtkNew<vtkChunkActorManager> full;
  full->SetRenderer(ren);
  show(full, mc.extractAll(), volume);
  auto fullImage = grabWindow(rw);
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(incrementalImage);
  diff->SetImageData(fullImage);
  diff->AllowShiftOff();
  diff->SetThreshold(0);
  diff->Update();
  std::printf("incremental vs full re-mesh image error: %g\n", diff->GetError());
  if (diff->GetError() != 0)
  {
    std::printf("ERROR: the incrementally updated chunks differ from a full re-mesh\n");
    ++failures;
  }
  full->SetVisibility(false);
  incremental->SetVisibility(true);

  const bool r = matchesBaseline(argc, argv, rw);
  return (r && failures == 0) ? 0 : 1;
}
