// Chunked marching cubes (paper Table 2 re-done): full extraction and the
// update of one chunk for several chunk sizes on 512^3 and 1024^3 dictionary
// volumes of an analytic sphere, and the re-mesh after one radius-15 sphere
// edit in a 1024^3 volume with 64^3 chunks.
// With a CUDA device: the GPU path on a 1024^3 float grid (resident on the
// device) and on one 64^3 chunk.
// Usage: bench_marching_cubes [maxN=1024] [repeats=3] [mode: 0 all | 1 GPU only | 2 CPU edit re-mesh only]
#include "BenchCommon.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Brush.h"
#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Cuda.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

using namespace lvdif;

namespace
{
std::size_t triangles(const std::vector<ChunkMesh>& m)
{
  std::size_t t = 0;
  for (const auto& c : m) t += c.triangles.size();
  return t;
}

/// A chunk the surface crosses: the one holding the sphere's +x pole.
std::int64_t surfaceChunk(const ChunkedMarchingCubes& mc, double cx, double cy, double cz, double r)
{
  const std::int64_t e = mc.options().chunkEdge;
  const std::int64_t x = static_cast<std::int64_t>(cx + r) / e, y = static_cast<std::int64_t>(cy) / e,
                     z = static_cast<std::int64_t>(cz) / e;
  return x + mc.chunkCounts()[0] * (y + mc.chunkCounts()[1] * z);
}
/// GPU: full extraction of an n^3 float grid sphere (grid already on the
/// device after a first call that uploads it) and one 64^3 chunk.
void gpuTable(std::int64_t n, int repeats)
{
  std::vector<float> grid(static_cast<std::size_t>(n * n * n));
  const double c = 0.5 * n + 0.37, r = 0.39 * n;
#pragma omp parallel for schedule(static)
  for (std::int64_t z = 0; z < n; ++z)
    for (std::int64_t y = 0; y < n; ++y)
      for (std::int64_t x = 0; x < n; ++x)
        grid[x + n * (y + n * z)] = static_cast<float>(
          std::sqrt((x - c) * (x - c) + (y - c + 0.21) * (y - c + 0.21) + (z - c - 0.13) * (z - c - 0.13)) - r);
  FloatGridView g;
  g.data = grid.data();
  g.geometry.dims = { n, n, n };
  std::vector<std::vector<std::string>> rows;
  for (int edge : { 32, 64, 128 })
  {
    MarchingCubesOptions o;
    o.chunkEdge = edge;
    o.device = Device::Cuda;
    ChunkedMarchingCubes mc(g, nullptr, o);
    bench::Stopwatch first;
    std::size_t tris = triangles(mc.extractAll());
    const double firstMs = first.ms();
    std::size_t meshes = 0;
    const double full = bench::medianMs(repeats, [&] {
      const auto all = mc.extractAll();
      tris = triangles(all);
      meshes = all.size();
    });
    // packed: one set of arrays in a page-locked block, reused from call to call
    PackedChunkMeshes packed;
    bench::Stopwatch firstPacked;
    mc.extractAllPacked(packed);
    const double firstPackedMs = firstPacked.ms();
    const double packedMs = bench::medianMs(std::max(repeats, 5), [&] { mc.extractAllPacked(packed); });
    const double mb = (packed.vertexCount() * (2 * sizeof(Vec3f) + sizeof(std::uint64_t)) +
                        packed.triangleCount() * (3 * sizeof(std::uint32_t) + sizeof(std::int64_t))) /
      1e6;
    const std::int64_t id = surfaceChunk(mc, c, c - 0.21, c + 0.13, r);
    std::size_t oneTris = 0;
    const double one = bench::medianMs(21, [&] { oneTris = mc.extractChunk(id).triangles.size(); });
    rows.push_back({ std::to_string(n) + "^3", std::to_string(edge) + "^3", std::to_string(meshes), std::to_string(tris),
      bench::fmt(firstMs, 1), bench::fmt(full, 2), bench::fmt(mb, 0), bench::fmt(firstPackedMs, 1),
      bench::fmt(packedMs, 2), std::to_string(oneTris), bench::fmt(one, 3) });
    if (packed.triangleCount() != tris) std::cerr << "packed and split triangle counts differ!\n";
  }
  std::cout << "\nGPU (" << cuda::deviceName()
            << "), float grid resident on the device, normals on; full = extractAll (per-chunk vectors), packed = "
               "extractAllPacked into a reused page-locked block (results on the host in both)\n";
  bench::printTable({ "volume", "MC chunk", "non-empty", "triangles", "first ms (upload)", "full ms", "packed MB",
                      "packed first ms", "packed ms", "one-chunk tris", "one-chunk ms" },
    rows);
}
} // namespace

