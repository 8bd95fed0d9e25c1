// Stroke-to-"meshes ready" latency of interactive editing through one
// lvdif::EditSession (the object the Qt editor, vtkLVDIFEditor and Python
// hold), on the Core pipeline only: machines without VTK/Qt (the GPU host).
// The VTK twin (Testing/Benchmarks/VTK/bench_stroke_latency.cxx) also builds
// actors; this one stops when the meshes are on the host ("ready to draw").
//
// A recorded-style stroke (samples with timestamps at 50 Hz along a 90-degree
// arc on the surface of an analytic sphere, Add, Drill kind: applied as it
// goes, as the editor does while dragging) is replayed at its own speed:
//   for each sample when its time comes:  session.addSample(sample)
//     GPU session: the brush runs on the device volume; then collectMeshes()
//       meshes the mesh chunks the sample invalidated on the device in one
//       batched launch and brings back only those meshes (the frame);
//     CPU session: the brush runs on the host; the marching cubes worker
//       meshes in its own thread; the loop waits up to --settle ms for it
//       (the Qt editor's settleMeshes) and collects what is finished, and a
//       15 ms poll collects the rest (--loop event), or polls at 60 Hz (tick).
//   Samples that came due while a frame was busy are handled together in the
//   next one (Qt compresses queued mouse moves), so a slow frame does not build
//   an ever longer queue.
// Latency of a sample = from its recorded time until every mesh chunk it
// invalidated has a collected mesh showing it (exact: the session says when each
// mesh's input was read, and the edit happened before). Nothing is drawn.
// CPU s = user + system time of the process (all threads) from the stroke's start
// until its last mesh: the work, which a loaded machine does not inflate as it does
// wall times; CPU ms/request divides it by the requests (samples that changed voxels).
// Frame = the editing thread's work per loop iteration (edit + mesh + collect on
// the GPU; edit + settle + collect on the CPU); fps = 1000 / mean frame time is
// what a drag could sustain if samples came faster than 50 Hz.
//
// usage: bench_stroke_latency_core [N=512] [--device cpu|cuda] [--radius 15,40]
//        [--samples 100] [--settle 6] [--loop event|tick] [--chunk E] [--phases] [--op add|subtract]
//        [--write-stroke FILE.jsonl] [--write-volume FILE.lvdv]
//        (E: storage and mesh chunk edge, 32 below 1024^3, 64 from 1024^3 as the paper)
// --write-stroke / --write-volume: write the stroke's samples as socket-protocol
// lines and the sphere volume, and exit: the same stroke on the same volume for
// lvdif-editor --open FILE.lvdv --benchmark-stroke FILE.jsonl (docs/BENCHMARKS.md).
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/EditSession.h"
#include "lvdif/Error.h"
#include "lvdif/VolumeFile.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

#include <sys/resource.h>

