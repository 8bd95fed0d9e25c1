// Mesh to SDF benchmark: per-phase times (build, distance, sign, write) for a
// mesh file at a resolution, sign mode, accelerator, device and output.
// usage: bench_mesh_to_sdf [DAMAGE:]MESH [RES=256] [SIGN=winding] [DEVICE=auto]
//        [ACCEL=bvh] [OUTPUT=volume|float] [BAND=8] [PADDING=2]
//        [RUNS=cold,warm,prepared,prepared] [--trace] [--check-cpu] [--reorient]
// A run may carry @SIGN (normal, pseudonormal, winding, unsigned: that run's
// sign mode instead of SIGN), @pervoxel (MeshToSdfOptions::farBlocks off) and
// @pageable (CUDA into a volume: the chunk keys come back through pageable
// memory, as when pinned memory is refused), @normalspath (PseudoNormal or
// Normal on a solid by its own path: MeshToSdfOptions::solidsByWinding off), e.g.
// prepared@winding,prepared@pseudonormal,prepared@pseudonormal@pervoxel:
// sign modes and paths compared in one process.
// DAMAGE: a seeded variant of the mesh made in memory before timing (any of
// signquality::damaged, SignQualityMeshes.h: patch10, duprev20, holes40,
// fins200, pair, sub2, ...). The bunny is not in the repository: pass its path (e.g. /work/shared/data/lvdif-bunny-30k.ply).
#include "BenchCommon.h"
#include "SignQualityMeshes.h"

#include "../../../Core/MeshToSdf/src/MeshToSdfCuda.h"

#include "lvdif/Cuda.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/Memory.h"

#include <omp.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace lvdif;

/// Minor page faults of this process so far (all threads).
static long minorFaults()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

