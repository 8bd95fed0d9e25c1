// Sign-quality study (docs/SIGN_QUALITY.md): the fraction
// of voxels whose sign is wrong, per sign mode, on closed, open and damaged
// meshes. Modes: Algorithm 1 (SignMode::Normal), Normal + SVF1, +SVF2, +SVF3,
// +SVF4 (the filters' defaults: threshold 2, axis x, boundary Outside),
// PseudoNormal and WindingNumber. All fields have no band (the SVFs need the
// magnitudes; WindingNumber, the reference, has band 4), voxel units, a grid fitted to the mesh with 2 voxels of padding.
//
// References, stated per column:
//  * "vs WN": the WindingNumber mode of meshToSdf (exact, docs/MESH_TO_SDF.md)
//    on every voxel of the grid;
//  * "vs BF": an independent brute-force winding number (SignQualityMeshes.h,
//    long double solid angles over all triangles) on a random subsample of
//    voxels, at the resolutions given with --bf-res (it costs samples x triangles).
// With --no-wn the WindingNumber mode is not run (on meshes with many
// mis-oriented faces, flip10/dup20, every such edge counts as boundary and it
// is very slow): every column is then measured against the brute-force
// reference on the subsample only, at every resolution, and "far" uses the
// exact unsigned distance of the Normal mode (no band) instead of the reference's.
// "far" counts only voxels farther than 1 voxel from the surface; "all" counts all.
//
// usage: bench_sign_quality [--res 128,256] [--bf-res 128] [--samples 4000] [--no-wn]
//          [--dump DIR --dump-mesh NAME --dump-res R] SPEC...
// SPEC is a mesh path, or DAMAGE:PATH with DAMAGE one of holes (8 round holes),
// flip10 (10 % of the faces reversed), dup20 (20 % of the faces duplicated),
// pair (the mesh and a shifted copy, intersecting). --dump writes the fields of
// the meshes NAME,NAME2,... (the SPEC's label, e.g. holes-armadillo) at resolution R as raw
// float32 files for scripts/sign_quality_images.py.
#include "BenchCommon.h"
#include "SignQualityMeshes.h"

#include "lvdif/Error.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/SignVoxelFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{

struct Mode
{
  std::string name;  // table label
  std::string file;  // dump file suffix
  std::vector<float> field;
  double seconds = 0;
  std::int64_t flips = 0;
};

std::vector<std::int64_t> parseList(const std::string& s)
{
  std::vector<std::int64_t> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(std::atoll(item.c_str()));
  return out;
}

std::string baseName(const std::string& path)
{
  std::string b = path.substr(path.find_last_of('/') + 1);
  return b.substr(0, b.find('.'));
}

// Loads SPEC, applies its damage; label names it in the tables.
TriangleMesh loadSpec(const std::string& spec, std::string& label)
{
  const auto colon = spec.find(':');
  const std::string damage = colon == std::string::npos ? "" : spec.substr(0, colon);
  const std::string path = colon == std::string::npos ? spec : spec.substr(colon + 1);
  const TriangleMesh m = loadMesh(path);
  label = damage.empty() ? baseName(path) : damage + "-" + baseName(path);
  if (damage.empty()) return m;
  if (damage == "holes") return signquality::punchHoles(m, 8, 0.03);
  if (damage == "flip10") return signquality::flipFaces(m, 0.10);
  if (damage == "dup20") return signquality::duplicateFaces(m, 0.20);
  if (damage == "pair") return signquality::intersectingPair(m);
  throw Error(ErrorCode::InvalidArgument, "unknown damage '" + damage + "' (holes, flip10, dup20, pair)");
}

double pct(std::int64_t n, std::int64_t d) { return d ? 100.0 * double(n) / double(d) : 0.0; }

} // namespace