namespace
{
using Clock = std::chrono::steady_clock;

/// CPU time of the whole process (every thread: brush, worker), user + system:
/// on a shared machine the work done, where wall times are mostly waiting.
double processCpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Config
{
  int n = 512, samples = 100, chunk = 0;
  std::vector<double> radii{ 15, 40 };
  double settleMs = 6;
  lvdif::Device device = lvdif::Device::Cpu;
  std::string loop = "event";
  bool phases = false;
  lvdif::BrushOp op = lvdif::BrushOp::Add;
  std::string writeStroke, writeVolume;
};

struct Request
{
  double editedAt = 0;   // stroke clock, seconds, right after the edit
  double sampleTime = 0; // the sample's recorded time
  std::vector<std::int64_t> chunks;
};

/// The sphere volume of the benchmark (radius 0.35 N about the centre).
std::shared_ptr<lvdif::DictionaryVolume> sphereVolume(int n, int edge)
{
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = edge;
  auto volume = std::make_shared<lvdif::DictionaryVolume>(o);
  const double c = 0.5 * (n - 1), r = 0.35 * n;
  lvdif::fillFromFunction(*volume, lvdif::sphereSdf(c, c, c, r));
  volume->takeDirtyChunks();
  return volume;
}

/// The stroke's samples: 50 Hz along a 90-degree arc on the sphere's surface.
std::vector<lvdif::BrushSample> strokeSamples(int n, int count)
{
  const double c = 0.5 * (n - 1), r = 0.35 * n;
  std::vector<lvdif::BrushSample> samples(count);
  for (int i = 0; i < count; ++i)
  {
    const double a = 0.5 * M_PI * i / std::max(1, count - 1);
    samples[i].position = { c + r * std::cos(a), c + r * std::sin(a), c };
    samples[i].time = i / 50.0;
    samples[i].buttons = 1;
  }
  return samples;
}

/// --phases: the same stroke without the clock, each sample's work done in turn
/// on the calling thread's OpenMP team: the edit (brush + the remesh rule), then
/// the mesh chunks it invalidated meshed at once (extractChunks, as the worker
/// does). Process CPU time per phase (all threads), and how many of the meshes
/// came out identical to the chunk's previous mesh (what a finer remesh rule
/// could still skip).
std::vector<std::string> runPhases(const Config& cfg, double radius)
{
  const int edge = cfg.chunk > 0 ? cfg.chunk : (cfg.n >= 1024 ? 64 : 32);
  auto volume = sphereVolume(cfg.n, edge);
  lvdif::EditSessionOptions so;
  so.device = lvdif::Device::Cpu;
  so.meshChunkEdge = edge;
  so.meshing = false; // the meshes are made below, synchronously
  lvdif::EditSession session(volume, so);
  session.brush().op = cfg.op;
  session.brush().color = lvdif::Rgba{ 230, 80, 50, 255 };
  session.stroke().kind = lvdif::BrushKind::Drill;
  session.stroke().radius = radius;
  const lvdif::ChunkedMarchingCubes& mc = session.mesher();
  std::map<std::int64_t, lvdif::ChunkMesh> previous; // the last mesh of every chunk the stroke meshed
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id)
    if (!mc.chunkIsEmpty(id))
      previous[id] = mc.extractChunk(id);
  auto same = [](const lvdif::ChunkMesh& a, const lvdif::ChunkMesh& b) {
    return a.triangles == b.triangles && a.edgeIds == b.edgeIds && a.colors == b.colors &&
      a.cornerColors == b.cornerColors && a.points.size() == b.points.size() &&
      std::equal(a.points.begin(), a.points.end(), b.points.begin()) && a.normals.size() == b.normals.size() &&
      std::equal(a.normals.begin(), a.normals.end(), b.normals.begin());
  };
  double editCpu = 0, meshCpu = 0;
  std::size_t chunks = 0, unchanged = 0, samplesWithWork = 0;
  session.beginStroke();
  const std::vector<lvdif::BrushSample> samples = strokeSamples(cfg.n, cfg.samples);
  for (std::size_t i = 0; i <= samples.size(); ++i)
  {
    double t = processCpuSeconds();
    if (i < samples.size())
      session.addSample(samples[i]);
    else
      session.endStroke();
    editCpu += processCpuSeconds() - t;
    const std::vector<std::int64_t> ids = session.lastRequest();
    if (ids.empty())
      continue;
    ++samplesWithWork;
    t = processCpuSeconds();
    const std::vector<lvdif::ChunkMesh> meshes = mc.extractChunks(ids);
    meshCpu += processCpuSeconds() - t;
    chunks += ids.size();
    for (const lvdif::ChunkMesh& m : meshes)
    {
      auto it = previous.find(m.chunkId);
      if (it == previous.end() ? m.empty() : same(it->second, m))
        ++unchanged;
      previous[m.chunkId] = m;
    }
  }
  const double k = 1e3 / static_cast<double>(std::max<std::size_t>(1, samplesWithWork));
  using bench::fmt;
  return { std::to_string(cfg.n) + "^3/" + std::to_string(edge), fmt(radius, 0), std::to_string(samplesWithWork),
    fmt(k * editCpu), fmt(k * meshCpu), fmt(static_cast<double>(chunks) / std::max<std::size_t>(1, samplesWithWork), 1),
    fmt(1e3 * meshCpu / static_cast<double>(std::max<std::size_t>(1, chunks)), 3),
    fmt(100.0 * static_cast<double>(unchanged) / static_cast<double>(std::max<std::size_t>(1, chunks)), 0) };
}

