// Stroke-to-frame latency of interactive editing (paper Table 2's
// "C3: marching cubes in its own thread"), headless.
//
// A recorded-style stroke (samples with timestamps, 50 Hz as the original's
// input, along an arc on the surface of a sphere volume) is replayed at its
// own speed against the editor's real pipeline:
//   UI loop (this thread, ticking at up to 60 Hz), through one
//   lvdif::EditSession as the Qt editor: deliver the samples whose time has
//     come -> EditSession::addSample (live application; the session queues the
//     mesh chunks the sample invalidated, lvdif::meshChunksToRemesh) -> collect
//     the meshes ready -> VolumeChunkToPolyData + vtkChunkActorManager::SetChunk
//     (vertex un-sharing for the tetrahedral shader included) -> [optional:
//     render a frame]
//   meshing: the session's marching cubes worker thread (CPU), or one batched
//     launch per collect on the GPU (a device-resident session).
// Latency of a sample = time from its application until every chunk it
// dirtied has a mesh reflecting it installed in the actor manager (exact: the
// worker says when each mesh's input was gathered). "From sample time" adds
// the wait before the loop applies the sample (its recorded time to its
// application: up to one tick) and the brush. FPS = loop ticks per second.
//
// Without --render no frame is drawn (the numbers then are the CPU pipeline
// up to "ready to draw"); --render draws every tick with whatever OpenGL the
// X server offers (Mesa llvmpipe on the development VM: software
// rasterisation of the whole model, which dominates and is not what a GPU
// would cost). Needs the Core editor (lvdif/Editor.h).
//
// Where the time goes (per sample, p95): edit = EditSession::addSample (brush,
// the worker's source lock, the remesh rule); per request, mesh = extractChunks
// of its chunks re-run synchronously after the stroke (all cores); per tick,
// install (and per tick that installed at least one mesh: what
// bench_stroke_latency_core, which has no VTK, leaves out).
//
// usage: bench_stroke_latency [N=512] [--render] [--samples 100] [--radius 8] [--device cpu|auto]
//        [--settle MS: wait up to MS per tick for the worker before collecting]
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/EditSession.h"

#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "LVDIFChunkedMarchingCubesOutput.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <thread>

using bench::percentile;

