// vtkTetrahedralColorMapper's draw ranges against drawing every triangle: a
// chunked, tetrahedrally coloured sphere (8 chunks of 32^3 cells, as the
// editor's, about 1,000 triangles each) is shown in two windows given the same
// edits, the same camera and partial redraws (vtkPartialRedrawCuller), one
// with draw ranges of 32 triangles and one with the ranges off (each chunk in
// one draw call, VTK's own draw). After each group of frames drawn in part the
// two pictures must be equal pixel for pixel (with multisampling too: both
// have the same scissored clears), and without multisampling both must equal
// a full redraw without ranges. The ranged window must draw fewer triangles
// than the other in those frames (the ranges were used). Cases: chunks
// re-meshed with a dent (damage from the changed triangles), a chunk removed
// (an open surface), chunk actors moved by their matrices, and the camera
// inside the sphere (ranges reaching behind the eye). Negative control: with a
// negative pad (ranges skipped although they reach into the scissor box by a
// few pixels) the pictures must differ, or this comparison could not fail.
#include "ChunkTestData.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkImageData.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "RenderTestHarness.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace lvdiftest;

namespace
{
const int Cells = 64, Edge = 32;
const double C[3] = { 32.3, 31.6, 32.5 }, R = 22.4;
const double Dent[3] = { 32.3 + 22.4 * 0.8, 31.6 + 22.4 * 0.6, 32.5 }; // on the sphere

double sphere(double x, double y, double z)
{
  return std::sqrt((x - C[0]) * (x - C[0]) + (y - C[1]) * (y - C[1]) + (z - C[2]) * (z - C[2])) - R;
}

std::function<double(double, double, double)> dented(double radius, double dz)
{
  return [radius, dz](double x, double y, double z) {
    const double d = std::sqrt(
      (x - Dent[0]) * (x - Dent[0]) + (y - Dent[1]) * (y - Dent[1]) + (z - Dent[2] - dz) * (z - Dent[2] - dz));
    return std::max(sphere(x, y, z), radius - d);
  };
}

using Chunks = std::map<vtkIdType, vtkSmartPointer<vtkPolyData>>;

// Background pixels (the renderer's background colour) of a grab.
long coloured(vtkImageData* a)
{
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  long n = 0;
  for (vtkIdType t = 0; t < pa->GetNumberOfTuples(); ++t)
    if (pa->GetValue(3 * t) != 41 || pa->GetValue(3 * t + 1) != 43 || pa->GetValue(3 * t + 2) != 51)
      ++n;
  return n;
}

struct Scene
{
  vtkNew<vtkRenderer> Ren;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkChunkActorManager> Manager;
  vtkNew<vtkPartialRedrawCuller> Culler;

  Scene(int samples, int rangeTriangles, const Chunks& chunks)
  {
    this->Ren->SetBackground(41 / 255.0, 43 / 255.0, 51 / 255.0);
    this->Window = makeTestWindow(360, 320);
    this->Window->SetMultiSamples(samples);
    this->Window->AddRenderer(this->Ren);
    this->Manager->SetRenderer(this->Ren);
    this->Manager->SetDrawRangeTriangles(rangeTriangles);
    this->Manager->GetProperty()->SetSpecular(0.25);
    this->Manager->GetProperty()->SetSpecularPower(25);
    for (auto& kv : chunks)
      this->Manager->SetChunk(kv.first, kv.second);
    const double box[6] = { 0, Cells, 0, Cells, 0, Cells };
    this->Ren->ResetCamera(box);
    this->Ren->GetActiveCamera()->Azimuth(35);
    this->Ren->GetActiveCamera()->Elevation(25);
    this->Ren->GetActiveCamera()->Zoom(1.6); // chunks larger than the view: most of a chunk outside a small damage
    this->Ren->ResetCameraClippingRange();
    this->Culler->SetEnabled(true);
    this->Culler->SetMaximumDamageFraction(0.6);
    this->Ren->AddCuller(this->Culler);
    this->Manager->SetRedrawCuller(this->Culler);
  }
  void SetPad(int pad)
  {
    for (vtkIdType id = 0; id < 8; ++id)
      if (vtkActor* a = this->Manager->GetChunkActor(id))
        vtkTetrahedralColorMapper::SafeDownCast(a->GetMapper())->SetDrawRangePad(pad);
  }
};
} // namespace

