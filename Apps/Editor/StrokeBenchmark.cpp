#include "StrokeBenchmark.h"

#include "EditorDriver.h"
#include "EditorRenderWindow.h"
#include "MainWindow.h"

#include "vtkCullerCollection.h"
#include "vtkChunkActorManager.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkRenderer.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRendererCollection.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include "lvdif/Error.h"
#include "lvdif/InputDevice.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h" // readScriptFile: the one reader of text files

#include <QApplication>
#include <QFileInfo>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace
{
double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

double ms(std::chrono::steady_clock::duration d)
{
  return std::chrono::duration<double, std::milli>(d).count();
}
} // namespace

std::vector<lvdif::BrushSample> StrokeBenchmark::loadSamples(const QString& path, const lvdif::Index3* dims)
{
  const std::string file = path.toStdString();
  std::vector<lvdif::BrushSample> samples;
  // the text first (the one reader of text files: a FIFO, a folder or a
  // device refused without blocking; its size within the memory limit: a FIFO
  // hung the editor for good in std::ifstream), then a recording by its
  // extension or its first line, as --script and Play recording tell one (a
  // recording saved without .lvr was read as samples: "expected '{'")
  std::string text;
  try
  {
    text = lvdif::readScriptFile(file);
  }
  catch (const lvdif::Error& e)
  {
    throw lvdif::Error(e.code(), "cannot read '" + file + "': " + e.what());
  }
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix == "lvr" || suffix == "lvrec" || isRecordingText(text))
  {
    std::istringstream in(text);
    const lvdif::Recording recording = lvdif::readRecording(in, file);
    const lvdif::Index3& c = recording.canvas;
    if (dims && c[0] > 0 && c != *dims)
    {
      auto size = [](const lvdif::Index3& d, const char* by) {
        return std::to_string(d[0]) + by + std::to_string(d[1]) + by + std::to_string(d[2]);
      };
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
        "'" + file + "' was recorded on a " + size(c, " x ") + " canvas; this volume is " + size(*dims, " x ") +
          ", where its stroke would go elsewhere or outside: run it on its canvas (--new " + size(c, "x") + ")");
    }
    for (const lvdif::EditRecord& r : recording.records)
      if (r.type == lvdif::EditRecord::Type::Edit)
        for (const lvdif::Dab& d : r.dabs)
        {
          lvdif::BrushSample s;
          s.position = d.center;
          s.time = static_cast<double>(samples.size()) / 50.0; // no sample times in recordings
          samples.push_back(s);
        }
  }
  else
  {
    std::istringstream in(text);
    std::string line;
    int number = 0;
    bool timed = false;
    while (std::getline(in, line))
    {
      ++number;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#')
        continue;
      lvdif::BrushSample s;
      std::string why;
      if (!lvdif::parseSampleJson(line, s, &why))
        throw lvdif::Error(lvdif::ErrorCode::ParseError, file + ":" + std::to_string(number) + ": " + why);
      timed = timed || s.time != 0;
      if (!samples.empty() && s.time < samples.back().time)
        throw lvdif::Error(lvdif::ErrorCode::ParseError,
          file + ":" + std::to_string(number) + ": sample times must not decrease");
      samples.push_back(s);
    }
    const double t0 = samples.empty() ? 0 : samples.front().time;
    for (std::size_t i = 0; i < samples.size(); ++i)
      samples[i].time = timed ? samples[i].time - t0 : static_cast<double>(i) / 50.0;
  }
  if (samples.size() < 2)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "'" + file + "' holds fewer than 2 samples");
  if (samples.back().time > 600)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "'" + file + "' lasts more than 10 minutes");
  return samples;
}

StrokeBenchmark::StrokeBenchmark(MainWindow& window, std::vector<lvdif::BrushSample> samples, const QString& name)
  : QObject(&window)
  , Window(window)
  , Samples(std::move(samples))
  , Name(name)
{
}

vtkPartialRedrawCuller* StrokeBenchmark::redrawCuller()
{
  vtkRenderer* ren = this->Window.renderWindow()->GetRenderers()->GetFirstRenderer();
  vtkCollectionSimpleIterator it;
  ren->GetCullers()->InitTraversal(it);
  while (vtkCuller* c = ren->GetCullers()->GetNextCuller(it))
    if (auto* p = vtkPartialRedrawCuller::SafeDownCast(c))
      return p->GetEnabled() ? p : nullptr;
  return nullptr;
}

