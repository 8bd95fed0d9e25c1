// vtkPartialRedrawCuller against the full redraw as the oracle: a chunked,
// tetrahedrally coloured sphere (512 chunks of 6^3 cells) with a gradient
// background and the brush cursor, edited as a stroke would: chunk meshes
// replaced by those of a dented sphere, a chunk removed and brought back, the
// cursor moved and resized (the manager declaring each replaced chunk's
// changed triangles to the culler, as in the editor). After each group of frames drawn in part, the
// window's pixels must equal, exactly, those of a full redraw of the same
// scene; each partial frame must have drawn fewer props than the scene holds.
// With 8 samples per pixel (the Qt view's default), the pixels may differ only
// on the one-pixel ring around a frame's damage rectangle, where Mesa's
// scissored clear of a multisampled framebuffer reaches.
// A camera change, a translucent prop in the damage and a large damage must
// fall back to full frames. The chunk actors' inputs change only through the
// manager, which announces them (a moved chunk announced: equal; the same
// move unannounced, negative control: differs).
#include "ChunkTestData.h"

#include "vtkActor.h"
#include "vtkBrushRepresentation.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMapper.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkPointData.h"
#include "RenderTestHarness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

using namespace lvdiftest;

namespace
{
const int Cells = 48, Edge = 6;
const double C[3] = { 24.2, 23.7, 24.4 }, R = 17.3;
const double Dent[3] = { 24.2 + 17.3, 23.7, 24.4 }; // on the sphere, +x side

double sphere(double x, double y, double z)
{
  return std::sqrt((x - C[0]) * (x - C[0]) + (y - C[1]) * (y - C[1]) + (z - C[2]) * (z - C[2])) - R;
}

double dented(double x, double y, double z)
{
  const double d = std::sqrt((x - Dent[0]) * (x - Dent[0]) + (y - Dent[1]) * (y - Dent[1]) + (z - Dent[2]) * (z - Dent[2]));
  return std::max(sphere(x, y, z), 5.5 - d);
}

// The scene drawn with this many samples per pixel; the number of failed checks.
int runScene(int samples)
{
  std::printf("---- %d samples per pixel\n", samples);
  const auto checker = [](int i, int j, int k) { return checkerColor(i, j, k); };
  auto before = splitChunks(contractMesh(sdfImage(Cells + 1, sphere), checker), Edge, Cells);
  auto after = splitChunks(contractMesh(sdfImage(Cells + 1, dented), checker), Edge, Cells);

  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.16, 0.17, 0.2);
  ren->SetBackground2(0.05, 0.05, 0.07);
  ren->GradientBackgroundOn();
  auto rw = makeTestWindow(320, 300);
  rw->SetMultiSamples(samples);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  mgr->GetProperty()->SetSpecular(0.25);
  mgr->GetProperty()->SetSpecularPower(25);
  for (auto& kv : before)
    mgr->SetChunk(kv.first, kv.second);
  vtkNew<vtkBrushRepresentation> cursor;
  cursor->SetRenderer(ren);
  ren->AddViewProp(cursor);
  cursor->SetRadius(3.0);
  cursor->SetCenter(Dent[0], Dent[1] + 4, Dent[2]);
  cursor->GetCursorProperty()->SetColor(1.0, 0.85, 0.2);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(50);
  ren->GetActiveCamera()->Elevation(20);
  ren->ResetCameraClippingRange();

  vtkNew<vtkPartialRedrawCuller> culler;
  culler->SetEnabled(true);
  ren->AddCuller(culler);
  mgr->SetRedrawCuller(culler); // replaced chunks declare the box of their changed triangles

  int failures = 0;
  const auto check = checkCounter(failures);
  const int props = mgr->GetNumberOfChunks() + 1;
  std::printf("scene: %d chunk actors and the cursor\n", props - 1);

  rw->Render();
  check(culler->GetNumberOfFullRedraws() == 1 && culler->GetLastNumberOfPropsDrawn() == props,
    "the first frame is drawn whole");
  rw->Render(); // whole again: the first frame created the renderer's light
  rw->Render();
  check(culler->GetNumberOfPartialRedraws() == 1 && culler->GetLastNumberOfPropsDrawn() == 0,
    "an unchanged frame draws nothing");