std::vector<std::string> runStroke(const Config& cfg, double radius)
{
  const int n = cfg.n;
  const int edge = cfg.chunk > 0 ? cfg.chunk : (n >= 1024 ? 64 : 32);
  bench::Stopwatch setup;
  auto volume = sphereVolume(n, edge);
  const double c = 0.5 * (n - 1), r = 0.35 * n;
  const double fillS = setup.seconds();
  lvdif::EditSessionOptions so;
  so.device = cfg.device;
  so.meshChunkEdge = edge;
  lvdif::EditSession session(volume, so);
  if (!session.notice().empty())
    std::printf("notice: %s\n", session.notice().c_str());
  const bool gpu = session.onDevice();
  session.brush().op = cfg.op;
  session.brush().color = lvdif::Rgba{ 230, 80, 50, 255 };
  session.stroke().kind = lvdif::BrushKind::Drill; // applied as it goes, as the editor does
  session.stroke().radius = radius;
  // Warm-up away from the stroke (the opposite side), a few frames of the same
  // size as the stroke's: first launches of the brush and of the marching cubes,
  // the buffers and the meshes' page-locked block at their working size. Undone.
  {
    session.beginStroke();
    for (int i = 0; i < 4; ++i)
    {
      lvdif::BrushSample w;
      w.position = { c - r, c + 0.5 * M_PI * r / std::max(1, cfg.samples - 1) * i, c }; // the stroke's sample spacing
      w.buttons = 1;
      session.addSample(w);
      session.waitMeshingIdle();
      session.collectMeshes();
    }
    session.endStroke();
    session.undo();
    session.waitMeshingIdle();
    session.collectMeshes();
  }
  const double setupS = setup.seconds();

  // The stroke: 50 Hz samples on the sphere's surface along a 90-degree arc.
  const std::vector<lvdif::BrushSample> samples = strokeSamples(n, cfg.samples);

  std::vector<double> brushMs, frameMs, collectMs;
  std::vector<Request> requests;
  // per mesh chunk: (when its input was gathered, when it was collected), in order
  std::map<std::int64_t, std::vector<std::pair<double, double>>> delivered;
  const double cpu0 = processCpuSeconds();
  const Clock::time_point t0 = Clock::now();
  auto at = [&](Clock::time_point t) { return std::chrono::duration<double>(t - t0).count(); };
  auto now = [&] { return at(Clock::now()); };
  const bool tickLoop = cfg.loop == "tick";
  const double period = tickLoop ? 1.0 / 60 : 0.015; // tick loop / the Qt editor's mesh poll timer
  session.beginStroke();
  std::size_t next = 0;
  int iterations = 0;
  bool ended = false;
  double lastCollect = 0;
  std::uint64_t triangles = 0;
  auto handle = [&](bool endStroke) {
    bench::Stopwatch b;
    if (endStroke)
      session.endStroke();
    else
      session.addSample(samples[next]);
    brushMs.push_back(b.ms());
    Request q;
    q.editedAt = at(session.lastRequestTime());
    q.sampleTime = samples[endStroke ? samples.size() - 1 : next].time;
    q.chunks = session.lastRequest();
    if (!q.chunks.empty())
      requests.push_back(std::move(q));
  };
  while (true)
  {
    const double t = now();
    bool edited = false;
    const double frameStart = t;
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
      // every sample that is due: samples that arrived while the last frame was
      // busy are handled together, as Qt delivers the mouse moves that queued up
      while (next < samples.size() && samples[next].time <= t)
      {
        handle(false);
        ++next;
      }
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
    if (edited && !gpu && cfg.settleMs > 0)
    {
      bench::Stopwatch w;
      while (!session.meshingIdle() && w.ms() < cfg.settleMs)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    const bool idleBefore = session.meshingIdle();
    bench::Stopwatch col;
    std::vector<Clock::time_point> gathered;
    const std::vector<lvdif::ChunkMesh> meshes = session.collectMeshes(&gathered);
    collectMs.push_back(col.ms());
    lastCollect = now(); // ready to draw
    if (edited)
      frameMs.push_back(1e3 * (lastCollect - frameStart));
    for (std::size_t i = 0; i < meshes.size(); ++i)
    {
      delivered[meshes[i].chunkId].emplace_back(at(gathered[i]), lastCollect);
      triangles += meshes[i].triangles.size();
    }
    ++iterations;
    if ((idleBefore || gpu) && ended && session.meshingIdle())
      break;
    if (tickLoop)
    {
      const double spent = now() - t;
      if (spent < period)
        std::this_thread::sleep_for(std::chrono::duration<double>(period - spent));
    }
  }
  const double duration = now();
  const double strokeCpu = processCpuSeconds() - cpu0;
  // A mesh chunk shows an edit from its first mesh gathered after the edit.
  std::vector<double> fromSample, fromEdit, chunkCounts;
  int missing = 0;
  for (const Request& q : requests)
  {
    double shownAt = q.editedAt;
    for (std::int64_t id : q.chunks)
    {
      const auto& d = delivered[id];
      auto it = std::find_if(d.begin(), d.end(), [&](const std::pair<double, double>& g) { return g.first >= q.editedAt; });
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
  double meanFrame = 0;
  for (double f : frameMs)
    meanFrame += f / static_cast<double>(std::max<std::size_t>(1, frameMs.size()));
  std::printf("volume %d^3, chunk %d^3 (storage and mesh), %lld mesh chunks, radius %.0f; setup %.1f s (fill %.1f s); "
              "session on %s%s; %llu triangles handed out; frames drawn: no (ready to draw, no VTK)\n",
    n, edge, static_cast<long long>(session.mesher().chunkCount()), radius, setupS, fillS,
    gpu ? "the GPU (device-resident volume, device marching cubes)" : "the CPU (host volume, marching cubes worker)",
    gpu ? "" : (", loop " + cfg.loop + ", settle " + bench::fmt(cfg.settleMs, 0) + " ms").c_str(),
    static_cast<unsigned long long>(triangles));
  using bench::fmt;
  using bench::percentile;
  auto p50p95 = [](const std::vector<double>& v) {
    return fmt(percentile(v, 0.5)) + " (" + fmt(percentile(v, 0.95)) + ")";
  };
  return { std::to_string(n) + "^3/" + std::to_string(edge), gpu ? "gpu" : "cpu", fmt(radius, 0),
    gpu ? "frame" : cfg.loop + ", settle " + fmt(cfg.settleMs, 0), std::to_string(requests.size()),
    fmt(percentile(chunkCounts, 0.5), 0) + " (" + fmt(percentile(chunkCounts, 0.95), 0) + ")",
    fmt(percentile(fromSample, 0.5)), fmt(percentile(fromSample, 0.95)), fmt(percentile(fromSample, 1.0)),
    p50p95(fromEdit), p50p95(frameMs), fmt(meanFrame > 0 ? 1e3 / meanFrame : 0, 0), fmt(iterations / duration, 1),
    p50p95(brushMs), p50p95(collectMs), fmt(strokeCpu, 2), fmt(1e3 * strokeCpu / static_cast<double>(std::max<std::size_t>(1, requests.size())), 1) };
}
} // namespace

static int benchMain(int argc, char** argv)
{
  Config cfg;
  for (int i = 1; i < argc; ++i)
  {
    const bool more = i + 1 < argc;
    if (!std::strcmp(argv[i], "--samples") && more)
      cfg.samples = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--radius") && more)
    {
      cfg.radii.clear();
      std::stringstream s(argv[++i]);
      std::string item;
      while (std::getline(s, item, ','))
        cfg.radii.push_back(std::atof(item.c_str()));
    }
    else if (!std::strcmp(argv[i], "--settle") && more)
      cfg.settleMs = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--chunk") && more)
      cfg.chunk = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--phases"))
      cfg.phases = true;
    else if (!std::strcmp(argv[i], "--op") && more)
      cfg.op = !std::strcmp(argv[++i], "subtract") ? lvdif::BrushOp::Subtract : lvdif::BrushOp::Add;
    else if (!std::strcmp(argv[i], "--write-stroke") && more)
      cfg.writeStroke = argv[++i];
    else if (!std::strcmp(argv[i], "--write-volume") && more)
      cfg.writeVolume = argv[++i];
    else if (!std::strcmp(argv[i], "--loop") && more)
      cfg.loop = argv[++i];
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
  bool radiiOk = !cfg.radii.empty();
  for (double r : cfg.radii)
    radiiOk = radiiOk && r > 0;
  if (cfg.n < 64 || cfg.samples < 2 || !radiiOk || (cfg.loop != "event" && cfg.loop != "tick"))
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "need N >= 64, samples >= 2, radii > 0, loop event|tick");
  if (!cfg.writeVolume.empty())
    lvdif::saveVolume(*sphereVolume(cfg.n, cfg.chunk > 0 ? cfg.chunk : (cfg.n >= 1024 ? 64 : 32)), cfg.writeVolume);
  if (!cfg.writeStroke.empty())
  {
    std::FILE* f = std::fopen(cfg.writeStroke.c_str(), "w");
    if (!f)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, "cannot write " + cfg.writeStroke);
    std::fprintf(f, "# bench_stroke_latency_core's stroke on its %d^3 sphere (--write-volume): %d samples at 50 Hz\n",
      cfg.n, cfg.samples);
    for (const lvdif::BrushSample& b : strokeSamples(cfg.n, cfg.samples))
      std::fprintf(f, "{\"position\":[%.6f,%.6f,%.6f],\"time\":%.4f}\n", b.position[0], b.position[1], b.position[2], b.time);
    if (std::fclose(f) != 0)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, "cannot write " + cfg.writeStroke);
  }
  if (!cfg.writeStroke.empty() || !cfg.writeVolume.empty())
    return 0;
  if (cfg.device == lvdif::Device::Cuda && lvdif::resolveDevice(cfg.device) != lvdif::Device::Cuda)
    throw lvdif::Error(lvdif::ErrorCode::Unsupported, "--device cuda: no usable CUDA device in this build/machine");
  std::cout << "bench_stroke_latency_core: " << bench::machineDescription() << "\n"
            << "Latency = from the sample's recorded time until every mesh chunk it invalidated has a collected "
               "mesh showing it (ready to draw). Not included: building VTK actors and drawing the frame.\n";
  std::vector<std::vector<std::string>> rows;
  if (cfg.phases)
  {
    for (double r : cfg.radii)
      rows.push_back(runPhases(cfg, r));
    std::cout << "Phases (--phases): the stroke's samples one after the other without the clock, CPU session; "
                 "process CPU ms (all threads) per sample that changed voxels.\n";
    bench::printTable({ "volume/chunk", "radius", "samples", "edit CPU ms/sample", "mesh CPU ms/sample",
                        "mesh chunks/sample", "mesh CPU ms/chunk", "% of meshes unchanged" },
      rows);
    return 0;
  }
  for (double r : cfg.radii)
    rows.push_back(runStroke(cfg, r));
  bench::printTable({ "volume/chunk", "session", "radius", "loop", "requests", "mesh chunks/request p50 (p95)",
                      "latency p50 ms", "latency p95 ms", "latency max ms", "from edit p50 (p95) ms",
                      "frame p50 (p95) ms", "fps (1/mean frame)", "loop it/s", "edit p50 (p95) ms",
                      "collect p50 (p95) ms", "CPU s (stroke)", "CPU ms/request" },
    rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
