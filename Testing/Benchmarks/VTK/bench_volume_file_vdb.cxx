// The volume file against OpenVDB's own .vdb (Blosc) of the same level set,
// in one run (the format's acceptance benchmark; the Core-only part with zstd
// levels is bench_volume_file). The shape is bench::makePaintedShape: the
// OpenVDB side gets a narrow-band level set FloatGrid `sdf` (background =
// band, active voxels |d| < band, inside made negative with signedFloodFill,
// as OpenVDB's level sets are) and an Int32Grid `rgba` (packed RGBA, active
// on the same voxels), so both files hold distances and colours.
//
// Times: save (our crash-safe save vs openvdb::io::File::write, with fsync
// for both) and load (full read: our loadVolume vs io::File opened without
// delayed loading + readGrid of both grids). Building the OpenVDB grids from
// our volume is not timed. CPU seconds of all threads beside wall times.
//
// Usage: bench_volume_file_vdb [max edge = 1024] [directory = /tmp]
#include "BenchCommon.h"
#include "BenchVolumeShape.h"

#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <cstdio>
#include <fcntl.h>
#include <iostream>
#include <unistd.h>

namespace
{

openvdb::GridPtrVec toVdb(const lvdif::DictionaryVolume& v)
{
  const float band = v.bandWidth();
  auto sdf = openvdb::FloatGrid::create(band);
  sdf->setName("sdf");
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  auto rgba = openvdb::Int32Grid::create(0);
  rgba->setName("rgba");
  auto sa = sdf->getAccessor();
  auto ca = rgba->getAccessor();
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    if (v.isUniform(id))
      continue; // uniform chunks are beyond the band: background / flood fill
    const lvdif::VoxelBox b = v.chunkBox(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          const lvdif::Voxel w = v.get(x, y, z);
          const float d = v.decode(w.sdf);
          if (std::fabs(d) < band)
          {
            const openvdb::Coord ijk{ static_cast<openvdb::Int32>(x), static_cast<openvdb::Int32>(y), static_cast<openvdb::Int32>(z) };
            sa.setValue(ijk, d);
            ca.setValue(ijk, static_cast<std::int32_t>(v.colors()[w.color].packed()));
          }
        }
  }
  openvdb::tools::signedFloodFill(sdf->tree());
  return { sdf, rgba };
}

void fsyncFile(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY);
  ::fsync(fd);
  ::close(fd);
}

std::uint64_t sizeOf(const std::string& path)
{
  lvdif::FileSource s(path);
  return s.size();
}

} // namespace

static int benchMain(int argc, char** argv)
{
  const std::int64_t maxEdge = argc > 1 ? std::atoll(argv[1]) : 1024;
  const std::string dir = argc > 2 ? argv[2] : "/tmp";
  openvdb::initialize();
  std::cout << "bench_volume_file_vdb: " << bench::machineDescription() << "\n"
            << "OpenVDB " << openvdb::getLibraryAbiVersionString() << ", Blosc "
            << (openvdb::io::Archive::hasBloscCompression() ? "available" : "NOT available") << "\n"
            << "shape: sphere + torus, band 8, chunk edge 32, 6 paint colours on the shell\n\n";
  std::vector<std::vector<std::string>> rows;
  for (std::int64_t n : { std::int64_t(512), std::int64_t(1024) })
  {
    if (n > maxEdge)
      continue;
    auto v = bench::makePaintedShape(n);
    const std::string lvdv = dir + "/bench_vdb.lvdv", vdb = dir + "/bench_vdb.vdb";

    double c0 = bench::cpuSeconds();
    const double ourSave = bench::medianMs(3, [&] { lvdif::saveVolume(*v, lvdv); });
    const double ourSaveCpu = (bench::cpuSeconds() - c0) / 3;
    c0 = bench::cpuSeconds();
    const double ourLoad = bench::medianMs(3, [&] { lvdif::loadVolume(lvdv); });
    const double ourLoadCpu = (bench::cpuSeconds() - c0) / 3;
    const double ourMiB = double(sizeOf(lvdv)) / (1 << 20);

    openvdb::GridPtrVec grids = toVdb(*v);
    const auto active = grids[0]->activeVoxelCount();
    c0 = bench::cpuSeconds();
    const double vdbSave = bench::medianMs(3, [&] {
      openvdb::io::File file(vdb);
      file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
      file.write(grids);
      file.close();
      fsyncFile(vdb);
    });
    const double vdbSaveCpu = (bench::cpuSeconds() - c0) / 3;
    c0 = bench::cpuSeconds();
    openvdb::Index64 loaded = 0;
    const double vdbLoad = bench::medianMs(3, [&] {
      openvdb::io::File file(vdb);
      file.open(/*delayLoad=*/false);
      auto s = file.readGrid("sdf");
      auto c = file.readGrid("rgba");
      loaded = s->activeVoxelCount() + c->activeVoxelCount();
      file.close();
    });
    const double vdbLoadCpu = (bench::cpuSeconds() - c0) / 3;
    const double vdbMiB = double(sizeOf(vdb)) / (1 << 20);
    if (loaded != 2 * active)
    {
      std::cerr << "the .vdb read back holds " << loaded << " active voxels, expected " << 2 * active << "\n";
      return 1;
    }
    const std::string vol = std::to_string(n) + "^3";
    rows.push_back({ vol, "lvdv (zstd 3)", bench::fmt(ourMiB, 1), bench::fmt(ourSave, 0), bench::fmt(ourSaveCpu, 2),
      bench::fmt(ourLoad, 0), bench::fmt(ourLoadCpu, 2), "" });
    rows.push_back({ vol, ".vdb Blosc (sdf + rgba)", bench::fmt(vdbMiB, 1), bench::fmt(vdbSave, 0),
      bench::fmt(vdbSaveCpu, 2), bench::fmt(vdbLoad, 0), bench::fmt(vdbLoadCpu, 2),
      std::to_string(active) + " active voxels; size " + bench::fmt(vdbMiB / ourMiB, 2) + "x lvdv" });
    std::remove(lvdv.c_str());
    std::remove(vdb.c_str());
  }
  bench::printTable({ "volume", "file", "MiB", "save ms", "save CPU s", "load ms", "load CPU s", "note" }, rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