  // Frames drawn in part, then the picture against a full redraw.
  auto partialFrames = [&](const char* what, const std::function<void(int)>& edit, int frames, bool few = true) {
    const int partialBefore = culler->GetNumberOfPartialRedraws();
    int most = 0;
    std::vector<std::array<int, 4>> damages;
    for (int f = 0; f < frames; ++f)
    {
      edit(f);
      rw->Render();
      most = std::max(most, culler->GetLastNumberOfPropsDrawn());
      const int* d = culler->GetLastDamage();
      damages.push_back({ d[0], d[1], d[0] + d[2], d[1] + d[3] });
      std::printf("  %s, frame %d: damage %d x %d at (%d, %d), %d props drawn\n", what, f, culler->GetLastDamage()[2],
        culler->GetLastDamage()[3], culler->GetLastDamage()[0], culler->GetLastDamage()[1],
        culler->GetLastNumberOfPropsDrawn());
    }
    auto partial = windowPixels(rw);
    culler->RequestFullRedraw();
    rw->Render();
    auto full = windowPixels(rw);
    // Multisampled: Mesa's scissored clear may reach the one-pixel ring just
    // outside a damage rectangle (the editor then redraws whole when still).
    auto onRing = [&](int x, int y) {
      for (const auto& r : damages)
      {
        const bool inGrown = x >= r[0] - 1 && x <= r[2] && y >= r[1] - 1 && y <= r[3];
        const bool inside = x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
        if (samples > 1 && inGrown && !inside)
          return true;
      }
      return false;
    };
    long ring = 0;
    const long diff = differingPixels(partial, full, onRing, &ring);
    std::printf("  %s: %ld pixels differ from the full redraw (and %ld on the ring around a damage rectangle)\n", what,
      diff, ring);
    check(culler->GetNumberOfPartialRedraws() == partialBefore + frames && (!few || most < props / 2),
      (std::string(what) + ": every frame drawn in part" + (few ? ", with fewer than half the props" : "")).c_str());
    check(diff == 0, (std::string(what) + ": the picture equals the full redraw's").c_str());
    rw->Render(); // whole: the grab set the renderer's camera, which the culler cannot tell from a change
  };

  // The dent, chunk by chunk, the cursor following it.
  std::vector<vtkIdType> changed;
  for (auto& kv : after)
  {
    auto b = before.find(kv.first);
    if (b == before.end() || b->second->GetNumberOfCells() != kv.second->GetNumberOfCells())
      changed.push_back(kv.first);
  }
  for (auto& kv : before)
    if (!after.count(kv.first))
      changed.push_back(kv.first);
  std::printf("the dent changes %zu chunks\n", changed.size());
  check(!changed.empty() && changed.size() < 12, "the dent changes a few chunks");
  partialFrames("dent", [&](int f) {
    const vtkIdType id = changed[static_cast<std::size_t>(f)];
    auto it = after.find(id);
    mgr->SetChunk(id, it == after.end() ? nullptr : it->second.Get());
    cursor->SetCenter(Dent[0], Dent[1] + 4 - f, Dent[2]);
  }, static_cast<int>(changed.size()));

  const vtkIdType hole = changed.front();
  partialFrames("a chunk removed, the cursor grown", [&](int f) {
    if (f == 0)
      mgr->RemoveChunk(hole);
    else
      cursor->SetRadius(4.0);
  }, 2);
  partialFrames("the chunk back", [&](int) {
    auto it = after.find(hole);
    mgr->SetChunk(hole, it == after.end() ? nullptr : it->second.Get());
  }, 1);
  // the editor's path: a frame's chunks in one SetChunks, which measures each
  // chunk's changed triangles in its parallel part
  auto showChanged = [&](const auto& chunks) {
    std::vector<vtkIdType> ids;
    std::vector<vtkPolyData*> meshes;
    for (vtkIdType id : changed)
    {
      auto it = chunks.find(id);
      ids.push_back(id);
      meshes.push_back(it == chunks.end() ? nullptr : it->second.Get());
    }
    mgr->SetChunks(ids, meshes);
  };
  partialFrames("the dent undone in one SetChunks call", [&](int) { showChanged(before); }, 1);
  partialFrames("the dent again in one SetChunks call", [&](int) { showChanged(after); }, 1);

  // Fallbacks to full frames.
  int fulls = culler->GetNumberOfFullRedraws();
  ren->GetActiveCamera()->Azimuth(5);
  rw->Render();
  check(culler->GetNumberOfFullRedraws() == fulls + 1, "a camera change draws the whole frame");
  cursor->GetCursorProperty()->SetOpacity(0.5);
  rw->Render();
  check(culler->GetNumberOfFullRedraws() == fulls + 2, "a translucent prop in the damage draws the whole frame");
  cursor->GetCursorProperty()->SetOpacity(1.0);
  rw->Render();
  culler->SetMaximumDamageFraction(1.0);
  partialFrames("every chunk changed (one damage rectangle around the surface)",
    [&](int) { mgr->GetProperty()->SetSpecular(0.3); }, 1, false);
  check(culler->GetLastNumberOfPropsDrawn() == props, "  ... drawn with every prop");
  culler->SetMaximumDamageFraction(0.15);
  fulls = culler->GetNumberOfFullRedraws();
  cursor->SetCenter(Dent[0], Dent[1] - 4, Dent[2] + 4);
  rw->Render();
  check(culler->GetNumberOfFullRedraws() == fulls, "a small damage is drawn in part");
  mgr->GetProperty()->SetSpecular(0.25);
  rw->Render();
  check(culler->GetNumberOfFullRedraws() == fulls + 1, "a damage above MaximumDamageFraction draws the whole frame");
  culler->SetEnabled(false);
  rw->Render();
  check(culler->GetLastNumberOfPropsDrawn() == props, "disabled: nothing is culled");

