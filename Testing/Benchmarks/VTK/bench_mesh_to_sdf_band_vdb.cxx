// Mesh to SDF in banded (sparse) mode on the CPU against OpenVDB, in one
// process, same grid, same thread count, same band: our lvdif::meshToSdf into a
// DictionaryVolume with band B (one call, preparation included) against
// OpenVDB's tools::meshToLevelSet (exterior = interior band = B voxels, a sparse
// FloatGrid). Rounds alternate between the two so that a change of load on a
// shared machine falls on both; the table gives the median wall time and the
// process CPU seconds of each. Then a check of the two outputs on every voxel
// OpenVDB holds active within B - 1 voxels of the surface: the largest distance
// difference and the sign disagreements there (OpenVDB's far distances are not
// exact, its near band is).
//
// usage: bench_mesh_to_sdf_band_vdb MESH [RES=512] [BAND=8] [THREADS=2] [ROUNDS=3] [SIGN=winding|pseudonormal]
#include "BenchCommon.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Timing
{
  std::vector<double> wall, cpu;
};

openvdb::FloatGrid::Ptr openvdbBand(const TriangleMesh& mesh, const GridGeometry& g, float band)
{
  auto xform = openvdb::math::Transform::createLinearTransform(g.spacing[0]);
  xform->postTranslate(openvdb::Vec3d(g.origin[0], g.origin[1], g.origin[2]));
  std::vector<openvdb::Vec3s> pts;
  std::vector<openvdb::Vec3I> tris;
  pts.reserve(mesh.points.size());
  tris.reserve(mesh.triangles.size());
  for (const auto& p : mesh.points) pts.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles) tris.emplace_back(t[0], t[1], t[2]);
  return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, pts, tris, band);
}

std::unique_ptr<DictionaryVolume> oursBand(const TriangleMesh& mesh, const GridGeometry& g, float band, SignMode sign)
{
  VolumeOptions vo = volumeOptionsOn(g);
  vo.bandWidth = band;
  auto vol = std::make_unique<DictionaryVolume>(vo);
  MeshToSdfOptions o;
  o.sign = sign;
  o.device = Device::Cpu;
  o.bandWidth = band;
  meshToSdf(mesh, *vol, o);
  return vol;
}

} // namespace

static int benchMain(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s MESH [RES=512] [BAND=8] [THREADS=2] [ROUNDS=3] [SIGN=winding|pseudonormal]\n",
      argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const std::int64_t res = argc > 2 ? std::atoll(argv[2]) : 512;
  const float band = argc > 3 ? static_cast<float>(std::atof(argv[3])) : 8.0f;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
  const int rounds = argc > 5 ? std::atoi(argv[5]) : 3;
  const std::string signName = argc > 6 ? argv[6] : "winding";
  if (res < 8 || !(band >= 1) || threads < 1 || rounds < 1 || (signName != "winding" && signName != "pseudonormal"))
  {
    std::fprintf(stderr, "bench_mesh_to_sdf_band_vdb: bad arguments (RES >= 8, BAND >= 1, THREADS >= 1, ROUNDS >= 1, "
                         "SIGN winding or pseudonormal)\n");
    return 2;
  }
  const SignMode sign = signName == "winding" ? SignMode::WindingNumber : SignMode::PseudoNormal;
  omp_set_num_threads(threads);
  tbb::global_control tbbThreads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  openvdb::initialize();
  const TriangleMesh mesh = loadMesh(path);
  const GridGeometry g = fitGridToMesh(mesh, res, 2.0);
  std::printf("machine: %s; OpenMP %d threads, TBB (OpenVDB) %d\n", bench::machineDescription().c_str(), threads,
    threads);
  std::printf("mesh %s: %zu points, %zu triangles; grid %lldx%lldx%lld; band %.1f voxels; our sign %s\n",
    path.c_str(), mesh.points.size(), mesh.triangles.size(), (long long)g.dims[0], (long long)g.dims[1],
    (long long)g.dims[2], band, signName.c_str());

  Timing ours, vdb;
  std::unique_ptr<DictionaryVolume> vol;
  openvdb::FloatGrid::Ptr grid;
  for (int r = 0; r < rounds; ++r)
  {
    // alternate the order each round
    for (int k = 0; k < 2; ++k)
    {
      const bool oursNow = (k == 0) == (r % 2 == 0);
      const double c0 = cpuSeconds();
      bench::Stopwatch w;
      if (oursNow)
        vol = oursBand(mesh, g, band, sign);
      else
        grid = openvdbBand(mesh, g, band);
      Timing& t = oursNow ? ours : vdb;
      t.wall.push_back(w.seconds());
      t.cpu.push_back(cpuSeconds() - c0);
    }
  }

  // the check on OpenVDB's active voxels well inside the band (index space = our voxels)
  const float toVoxel = static_cast<float>(1.0 / g.spacing[0]);
  double maxDiff = 0;
  std::int64_t compared = 0, signDiffer = 0;
  for (auto it = grid->cbeginValueOn(); it; ++it)
  {
    const openvdb::Coord c = it.getCoord();
    if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= g.dims[0] || c.y() >= g.dims[1] || c.z() >= g.dims[2])
      continue;
    const float dv = *it * toVoxel;
    if (std::fabs(dv) > band - 1.0f) continue;
    const float d = vol->sdf(c.x(), c.y(), c.z());
    ++compared;
    maxDiff = std::max(maxDiff, double(std::fabs(std::fabs(d) - std::fabs(dv))));
    signDiffer += (d < 0) != (dv < 0) && std::fabs(dv) > 1.0f;
  }

  const double oursWall = bench::percentile(ours.wall, 50), vdbWall = bench::percentile(vdb.wall, 50);
  const double oursCpu = bench::percentile(ours.cpu, 50), vdbCpu = bench::percentile(vdb.cpu, 50);
  std::vector<std::vector<std::string>> rows;
  auto all = [](const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : " / ") + bench::fmt(x, 3);
    return s;
  };
  rows.push_back({ "ours meshToSdf -> DictionaryVolume (" + signName + ")", bench::fmt(oursWall, 3), all(ours.wall),
    bench::fmt(oursCpu, 2), "1.00", std::to_string(vol->expandedChunkCount()) + " of " +
      std::to_string(vol->chunkCount()) + " chunks expanded" });
  rows.push_back({ "OpenVDB meshToLevelSet (sparse FloatGrid)", bench::fmt(vdbWall, 3), all(vdb.wall),
    bench::fmt(vdbCpu, 2), bench::fmt(vdbWall / oursWall, 2),
    std::to_string(grid->activeVoxelCount()) + " active voxels" });
  bench::printTable({ "method", "median s (wall)", "every round", "median CPU s", "time / ours", "output" }, rows);
  std::printf("OpenVDB / ours: %.2f by wall time, %.2f by process CPU time (median of %d rounds)\n",
    vdbWall / oursWall, vdbCpu / oursCpu, rounds);
  std::printf("check on %lld OpenVDB voxels within %.0f voxels of the surface: max | |d| - |d_vdb| | = %.4f voxels, "
              "%lld signs differ (farther than 1 voxel)\n",
    (long long)compared, band - 1.0f, maxDiff, (long long)signDiffer);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