int TestDrawRanges(int, char*[])
{
  const auto checker = [](int i, int j, int k) { return checkerColor(i, j, k); };
  const Chunks before = splitChunks(contractMesh(sdfImage(Cells + 1, sphere), checker), Edge, Cells);
  std::vector<Chunks> dents;
  for (int f = 0; f < 4; ++f)
    dents.push_back(splitChunks(contractMesh(sdfImage(Cells + 1, dented(3.0 + f, 1.5 * f)), checker), Edge, Cells));

  int failures = 0;
  const auto check = checkCounter(failures);

  for (int samples : { 0, 8 })
  {
    std::printf("---- %d samples per pixel\n", samples);
    Scene ranged(samples, 32, before), plain(samples, 0, before);
    vtkIdType total = ranged.Manager->GetNumberOfTriangles();
    std::printf("scene: %d chunks, %lld triangles\n", ranged.Manager->GetNumberOfChunks(), static_cast<long long>(total));
    check(ranged.Manager->GetNumberOfChunks() == 8 && total > 5000, "8 chunks of 32^3 cells");

    // The same edit in both scenes, one frame each; the triangles each drew.
    vtkIdType drewRanged = 0, drewPlain = 0;
    auto frame = [&](const std::function<void(Scene&)>& edit) {
      for (Scene* s : { &ranged, &plain })
      {
        edit(*s);
        s->Window->Render();
      }
      const vtkIdType a = ranged.Manager->GetLastNumberOfTrianglesDrawn();
      const vtkIdType b = plain.Manager->GetLastNumberOfTrianglesDrawn();
      drewRanged += a;
      drewPlain += b;
      const int* d = ranged.Culler->GetLastDamage();
      std::printf("  frame: damage %d x %d at (%d, %d), %d props; triangles drawn %lld with ranges, %lld without\n", d[2],
        d[3], d[0], d[1], ranged.Culler->GetLastNumberOfPropsDrawn(), static_cast<long long>(a),
        static_cast<long long>(b));
    };
    auto settle = [&] {
      for (Scene* s : { &ranged, &plain })
      {
        s->Culler->RequestFullRedraw();
        s->Window->Render();
        s->Window->Render(); // the first frames create the light; then the culler has a valid frame
      }
    };
    // After frames drawn in part: the two pictures, and (without multisampling) a full redraw without ranges.
    auto compare = [&](const std::string& what, bool expectEqual = true) {
      const int partialRanged = ranged.Culler->GetNumberOfPartialRedraws();
      auto a = windowPixels(ranged.Window);
      auto b = windowPixels(plain.Window);
      const long diff = differingPixels(a, b);
      std::printf("  %s: %ld pixels differ between the ranged and the plain draw (%ld pixels not background)\n",
        what.c_str(), diff, coloured(a));
      if (expectEqual)
      {
        check(diff == 0, what + ": the ranged picture equals drawing every triangle");
        check(drewRanged < drewPlain, what + ": the ranges drew fewer triangles");
      }
      else
        check(diff > 0, what + ": negative control, the comparison sees the skipped triangles");
      if (samples == 0 && expectEqual)
      {
        ranged.Manager->SetDrawRangeTriangles(0);
        ranged.Culler->RequestFullRedraw();
        ranged.Window->Render();
        const long full = differingPixels(a, windowPixels(ranged.Window));
        std::printf("  %s: %ld pixels differ from a full redraw without ranges\n", what.c_str(), full);
        check(full == 0, what + ": the picture equals a full redraw");
        ranged.Manager->SetDrawRangeTriangles(32);
      }
      check(partialRanged > 0, what + ": frames were drawn in part");
      drewRanged = drewPlain = 0;
      settle();
    };

    settle();
    // 1. re-meshed chunks: a dent growing, each frame's meshes replacing the chunks that changed
    const int partialStart = ranged.Culler->GetNumberOfPartialRedraws();
    for (int f = 0; f < 4; ++f)
      frame([&](Scene& s) {
        for (auto& kv : dents[static_cast<std::size_t>(f)])
        {
          const Chunks& prev = f == 0 ? before : dents[static_cast<std::size_t>(f - 1)];
          auto p = prev.find(kv.first);
          if (p == prev.end() || p->second->GetNumberOfCells() != kv.second->GetNumberOfCells())
            s.Manager->SetChunk(kv.first, kv.second);
        }
      });
    check(ranged.Culler->GetNumberOfPartialRedraws() == partialStart + 4, "the dent's frames were drawn in part");
    compare("a dent re-meshed");

    // 2. the dent's chunk removed (an open surface), then back
    vtkIdType dentChunk = -1;
    for (auto& kv : dents[3])
      if (before.count(kv.first) && before.at(kv.first)->GetNumberOfCells() != kv.second->GetNumberOfCells())
        dentChunk = kv.first;
    check(dentChunk >= 0, "the dent lies in a chunk");
    // small damage: another chunk's re-mesh, after the removal (the hole is drawn whole)
    frame([&](Scene& s) { s.Manager->RemoveChunk(dentChunk); });
    settle();
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, before.at(dentChunk)); });
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[1].at(dentChunk)); });
    compare("a chunk removed, back, re-meshed (open surface)");

    // 3. chunk actors moved by their matrices
    for (Scene* s : { &ranged, &plain })
      for (vtkIdType id = 0; id < 8; ++id)
        if (vtkActor* a = s->Manager->GetChunkActor(id))
        {
          a->SetPosition(1.5, -2.0, 0.5);
          a->SetOrientation(0, 0, 4);
        }
    settle();
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[2].at(dentChunk)); });
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[3].at(dentChunk)); });
    compare("actors with matrices");
    for (Scene* s : { &ranged, &plain })
      for (vtkIdType id = 0; id < 8; ++id)
        if (vtkActor* a = s->Manager->GetChunkActor(id))
        {
          a->SetPosition(0, 0, 0);
          a->SetOrientation(0, 0, 0);
        }

    // 4. the camera inside the sphere, looking at the dent from within
    for (Scene* s : { &ranged, &plain })
    {
      vtkCamera* cam = s->Ren->GetActiveCamera();
      cam->SetPosition(C[0] - 6, C[1] - 4, C[2] + 1);
      cam->SetFocalPoint(Dent[0], Dent[1], Dent[2]);
      cam->SetViewUp(0, 0, 1);
      cam->SetViewAngle(100);
      cam->SetClippingRange(0.5, 200);
    }
    settle();
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[0].at(dentChunk)); });
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[2].at(dentChunk)); });
    compare("the camera inside the sphere");

    // Negative control: ranges culled 6 pixels inside their rectangles.
    ranged.SetPad(-6);
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[3].at(dentChunk)); });
    frame([&](Scene& s) { s.Manager->SetChunk(dentChunk, dents[1].at(dentChunk)); });
    compare("pad -6 (negative control)", false);
    ranged.SetPad(1);
  }
  std::printf("%s\n", failures ? "FAILED" : "passed");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
