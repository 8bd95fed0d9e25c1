// Memory of mesh -> volume -> sign voxel filters as vtkSignVoxelFilter runs
// them on a sparse volume: the filter leaves its input alone, so it filters a
// clone of the Core volume (DictionaryVolume::clone, then signVoxelFilter on
// the volume). The same source builds against older commits, so the peak RSS
// of this process (/usr/bin/time -v) compares the two.
// Mesh: a UV sphere (256 x 512 quads' triangles) of radius 0.4 N voxels in an
// N^3 volume (band 8, chunk edge 32), CPU.
// usage: bench_svf_chain N
#include "BenchCommon.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Memory.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/SignVoxelFilter.h"
#include "lvdif/TriangleMesh.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <sys/resource.h>

namespace
{
/// Peak resident memory of this process so far (VmHWM), MiB.
double peakMiB()
{
  std::ifstream f("/proc/self/status");
  std::string key;
  double kb = 0;
  while (f >> key)
  {
    if (key == "VmHWM:")
    {
      f >> kb;
      break;
    }
  }
  return kb / 1024.0;
}

/// CPU seconds (user + system) of this process so far: a loaded machine's
/// wall times say little, its CPU times compare.
double cpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Starts a new peak at the current resident memory (Linux: clear_refs 5).
void resetPeak()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}
} // namespace

static int benchMain(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: bench_svf_chain N\n");
    return 2;
  }
  const std::int64_t n = std::atoll(argv[1]);
  const auto mib = [](std::uint64_t b) { return double(b) / (1 << 20); };
  std::printf("machine: %s\n", bench::machineDescription().c_str());
  const float c = 0.5f * float(n - 1);
  const lvdif::TriangleMesh mesh = lvdif::makeSphereMesh(c, c, c, 0.4f * float(n), 256, 512);
  lvdif::VolumeOptions vo;
  vo.dims = { n, n, n };
  vo.chunkEdge = 32;
  vo.bandWidth = 8.0f;
  std::printf("start: RSS %.0f MiB\n", mib(lvdif::residentMemoryBytes()));

  bench::Stopwatch w;
  const double c0 = cpuSeconds();
  lvdif::DictionaryVolume volume(vo);
  lvdif::MeshToSdfOptions mo;
  mo.device = lvdif::Device::Cpu;
  lvdif::meshToSdf(mesh, volume, mo);
  const double tSdf = w.seconds();
  const double cSdf = cpuSeconds() - c0;
  const double peakSdf = peakMiB();
  std::printf("mesh to SDF: %.2f s, volume %.0f MiB (%lld of %lld chunks expanded), RSS %.0f MiB, peak %.0f MiB\n",
    tSdf, mib(volume.memoryBytes()), static_cast<long long>(volume.expandedChunkCount()),
    static_cast<long long>(volume.chunkCount()), mib(lvdif::residentMemoryBytes()), peakSdf);

  resetPeak();
  const double before = mib(lvdif::residentMemoryBytes());
  w.reset();
  const double c1 = cpuSeconds();
  std::unique_ptr<lvdif::DictionaryVolume> filtered = volume.clone();
  lvdif::SignVoxelFilterParams sp;
  sp.device = lvdif::Device::Cpu;
  const lvdif::SignVoxelFilterStats st = lvdif::signVoxelFilter(*filtered, sp);
  const double tSvf = w.seconds();
  const double cSvf = cpuSeconds() - c1;
  const double peakSvf = peakMiB();
  std::printf("clone + sign voxel filters: %.2f s, %lld flips, RSS %.0f MiB, peak %.0f MiB (+%.0f over the %.0f before)\n",
    tSvf, static_cast<long long>(st.totalFlips()), mib(lvdif::residentMemoryBytes()), peakSvf, peakSvf - before,
    before);
  std::printf("BENCH n=%lld sdf_s=%.2f svf_s=%.2f sdf_cpu_s=%.2f svf_cpu_s=%.2f volume_mib=%.0f sdf_peak_mib=%.0f "
              "svf_peak_mib=%.0f svf_added_mib=%.0f\n",
    static_cast<long long>(n), tSdf, tSvf, cSdf, cSvf, mib(volume.memoryBytes()), peakSdf, peakSvf, peakSvf - before);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
