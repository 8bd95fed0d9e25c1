// Nearest-triangle queries of mesh to SDF, CPU: the binary Bvh (the GPU's
// tree) against the CPU NearestIndex (one point, and RowPoints points of a row
// per traversal as Engine::distanceRow uses it), on every voxel of a fitted grid, rows in
// parallel with the previous voxel's triangle as hint (as Engine::distanceRow
// does), in one process. Checks that both give the same triangle and the same
// double distance on every voxel (and, with CHECK=1, brute force on a sample).
// usage: bench_mesh_to_sdf_nearest MESH [RES=128] [THREADS=2] [CHECK=0]
#include "BenchCommon.h"

#include "../../../Core/MeshToSdf/src/MeshToSdfNearest.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
template <typename Q>
double sweep(const GridGeometry& g, Q&& query, std::vector<double>& d2, std::vector<std::int32_t>& tri)
{
  bench::Stopwatch w;
  const std::int64_t rows = g.dims[1] * g.dims[2];
#pragma omp parallel for schedule(dynamic, 2)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const std::int64_t j = r % g.dims[1], k = r / g.dims[1];
    std::int32_t hint = -1;
    for (std::int64_t i = 0; i < g.dims[0]; ++i)
    {
      const V3 p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
      const NearestResult n = query(p, hint);
      hint = n.tri;
      d2[static_cast<std::size_t>(r * g.dims[0] + i)] = n.dist2;
      tri[static_cast<std::size_t>(r * g.dims[0] + i)] = n.tri;
    }
  }
  return w.seconds();
}
double rowSweep(const GridGeometry& g, const NearestIndex& index, std::vector<double>& d2, std::vector<std::int32_t>& tri)
{
  bench::Stopwatch w;
  const std::int64_t rows = g.dims[1] * g.dims[2];
  const std::int64_t nx = g.dims[0];
  // blocks of 8 consecutive rows: the row below seeds each point (as computeBox does)
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t r0 = 0; r0 < rows; r0 += 8)
  {
    for (std::int64_t r = r0; r < std::min(rows, r0 + 8); ++r)
    {
      const std::int64_t j = r % g.dims[1], k = r / g.dims[1];
      const bool below = r > r0 && j > 0;
      std::int32_t hint = -1;
      for (std::int64_t i = 0; i < nx; i += NearestIndex::RowPoints)
      {
        const int n = static_cast<int>(std::min<std::int64_t>(NearestIndex::RowPoints, nx - i));
        V3 p[NearestIndex::RowPoints];
        NearestResult res[NearestIndex::RowPoints];
        for (int q = 0; q < n; ++q)
          p[q] = { g.origin[0] + (i + q) * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
        index.nearestRow(p, n, hint, below ? tri.data() + (r - 1) * nx + i : nullptr, res);
        hint = res[n - 1].tri;
        for (int q = 0; q < n; ++q)
        {
          d2[static_cast<std::size_t>(r * nx + i + q)] = res[q].dist2;
          tri[static_cast<std::size_t>(r * nx + i + q)] = res[q].tri;
        }
      }
    }
  }
  return w.seconds();
}
} // namespace

static int benchMain(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s MESH [RES=128] [THREADS=2] [CHECK=0]\n", argv[0]);
    return 2;
  }
  const std::int64_t res = argc > 2 ? std::atoll(argv[2]) : 128;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  const bool check = argc > 4 && std::atoi(argv[4]) != 0;
  omp_set_num_threads(threads);
  const TriangleMesh mesh = loadMesh(argv[1]);
  const GridGeometry g = fitGridToMesh(mesh, res, 2.0);
  bench::Stopwatch w;
  const PreparedMesh pm = prepareMesh(mesh);
  const double prepSec = w.seconds();
  w.reset();
  const Bvh bvh(pm.tris);
  const double bvhSec = w.seconds();
  w.reset();
  const NearestIndex index(pm.tris);
  const double indexSec = w.seconds();
  std::printf("machine: %s; %d threads\n", bench::machineDescription().c_str(), threads);
  std::printf("mesh %s: %zu triangles; grid %lldx%lldx%lld; prepare %.3f s, Bvh build %.3f s, NearestIndex build "
              "%.3f s (%zu nodes, depth %zu)\n",
    argv[1], pm.tris.size(), (long long)g.dims[0], (long long)g.dims[1], (long long)g.dims[2], prepSec, bvhSec,
    indexSec, index.nodes().size(), index.depth());
  const std::size_t n = static_cast<std::size_t>(g.count());
  std::vector<double> d2a(n), d2b(n);
  std::vector<std::int32_t> ta(n), tb(n);
  std::vector<double> d2c(n);
  std::vector<std::int32_t> tc(n);
  const double tNew = sweep(g, [&](V3 p, std::int32_t h) { return index.nearest(p, h, 1e300); }, d2b, tb);
  const double tRow = rowSweep(g, index, d2c, tc);
  const double tOld = sweep(g, [&](V3 p, std::int32_t h) { return bvh.nearest(p, h, 1e300); }, d2a, ta);
  std::int64_t diff = 0;
  for (std::size_t i = 0; i < n; ++i) diff += d2a[i] != d2b[i] || ta[i] != tb[i] || d2a[i] != d2c[i] || ta[i] != tc[i];
  std::printf("Bvh %.3f s, NearestIndex::nearest %.3f s (x%.2f), NearestIndex::nearestRow %.3f s (x%.2f); voxels "
              "differing: %lld of %zu\n",
    tOld, tNew, tOld / tNew, tRow, tOld / tRow, (long long)diff, n);
  if (check)
  {
    std::int64_t bad = 0, tested = 0;
    for (std::size_t i = 0; i < n; i += 997)
    {
      const std::int64_t x = static_cast<std::int64_t>(i) % g.dims[0], r = static_cast<std::int64_t>(i) / g.dims[0];
      const V3 p{ g.origin[0] + x * g.spacing[0], g.origin[1] + (r % g.dims[1]) * g.spacing[1],
        g.origin[2] + (r / g.dims[1]) * g.spacing[2] };
      double best = 1e300;
      std::int32_t bt = -1;
      for (std::size_t t = 0; t < pm.tris.size(); ++t)
      {
        const Tri& tr = pm.tris[t];
        const V3 d = closestPointOnTriangle(p, tr.v[0], tr.v[1], tr.v[2]).point - p;
        if (dot(d, d) < best) best = dot(d, d), bt = static_cast<std::int32_t>(t);
      }
      bad += best != d2b[i] || bt != tb[i];
      ++tested;
    }
    std::printf("brute force on %lld voxels: %lld differ\n", (long long)tested, (long long)bad);
  }
  return diff == 0 ? 0 : 1;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
