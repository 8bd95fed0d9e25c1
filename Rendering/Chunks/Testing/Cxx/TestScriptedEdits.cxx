// A surface after a few scripted CSG edits (two coloured unions, a cube cut,
// a painted band) on a dictionary volume, meshed by the Core's chunked
// marching cubes and shown through vtkChunkActorManager. The manager is fed
// incrementally (only the chunks the edits dirtied are re-meshed and
// replaced); the oracle is a second manager fed with a full re-mesh of the
// final volume: both images must be identical. Then a regression image.
#include "vtkChunkActorManager.h"
#include "vtkLVDIFChunkMesh.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/ChunkedMarchingCubes.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace
{
using Dist = std::function<double(double, double, double)>;

// One edit of the script: union (add), subtraction or paint of a primitive.
void edit(lvdif::DictionaryVolume& v, int op, const Dist& s, const int box[6], lvdif::Rgba color)
{
  const lvdif::ColorKey key = v.colors().add(color);
  for (int z = std::max(0, box[4]); z <= std::min<int>(v.dims()[2] - 1, box[5]); ++z)
    for (int y = std::max(0, box[2]); y <= std::min<int>(v.dims()[1] - 1, box[3]); ++y)
      for (int x = std::max(0, box[0]); x <= std::min<int>(v.dims()[0] - 1, box[1]); ++x)
      {
        const lvdif::Voxel old = v.get(x, y, z);
        const double d = v.decode(old.sdf), sd = s(x, y, z);
        lvdif::Voxel nv = old;
        if (op == 0)
        {
          nv.sdf = v.encode(static_cast<float>(std::min(d, sd)));
          if (sd <= 1.5)
            nv.color = key;
        }
        else if (op == 1)
          nv.sdf = v.encode(static_cast<float>(std::max(d, -sd)));
        else if (sd <= 0 && std::fabs(d) <= 1.5)
          nv.color = key;
        if (nv != old)
          v.set(x, y, z, nv);
      }
}

void show(vtkChunkActorManager* mgr, const std::vector<lvdif::ChunkMesh>& meshes, const lvdif::DictionaryVolume& v)
{
  for (const auto& m : meshes)
  {
    if (m.empty())
      mgr->RemoveChunk(m.chunkId);
    else
      mgr->SetChunk(m.chunkId, vtkLVDIFChunkMesh::ToPolyData(m, v.colors(), v.dims()));
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

vtkSmartPointer<vtkImageData> grab(vtkRenderWindow* rw)
{
  rw->Render();
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(rw);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOff();
  w2i->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->DeepCopy(w2i->GetOutput());
  return img;
}
} // namespace

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

  vtkNew<vtkRenderWindow> rw;
  rw->SetSize(400, 400);
  rw->SetMultiSamples(0);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.12, 0.12, 0.15);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> incremental;
  incremental->SetRenderer(ren);
  show(incremental, mc.extractAll(), volume);
  const int initialChunks = incremental->GetNumberOfChunks();
  setCamera(ren);
  rw->Render();

  // The script.
  auto sphere = [](double cx, double cy, double cz, double r) -> Dist {
    return [=](double x, double y, double z) { return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r; };
  };
  // Boxes: where each primitive (plus the 8-voxel band) can change voxels.
  const int b1[6] = { 28, 60, 0, 32, 30, 62 }, b2[6] = { 0, 30, 0, 32, 0, 32 }, b3[6] = { 0, 31, 0, 31, 40, 46 },
            b4[6] = { 18, 46, 0, 30, 36, 64 };
  edit(volume, 0, sphere(44, 16, 44, 8.0), b1, { 230, 70, 40, 255 });  // red bump
  edit(volume, 0, sphere(16, 18, 20, 6.5), b2, { 60, 200, 90, 255 });  // green bump
  edit(volume, 1, [](double x, double y, double z) { // a cube cut into the top
    const double qx = std::fabs(x - 32) - 6, qy = std::fabs(y - 16) - 6, qz = std::fabs(z - 50) - 6;
    const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
    return std::sqrt(ox * ox + oy * oy + oz * oz) + std::min(std::max(qx, std::max(qy, qz)), 0.0);
  }, b4, { 0, 0, 0, 255 });
  edit(volume, 2, [](double, double, double z) { return std::fabs(z - 43) - 2; }, b3, { 250, 210, 40, 255 }); // band

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
  auto incrementalImage = grab(rw);

  // Oracle: everything re-meshed from scratch.
  incremental->SetVisibility(false);
  vtkNew<vtkChunkActorManager> full;
  full->SetRenderer(ren);
  show(full, mc.extractAll(), volume);
  auto fullImage = grab(rw);
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

  vtkNew<vtkRenderWindowInteractor> iren;
  iren->SetRenderWindow(rw);
  rw->Render();
  int r = vtkRegressionTestImage(rw);
  if (r == vtkRegressionTester::DO_INTERACTOR)
    iren->Start();
  return (r && failures == 0) ? 0 : 1;
}