void StrokeBenchmark::measureStillFrames()
{
  // The floor of a frame: the still scene drawn whole, and drawn again
  // unchanged (with partial redraws: nothing to draw, the frame's fixed cost).
  vtkRenderWindow* rw = this->Window.renderWindow();
  vtkPartialRedrawCuller* culler = this->redrawCuller();
  auto timed = [&](bool whole) {
    if (whole && culler)
      culler->RequestFullRedraw();
    const auto t0 = std::chrono::steady_clock::now();
    rw->Render();
    rw->WaitForCompletion();
    return ms(std::chrono::steady_clock::now() - t0);
  };
  std::vector<double> whole, unchanged;
  for (int i = 0; i < 3; ++i)
    whole.push_back(timed(true));
  for (int i = 0; i < 3; ++i)
    unchanged.push_back(timed(false));
  std::printf("benchmark-stroke: still scene before the stroke (render + glFinish, median of 3): drawn whole %.2f ms, "
              "unchanged %.2f ms (%s)\n",
    percentile(whole, 0.5), percentile(unchanged, 0.5),
    culler ? "partial redraw: nothing to draw" : "--full-redraw: drawn whole");
  if (culler)
  {
    this->FullBefore = culler->GetNumberOfFullRedraws();
    this->PartialBefore = culler->GetNumberOfPartialRedraws();
  }
  if (auto* erw = EditorRenderWindow::SafeDownCast(rw))
    this->SingleSampledBefore = erw->GetNumberOfSingleSampledFrames();
}

vtkSmartPointer<vtkUnsignedCharArray> StrokeBenchmark::grabShown()
{
  vtkRenderWindow* rw = this->Window.renderWindow();
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(rw);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOn();
  w2i->ShouldRerenderOff();
  w2i->Update();
  vtkSmartPointer<vtkUnsignedCharArray> a = vtkUnsignedCharArray::New();
  a->Delete();
  a->DeepCopy(w2i->GetOutput()->GetPointData()->GetScalars());
  return a;
}

long StrokeBenchmark::pixelsDifferingFromFullRedraw(vtkUnsignedCharArray* earlier, long* earlierDiffer)
{
  // The picture shown (the display framebuffer, as Qt presents it) against
  // the same scene drawn whole.
  vtkRenderWindow* rw = this->Window.renderWindow();
  auto shown = this->grabShown();
  this->redrawCuller()->RequestFullRedraw();
  rw->Render();
  auto whole = this->grabShown();
  auto differ = [&whole](vtkUnsignedCharArray* a) {
    if (a->GetNumberOfValues() != whole->GetNumberOfValues())
      return -1L;
    long n = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); i += 3)
      n += a->GetValue(i) != whole->GetValue(i) || a->GetValue(i + 1) != whole->GetValue(i + 1) ||
        a->GetValue(i + 2) != whole->GetValue(i + 2);
    return n;
  };
  if (earlier && earlierDiffer)
    *earlierDiffer = differ(earlier);
  return differ(shown);
}

void StrokeBenchmark::start()
{
  this->measureStillFrames();
  connect(&this->Window, &MainWindow::meshesShown, this, &StrokeBenchmark::frameRendered);
  this->Window.resetStrokeProfile();
  this->Start = std::chrono::steady_clock::now();
  if (std::getenv("LVDIF_BENCH_TRACE")) // the clock's own time too: to cut a profile (perf -k CLOCK_MONOTONIC) to the stroke
    std::fprintf(stderr, "benchmark-stroke-trace: stroke starts at %.6f s of the steady clock\n",
      std::chrono::duration<double>(this->Start.time_since_epoch()).count());
  this->LastFrame = this->Start;
  if (!this->Window.beginStroke())
  {
    std::printf("benchmark-stroke: the stroke could not start (no volume?)\n");
    QApplication::exit(1);
    return;
  }
  // One timer per sample, as a device's events would arrive; precise timers
  // fire within a millisecond when the loop is free, later when it is busy
  // (that wait is part of the latency, as for a real mouse event).
  for (std::size_t i = 0; i < this->Samples.size(); ++i)
  {
    const auto due = this->Start + std::chrono::microseconds(static_cast<std::int64_t>(this->Samples[i].time * 1e6));
    const int inMs = std::max(0, static_cast<int>(std::floor(ms(due - std::chrono::steady_clock::now()))));
    QTimer::singleShot(inMs, Qt::PreciseTimer, this, [this, i] { this->deliver(i); });
  }
}

