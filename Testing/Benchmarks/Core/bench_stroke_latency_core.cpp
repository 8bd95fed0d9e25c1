// Stroke-to-"ready to draw" latency of interactive editing on the Core
// pipeline only (paper Table 2's "C3: marching cubes in its own
// thread"), for machines without VTK/Qt (the GPU host). The VTK twin is
// Testing/Benchmarks/VTK/bench_stroke_latency.cxx, which also installs the
// meshes into vtkChunkActorManager; this one stops before that.
//
// A recorded-style stroke (samples with timestamps at 50 Hz along a 90-degree
// arc on the surface of an analytic sphere, brush radius 8, Add) is replayed
// at its own speed:
//   editing thread (this one):
//     apply the sample (under the worker's source mutex), with one of
//       cpu    lvdif::Editor::addSample (Drill: applied as it goes, undo step):
//              what the Qt editor does today, also on a machine with a GPU;
//       cuda   StrokeBuilder + lvdif::cuda::applyDabs (the CUDA brush: the
//              touched chunks go to the device and back per call), same undo;
//       device StrokeBuilder + cuda::DeviceVolume::applyDabs + sync() (the
//              device-resident volume; sync writes the host copy that the
//              marching cubes read, with the undo observer);
//     -> request the marching cubes chunks the sample changed
//        (chunksAffectedBy(changedBox) as the editor does; the device path
//        reports no box, so it uses the dirty storage chunks intersected with
//        the dabs' reach box)
//     -> wait up to --settle ms for the worker (MainWindow::settleMeshes)
//     -> collect the finished chunk meshes (never blocks on meshing).
//   worker thread: lvdif::MarchingCubesWorker on --device cpu|cuda.
// Loop (--loop): "event" (default) is the Qt editor's: each sample is handled
// when its time comes, and a 15 ms timer collects what settling left over;
// "tick" is the VTK bench's 60 Hz polling loop (all due samples per tick).
//
// Latency of a sample = from its recorded time until every chunk it dirtied
// has a collected mesh reflecting it ("ready to draw"; exact: the worker says
// when each mesh's input was gathered under the mutex, and the edit was made
// under it before). NOTHING IS DRAWN and no VTK object is built: the cost of
// turning the collected meshes into actors (LVDIFChunkMesh::ToPolyData +
// vtkChunkActorManager::SetChunk, "install" in the VTK bench) and of the
// frame itself is not in these numbers.
//
// usage: bench_stroke_latency_core [N=512] [--device cpu|cuda] [--brush cpu|cuda|device|all]
//        [--samples 100] [--radius 8] [--settle 6] [--loop event|tick] [--chunk E]
//        (E: 32 below 1024^3, 64 from 1024^3 as the paper)
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/BrushCuda.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/DeviceVolume.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/MarchingCubesWorker.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace
{
using Clock = std::chrono::steady_clock;

struct Config
{
  int n = 512, samples = 100, chunk = 0;
  double radius = 8, settleMs = 6;
  lvdif::Device device = lvdif::Device::Cpu;
  std::string brush, loop = "event";
};

// The Core twin of LVDIFChunkMesh::ChunksToRemesh(mc, dirty, EditResult):
// the chunks the edit's changed box reaches, plus the storage-chunk rule for
// dirty chunks the edit does not name.
std::vector<std::int64_t> chunksForEdit(const lvdif::ChunkedMarchingCubes& mc,
  const std::vector<std::int64_t>& dirty, const lvdif::EditResult& edit)
{
  std::vector<std::int64_t> foreign;
  std::set_difference(dirty.begin(), dirty.end(), edit.changedChunks.begin(), edit.changedChunks.end(),
    std::back_inserter(foreign));
  std::vector<std::int64_t> ids = edit.changedBox.empty() ? std::vector<std::int64_t>() : mc.chunksAffectedBy(edit.changedBox);
  const std::vector<std::int64_t> more = mc.chunksAffectedByStorageChunks(foreign);
  ids.insert(ids.end(), more.begin(), more.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// Storage-chunk rule intersected with the box every voxel the dabs can change
// lies in (radius, band, colour skin, blend, one voxel of rounding).
std::vector<std::int64_t> chunksForDabs(const lvdif::ChunkedMarchingCubes& mc, const std::vector<std::int64_t>& dirty,
  const std::vector<lvdif::Dab>& dabs, double extra)
{
  std::vector<std::int64_t> byStorage = mc.chunksAffectedByStorageChunks(dirty);
  if (byStorage.empty() || dabs.empty())
    return byStorage;
  lvdif::VoxelBox box;
  for (const lvdif::Dab& d : dabs)
  {
    const double reach = d.radius * std::sqrt(3.0) + extra; // a cube's corner, at most
    lvdif::VoxelBox b;
    for (int k = 0; k < 3; ++k)
    {
      b.lo[k] = static_cast<std::int64_t>(std::floor(d.center[k] - reach));
      b.hi[k] = static_cast<std::int64_t>(std::ceil(d.center[k] + reach));
    }
    box = box.unite(b);
  }
  std::vector<std::int64_t> byBox = mc.chunksAffectedBy(box);
  std::sort(byBox.begin(), byBox.end());
  std::sort(byStorage.begin(), byStorage.end());
  std::vector<std::int64_t> both;
  std::set_intersection(byStorage.begin(), byStorage.end(), byBox.begin(), byBox.end(), std::back_inserter(both));
  return both;
}

// One brush path: applies a sample (or the stroke's end) and returns the
// marching cubes chunks to re-mesh. Called with the source mutex held.
class BrushPath
{
public:
  BrushPath(const std::string& kind, lvdif::DictionaryVolume& volume, const lvdif::ChunkedMarchingCubes& mc,
    const lvdif::BrushSettings& brush, const lvdif::StrokeSettings& stroke)
    : Kind(kind), Volume(volume), Mc(mc), Ed(volume), Undo(volume)
  {
    this->Ed.brush = brush;
    this->Ed.stroke = stroke;
    this->Extra = volume.bandWidth() + brush.colorOffset + brush.blend + 1;
    if (kind == "device")
      this->Dev = std::make_unique<lvdif::cuda::DeviceVolume>(volume);
  }
  // One dab away from the stroke (first CUDA launches, lazy module loading).
  void warmUp(const lvdif::Dab& d)
  {
    if (this->Kind == "device")
    {
      this->Dev->applyDabs({ d }, this->Ed.brush);
      this->Dev->sync();
    }
    else if (this->Kind == "cuda")
      lvdif::cuda::applyDabs(this->Volume, { d }, this->Ed.brush);
    else
      lvdif::applyDabs(this->Volume, { d }, this->Ed.brush);
    this->Volume.takeDirtyChunks();
  }
  void begin()
  {
    if (this->Kind == "cpu")
      return this->Ed.beginStroke();
    this->Builder = std::make_unique<lvdif::StrokeBuilder>(this->Ed.stroke);
    this->Undo.beginStep("stroke");
  }
  std::vector<std::int64_t> add(const lvdif::BrushSample& s)
  {
    if (this->Kind == "cpu")
    {
      this->Ed.addSample(s);
      return chunksForEdit(this->Mc, this->Volume.takeDirtyChunks(), this->Ed.lastWrite());
    }
    this->Builder->add(s);
    return this->apply(this->Builder->takeReady());
  }
  std::vector<std::int64_t> end()
  {
    if (this->Kind == "cpu")
    {
      this->Ed.endStroke();
      return chunksForEdit(this->Mc, this->Volume.takeDirtyChunks(), this->Ed.lastWrite());
    }
    const std::vector<std::int64_t> ids = this->apply(this->Builder->finish());
    this->Undo.endStep();
    return ids;
  }

private:
  std::vector<std::int64_t> apply(const std::vector<lvdif::Dab>& dabs)
  {
    if (dabs.empty())
      return {};
    if (this->Kind == "cuda")
    {
      const lvdif::EditResult r = lvdif::cuda::applyDabs(this->Volume, dabs, this->Ed.brush, &this->Undo);
      return chunksForEdit(this->Mc, this->Volume.takeDirtyChunks(), r);
    }
    this->Dev->applyDabs(dabs, this->Ed.brush);
    this->Dev->sync(&this->Undo);
    return chunksForDabs(this->Mc, this->Volume.takeDirtyChunks(), dabs, this->Extra);
  }

  std::string Kind;
  lvdif::DictionaryVolume& Volume;
  const lvdif::ChunkedMarchingCubes& Mc;
  lvdif::Editor Ed;
  lvdif::UndoStack Undo; // the cuda/device paths' undo (the Editor has its own)
  std::unique_ptr<lvdif::StrokeBuilder> Builder;
  std::unique_ptr<lvdif::cuda::DeviceVolume> Dev;
  double Extra = 0;
};

struct Request
{
  double editedAt = 0;   // stroke clock, seconds, taken under the mutex right after the edit
  double sampleTime = 0; // the sample's recorded time
  std::vector<std::int64_t> chunks;
};

std::vector<std::string> runStroke(const Config& cfg, const std::string& brushKind)
{
  const int n = cfg.n;
  const int edge = cfg.chunk > 0 ? cfg.chunk : (n >= 1024 ? 64 : 32);
  bench::Stopwatch setup;
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = edge;
  lvdif::DictionaryVolume volume(o);
  const double c = 0.5 * (n - 1), r = 0.35 * n;
  lvdif::fillFromFunction(volume, lvdif::sphereSdf(c, c, c, r));
  volume.takeDirtyChunks();
  const double fillS = setup.seconds();
  lvdif::MarchingCubesOptions mo;
  mo.chunkEdge = edge;
  mo.device = cfg.device;
  lvdif::ChunkedMarchingCubes mc(volume, mo);

  lvdif::BrushSettings brush;
  brush.op = lvdif::BrushOp::Add;
  brush.color = lvdif::Rgba{ 230, 80, 50, 255 };
  lvdif::StrokeSettings stroke;
  stroke.kind = lvdif::BrushKind::Drill; // applied as it goes, as the editor does
  stroke.radius = cfg.radius;
  BrushPath path(brushKind, volume, mc, brush, stroke);
  // Warm-up away from the stroke (opposite side of the sphere): first launches
  // of the brush and of the marching cubes on the chosen device.
  {
    lvdif::Dab d;
    d.center = { c - r, c, c };
    d.radius = cfg.radius;
    path.warmUp(d);
    const auto ids = mc.chunksAffectedBy(lvdif::VoxelBox{ { static_cast<std::int64_t>(c - r), static_cast<std::int64_t>(c), static_cast<std::int64_t>(c) },
      { static_cast<std::int64_t>(c - r), static_cast<std::int64_t>(c), static_cast<std::int64_t>(c) } });
    mc.extractChunks(ids);
  }
  lvdif::MarchingCubesWorker worker(mc);
  std::printf("volume %d^3, chunk %d^3 (storage and marching cubes), %lld marching cubes chunks; setup %.1f s "
              "(fill %.1f s); brush %s, marching cubes on %s, loop %s, settle %.0f ms; frames drawn: no "
              "(ready to draw, no VTK)\n",
    n, edge, static_cast<long long>(mc.chunkCount()), setup.seconds(), fillS, brushKind.c_str(),
    lvdif::resolveDevice(cfg.device) == lvdif::Device::Cuda ? "cuda" : "cpu", cfg.loop.c_str(), cfg.settleMs);

  // The stroke: 50 Hz samples on the sphere's surface along a 90-degree arc.
  std::vector<lvdif::BrushSample> samples(cfg.samples);
  for (int i = 0; i < cfg.samples; ++i)
  {
    const double a = 0.5 * M_PI * i / std::max(1, cfg.samples - 1);
    samples[i].position = { c + r * std::cos(a), c + r * std::sin(a), c };
    samples[i].time = i / 50.0;
    samples[i].buttons = 1;
  }

  std::vector<double> brushMs, lockMs, requestMs, settleMs, collectMs;
  std::vector<Request> requests;
  // per chunk: (when its input was gathered, when it was collected), in order
  std::map<std::int64_t, std::vector<std::pair<double, double>>> delivered;
  const Clock::time_point t0 = Clock::now();
  auto at = [&](Clock::time_point t) { return std::chrono::duration<double>(t - t0).count(); };
  auto now = [&] { return at(Clock::now()); };
  const bool tickLoop = cfg.loop == "tick";
  const double period = tickLoop ? 1.0 / 60 : 0.015; // tick loop / the Qt editor's mesh poll timer
  {
    std::lock_guard<std::mutex> lock(worker.sourceMutex());
    path.begin();
  }
  std::size_t next = 0;
  int iterations = 0;
  bool ended = false;
  double lastCollect = 0;
  auto handle = [&](bool endStroke) {
    bench::Stopwatch wait;
    std::lock_guard<std::mutex> lock(worker.sourceMutex());
    lockMs.push_back(wait.ms());
    bench::Stopwatch b;
    std::vector<std::int64_t> ids = endStroke ? path.end() : path.add(samples[next]);
    brushMs.push_back(b.ms());
    Request q;
    q.editedAt = now();
    q.sampleTime = samples[endStroke ? samples.size() - 1 : next].time;
    bench::Stopwatch rq;
    worker.request(ids);
    requestMs.push_back(rq.ms());
    q.chunks = std::move(ids);
    if (!q.chunks.empty())
      requests.push_back(std::move(q));
  };
  while (true)
  {
    const double t = now();
    bool edited = false;
    if (tickLoop)
    {
      while (next < samples.size() && samples[next].time <= t)
      {
        handle(false);
        ++next;
        edited = true;
      }
    }
    else if (next < samples.size() && samples[next].time <= t)
    {
      handle(false);
      ++next;
      edited = true;
    }
    else if (t < lastCollect + period && !(next == samples.size() && !ended))
    {
      // nothing due: sleep until the next sample or the next poll
      double wake = lastCollect + period;
      if (next < samples.size())
        wake = std::min(wake, samples[next].time);
      std::this_thread::sleep_for(std::chrono::duration<double>(std::max(0.0, wake - t)));
      continue;
    }
    if (next == samples.size() && !ended)
    {
      handle(true);
      ended = true;
      edited = true;
    }
    if (edited && cfg.settleMs > 0)
    {
      bench::Stopwatch w;
      while (!worker.idle() && w.ms() < cfg.settleMs)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      settleMs.push_back(w.ms());
    }
    const bool idleBefore = worker.idle();
    bench::Stopwatch col;
    std::vector<Clock::time_point> gathered;
    const std::vector<lvdif::ChunkMesh> meshes = worker.collect(&gathered);
    std::map<std::int64_t, const lvdif::ChunkMesh*> newest; // what a front end would install
    for (const auto& m : meshes)
      newest[m.chunkId] = &m;
    collectMs.push_back(col.ms());
    lastCollect = now(); // ready to draw
    for (std::size_t i = 0; i < meshes.size(); ++i)
      delivered[meshes[i].chunkId].emplace_back(at(gathered[i]), lastCollect);
    ++iterations;
    if (idleBefore && ended)
      break;
    if (tickLoop)
    {
      const double spent = now() - t;
      if (spent < period)
        std::this_thread::sleep_for(std::chrono::duration<double>(period - spent));
    }
  }
  const double duration = now();
  // A chunk shows an edit from its first mesh gathered after the edit.
  std::vector<double> fromSample, fromEdit, chunkCounts;
  int missing = 0;
  for (const Request& q : requests)
  {
    double shownAt = q.editedAt;
    for (std::int64_t id : q.chunks)
    {
      const auto& d = delivered[id];
      auto it = std::find_if(d.begin(), d.end(), [&](const std::pair<double, double>& g) { return g.first > q.editedAt; });
      if (it == d.end())
      {
        ++missing;
        continue;
      }
      shownAt = std::max(shownAt, it->second);
    }
    fromSample.push_back(1e3 * (shownAt - q.sampleTime));
    fromEdit.push_back(1e3 * (shownAt - q.editedAt));
    chunkCounts.push_back(static_cast<double>(q.chunks.size()));
  }
  if (missing)
    std::printf("warning: %d requested chunk meshes never arrived\n", missing);
  // Meshing cost of each request on its own, synchronously after the stroke
  // (the chunks' final content) on the chosen device.
  std::vector<double> meshMs;
  for (const Request& q : requests)
  {
    bench::Stopwatch m;
    mc.extractChunks(q.chunks);
    meshMs.push_back(m.ms());
  }
  using bench::fmt;
  using bench::percentile;
  auto p50p95 = [](const std::vector<double>& v) {
    return fmt(percentile(v, 0.5)) + " (" + fmt(percentile(v, 0.95)) + ")";
  };
  return { std::to_string(n) + "^3/" + std::to_string(edge), lvdif::resolveDevice(cfg.device) == lvdif::Device::Cuda ? "cuda" : "cpu",
    brushKind, cfg.loop + (cfg.settleMs > 0 ? ", settle " + fmt(cfg.settleMs, 0) : ""),
    std::to_string(requests.size()), fmt(percentile(chunkCounts, 0.5), 0) + " (" + fmt(percentile(chunkCounts, 0.95), 0) + ")",
    fmt(percentile(fromSample, 0.5)), fmt(percentile(fromSample, 0.95)), fmt(percentile(fromSample, 1.0)),
    p50p95(fromEdit), fmt(iterations / duration, 1), p50p95(brushMs), fmt(percentile(lockMs, 0.95)),
    fmt(percentile(requestMs, 0.95)), p50p95(meshMs), p50p95(collectMs) };
}
} // namespace

int main(int argc, char* argv[])
{
  Config cfg;
  try
  {
    for (int i = 1; i < argc; ++i)
    {
      const bool more = i + 1 < argc;
      if (!std::strcmp(argv[i], "--samples") && more)
        cfg.samples = std::atoi(argv[++i]);
      else if (!std::strcmp(argv[i], "--radius") && more)
        cfg.radius = std::atof(argv[++i]);
      else if (!std::strcmp(argv[i], "--settle") && more)
        cfg.settleMs = std::atof(argv[++i]);
      else if (!std::strcmp(argv[i], "--chunk") && more)
        cfg.chunk = std::atoi(argv[++i]);
      else if (!std::strcmp(argv[i], "--loop") && more)
        cfg.loop = argv[++i];
      else if (!std::strcmp(argv[i], "--brush") && more)
        cfg.brush = argv[++i];
      else if (!std::strcmp(argv[i], "--device") && more)
      {
        const std::string d = argv[++i];
        if (d != "cpu" && d != "cuda")
          throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--device must be cpu or cuda, not " + d);
        cfg.device = d == "cuda" ? lvdif::Device::Cuda : lvdif::Device::Cpu;
      }
      else if (argv[i][0] != '-')
        cfg.n = std::atoi(argv[i]);
      else
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, std::string("unknown option ") + argv[i]);
    }
    if (cfg.n < 64 || cfg.samples < 2 || cfg.radius <= 0 || (cfg.loop != "event" && cfg.loop != "tick"))
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "need N >= 64, samples >= 2, radius > 0, loop event|tick");
    if (cfg.device == lvdif::Device::Cuda && lvdif::resolveDevice(cfg.device) != lvdif::Device::Cuda)
      throw lvdif::Error(lvdif::ErrorCode::Unsupported, "--device cuda: no usable CUDA device in this build/machine");
    std::vector<std::string> brushes;
    const std::string b = cfg.brush.empty() ? (cfg.device == lvdif::Device::Cuda ? "all" : "cpu") : cfg.brush;
    if (b == "all")
      brushes = cfg.device == lvdif::Device::Cuda ? std::vector<std::string>{ "cpu", "cuda", "device" }
                                                  : std::vector<std::string>{ "cpu" };
    else if (b == "cpu" || b == "cuda" || b == "device")
      brushes = { b };
    else
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--brush must be cpu, cuda, device or all");
    std::cout << "bench_stroke_latency_core: " << bench::machineDescription() << "\n"
              << "Latency = from the sample's recorded time until every chunk it changed has a collected mesh "
                 "showing it (ready to draw). Not included: building VTK actors from the meshes and drawing "
                 "the frame (no VTK/OpenGL here).\n";
    std::vector<std::vector<std::string>> rows;
    for (const std::string& k : brushes)
      rows.push_back(runStroke(cfg, k));
    bench::printTable({ "volume/chunk", "mc device", "brush", "loop", "requests", "chunks/request p50 (p95)",
                        "latency p50 ms", "latency p95 ms", "latency max ms", "from edit p50 (p95) ms",
                        "loop it/s", "brush p50 (p95) ms", "lock p95 ms", "request p95 ms",
                        "mesh/request p50 (p95) ms", "collect p50 (p95) ms" },
      rows);
  }
  catch (const std::exception& e)
  {
    std::cerr << "bench_stroke_latency_core: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