static int benchMain(int argc, char** argv)
{
  std::vector<std::int64_t> resolutions{ 128, 256 }, bfResolutions{ 128 };
  std::int64_t samples = 4000;
  std::string dumpDir, dumpMesh;
  std::int64_t dumpRes = 128;
  bool noWn = false;
  std::vector<std::string> specs;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--res" && hasValue) resolutions = parseList(argv[++i]);
    else if (a == "--bf-res" && hasValue) bfResolutions = parseList(argv[++i]);
    else if (a == "--samples" && hasValue) samples = std::atoll(argv[++i]);
    else if (a == "--dump" && hasValue) dumpDir = argv[++i];
    else if (a == "--dump-mesh" && hasValue) dumpMesh = argv[++i];
    else if (a == "--dump-res" && hasValue) dumpRes = std::atoll(argv[++i]);
    else if (a == "--no-wn") noWn = true;
    else specs.push_back(a);
  }
  if (specs.empty())
  {
    std::fprintf(stderr, "usage: %s [--res 128,256] [--bf-res 128] [--samples N] [--no-wn] [--dump DIR --dump-mesh NAME "
                         "--dump-res R] [holes:|flip10:|dup20:|pair:]MESH...\n", argv[0]);
    return 2;
  }
  std::printf("machine: %s\n", bench::machineDescription().c_str());
  std::vector<std::vector<std::string>> summaryFar, summaryAll, summaryBf;
  const std::vector<std::string> modeNames{ "Normal (Alg. 1)", "SVF1", "+SVF2", "+SVF3", "+SVF4", "PseudoNormal",
    "WindingNumber" };
  for (const std::string& spec : specs)
  {
    std::string label;
    const TriangleMesh mesh = loadSpec(spec, label);
    for (const std::int64_t res : resolutions)
    {
      const GridGeometry g = fitGridToMesh(mesh, res, 2.0);
      const auto n = static_cast<std::size_t>(g.count());
      MeshToSdfOptions o;
      o.device = Device::Cpu;
      std::vector<Mode> modes(7);
      const char* files[7] = { "normal", "svf1", "svf12", "svf123", "svf1234", "pseudo", "winding" };
      for (int m = 0; m < 7; ++m) modes[m].name = modeNames[m], modes[m].file = files[m];
      MeshToSdfStats st;
      auto compute = [&](Mode& md, SignMode s) {
        md.field.assign(n, 0.0f);
        o.sign = s;
        // Only WindingNumber profits from a band (its distance queries stop there); the
        // reference needs only signs and |d| > 1, so it gets band 4.
        o.bandWidth = s == SignMode::WindingNumber ? 4.0f : std::numeric_limits<float>::infinity();
        bench::Stopwatch w;
        st = meshToSdf(mesh, FloatGridView{ md.field.data(), g }, o);
        md.seconds = w.seconds();
      };
      if (!noWn) compute(modes[6], SignMode::WindingNumber);
      compute(modes[0], SignMode::Normal);
      compute(modes[5], SignMode::PseudoNormal);
      for (int k = 1; k <= 4; ++k)
      {
        modes[k].field = modes[0].field;
        SignVoxelFilterParams p;
        p.filters = svfCumulative(k);
        p.device = Device::Cpu;
        bench::Stopwatch w;
        const SignVoxelFilterStats fs = signVoxelFilter(FloatGridView{ modes[k].field.data(), g }, p);
        modes[k].seconds = w.seconds();
        modes[k].flips = fs.totalFlips();
      }
      // ref: the full-grid reference (empty with --no-wn); dist: whose |d| decides "far"
      // (the exact distance of either field: WindingNumber's within its band 4, Normal's everywhere).
      const std::vector<float>& ref = modes[6].field;
      const std::vector<float>& dist = noWn ? modes[0].field : ref;
      std::int64_t farCount = 0;
      for (float v : dist) farCount += std::fabs(v) > 1.0f;

      // Brute-force reference on a subsample (same voxels for every mode).
      const bool bf = noWn || std::find(bfResolutions.begin(), bfResolutions.end(), res) != bfResolutions.end();
      std::vector<std::int64_t> pick;
      std::vector<signed char> bfInside;
      if (bf)
      {
        std::mt19937_64 rng(42);
        std::uniform_int_distribution<std::int64_t> u(0, g.count() - 1);
        for (std::int64_t i = 0; i < samples; ++i) pick.push_back(u(rng));
        bfInside.assign(pick.size(), 0);
#pragma omp parallel for schedule(dynamic, 8)
        for (std::int64_t s = 0; s < static_cast<std::int64_t>(pick.size()); ++s)
        {
          const std::int64_t idx = pick[s];
          const std::int64_t x = idx % g.dims[0], y = (idx / g.dims[0]) % g.dims[1], z = idx / (g.dims[0] * g.dims[1]);
          const std::array<double, 3> p{ g.origin[0] + x * g.spacing[0], g.origin[1] + y * g.spacing[1],
            g.origin[2] + z * g.spacing[2] };
          bfInside[s] = std::fabs(signquality::bruteWinding(mesh, p)) >= 0.5L;
        }
      }
      std::printf("\n%s at %lld: %zu triangles, %zu boundary edges, %zu degenerate skipped, grid %lldx%lldx%lld, "
                  "%.2f %% of the voxels farther than 1 voxel\n",
        label.c_str(), static_cast<long long>(res), st.triangles, st.boundaryEdges, st.degenerateSkipped,
        static_cast<long long>(g.dims[0]), static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]),
        pct(farCount, g.count()));
      std::vector<std::vector<std::string>> rows;
      std::vector<std::string> rowFar{ label, std::to_string(res) }, rowAll = rowFar, rowBf = rowFar;
      for (const Mode& md : modes)
      {
        if (noWn)
        {
          // Every column against the brute force on the subsample: far and all.
          std::string farCell = "-", allCell = "-", farPct = "-", allPct = "-";
          if (!md.field.empty())
          {
            std::int64_t wf = 0, nf = 0, wa = 0;
            for (std::size_t s = 0; s < pick.size(); ++s)
            {
              const auto idx = static_cast<std::size_t>(pick[s]);
              const bool wrong = (md.field[idx] < 0) != (bfInside[s] != 0);
              wa += wrong;
              if (std::fabs(dist[idx]) <= 1.0f) continue;
              ++nf;
              wf += wrong;
            }
            const auto na = static_cast<std::int64_t>(pick.size());
            farPct = bench::fmt(pct(wf, nf), 3);
            allPct = bench::fmt(pct(wa, na), 3);
            farCell = std::to_string(wf) + "/" + std::to_string(nf);
            allCell = std::to_string(wa) + "/" + std::to_string(na);
          }
          rows.push_back({ md.name, farPct, farCell, allPct, allCell, md.flips ? std::to_string(md.flips) : "-",
            md.field.empty() ? "not run" : bench::fmt(md.seconds, 2) });
          rowFar.push_back(farPct);
          rowAll.push_back(allPct);
          rowBf.push_back(farCell);
          continue;
        }
        std::int64_t wrongFar = 0, wrongAll = 0;
        for (std::size_t i = 0; i < n; ++i)
        {
          const bool wrong = (md.field[i] < 0) != (ref[i] < 0);
          wrongAll += wrong;
          wrongFar += wrong && std::fabs(ref[i]) > 1.0f;
        }
        std::string bfCell = "-";
        if (bf)
        {
          std::int64_t wf = 0, nf = 0;
          for (std::size_t s = 0; s < pick.size(); ++s)
          {
            const auto idx = static_cast<std::size_t>(pick[s]);
            if (std::fabs(ref[idx]) <= 1.0f) continue;
            ++nf;
            wf += (md.field[idx] < 0) != (bfInside[s] != 0);
          }
          bfCell = std::to_string(wf) + "/" + std::to_string(nf) + " (" + bench::fmt(pct(wf, nf), 2) + " %)";
        }
        rows.push_back({ md.name, bench::fmt(pct(wrongFar, farCount), 3), std::to_string(wrongFar),
          bench::fmt(pct(wrongAll, g.count()), 3), std::to_string(wrongAll), bfCell,
          md.flips ? std::to_string(md.flips) : "-", bench::fmt(md.seconds, 2) });
        rowFar.push_back(bench::fmt(pct(wrongFar, farCount), 3));
        rowAll.push_back(bench::fmt(pct(wrongAll, g.count()), 3));
        rowBf.push_back(bfCell);
      }
      if (noWn)
        bench::printTable({ "mode", "far wrong % (vs BF samples)", "far wrong / sampled far",
                            "all wrong % (vs BF samples)", "all wrong / sampled", "SVF flips", "seconds" },
          rows);
      else
        bench::printTable({ "mode", "far wrong % (vs WN)", "far wrong", "all wrong % (vs WN)", "all wrong",
                            "far wrong vs BF samples", "SVF flips", "seconds" },
          rows);
      summaryFar.push_back(rowFar);
      summaryAll.push_back(rowAll);
      if (bf) summaryBf.push_back(rowBf);
      std::fflush(stdout);

      if (!dumpDir.empty() && ("," + dumpMesh + ",").find("," + label + ",") != std::string::npos && res == dumpRes)
      {
        const std::string stem = dumpDir + "/" + label + "_" + std::to_string(res);
        std::ofstream hdr(stem + ".txt");
        hdr << g.dims[0] << " " << g.dims[1] << " " << g.dims[2] << "\n"
            << g.origin[0] << " " << g.origin[1] << " " << g.origin[2] << "\n"
            << g.spacing[0] << " " << g.spacing[1] << " " << g.spacing[2] << "\n";
        for (const Mode& md : modes)
        {
          std::ofstream f(stem + "_" + md.file + ".f32", std::ios::binary);
          f.write(reinterpret_cast<const char*>(md.field.data()), static_cast<std::streamsize>(n * sizeof(float)));
        }
        std::printf("dumped %s_*.f32\n", stem.c_str());
      }
    }
  }
  std::vector<std::string> header{ "mesh", "res" };
  header.insert(header.end(), modeNames.begin(), modeNames.end());
  const std::string refName = noWn ? "brute-force winding number on " + std::to_string(samples) +
      " random voxels per grid (--no-wn: WindingNumber not run)" : "WindingNumber on every voxel";
  std::printf("\nSummary: wrong-sign %% of the voxels farther than 1 voxel from the surface, reference: %s\n",
    refName.c_str());
  bench::printTable(header, summaryFar);
  std::printf("\nSummary: wrong-sign %% of all voxels, reference: %s\n", refName.c_str());
  bench::printTable(header, summaryAll);
  if (!summaryBf.empty())
  {
    std::printf("\nSummary: wrong / sampled far voxels, reference: brute-force winding number (long double) on %lld "
                "random voxels\n", static_cast<long long>(samples));
    bench::printTable(header, summaryBf);
  }
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