static int benchMain(int argc, char** argv)
{
  // --trace (anywhere): MeshToSdfOptions::tracePhases, the host phases' times on stderr
  // --check-cpu (anywhere; float output): after the runs, the same grid on the
  // CPU, compared bit for bit with the last run's floats (signs and distances)
  // --reorient (anywhere): MeshToSdfOptions::reorientFaces (winding sign)
  bool tracePhases = false, checkCpu = false, reorient = false;
  for (int i = 1; i < argc;)
  {
    const std::string a = argv[i];
    if (a != "--trace" && a != "--check-cpu" && a != "--reorient")
    {
      ++i;
      continue;
    }
    (a == "--trace" ? tracePhases : a == "--check-cpu" ? checkCpu : reorient) = true;
    for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
    --argc;
  }
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s MESH [RES] [normal|pseudonormal|winding|unsigned] [cpu|cuda|auto] "
                         "[bvh|faithful|bruteforce] [volume|float] [BAND] [PADDING] [RUNS] [--trace] [--check-cpu] [--reorient]\n", argv[0]);
    return 2;
  }
  // DAMAGE:...:PATH, applied from the right (patch10:sub2:m = patches on the subdivided mesh)
  const signquality::DamagedPath input = signquality::parseDamagedPath(argv[1]);
  const std::string& path = input.path;
  const std::string damage = input.label();
  const bool damaged = !input.damages.empty();
  const std::int64_t res = argc > 2 ? std::atoll(argv[2]) : 256;
  const std::string sign = argc > 3 ? argv[3] : "winding";
  const std::string device = argc > 4 ? argv[4] : "auto";
  const std::string accel = argc > 5 ? argv[5] : "bvh";
  const std::string output = argc > 6 ? argv[6] : "volume";
  const float band = argc > 7 ? static_cast<float>(std::atof(argv[7])) : 8.0f;
  const double padding = argc > 8 ? std::atof(argv[8]) : 2.0;
  // which calls to time, in order (fewer on slow cases keep a GPU session short)
  std::vector<std::string> runs;
  {
    std::string list = argc > 9 ? argv[9] : "cold,warm,prepared,prepared";
    for (std::size_t a = 0; a <= list.size();)
    {
      const std::size_t b = std::min(list.find(',', a), list.size());
      if (b > a) runs.push_back(list.substr(a, b - a));
      a = b + 1;
    }
  }

  bench::Stopwatch readClock;
  TriangleMesh mesh = input.load([](const std::string& p) { return loadMesh(p); });
  const double readMs = readClock.ms(); // includes making the damaged variant

  MeshToSdfOptions o;
  o.tracePhases = tracePhases;
  auto signOf = [](const std::string& name) {
    return name == "normal" ? SignMode::Normal
      : name == "pseudonormal" ? SignMode::PseudoNormal
      : name == "unsigned"     ? SignMode::Unsigned
                               : SignMode::WindingNumber;
  };
  o.sign = signOf(sign);
  o.reorientFaces = reorient;
  o.device = device == "cpu" ? Device::Cpu : device == "cuda" ? Device::Cuda : Device::Auto;
  o.accel = accel == "faithful" ? MeshToSdfAccel::Faithful
    : accel == "bruteforce"     ? MeshToSdfAccel::BruteForce
                                : MeshToSdfAccel::Bvh;
  o.bandWidth = band > 0 ? band : std::numeric_limits<float>::infinity();
  const GridGeometry g = fitGridToMesh(mesh, res, padding);

  std::printf("machine: %s\n", bench::machineDescription().c_str());
  std::printf("mesh: %s%s%s (%zu points, %zu triangles), grid %lld x %lld x %lld, sign %s, accel %s, output %s, "
              "band %s%s\n",
    damage.c_str(), damaged ? ":" : "", path.c_str(), mesh.points.size(), mesh.triangles.size(), static_cast<long long>(g.dims[0]),
    static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]), toString(o.sign), toString(o.accel),
    output.c_str(), band > 0 ? bench::fmt(band, 1).c_str() : "none", reorient ? ", faces re-oriented" : "");

  resolveDevice(o.device); // CUDA context creation is not part of the timing
  std::vector<std::vector<std::string>> rows;
  MeshToSdfStats st;
  std::vector<float> out;
  if (output == "float")
  {
    requireMemory(static_cast<std::uint64_t>(g.count()) * 4, "benchmark float grid");
    out.assign(static_cast<std::size_t>(g.count()), 0.0f); // touched before timing
  }
  // cold/warm: the one-call API (prepare + compute); prepared: a
  // MeshToSdfPrepared made once (its time in the "prepare ms" line) and reused
  bench::Stopwatch prepClock;
  const MeshToSdfPrepared prepared = prepareMeshToSdf(mesh, o.sign);
  const double prepareMs = prepClock.ms();
  const MeshToSdfOptions base = o;
  for (const std::string& spec : runs)
  {
    // RUN[@SIGN][@pervoxel][@pageable][@normalspath]
    const std::string run = spec.substr(0, spec.find('@'));
    o = base;
    bool pageable = false;
    for (std::size_t at = spec.find('@'); at != std::string::npos;)
    {
      const std::size_t next = spec.find('@', at + 1);
      const std::string tag = spec.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
      if (tag == "pervoxel")
        o.farBlocks = false;
      else if (tag == "normalspath")
        o.solidsByWinding = false;
      else if (tag == "pageable")
        pageable = true;
      else
        o.sign = signOf(tag);
      at = next;
    }
    detail::meshtosdf_cuda::refusePinnedKeys(pageable);
    std::int64_t expanded = 0, inside = 0;
    double callMs = 0;
    // process CPU time of the call (all threads): robust to a loaded machine
    const std::clock_t cpu0 = std::clock();
    double cpuSeconds = 0;
    // minor page faults of the call (all threads): a store that faults its
    // chunks in anew shows here (the allocator returned the last volume's pages)
    const long faults0 = minorFaults();
    const bool usePrepared = run == "prepared";
    if (output == "float")
    {
      bench::Stopwatch call;
      st = usePrepared ? meshToSdf(prepared, FloatGridView{ out.data(), g }, o)
                       : meshToSdf(mesh, FloatGridView{ out.data(), g }, o);
      callMs = call.ms();
      cpuSeconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
      for (float v : out) inside += v < 0;
    }
    else
    {
      VolumeOptions vo = volumeOptionsOn(g);
      vo.chunkEdge = 32;
      vo.bandWidth = o.bandWidth;
      DictionaryVolume vol(vo);
      bench::Stopwatch call;
      st = usePrepared ? meshToSdf(prepared, vol, o) : meshToSdf(mesh, vol, o);
      callMs = call.ms();
      cpuSeconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
      expanded = vol.expandedChunkCount();
      const SdfKey zero = vol.sdfDictionary().zeroKey();
      for (std::int64_t c = 0; c < vol.chunkCount(); ++c)
      {
        const VoxelBox b = vol.chunkBox(c);
        if (vol.isUniform(c))
        {
          if (vol.uniformValue(c).sdf < zero) inside += b.voxelCount();
          continue;
        }
        for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
          for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
            for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x) inside += vol.get(x, y, z).sdf < zero;
      }
    }
    rows.push_back({ spec, toString(st.device), bench::fmt(readMs, 1), bench::fmt(st.buildSeconds * 1e3, 1),
      bench::fmt(st.distanceSeconds * 1e3, 1), bench::fmt(st.signSeconds * 1e3, 1),
      bench::fmt(st.writeSeconds * 1e3, 1), bench::fmt(callMs, 1), std::to_string(st.windingEvaluations),
      std::to_string(st.windingExact), std::to_string(inside), std::to_string(expanded),
      std::to_string(st.degenerateSkipped), std::to_string(st.farVoxels), bench::fmt(cpuSeconds, 2),
      std::to_string(minorFaults() - faults0) });
  }
  bench::printTable({ "run", "device", "read ms", "build ms", "distance ms", "sign ms", "write ms",
                      "end-to-end ms", "winding evals", "fallback", "inside voxels", "expanded chunks",
                      "degenerate", "far-block voxels", "CPU s", "minor faults" },
    rows);
  std::printf("prepareMeshToSdf: %.1f ms (%d OpenMP threads); the first prepared row includes the upload\n",
    prepareMs, omp_get_max_threads());
  if (st.devicePeakBytes) std::printf("device memory peak: %s\n", formatBytes(st.devicePeakBytes).c_str());
  if (checkCpu && output == "float")
  {
    std::vector<float> cpu(out.size());
    MeshToSdfOptions oc = o;
    oc.device = Device::Cpu;
    bench::Stopwatch call;
    meshToSdf(prepared, FloatGridView{ cpu.data(), g }, oc);
    const double cpuMs = call.ms();
    std::int64_t sign = 0, dist = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i)
    {
      sign += std::signbit(cpu[i]) != std::signbit(out[i]);
      dist += std::fabs(cpu[i]) != std::fabs(out[i]);
    }
    std::printf("cpu check: %lld sign and %lld distance differences of %lld voxels (%s run vs cpu; cpu %.1f ms)\n",
      static_cast<long long>(sign), static_cast<long long>(dist), static_cast<long long>(cpu.size()),
      toString(st.device), cpuMs);
  }
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