static int benchMain(int argc, char** argv)
{
  const std::int64_t maxN = argc > 1 ? std::atoll(argv[1]) : 1024;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  const int mode = argc > 3 ? std::atoi(argv[3]) : 0;
  const bool gpuOnly = mode == 1, editOnly = mode == 2;
  std::cout << "# bench_marching_cubes\n" << bench::machineDescription() << "\n\n";
  if (cuda::available() && !editOnly) gpuTable(maxN, std::max(repeats, 3));
  if (gpuOnly) return 0;
  std::vector<std::vector<std::string>> rows;
  std::unique_ptr<DictionaryVolume> big;
  for (std::int64_t n : { std::int64_t(512), std::int64_t(1024) })
  {
    if (n > maxN || (editOnly && n != 1024)) continue;
    VolumeOptions vo;
    vo.dims = { n, n, n };
    vo.chunkEdge = 32;
    auto vol = std::make_unique<DictionaryVolume>(vo);
    const double c = 0.5 * n + 0.37, r = 0.39 * n;
    bench::Stopwatch fill;
    fillFromFunction(*vol, sphereSdf(c, c - 0.21, c + 0.13, r));
    std::cerr << n << "^3 filled in " << fill.ms() << " ms\n";
    for (int edge : { 32, 64, 128, 256 })
    {
      if (editOnly) break;
      MarchingCubesOptions o;
      o.chunkEdge = edge;
      ChunkedMarchingCubes mc(*vol, o);
      std::size_t tris = 0, meshes = 0;
      const double full = bench::medianMs(repeats, [&] {
        const auto all = mc.extractAll();
        tris = triangles(all);
        meshes = all.size();
      });
      const std::int64_t id = surfaceChunk(mc, c, c - 0.21, c + 0.13, r);
      std::size_t oneTris = 0;
      const double one = bench::medianMs(std::max(repeats, 5), [&] { oneTris = mc.extractChunk(id).triangles.size(); });
      rows.push_back({ std::to_string(n) + "^3", std::to_string(edge) + "^3", std::to_string(mc.chunkCount()),
        std::to_string(meshes), std::to_string(tris), bench::fmt(full, 1), bench::fmt(tris / full / 1e3, 2),
        std::to_string(oneTris), bench::fmt(one, 3) });
    }
    if (n == 1024) big = std::move(vol);
  }
  if (!editOnly)
    bench::printTable({ "volume", "MC chunk", "chunks", "non-empty", "triangles", "full ms", "Mtri/s",
                      "one-chunk tris", "one-chunk ms" },
    rows);

  if (big)
  {
    // one radius-15 sphere edit (CSG union written directly), then re-mesh the touched 64^3 chunks
    MarchingCubesOptions o;
    o.chunkEdge = 64;
    ChunkedMarchingCubes mc(*big, o);
    big->takeDirtyChunks();
    std::vector<std::vector<std::string>> erows;
    const double c = 0.5 * 1024 + 0.37, r = 0.39 * 1024;
    BrushSettings add;
    add.op = BrushOp::Add;
    add.color = Rgba{ 200, 40, 40, 255 };
    for (int k = 0; k < 5; ++k)
    {
      // centre on the surface, a different spot each time
      const double a = 0.3 + 0.25 * k;
      const double ex = c + r * std::cos(a), ey = c - 0.21 + r * std::sin(a), ez = c + 0.13 + 0.1 * k;
      bench::Stopwatch write;
      const EditResult edit = applyDab(*big, Dab{ BrushShape::Sphere, { ex, ey, ez }, 15.0, {} }, add);
      const double writeMs = write.ms();
      const auto storageIds = mc.chunksAffectedByStorageChunks(big->takeDirtyChunks());
      // re-meshing is idempotent: median of 7 (the machine is shared), first run separately
      std::vector<ChunkMesh> meshes;
      std::vector<std::int64_t> ids;
      bench::Stopwatch firstRun;
      ids = mc.chunksAffectedBy(edit.changedBox);
      meshes = mc.extractChunks(ids);
      const double firstMs = firstRun.ms();
      const double remeshMs = bench::medianMs(7, [&] {
        ids = mc.chunksAffectedBy(edit.changedBox);
        meshes = mc.extractChunks(ids);
      });
      const double storageMs = bench::medianMs(7, [&] { mc.extractChunks(storageIds); });
      std::size_t nonEmpty = 0;
      for (const auto& m : meshes) nonEmpty += !m.empty();
      erows.push_back({ std::to_string(k), bench::fmt(writeMs, 2), std::to_string(storageIds.size()),
        bench::fmt(storageMs, 2), std::to_string(ids.size()), std::to_string(nonEmpty), std::to_string(triangles(meshes)),
        bench::fmt(firstMs, 2), bench::fmt(remeshMs, 2), bench::fmt(storageMs / remeshMs, 2) });
    }
    std::cout << "\nRe-mesh after one radius-15 sphere brush (applyDab, add), 1024^3, 64^3 MC chunks (storage chunks "
                 "32^3); re-mesh = chunksAffectedBy(changedBox) + extractChunks\n";
    bench::printTable({ "edit", "brush ms", "chunks (storage rule)", "storage-rule ms", "chunks (changedBox)",
                        "non-empty", "triangles", "first ms", "re-mesh ms", "ratio" },
      erows);
  }
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