std::vector<std::string> runStroke(int n, int samples, double radius, bool render, lvdif::Device device, double settleMs)
{
  bench::Stopwatch setup;
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = 32;
  auto shared = std::make_shared<lvdif::DictionaryVolume>(o);
  const double c = 0.5 * (n - 1), r = 0.35 * n;
  lvdif::fillFromFunction(*shared, lvdif::sphereSdf(c, c, c, r));
  lvdif::EditSessionOptions so;
  so.device = device;
  so.meshChunkEdge = 32;
  lvdif::EditSession session(shared, so);
  if (!session.notice().empty())
    std::printf("notice: %s\n", session.notice().c_str());
  const lvdif::DictionaryVolume& volume = session.hostVolume(); // geometry and colours
  vtkNew<vtkChunkActorManager> actors;
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkRenderWindow> rw;
  actors->SetRenderer(ren);
  session.requestAllMeshes();
  session.waitMeshingIdle();
  for (const auto& m : session.collectMeshes())
    if (!m.empty())
      actors->SetChunk(m.chunkId, LVDIFChunkedMarchingCubesOutput::VolumeChunkToPolyData(m, volume));
  if (render)
  {
    rw->SetSize(640, 480);
    rw->AddRenderer(ren);
    ren->ResetCamera();
    rw->Render();
  }
  std::printf("volume %d^3, chunk 32^3, %d chunk actors, %lld triangles; setup %.1f s; frames drawn: %s\n", n,
    actors->GetNumberOfChunks(), static_cast<long long>(actors->GetNumberOfTriangles()), setup.seconds(),
    render ? "yes (this X server's OpenGL)" : "no (ready-to-draw)");

  session.brush().op = lvdif::BrushOp::Add;
  session.brush().color = lvdif::Rgba{ 230, 80, 50, 255 };
  session.stroke().kind = lvdif::BrushKind::Drill; // applied as it goes, as the editor does
  session.stroke().radius = radius;

  // The stroke: 50 Hz samples on the sphere's surface along a 90-degree arc.
  std::vector<lvdif::BrushSample> stroke(samples);
  for (int i = 0; i < samples; ++i)
  {
    const double a = 0.5 * M_PI * i / std::max(1, samples - 1);
    stroke[i].position = { c + r * std::cos(a), c + r * std::sin(a), c };
    stroke[i].time = i / 50.0;
    stroke[i].buttons = 1;
  }

  std::vector<double> tickMs, brushMs, installMs, installBusyMs;
  // For the latency: which chunks each sample dirtied, and when each chunk's meshes arrived.
  std::vector<std::pair<double, std::vector<std::int64_t>>> requests; // (arrival time, chunks)
  std::vector<double> sampleTimes; // the stroke time of each request's sample
  // per chunk: (when its input was gathered, when it was installed), in order
  std::map<std::int64_t, std::vector<std::pair<double, double>>> delivered;
  const auto t0 = std::chrono::steady_clock::now();
  struct
  {
    std::chrono::steady_clock::time_point start;
    double at(std::chrono::steady_clock::time_point t) const
    {
      return std::chrono::duration<double>(t - start).count();
    }
    double seconds() const { return this->at(std::chrono::steady_clock::now()); }
  } clock{ t0 };
  std::size_t next = 0;
  int ticks = 0;
  session.beginStroke();
  bool ended = false;
  while (true)
  {
    bench::Stopwatch tick;
    const double now = clock.seconds();
    while (next < stroke.size() && stroke[next].time <= now)
    {
      bench::Stopwatch b;
      session.addSample(stroke[next]);
      brushMs.push_back(b.ms());
      requests.emplace_back(clock.at(session.lastRequestTime()), session.lastRequest());
      sampleTimes.push_back(stroke[next].time);
      ++next;
    }
    if (next == stroke.size() && !ended)
    {
      session.endStroke();
      if (!session.lastRequest().empty())
      {
        requests.emplace_back(clock.at(session.lastRequestTime()), session.lastRequest()); // the stroke's last dabs
        sampleTimes.push_back(stroke.back().time);
      }
      ended = true;
    }
    // --settle: give the worker up to this long to finish what this tick
    // requested, so its meshes are installed now instead of one tick later.
    if (settleMs > 0)
    {
      bench::Stopwatch w;
      while (!session.meshingIdle() && w.ms() < settleMs)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    const bool idleBefore = session.meshingIdle();
    bench::Stopwatch inst;
    std::vector<std::chrono::steady_clock::time_point> gathered;
    const std::vector<lvdif::ChunkMesh> meshes = session.collectMeshes(&gathered);
    std::map<std::int64_t, const lvdif::ChunkMesh*> newest; // a later mesh of a chunk supersedes an earlier one
    for (const auto& m : meshes)
      newest[m.chunkId] = &m;
    for (const auto& kv : newest)
    {
      const lvdif::ChunkMesh& m = *kv.second;
      if (m.empty())
        actors->RemoveChunk(m.chunkId);
      else
        actors->SetChunk(m.chunkId, LVDIFChunkedMarchingCubesOutput::VolumeChunkToPolyData(m, volume));
    }
    installMs.push_back(inst.ms());
    if (!newest.empty())
      installBusyMs.push_back(installMs.back()); // ticks that installed something
    if (render)
      rw->Render();
    const double shown = clock.seconds(); // ready to draw (or drawn with --render)
    for (std::size_t i = 0; i < meshes.size(); ++i)
      delivered[meshes[i].chunkId].emplace_back(clock.at(gathered[i]), shown);
    ++ticks;
    if (idleBefore && ended && session.meshingIdle())
      break;
    const double spent = tick.seconds();
    tickMs.push_back(1e3 * spent);
    if (spent < 1.0 / 60)
      std::this_thread::sleep_for(std::chrono::duration<double>(1.0 / 60 - spent));
  }
  const double duration = clock.seconds();
  // A chunk requested at time r shows the edit from the first of its meshes
  // whose input was gathered after r (gathers and edits both hold the source
  // mutex, so that mesh includes the edit and earlier ones do not). Latency
  // of a sample = until its last chunk shows it.
  std::vector<double> latency, fromInput;
  int missing = 0;
  for (std::size_t r = 0; r < requests.size(); ++r)
  {
    const auto& req = requests[r];
    double worst = 0, shownAt = req.first;
    for (std::int64_t id : req.second)
    {
      const auto& d = delivered[id];
      auto it = std::find_if(d.begin(), d.end(), [&](const std::pair<double, double>& g) { return g.first >= req.first; });
      if (it == d.end())
      {
        ++missing; // never happens unless the worker dropped a request
        continue;
      }
      worst = std::max(worst, it->second - req.first);
      shownAt = std::max(shownAt, it->second);
    }
    latency.push_back(1e3 * worst);
    fromInput.push_back(1e3 * (shownAt - sampleTimes[r]));
  }
  if (missing)
    std::printf("warning: %d requested chunk meshes never arrived\n", missing);
  // Meshing cost of each request on its own (synchronously, after the stroke:
  // the chunks' final content, same chunk count as in the stroke).
  std::vector<double> meshMs, chunkCounts;
  session.sync();
  for (const auto& req : requests)
  {
    bench::Stopwatch m;
    const auto meshes = session.mesher().extractChunks(req.second);
    meshMs.push_back(m.ms());
    chunkCounts.push_back(static_cast<double>(req.second.size()));
  }
  return { std::to_string(n) + "^3",
    std::string(session.onDevice() ? "gpu" : "cpu") + (settleMs > 0 ? ", settle " + bench::fmt(settleMs, 0) + " ms" : ""), std::to_string(samples),
    bench::fmt(radius, 1),
    bench::fmt(percentile(chunkCounts, 0.5), 0) + " (" + bench::fmt(percentile(chunkCounts, 0.95), 0) + ")",
    bench::fmt(percentile(latency, 0.5)), bench::fmt(percentile(latency, 0.95)), bench::fmt(percentile(latency, 1.0)),
    bench::fmt(percentile(fromInput, 0.5)) + " (" + bench::fmt(percentile(fromInput, 0.95)) + ")",
    bench::fmt(ticks / duration, 1),
    bench::fmt(percentile(tickMs, 0.95)), bench::fmt(percentile(brushMs, 0.95)),
    bench::fmt(percentile(meshMs, 0.5)) + " (" + bench::fmt(percentile(meshMs, 0.95)) + ")",
    bench::fmt(percentile(installMs, 0.95)),
    bench::fmt(percentile(installBusyMs, 0.5)) + " (" + bench::fmt(percentile(installBusyMs, 0.95)) + ")",
    render ? "yes" : "no" };
}

static int benchMain(int argc, char** argv)
{
  int n = 512, samples = 100;
  double radius = 8;
  bool render = false;
  lvdif::Device device = lvdif::Device::Cpu;
  double settleMs = 0;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--render"))
      render = true;
    else if (!std::strcmp(argv[i], "--samples") && i + 1 < argc)
      samples = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--radius") && i + 1 < argc)
      radius = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--settle") && i + 1 < argc)
      settleMs = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--device") && i + 1 < argc)
      device = std::strcmp(argv[++i], "cpu") ? lvdif::Device::Auto : lvdif::Device::Cpu;
    else
      n = std::atoi(argv[i]);
  }
  std::cout << "bench_stroke_latency: " << bench::machineDescription() << "\n";
  std::vector<std::vector<std::string>> rows;
  rows.push_back(runStroke(n, samples, radius, render, device, settleMs));
  bench::printTable({ "volume", "session", "samples", "radius", "mesh chunks/request p50 (p95)",
                      "latency p50 ms", "latency p95 ms", "latency max ms",
                      "from sample time p50 (p95) ms", "loop FPS", "tick p95 ms",
                      "edit p95 ms", "mesh/request p50 (p95) ms",
                      "install p95 ms", "install/busy tick p50 (p95) ms", "frames drawn" },
    rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