void StrokeBenchmark::deliver(std::size_t i)
{
  VolumeDocument& doc = this->Window.document();
  const auto& o = doc.volume().options();
  const lvdif::BrushSample& s = this->Samples[i];
  double world[4];
  for (int a = 0; a < 3; ++a)
    world[a] = o.origin[a] + o.spacing[a] * s.position[a];
  world[3] = doc.editor().stroke.radius * o.spacing[0]; // the tool panel's, set at the stroke's start
  this->CurrentSampleTime = s.time;
  this->Window.addBrushSample(world); // applies, settles; the frame follows when the loop is free
  this->sampleApplied();
  if (i + 1 == this->Samples.size())
  {
    this->Window.endStroke();
    this->EndAt = std::chrono::steady_clock::now();
    this->sampleApplied(); // the stroke's last dabs (Drill): one more request
    this->Ended = true;
    this->finishWhenIdle();
  }
}

void StrokeBenchmark::sampleApplied()
{
  const VolumeDocument& doc = this->Window.document();
  const std::vector<std::int64_t>& ids = doc.lastRequest();
  if (ids.empty() || (!this->Requests.empty() && this->Requests.back().editedAt == doc.lastRequestTime()))
    return;
  Request r;
  r.sampleTime = this->CurrentSampleTime;
  r.editedAt = doc.lastRequestTime();
  r.chunks = ids;
  this->Requests.push_back(std::move(r));
}

void StrokeBenchmark::frameRendered(const ShownMeshes& shown)
{
  // called right after the window's Render(): the frame is drawn, not just queued
  this->Window.renderWindow()->WaitForCompletion();
  const TimePoint renderEnd = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < shown.chunks.size() && i < shown.gatheredAt.size(); ++i)
    this->Delivered[shown.chunks[i]].push_back(
      Shown{ shown.gatheredAt[i], renderEnd, i < shown.levels.size() ? shown.levels[i] : 0 });
  if (!shown.drawn)
  {
    // every mesh equalled its chunk's shown one: the last frame drawn shows them
    ++this->UndrawnFrames;
    return;
  }
  this->RenderMs.push_back(ms(renderEnd - shown.installStart));
  this->DrawMs.push_back(ms(renderEnd - shown.renderStart));
  this->LastFrame = renderEnd;
  // LVDIF_BENCH_TRACE=1: each frame's and each sample's times (ms after the stroke's start) on stderr
  if (std::getenv("LVDIF_BENCH_TRACE"))
    std::fprintf(stderr, "benchmark-stroke-trace: frame install %.1f render %.1f end %.1f chunks %zu\n", ms(shown.installStart - this->Start),
      ms(shown.renderStart - this->Start), ms(renderEnd - this->Start), shown.chunks.size());
  int calls = 0;
  this->TrianglesDrawn.push_back(static_cast<double>(this->Window.chunkActors()->GetLastNumberOfTrianglesDrawn(&calls)));
  this->DrawCalls.push_back(calls);
  ++this->Frames;
}

void StrokeBenchmark::finishWhenIdle()
{
  if (!this->Window.document().meshingIdle())
  {
    QTimer::singleShot(5, Qt::PreciseTimer, this, [this] { this->finishWhenIdle(); });
    return;
  }
  this->Window.showFinishedMeshes(); // what the worker finished since the last poll
  auto* erw = EditorRenderWindow::SafeDownCast(this->Window.renderWindow());
  if (erw && erw->GetNumberOfSingleSampledFrames() > this->SingleSampledBefore && this->redrawCuller())
  {
    // The stroke's frames had one sample per pixel: their picture now, then
    // the window's own still frame (MainWindow's still timer, 250 ms after the
    // last frame once the stroke has ended) is what the report checks.
    this->StrokePicture = this->grabShown();
    QTimer::singleShot(600, Qt::PreciseTimer, this, [this] { this->report(); });
    return;
  }
  this->report();
}

