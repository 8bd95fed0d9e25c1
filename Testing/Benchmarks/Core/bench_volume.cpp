// Dictionary volume benchmark: voxel read/write rates, chunk
// iteration, and resident memory of a 1024^3 sphere volume, sparse (band 8)
// against the paper's dense layout (every chunk expanded, 4 bytes/voxel).
// CPU rates are also given as a ratio to a flat std::vector<uint32_t> peer
// doing the same accesses in the same process.
//
// usage: bench_volume [edge=1024] [--no-dense]
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Memory.h"

#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>

using namespace lvdif;

static int benchMain(int argc, char** argv)
{
  std::int64_t n = 1024;
  bool dense = true;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--no-dense") == 0) dense = false;
    else n = std::atoll(argv[i]);
  }
  std::cout << "# bench_volume: " << n << "^3 sphere (radius 0.4 n), band 8, chunk 32\n";
  std::cout << "# machine: " << bench::machineDescription() << "\n\n";

  VolumeOptions o;
  o.dims = { n, n, n };
  const double c = 0.5 * n + 0.3, r = 0.4 * n;
  std::vector<std::vector<std::string>> rows;

  const std::uint64_t rss0 = residentMemoryBytes();
  bench::Stopwatch w;
  DictionaryVolume v(o);
  fillFromFunction(v, sphereSdf(c, c, c, r));
  const double fillS = w.seconds();
  const std::uint64_t rssSparse = residentMemoryBytes() - rss0;
  rows.push_back({ "sparse (band 8)", std::to_string(v.expandedChunkCount()) + "/" + std::to_string(v.chunkCount()),
    formatBytes(v.memoryBytes()), formatBytes(rssSparse), bench::fmt(fillS, 2) });

  if (dense)
  {
    const std::uint64_t need = DictionaryVolume::denseBytes(o);
    if (need < memoryLimitBytes() - v.memoryBytes())
    {
      VolumeOptions full = o;
      full.bandWidth = std::numeric_limits<float>::infinity();
      const std::uint64_t rss1 = residentMemoryBytes();
      w.reset();
      DictionaryVolume d(full);
#pragma omp parallel for schedule(dynamic, 16)
      for (std::int64_t id = 0; id < d.chunkCount(); ++id) d.expandChunk(id);
      fillFromFunction(d, sphereSdf(c, c, c, r)); // full band: nothing collapses
      rows.push_back({ "dense (paper layout)", std::to_string(d.expandedChunkCount()) + "/" + std::to_string(d.chunkCount()),
        formatBytes(d.memoryBytes()), formatBytes(residentMemoryBytes() - rss1), bench::fmt(w.seconds(), 2) });
    }
    else
    {
      rows.push_back({ "dense (paper layout)", "-", formatBytes(need), "not allocated: over the memory limit", "-" });
    }
  }
  std::cout << "## Memory\n";
  bench::printTable({ "layout", "expanded chunks", "volume bytes", "RSS increase", "fill s" }, rows);

  // ---- access rates (single thread; the per-voxel API is what brushes use) ----
  const std::int64_t samples = 20'000'000;
  std::mt19937_64 rng(42);
  std::vector<std::int64_t> xs(samples), ys(samples), zs(samples);
  for (std::int64_t i = 0; i < samples; ++i)
  {
    // near the surface, where edits happen: a shell around the sphere
    xs[i] = static_cast<std::int64_t>(rng() % n);
    ys[i] = static_cast<std::int64_t>(rng() % n);
    zs[i] = static_cast<std::int64_t>(rng() % n);
  }
  const std::int64_t flatN = std::min<std::int64_t>(n, 512);
  std::vector<std::uint32_t> flat(static_cast<size_t>(flatN * flatN * flatN), 1u);
  std::uint64_t sink = 0;
  rows.clear();
  double t = bench::medianMs(3, [&] {
    for (std::int64_t i = 0; i < samples; ++i) sink += v.get(xs[i], ys[i], zs[i]).sdf;
  });
  double tFlat = bench::medianMs(3, [&] {
    for (std::int64_t i = 0; i < samples; ++i)
      sink += flat[static_cast<size_t>(xs[i] % flatN + flatN * (ys[i] % flatN + flatN * (zs[i] % flatN)))];
  });
  rows.push_back({ "random get()", bench::fmt(samples / t / 1e3, 1), bench::fmt(samples / tFlat / 1e3, 1), bench::fmt(tFlat / t, 2) });

  // sequential get() along x rows of a surface slab
  const std::int64_t z0 = static_cast<std::int64_t>(c);
  t = bench::medianMs(3, [&] {
    for (std::int64_t y = 0; y < n; ++y)
      for (std::int64_t x = 0; x < n; ++x) sink += v.get(x, y, z0).sdf;
  });
  tFlat = bench::medianMs(3, [&] {
    for (std::int64_t y = 0; y < n; ++y)
      for (std::int64_t x = 0; x < n; ++x) sink += flat[static_cast<size_t>(x % flatN + flatN * (y % flatN))];
  });
  rows.push_back({ "row-order get()", bench::fmt(n * n / t / 1e3, 1), bench::fmt(n * n / tFlat / 1e3, 1), bench::fmt(tFlat / t, 2) });

  // random set() inside a 64^3 box at the surface (chunks expand on first write)
  const std::int64_t bx = static_cast<std::int64_t>(c + r) - 32;
  t = bench::medianMs(3, [&] {
    for (std::int64_t i = 0; i < samples / 4; ++i)
      v.set(bx + (xs[i] & 63), z0 - 32 + (ys[i] & 63), z0 - 32 + (zs[i] & 63), Voxel{ static_cast<SdfKey>(i), 0 });
  });
  tFlat = bench::medianMs(3, [&] {
    for (std::int64_t i = 0; i < samples / 4; ++i)
      flat[static_cast<size_t>((xs[i] & 63) + flatN * ((ys[i] & 63) + flatN * (zs[i] & 63)))] = static_cast<std::uint32_t>(i);
  });
  rows.push_back({ "random set() (64^3 box)", bench::fmt(samples / 4 / t / 1e3, 1), bench::fmt(samples / 4 / tFlat / 1e3, 1), bench::fmt(tFlat / t, 2) });
  std::cout << "\n## Voxel access (1 thread; M voxels/s)\n";
  bench::printTable({ "operation", "volume", "flat array peer", "volume / peer" }, rows);

  // ---- chunk-level access ----
  rows.clear();
  t = bench::medianMs(3, [&] {
    for (std::int64_t id = 0; id < v.chunkCount(); ++id)
    {
      if (const Voxel* d = v.chunkData(id))
      {
        for (std::int64_t i = 0; i < 32 * 32 * 32; ++i) sink += d[i].sdf;
      }
      else
      {
        sink += v.uniformValue(id).sdf;
      }
    }
  });
  rows.push_back({ "visit every voxel via chunkData()", bench::fmt(t, 1) + " ms",
    bench::fmt(static_cast<double>(v.expandedChunkCount()) * 32768 / t / 1e3, 0) + " M voxels/s" });
  VoxelBox box;
  box.lo = { bx - 40, z0 - 40, z0 - 40 };
  box.hi = { bx + 40, z0 + 40, z0 + 40 };
  std::int64_t visited = 0;
  t = bench::medianMs(5, [&] { v.forEachChunkInBox(box, [&](std::int64_t) { ++visited; }); });
  rows.push_back({ "forEachChunkInBox (81^3 box)", bench::fmt(t * 1e3, 1) + " us", std::to_string(v.chunksInBox(box).size()) + " chunks" });
  t = bench::medianMs(3, [&] { sink += v.takeDirtyChunks().size(); });
  rows.push_back({ "takeDirtyChunks (all chunks scanned)", bench::fmt(t, 2) + " ms", std::to_string(v.chunkCount()) + " chunks" });
  t = bench::medianMs(1, [&] {
    for (std::int64_t id = 0; id < v.chunkCount(); ++id) sink += v.chunkRange(id).first;
  });
  rows.push_back({ "chunkRange of every chunk (first call)", bench::fmt(t, 1) + " ms", "" });
  std::cout << "\n## Chunks\n";
  bench::printTable({ "operation", "time", "note" }, rows);
  std::cerr << "(checksum " << sink << ")\n";
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
