// Chunk actors vs one merged actor: the cost of showing an edit
// that changed ONE chunk, and the cost of a frame without edits.
//
//   per-chunk : vtkChunkActorManager::SetChunk(id, mesh) + Render()
//               (prepares and uploads that chunk only)
//   merged    : append the (already prepared) chunk meshes into one poly data,
//               hand it to one mapper + Render() (re-uploads the whole model)
//
// The mesh is an analytic sphere extracted with vtkFlyingEdges3D and the
// contract arrays (as the marching cubes filter delivers them), cut into
// chunks of `edge` cells. Needs an X server (xvfb-run). Figures are ratios
// in one process on Mesa's llvmpipe (software GL): the upload costs CPU time
// there as a driver copy does on a GPU.
//
// usage: bench_chunk_actors [gridPoints=160] [chunkEdge=32] [frames=20]
#include "BenchCommon.h"

#include "../../../Rendering/Chunks/Testing/Cxx/ChunkTestData.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

using namespace lvdiftest;

static int benchMain(int argc, char** argv)
{
  const int n = argc > 1 ? std::atoi(argv[1]) : 160;
  const int edge = argc > 2 ? std::atoi(argv[2]) : 32;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 20;
  std::cout << "bench_chunk_actors: " << bench::machineDescription() << "\n";
  auto img = sdfImage(n, [n](double x, double y, double z) {
    const double c = 0.5 * (n - 1) + 0.13;
    return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - 0.4 * n;
  });
  auto mesh = contractMesh(img, checkerColor);
  auto chunks = splitChunks(mesh, edge, n - 1);
  std::printf("grid %d^3, %lld triangles, %zu non-empty chunks of %d^3 cells\n", n,
    static_cast<long long>(mesh->GetNumberOfPolys()), chunks.size(), edge);

  vtkNew<vtkRenderWindow> rw;
  rw->SetSize(400, 300);
  rw->SetMultiSamples(0);
  std::vector<std::vector<std::string>> rows;
  for (int mode : { vtkTetrahedralColorMapper::Tetrahedral, vtkTetrahedralColorMapper::PerVertex })
  {
    const char* modeName = mode == vtkTetrahedralColorMapper::Tetrahedral ? "tetrahedral" : "per-vertex";
    // ---- per-chunk actors
    vtkNew<vtkRenderer> ren;
    rw->AddRenderer(ren);
    vtkNew<vtkChunkActorManager> mgr;
    mgr->SetInterpolationMode(mode);
    mgr->SetRenderer(ren);
    std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> prepared;
    for (auto& kv : chunks)
    {
      mgr->SetChunk(kv.first, kv.second);
      prepared[kv.first] = mgr->PrepareChunk(kv.second);
    }
    ren->ResetCamera();
    rw->Render();
    // The edited chunk: the one holding the most triangles (worst case).
    vtkIdType edited = chunks.begin()->first;
    for (auto& kv : chunks)
      if (kv.second->GetNumberOfPolys() > chunks[edited]->GetNumberOfPolys())
        edited = kv.first;
    const double chunkIdle = bench::medianMs(frames, [&] {
      ren->GetActiveCamera()->Azimuth(1);
      rw->Render();
      rw->WaitForCompletion();
    });
    const double chunkEdit = bench::medianMs(frames, [&] {
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->DeepCopy(chunks[edited]); // a freshly meshed chunk
      mgr->SetChunk(edited, copy);
      ren->GetActiveCamera()->Azimuth(1); // same camera motion as the no-edit frames
      rw->Render();
      rw->WaitForCompletion();
    });
    mgr->RemoveAllChunks();
    rw->RemoveRenderer(ren);

    // ---- one merged actor
    vtkNew<vtkRenderer> ren2;
    rw->AddRenderer(ren2);
    vtkNew<vtkTetrahedralColorMapper> mapper;
    mapper->SetInterpolationMode(mode);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    ren2->AddActor(actor);
    auto merge = [&] {
      vtkNew<vtkAppendPolyData> append;
      for (auto& kv : prepared)
        append->AddInputData(kv.second);
      append->Update();
      auto out = vtkSmartPointer<vtkPolyData>::New();
      out->ShallowCopy(append->GetOutput());
      return out;
    };
    mapper->SetInputData(merge());
    ren2->ResetCamera();
    rw->Render();
    const double mergedIdle = bench::medianMs(frames, [&] {
      ren2->GetActiveCamera()->Azimuth(1);
      rw->Render();
      rw->WaitForCompletion();
    });
    const double mergedEdit = bench::medianMs(frames, [&] {
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->DeepCopy(prepared[edited]);
      prepared[edited] = copy;
      mapper->SetInputData(merge());
      ren2->GetActiveCamera()->Azimuth(1);
      rw->Render();
      rw->WaitForCompletion();
    });
    rw->RemoveRenderer(ren2);
    rows.push_back({ modeName, "frame, no edit", bench::fmt(chunkIdle), bench::fmt(mergedIdle),
      bench::fmt(mergedIdle / chunkIdle) });
    rows.push_back({ modeName, "frame after a 1-chunk edit", bench::fmt(chunkEdit), bench::fmt(mergedEdit),
      bench::fmt(mergedEdit / chunkEdit) });
  }
  bench::printTable({ "colour", "case", "per-chunk actors (ms)", "one merged actor (ms)", "merged / per-chunk" }, rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
