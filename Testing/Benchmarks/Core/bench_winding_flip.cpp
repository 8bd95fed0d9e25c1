// Winding-number sign on meshes with reversed faces: process CPU
// seconds of meshToSdf with SignMode::WindingNumber against PseudoNormal in
// the same process (the ratio is the figure to compare across machines), the
// counts of per-voxel evaluations and full exact sums, and a check of the
// WindingNumber signs against an independent brute-force winding number
// (long double solid angles, SignQualityMeshes.h) on a random subsample of
// voxels farther than 1 voxel from the mesh.
//
// usage: bench_winding_flip [--res 64,128] [--samples 1000] SPEC...
// SPEC is a mesh path, or DAMAGE:PATH with DAMAGE flipNN (NN % of the faces
// reversed, signquality::flipFaces, seed 2: flip10 is bench_sign_quality's),
// any damage of signquality::damaged (SignQualityMeshes.h: flipNN, patchNN,
// dupNN, duprevNN, holes[NN], finsNN, pair). "WN/clean WN": the WindingNumber
// CPU time against the undamaged mesh's on a grid of the same size, same process.
// A line "signs: LABEL RES inside N hash H" fingerprints each WindingNumber
// sign field (compare two builds: equal hashes, the same signs).
#include "BenchCommon.h"
#include "SignQualityMeshes.h"

#include "lvdif/Error.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
double cpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

TriangleMesh loadSpec(const std::string& spec, std::string& label, std::string* cleanPath = nullptr)
{
  const auto colon = spec.find(':');
  const std::string damage = colon == std::string::npos ? "" : spec.substr(0, colon);
  const std::string path = colon == std::string::npos ? spec : spec.substr(colon + 1);
  std::string base = path.substr(path.find_last_of('/') + 1);
  base = base.substr(0, base.find('.'));
  label = damage.empty() ? base : damage + "-" + base;
  if (cleanPath) *cleanPath = path;
  return signquality::damaged(loadMesh(path), damage);
}

std::vector<double> parseList(const std::string& s)
{
  std::vector<double> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(std::atof(item.c_str()));
  return out;
}
} // namespace