  return failures;
}
// A window showing chunks through a manager with an enabled culler set
// before the first meshes (so that those are hashed too, and replacements
// declare their changed triangles' points; the runs above, with the culler
// set after the first meshes, declare boxes), with the surface margin given,
// the camera of the tests, and two frames drawn.
struct CulledScene
{
  CulledScene(const std::map<vtkIdType, vtkSmartPointer<vtkPolyData>>& chunks, int margin)
  {
    rw->SetMultiSamples(0);
    rw->AddRenderer(ren);
    mgr->SetRenderer(ren);
    culler->SetEnabled(true);
    culler->SetSurfaceMargin(margin);
    mgr->SetRedrawCuller(culler);
    for (auto& kv : chunks)
      mgr->SetChunk(kv.first, kv.second);
    ren->ResetCamera();
    ren->GetActiveCamera()->Azimuth(50);
    ren->GetActiveCamera()->Elevation(20);
    ren->ResetCameraClippingRange();
    ren->AddCuller(culler);
    rw->Render();
    rw->Render();
  }
  vtkNew<vtkRenderer> ren;
  vtkSmartPointer<vtkRenderWindow> rw = makeTestWindow(320, 300);
  vtkNew<vtkChunkActorManager> mgr;
  vtkNew<vtkPartialRedrawCuller> culler;
};

// The margin of surface props (vtkPartialRedrawCuller::SurfaceMargin, 1 pixel)
// and the damage from the changed triangles' points, against a negative
// control: the dent's frames drawn in part with margin 1 equal the full
// redraw; with margin -4 (damages and rectangles 4 pixels too small on each
// side) they must not, or these comparisons could not see a margin that is
// too small.
int runMarginControl()
{
  std::printf("---- surface margin: 1 against -4 (negative control)\n");
  const auto checker = [](int i, int j, int k) { return checkerColor(i, j, k); };
  auto before = splitChunks(contractMesh(sdfImage(Cells + 1, sphere), checker), Edge, Cells);
  auto after = splitChunks(contractMesh(sdfImage(Cells + 1, dented), checker), Edge, Cells);
  int failures = 0;
  for (int margin : { 1, -4 })
  {
    CulledScene scene(before, margin);
    auto& [ren, rw, mgr, culler] = scene;
    const int partial = culler->GetNumberOfPartialRedraws();
    int frames = 0;
    for (auto& kv : after)
    {
      auto b = before.find(kv.first);
      if (b != before.end() && b->second->GetNumberOfCells() != kv.second->GetNumberOfCells())
      {
        mgr->SetChunk(kv.first, kv.second);
        rw->Render();
        ++frames;
      }
    }
    auto drawn = windowPixels(rw);
    culler->RequestFullRedraw();
    rw->Render();
    const long diff = differingPixels(drawn, windowPixels(rw));
    const bool inPart = culler->GetNumberOfPartialRedraws() == partial + frames && frames > 0;
    const bool ok = inPart && (margin >= 0 ? diff == 0 : diff > 0);
    std::printf("%s: margin %d, %d frames drawn in part: %ld pixels differ from the full redraw (%s)\n",
      ok ? "ok" : "FAILED", margin, frames, diff, margin >= 0 ? "expected none" : "expected some");
    failures += ok ? 0 : 1;
  }
  return failures;
}

