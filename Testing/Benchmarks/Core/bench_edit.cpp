// Editing benchmark (paper Sect. 3.4, Fig. 7): one radius-15 dab and the
// 200^3 primitives of Fig. 7a on a 1024^3 sphere volume, and the dice script
// end to end. CPU times are reported with a peer measured in the same process:
// the same primitive's SDF evaluated over the same influence box into a plain
// float array (no dictionary, no sparse chunks), so the ratio shows the cost
// of the dictionary volume's bookkeeping. With a CUDA build the GPU dab is
// timed too (absolute times only on the GPU).
//
// Usage: bench_edit [edge=1024] [dabs=40]
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/BrushCuda.h"
#include "lvdif/Cuda.h"
#include "lvdif/DeviceVolume.h"
#include "lvdif/Editor.h"
#include "lvdif/Memory.h"
#include "lvdif/Script.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

namespace
{

// The peer: the dab's SDF over its influence box into a dense float array.
double peerMs(const lvdif::DictionaryVolume& v, const lvdif::Dab& d, const lvdif::BrushSettings& s)
{
  const lvdif::VoxelBox b = lvdif::dabInfluenceBox(v, d, s);
  const std::int64_t nx = b.hi[0] - b.lo[0] + 1, ny = b.hi[1] - b.lo[1] + 1, nz = b.hi[2] - b.lo[2] + 1;
  std::vector<float> out(static_cast<size_t>(nx * ny * nz));
  bench::Stopwatch w;
#pragma omp parallel for schedule(static)
  for (std::int64_t z = 0; z < nz; ++z)
    for (std::int64_t y = 0; y < ny; ++y)
      for (std::int64_t x = 0; x < nx; ++x)
      {
        const double s0 = lvdif::dabDistance(d, double(b.lo[0] + x), double(b.lo[1] + y), double(b.lo[2] + z));
        float& o = out[static_cast<size_t>(x + nx * (y + ny * z))];
        o = std::min(o == 0 ? 8.0f : o, static_cast<float>(s0));
      }
  const double ms = w.ms();
  volatile float sink = out[out.size() / 2];
  (void)sink;
  return ms;
}

std::array<double, 3> surfacePoint(std::mt19937& rng, double c, double r)
{
  std::normal_distribution<double> g;
  double p[3] = { g(rng), g(rng), g(rng) };
  const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return { c + r * p[0] / n, c + r * p[1] / n, c + r * p[2] / n };
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace

static int benchMain(int argc, char** argv)
{
  const std::int64_t edge = argc > 1 ? std::atoll(argv[1]) : 1024;
  const int dabs = argc > 2 ? std::atoi(argv[2]) : 40;
  std::cout << "bench_edit: " << bench::machineDescription() << "\n";
  lvdif::VolumeOptions o;
  o.dims = { edge, edge, edge };
  o.chunkEdge = 32;
  lvdif::DictionaryVolume v(o);
  const double c = edge / 2.0, r = 0.35 * edge;
  bench::Stopwatch fill;
  lvdif::fillFromFunction(v, lvdif::sphereSdf(c, c, c, r));
  std::cout << "sphere volume " << edge << "^3 (radius " << r << ") filled in " << bench::fmt(fill.seconds(), 2)
            << " s, " << lvdif::formatBytes(v.memoryBytes()) << "\n";

  std::vector<std::vector<std::string>> rows;
  std::mt19937 rng(1);
  auto timeDabs = [&](const char* name, lvdif::BrushShape shape, double radius, lvdif::BrushOp op, int count,
                    bool withUndo) {
    std::vector<double> t, peer;
    lvdif::BrushSettings s;
    s.op = op;
    lvdif::Editor editor(v);
    editor.brush = s;
    for (int i = 0; i < count; ++i)
    {
      const lvdif::Dab d{ shape, surfacePoint(rng, c, r), radius, {} };
      bench::Stopwatch w;
      if (withUndo)
        editor.dab(d);
      else
        lvdif::applyDab(v, d, s);
      t.push_back(w.ms());
      peer.push_back(peerMs(v, d, s));
    }
    std::sort(t.begin(), t.end());
    std::sort(peer.begin(), peer.end());
    const double med = t[t.size() / 2], pmed = peer[peer.size() / 2];
    rows.push_back({ name, std::to_string(count), bench::fmt(med, 3), bench::fmt(pmed, 3), bench::fmt(med / pmed, 2) });
  };
  timeDabs("dab sphere r=15 add", lvdif::BrushShape::Sphere, 15, lvdif::BrushOp::Add, dabs, false);
  timeDabs("dab sphere r=15 subtract", lvdif::BrushShape::Sphere, 15, lvdif::BrushOp::Subtract, dabs, false);
  timeDabs("dab sphere r=15 paint", lvdif::BrushShape::Sphere, 15, lvdif::BrushOp::Paint, dabs, false);
  timeDabs("dab sphere r=15 add + undo snapshot", lvdif::BrushShape::Sphere, 15, lvdif::BrushOp::Add, dabs, true);
  timeDabs("sphere 200^3 union (Fig. 7a)", lvdif::BrushShape::Sphere, 100, lvdif::BrushOp::Add, 5, false);
  timeDabs("cube 200^3 union (Fig. 7a)", lvdif::BrushShape::Cube, 100, lvdif::BrushOp::Add, 5, false);
  timeDabs("sphere 200^3 subtraction", lvdif::BrushShape::Sphere, 100, lvdif::BrushOp::Subtract, 5, false);
  std::cout << "\nCPU, median ms; peer = the same SDF over the same box into a dense float array\n";
  bench::printTable({ "edit", "runs", "ms", "peer ms", "ratio" }, rows);

  // the dice script end to end (canvas, 2 cubes, 9 pips) at a few sizes
  const std::string dir = argc > 3 ? argv[3] : std::string(LVDIF_SOURCE_DIR) + "/Data/scripts";
  const std::string dice = readFile(dir + "/dice.lvs");
  if (!dice.empty())
  {
    std::vector<std::vector<std::string>> drows;
    for (int n : { 128, 256, 512 })
    {
      std::string src = dice;
      const auto at = src.find("n = 128");
      if (at != std::string::npos)
        src.replace(at, 7, "n = " + std::to_string(n));
      lvdif::ScriptRunner runner;
      bench::Stopwatch w;
      runner.run(src);
      drows.push_back({ std::to_string(n), bench::fmt(w.ms(), 1), std::to_string(runner.edits()),
        lvdif::formatBytes(runner.volume()->memoryBytes()) });
    }
    std::cout << "\ndice.lvs end to end (CPU)\n";
    bench::printTable({ "n", "ms", "edits", "volume memory" }, drows);
  }
  else
  {
    std::cout << "dice.lvs not found in " << dir << "\n";
  }

  if (lvdif::cuda::available())
  {
    std::vector<std::vector<std::string>> grows;
    auto gpu = [&](const char* name, lvdif::BrushShape shape, double radius, int count) {
      lvdif::BrushSettings s;
      std::vector<double> t;
      for (int i = 0; i < count; ++i)
      {
        const lvdif::Dab d{ shape, surfacePoint(rng, c, r), radius, {} };
        bench::Stopwatch w;
        lvdif::cuda::applyDabs(v, { d }, s);
        t.push_back(w.ms());
      }
      std::sort(t.begin(), t.end());
      grows.push_back({ name, std::to_string(count), bench::fmt(t[t.size() / 2], 3) });
    };
    gpu("dab sphere r=15 add", lvdif::BrushShape::Sphere, 15, dabs);
    gpu("sphere 200^3 union", lvdif::BrushShape::Sphere, 100, 5);
    std::cout << "\nGPU (" << lvdif::cuda::deviceName() << "), median ms including transfers of the touched chunks\n";
    bench::printTable({ "edit", "runs", "ms" }, grows);

    // device-resident (DeviceVolume): the edit runs on the device copy; sync writes the changed chunks back
    bench::Stopwatch up;
    lvdif::cuda::DeviceVolume dev(v);
    const double uploadMs = up.ms();
    std::vector<std::vector<std::string>> rrows;
    auto resident = [&](const char* name, lvdif::BrushShape shape, double radius, int count) {
      lvdif::BrushSettings s;
      std::vector<double> t, ts;
      for (int i = 0; i < count; ++i)
      {
        const lvdif::Dab d{ shape, surfacePoint(rng, c, r), radius, {} };
        bench::Stopwatch w;
        dev.applyDabs({ d }, s);
        t.push_back(w.ms());
        bench::Stopwatch ws;
        dev.sync();
        ts.push_back(ws.ms());
      }
      std::sort(t.begin(), t.end());
      std::sort(ts.begin(), ts.end());
      rrows.push_back({ name, std::to_string(count), bench::fmt(t[t.size() / 2], 3), bench::fmt(ts[ts.size() / 2], 3) });
    };
    resident("dab sphere r=15 add", lvdif::BrushShape::Sphere, 15, dabs);
    resident("sphere 200^3 union", lvdif::BrushShape::Sphere, 100, 5);
    resident("cube 200^3 union", lvdif::BrushShape::Cube, 100, 5);
    // a stroke of 100 dabs applied one dab per call before one sync (interactive drawing)
    {
      lvdif::BrushSettings s;
      const auto p0 = surfacePoint(rng, c, r);
      bench::Stopwatch w;
      for (int i = 0; i < 100; ++i)
        dev.applyDabs({ lvdif::Dab{ lvdif::BrushShape::Sphere, { p0[0] + 1.6 * i, p0[1], p0[2] }, 15, {} } }, s);
      const double applyMs = w.ms();
      bench::Stopwatch ws;
      dev.sync();
      rrows.push_back({ "100 dabs r=15, then 1 sync", "1", bench::fmt(applyMs / 100, 3) + " per dab", bench::fmt(ws.ms(), 3) });
    }
    std::cout << "\nGPU device-resident (DeviceVolume, upload " << bench::fmt(uploadMs, 1) << " ms, "
              << lvdif::formatBytes(dev.deviceBytes()) << " on the device), median ms\n";
    bench::printTable({ "edit", "runs", "apply ms (device, blocking)", "sync ms (to host)" }, rrows);
  }
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