static int benchMain(int argc, char** argv)
{
  std::vector<double> resolutions{ 64, 128 };
  std::int64_t samples = 1000;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--res" && i + 1 < argc) resolutions = parseList(argv[++i]);
    else if (a == "--samples" && i + 1 < argc) samples = std::atoll(argv[++i]);
    else meshes.push_back(a);
  }
  if (meshes.empty())
  {
    std::fprintf(stderr, "usage: %s [--res 64,128] [--samples N] [flipNN:|dupNN:|holes:|pair:]MESH...\n", argv[0]);
    return 2;
  }
  std::printf("machine: %s\n", bench::machineDescription().c_str());
  std::vector<std::vector<std::string>> rows;
  // the undamaged mesh's WindingNumber CPU seconds per (path, res), same process
  std::map<std::pair<std::string, std::int64_t>, double> cleanCpu;
  auto windingCpu = [](const TriangleMesh& m, const GridGeometry& g, std::vector<float>& buf) {
    MeshToSdfOptions o;
    o.device = Device::Cpu;
    o.sign = SignMode::WindingNumber;
    o.bandWidth = 4.0f;
    const double c0 = cpuSeconds();
    meshToSdf(m, FloatGridView{ buf.data(), g }, o);
    return cpuSeconds() - c0;
  };
  for (const std::string& spec : meshes)
  {
    std::string label, path;
    const TriangleMesh mesh = loadSpec(spec, label, &path);
    {
      for (double resD : resolutions)
      {
        const auto res = static_cast<std::int64_t>(resD);
        const GridGeometry g = fitGridToMesh(mesh, res, 2.0);
        std::vector<float> pn(static_cast<std::size_t>(g.count())), wn(pn.size());
        MeshToSdfOptions o;
        o.device = Device::Cpu;
        o.sign = SignMode::PseudoNormal;
        o.bandWidth = 4.0f;
        double c0 = cpuSeconds();
        bench::Stopwatch w;
        meshToSdf(mesh, FloatGridView{ pn.data(), g }, o);
        const double pnCpu = cpuSeconds() - c0, pnWall = w.seconds();
        o.sign = SignMode::WindingNumber;
        c0 = cpuSeconds();
        w.reset();
        const MeshToSdfStats st = meshToSdf(mesh, FloatGridView{ wn.data(), g }, o);
        const double wnCpu = cpuSeconds() - c0, wnWall = w.seconds();
        // the clean mesh on the grid fitted to it, so the same grid size
        const auto key = std::make_pair(path, res);
        if (!cleanCpu.count(key))
        {
          const TriangleMesh clean = loadMesh(path);
          const GridGeometry cg = fitGridToMesh(clean, res, 2.0);
          std::vector<float> buf(static_cast<std::size_t>(cg.count()));
          cleanCpu[key] = windingCpu(clean, cg, buf);
        }
        // brute-force check on a subsample of far voxels
        std::mt19937_64 rng(42);
        std::uniform_int_distribution<std::int64_t> u(0, g.count() - 1);
        std::vector<std::int64_t> pick;
        while (static_cast<std::int64_t>(pick.size()) < samples && samples > 0)
        {
          const std::int64_t idx = u(rng);
          if (std::fabs(wn[static_cast<std::size_t>(idx)]) > 1.0f) pick.push_back(idx);
        }
        std::int64_t wrong = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : wrong)
        for (std::int64_t s = 0; s < samples; ++s)
        {
          const std::int64_t idx = pick[static_cast<std::size_t>(s)];
          const std::int64_t x = idx % g.dims[0], y = (idx / g.dims[0]) % g.dims[1], z = idx / (g.dims[0] * g.dims[1]);
          const std::array<double, 3> p{ g.origin[0] + x * g.spacing[0], g.origin[1] + y * g.spacing[1],
            g.origin[2] + z * g.spacing[2] };
          const bool inside = std::fabs(signquality::bruteWinding(mesh, p)) >= 0.5L;
          wrong += (wn[static_cast<std::size_t>(idx)] < 0) != inside;
        }
        // the sign field's fingerprint (FNV-1a over the voxels' inside bits): equal
        // before and after a change of the decision means the same signs everywhere
        std::uint64_t signHash = 1469598103934665603ull;
        std::int64_t insideCount = 0;
        for (const float v : wn)
        {
          const bool in = std::signbit(v);
          insideCount += in;
          signHash = (signHash ^ static_cast<std::uint64_t>(in)) * 1099511628211ull;
        }
        std::printf("signs: %s %lld inside %lld hash %016llx\n", label.c_str(), static_cast<long long>(res),
          static_cast<long long>(insideCount), static_cast<unsigned long long>(signHash));
        rows.push_back({ label, std::to_string(res),
          std::to_string(st.triangles), std::to_string(st.boundaryEdges), bench::fmt(pnCpu, 2), bench::fmt(wnCpu, 2),
          bench::fmt(wnCpu / pnCpu, 2), bench::fmt(wnCpu / cleanCpu[key], 2),
          bench::fmt(pnWall, 2), bench::fmt(wnWall, 2), bench::fmt(st.signSeconds, 2),
          std::to_string(st.windingEvaluations), std::to_string(st.windingFullSums), std::to_string(st.windingExact),
          std::to_string(wrong) + "/" + std::to_string(samples) });
        std::printf("row: %s\n", [&] {
          std::string line;
          for (const auto& c : rows.back()) line += c + " | ";
          return line;
        }().c_str());
        std::fflush(stdout);
      }
    }
  }
  bench::printTable({ "mesh", "res", "tris", "boundary edges", "PN cpu s", "WN cpu s", "WN/PN", "WN/clean WN", "PN wall s", "WN wall s",
                      "WN sign s", "evaluations", "full sums", "ambig. rows vox", "WN vs BF wrong (far)" },
    rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