void StrokeBenchmark::report()
{
  disconnect(&this->Window, &MainWindow::meshesShown, this, &StrokeBenchmark::frameRendered);
  std::vector<double> latency;
  int missing = 0;
  for (const Request& r : this->Requests)
  {
    TimePoint shown = r.editedAt;
    for (std::int64_t id : r.chunks)
    {
      const auto& d = this->Delivered[id];
      const auto it = std::find_if(d.begin(), d.end(), [&](const Shown& g) { return g.gathered > r.editedAt; });
      if (it == d.end())
      {
        ++missing;
        continue;
      }
      shown = std::max(shown, it->rendered);
    }
    latency.push_back(ms(shown - this->Start) - 1e3 * r.sampleTime);
    if (std::getenv("LVDIF_BENCH_TRACE"))
      std::fprintf(stderr, "benchmark-stroke-trace: sample %.1f edited %.1f shown %.1f lat %.1f\n", 1e3 * r.sampleTime,
        ms(r.editedAt - this->Start), ms(shown - this->Start), latency.back());
  }
  const double seconds = std::max(1e-9, ms(this->LastFrame - this->Start) / 1e3);
  const auto& d = this->Window.document().volume().dims();
  std::printf("benchmark-stroke: %s: %zu samples over %.2f s, volume %lldx%lldx%lld, %zu re-mesh requests\n",
    this->Name.toLocal8Bit().constData(), this->Samples.size(), this->Samples.back().time,
    static_cast<long long>(d[0]), static_cast<long long>(d[1]), static_cast<long long>(d[2]), this->Requests.size());
  // the stroke's level of detail: how many of its meshes were coarse, and when
  // every chunk it changed showed its full-resolution mesh of its last edit
  std::map<std::int64_t, TimePoint> lastEdit;
  for (const Request& r : this->Requests)
    for (std::int64_t id : r.chunks)
      lastEdit[id] = std::max(lastEdit[id], r.editedAt);
  int coarse = 0, meshes = 0, unrefined = 0;
  TimePoint refined = this->EndAt;
  for (const auto& kv : this->Delivered)
    for (const Shown& g : kv.second)
    {
      ++meshes;
      coarse += g.level != 0;
    }
  for (const auto& kv : lastEdit)
  {
    const auto& d = this->Delivered[kv.first];
    const auto it =
      std::find_if(d.begin(), d.end(), [&](const Shown& g) { return g.level == 0 && g.gathered > kv.second; });
    if (it == d.end())
      ++unrefined;
    else
      refined = std::max(refined, it->rendered);
  }
  std::printf("benchmark-stroke: latency from sample time to rendered frame: p50 %.2f ms, p95 %.2f ms, max %.2f ms "
              "(--stroke-lod %s: %s; %d of the %d meshes shown were coarse)\n",
    percentile(latency, 0.5), percentile(latency, 0.95), percentile(latency, 1.0),
    this->Window.strokeLod().toLocal8Bit().constData(),
    coarse ? "the latency counts the coarse meshes" : "every mesh at full resolution", coarse, meshes);
  std::printf("benchmark-stroke: refine: every one of the %zu chunks the stroke changed shown at full resolution "
              "%.2f ms after the stroke's end (%zu chunks were asked again at full resolution)\n",
    lastEdit.size(), ms(refined - this->EndAt), this->Window.refinedChunks());
  if (unrefined)
    std::printf("benchmark-stroke: error: %d chunks the stroke changed never showed their full-resolution mesh\n", unrefined);
  std::printf("benchmark-stroke: frames with new meshes: %d in %.2f s, %.1f fps; install+render p50 %.2f ms, p95 %.2f ms "
              "(and %d not drawn: every mesh equal to its chunk's shown one)\n",
    this->Frames, seconds, this->Frames / seconds, percentile(this->RenderMs, 0.5), percentile(this->RenderMs, 0.95),
    this->UndrawnFrames);
  std::printf("benchmark-stroke: render (drawing the frame, glFinish included) p50 %.2f ms, p95 %.2f ms, max %.2f ms\n",
    percentile(this->DrawMs, 0.5), percentile(this->DrawMs, 0.95), percentile(this->DrawMs, 1.0));
  std::printf("benchmark-stroke: chunk triangles drawn per frame p50 %.0f, p95 %.0f, in p50 %.0f draw calls "
              "(of %lld triangles in %d chunks; draw ranges of %d triangles)\n",
    percentile(this->TrianglesDrawn, 0.5), percentile(this->TrianglesDrawn, 0.95), percentile(this->DrawCalls, 0.5),
    static_cast<long long>(this->Window.chunkActors()->GetNumberOfTriangles()),
    this->Window.chunkActors()->GetNumberOfChunks(), this->Window.chunkActors()->GetDrawRangeTriangles());
  const StrokeProfile& p = this->Window.strokeProfile();
  std::printf("benchmark-stroke: UI thread, summed over the stroke: brush %.0f ms (%d samples), settle wait %.0f ms, "
              "mesh to polydata %.0f ms + actor update %.0f ms (%d chunk meshes, %d of them equal to the shown mesh and "
              "left as shown), Render() %.0f ms (%d frames); "
              "%d frames stopped waiting for the worker before it was idle\n",
    p.brushMs, p.samples, p.settleMs, p.convertMs, p.setChunkMs, p.meshes, p.unchangedMeshes, p.renderMs, p.frames,
    p.settleTimeouts);
  std::printf("benchmark-stroke: frames are drawn by this display's OpenGL; under Xvfb (Mesa llvmpipe, software) "
              "frame times are not representative of a GPU\n");
  long differ = 0;
  if (vtkPartialRedrawCuller* culler = this->redrawCuller())
  {
    std::printf("benchmark-stroke: renders during the stroke: %d drawn in part, %d drawn whole\n",
      culler->GetNumberOfPartialRedraws() - this->PartialBefore, culler->GetNumberOfFullRedraws() - this->FullBefore);
    vtkRenderWindow* rw = this->Window.renderWindow();
    const long pixels = static_cast<long>(rw->GetSize()[0]) * rw->GetSize()[1];
    auto* erw = EditorRenderWindow::SafeDownCast(rw);
    const int single = erw ? erw->GetNumberOfSingleSampledFrames() - this->SingleSampledBefore : 0;
    long strokeDiffer = 0;
    bool controlFailed = false;
    const bool stillDrawn = this->StrokePicture && erw && !erw->GetLastFrameSingleSampled();
    differ = this->pixelsDifferingFromFullRedraw(this->StrokePicture, &strokeDiffer);
    if (this->StrokePicture)
    {
      std::printf("benchmark-stroke: %d frames of the stroke drawn with one sample per pixel (the view has %d); their "
                  "picture differs from the scene drawn whole in %ld of %ld pixels; the still frame after the stroke %s\n",
        single, rw->GetMultiSamples(), strokeDiffer, pixels,
        stillDrawn ? "was drawn whole, multisampled" : "was NOT drawn (error)");
      // Negative control: the comparison must see the single-sampled frames'
      // picture, or it could not tell whether the still frame replaced it.
      if (strokeDiffer <= 0 || !stillDrawn)
      {
        std::printf("benchmark-stroke: error: %s\n",
          stillDrawn ? "the comparison did not see the single-sampled frames" : "no still frame after the stroke");
        controlFailed = true;
      }
    }
    if (differ == 0)
      std::printf("benchmark-stroke: the picture after the stroke equals the scene drawn whole\n");
    else
      std::printf("benchmark-stroke: the picture after the stroke differs from the scene drawn whole in %ld of %ld pixels "
                  "(%d samples per pixel: edges of the redrawn rectangles; the view is drawn whole once still)\n",
        differ, pixels, rw->GetMultiSamples());
    // Multisampled partial frames may differ on their rectangles' edges;
    // more than that (1% of the view) is an error, as is any difference without multisampling.
    // After single-sampled stroke frames the still frame must equal it exactly.
    differ = controlFailed || differ < 0 ||
      (rw->GetMultiSamples() > 1 && !this->StrokePicture ? differ * 100 > pixels : differ > 0);
  }
  else
    std::printf("benchmark-stroke: renders during the stroke: every one drawn whole (--full-redraw)\n");
  if (missing)
    std::printf("benchmark-stroke: error: %d requested chunk meshes never showed\n", missing);
  std::fflush(stdout);
  QApplication::exit(missing || unrefined || differ || this->Requests.empty() ? 1 : 0);
}
