// The volume file against the raw 4 bytes/voxel layout (the paper's and the
// original code's .bv): file size, save and load time for 512^3 and 1024^3
// SDF volumes of a closed shape (a sphere fused with a torus, band 8) with a
// painted colour pattern on the shell; then zstd levels 1, 3, 5, 9 at 512^3
// to justify the default level.
//
// Raw baseline (the peer in the same process): writing a dense, already
// materialized 4N^3-byte buffer with fsync, and reading it back into memory,
// a lower bound of any raw layout. Loads of both read from the page cache
// (the file was just written), so they measure decoding, not the disk.
//
// On a shared machine the wall times depend on the load; the CPU seconds
// (all threads) of each operation are printed beside them.
//
// Usage: bench_volume_file [max edge = 1024] [directory = /tmp] [MESH]
// With MESH, the volumes are that mesh's SDF (mesh to SDF, WindingNumber signs,
// fitted to the largest edge, band 8) painted like the shape, e.g. the bunny.
#include "BenchCommon.h"
#include "BenchVolumeShape.h"

#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <sys/resource.h>
#include <iostream>
#include <unistd.h>

using namespace lvdif;

namespace
{


std::uint64_t fileSize(const std::string& path)
{
  FileSource s(path);
  return s.size();
}

struct Row
{
  std::string name;
  double mib, saveMs, loadMs;
  double saveCpu = 0, loadCpu = 0; // CPU seconds per operation
};

Row measure(const DictionaryVolume& v, const std::string& path, int level)
{
  VolumeFileWriteOptions o;
  o.compressionLevel = level;
  Row r;
  double c0 = bench::cpuSeconds();
  r.saveMs = bench::medianMs(3, [&] { saveVolume(v, path, o); });
  r.saveCpu = (bench::cpuSeconds() - c0) / 3;
  c0 = bench::cpuSeconds();
  r.mib = double(fileSize(path)) / (1 << 20);
  bool same = true;
  r.loadMs = bench::medianMs(3, [&] {
    auto back = loadVolume(path);
    same = back->expandedChunkCount() == v.expandedChunkCount();
  });
  r.loadCpu = (bench::cpuSeconds() - c0) / 3;
  if (!same)
  {
    std::cerr << "round trip changed the chunk structure\n";
    std::exit(1);
  }
  std::remove(path.c_str());
  return r;
}

Row measureRaw(std::int64_t n, const std::string& path)
{
  const std::uint64_t bytes = std::uint64_t(n) * n * n * 4;
  requireMemory(bytes, "raw baseline buffer");
  std::vector<std::uint8_t> dense(bytes, 0x5a);
  Row r;
  double c0 = bench::cpuSeconds();
  r.saveMs = bench::medianMs(1, [&] {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    for (std::uint64_t off = 0; off < bytes;)
    {
      const ssize_t w = ::write(fd, dense.data() + off, std::min<std::uint64_t>(bytes - off, 1u << 30));
      if (w <= 0) { std::cerr << "raw write failed\n"; std::exit(1); }
      off += std::uint64_t(w);
    }
    ::fsync(fd);
    ::close(fd);
  });
  r.saveCpu = bench::cpuSeconds() - c0;
  r.mib = double(bytes) / (1 << 20);
  c0 = bench::cpuSeconds();
  r.loadMs = bench::medianMs(1, [&] {
    FileSource s(path);
    for (std::uint64_t off = 0; off < bytes; off += 1u << 30)
      s.read(off, dense.data() + off, std::min<std::uint64_t>(bytes - off, 1u << 30));
  });
  r.loadCpu = bench::cpuSeconds() - c0;
  std::remove(path.c_str());
  return r;
}

} // namespace

static int benchMain(int argc, char** argv)
{
  const std::int64_t maxEdge = argc > 1 ? std::atoll(argv[1]) : 1024;
  const std::string dir = argc > 2 ? argv[2] : "/tmp";
  const std::string path = dir + "/bench_volume_file.lvdv";
  const std::string meshPath = argc > 3 ? argv[3] : "";
  TriangleMesh mesh;
  if (!meshPath.empty()) mesh = loadMesh(meshPath);
  auto makeVolume = [&](std::int64_t n) {
    if (meshPath.empty()) return bench::makePaintedShape(n);
    auto v = std::make_unique<DictionaryVolume>(volumeOptionsOn(fitGridToMesh(mesh, n, 2.0)));
    MeshToSdfOptions mo;
    mo.sign = SignMode::WindingNumber;
    mo.device = Device::Auto;
    meshToSdf(mesh, *v, mo);
    bench::paintShell(*v);
    return v;
  };
  const int level = VolumeFileWriteOptions().compressionLevel; // the default
  std::cout << "bench_volume_file: " << bench::machineDescription() << "\n"
            << "shape: " << (meshPath.empty() ? std::string("sphere + torus") : "mesh " + meshPath + " (WindingNumber)")
            << ", band 8, chunk edge 32, 6 paint colours on the shell\n\n";

  std::vector<std::vector<std::string>> rows;
  for (std::int64_t n : { std::int64_t(512), std::int64_t(1024) })
  {
    if (n > maxEdge)
      continue;
    bench::Stopwatch fill;
    auto v = makeVolume(n);
    std::cout << n << "^3: filled in " << bench::fmt(fill.seconds(), 1) << " s, " << v->expandedChunkCount() << " of "
              << v->chunkCount() << " chunks non-uniform, " << formatBytes(v->memoryBytes()) << " in memory\n";
    const Row f = measure(*v, path, level);
    const Row raw = measureRaw(n, dir + "/bench_volume_file.raw");
    rows.push_back({ std::to_string(n) + "^3", "lvdv zstd " + std::to_string(level), bench::fmt(f.mib, 1),
      bench::fmt(f.saveMs, 0), bench::fmt(f.saveCpu, 2), bench::fmt(f.loadMs, 0), bench::fmt(f.loadCpu, 2),
      bench::fmt(raw.mib / f.mib, 1) + "x smaller" });
    rows.push_back({ std::to_string(n) + "^3", "raw 4 B/voxel", bench::fmt(raw.mib, 1), bench::fmt(raw.saveMs, 0),
      bench::fmt(raw.saveCpu, 2), bench::fmt(raw.loadMs, 0), bench::fmt(raw.loadCpu, 2), "save " + bench::fmt(raw.saveMs / f.saveMs, 1) + "x, load " +
        bench::fmt(raw.loadMs / f.loadMs, 1) + "x the lvdv time" });
  }
  bench::printTable({ "volume", "layout", "MiB", "save ms", "save CPU s", "load ms", "load CPU s", "vs peer" }, rows);

  std::cout << "\nzstd level at 512^3 (same shape):\n";
  auto v = makeVolume(std::min<std::int64_t>(512, maxEdge));
  std::vector<std::vector<std::string>> levels;
  for (int level : { 1, 3, 5, 9 })
  {
    const Row r = measure(*v, path, level);
    levels.push_back({ std::to_string(level), bench::fmt(r.mib, 2), bench::fmt(r.saveMs, 0), bench::fmt(r.saveCpu, 2),
      bench::fmt(r.loadMs, 0), bench::fmt(r.loadCpu, 2) });
  }
  bench::printTable({ "level", "MiB", "save ms", "save CPU s", "load ms", "load CPU s" }, levels);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