// Replaced chunks refill the arrays they show (vtkChunkActorManager keeps the
// array objects, so the buffer cache re-uploads them in place): the picture
// after replacing every changed chunk must equal, exactly, that of a new
// window and manager given the new meshes from the start.
int runRefill()
{
  std::printf("---- replaced chunks against a scene made of the new meshes\n");
  const auto checker = [](int i, int j, int k) { return checkerColor(i, j, k); };
  auto before = splitChunks(contractMesh(sdfImage(Cells + 1, sphere), checker), Edge, Cells);
  auto after = splitChunks(contractMesh(sdfImage(Cells + 1, dented), checker), Edge, Cells);
  auto scene = [](std::vector<std::map<vtkIdType, vtkSmartPointer<vtkPolyData>>*> steps) {
    vtkNew<vtkRenderer> ren;
    auto rw = makeTestWindow(320, 300);
    rw->SetMultiSamples(0);
    rw->AddRenderer(ren);
    vtkNew<vtkChunkActorManager> mgr;
    mgr->SetRenderer(ren);
    for (std::size_t i = 0; i < steps.size(); ++i)
    {
      if (i == 0)
      {
        for (auto& kv : *steps[i])
          mgr->SetChunk(kv.first, kv.second);
      }
      else
      {
        // the editor's path for a frame's chunks: prepared in parallel, refilled in place
        std::vector<vtkIdType> ids;
        std::vector<vtkPolyData*> meshes;
        for (auto& kv : *steps[i])
        {
          ids.push_back(kv.first);
          meshes.push_back(kv.second);
        }
        mgr->SetChunks(ids, meshes);
      }
      if (i == 0)
      {
        const double box[6] = { 0, Cells, 0, Cells, 0, Cells }; // the same camera in both scenes
        ren->ResetCamera(box);
        ren->GetActiveCamera()->Azimuth(50);
        ren->GetActiveCamera()->Elevation(20);
        ren->ResetCameraClippingRange();
      }
      rw->Render();
    }
    return windowPixels(rw);
  };
  std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> replaced;
  for (auto& kv : after)
    if (before.count(kv.first))
      replaced[kv.first] = kv.second;
  std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> start = before, fresh;
  for (auto& kv : before)
    fresh[kv.first] = after.count(kv.first) ? after[kv.first] : kv.second;
  for (auto& kv : after)
    if (!before.count(kv.first))
      start.erase(kv.first);
  auto edited = scene({ &start, &replaced });
  auto made = scene({ &fresh });
  const long diff = differingPixels(edited, made);
  std::printf("%s: the replaced chunks show their new meshes (%ld pixels differ)\n", diff == 0 ? "ok" : "FAILED", diff);
  return diff == 0 ? 0 : 1;
}
// The manager's chunk actors are the culler's announced actors
// (SetInputChangesAnnounced): a frame takes their inputs' MTimes as of the
// last announcement. A chunk's input moved in place and announced
// (InputDataChanged) must give a partial frame equal to the full redraw; the
// same move unannounced (negative control) must leave the old picture, or
// this test could not tell that the announcement is what the culler goes by.
int runAnnouncedInputs()
{
  std::printf("---- announced input changes, against an unannounced one (negative control)\n");
  const auto checker = [](int i, int j, int k) { return checkerColor(i, j, k); };
  auto before = splitChunks(contractMesh(sdfImage(Cells + 1, sphere), checker), Edge, Cells);
  auto after = splitChunks(contractMesh(sdfImage(Cells + 1, dented), checker), Edge, Cells);
  int failures = 0;
  for (bool announce : { true, false })
  {
    CulledScene scene(before, 1);
    auto& [ren, rw, mgr, culler] = scene;
    // a chunk in view: one the dent changes
    vtkIdType id = -1;
    for (auto& kv : after)
      if (before.count(kv.first) && before[kv.first]->GetNumberOfCells() != kv.second->GetNumberOfCells())
        id = kv.first;
    vtkActor* actor = mgr->GetChunkActor(id);
    auto* shown = actor ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0)) : nullptr;
    if (!shown)
    {
      std::printf("FAILED: no chunk in view\n");
      ++failures;
      continue;
    }
    vtkDataArray* xyz = shown->GetPoints()->GetData();
    for (vtkIdType p = 0; p < xyz->GetNumberOfTuples(); ++p)
      for (int a = 0; a < 3; ++a)
        xyz->SetComponent(p, a, xyz->GetComponent(p, a) + 0.7);
    xyz->Modified();
    shown->GetPoints()->Modified();
    if (announce)
      culler->InputDataChanged(actor);
    const int partial = culler->GetNumberOfPartialRedraws();
    rw->Render();
    auto drawn = windowPixels(rw);
    const bool inPart = culler->GetNumberOfPartialRedraws() == partial + 1;
    culler->RequestFullRedraw();
    rw->Render();
    const long diff = differingPixels(drawn, windowPixels(rw));
    const bool ok = inPart && (announce ? diff == 0 : diff > 0);
    std::printf("%s: a chunk moved in place, %s, drawn in part: %ld pixels differ from the full redraw (%s)\n",
      ok ? "ok" : "FAILED", announce ? "announced" : "not announced", diff, announce ? "expected none" : "expected some");
    failures += ok ? 0 : 1;
  }
  return failures;
}
} // namespace

int TestPartialRedraw(int, char*[])
{
  const int failures = runScene(0) + runScene(8) + runRefill() + runMarginControl() + runAnnouncedInputs();
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
