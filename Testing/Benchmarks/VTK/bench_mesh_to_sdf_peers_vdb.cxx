// Mesh to SDF on the CPU against its peers, in one process: our lvdif::meshToSdf (BVH; WindingNumber and PseudoNormal
// signs) vs OpenVDB tools::meshToSignedDistanceField producing the same dense
// field (exterior band = the largest distance in the grid, interior band
// unbounded, then copied into a dense x-fastest array), and vs VTK's
// vtkImplicitPolyDataDistance evaluated in a plain loop on ONE thread (it is
// not thread-safe; at a lower resolution, timed per voxel and extrapolated:
// it is far slower).
// Every field is compared with ours: max |distance difference| (voxels) and
// the voxels whose sign differs from our WindingNumber field.
// Then the sign check: OpenVDB's level set of an OPEN mesh (the
// lvdif bunny, open base), wrong-sign fraction against our WindingNumber.
//
// usage: bench_mesh_to_sdf_peers_vdb MESH [RES=256] [VTKRES=64] [THREADS=2] [OPENMESH]
#include "BenchCommon.h"

#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImplicitPolyDataDistance.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{

struct Compare
{
  double maxDiff = 0;          // voxels, over voxels farther than 1 voxel from the surface... and all
  std::int64_t signWrongFar = 0, signWrongAll = 0, far = 0;
};

// a: the field tested, ref: our WindingNumber field (the sign reference), both in voxel units.
Compare compare(const std::vector<float>& a, const std::vector<float>& ref)
{
  Compare c;
  for (std::size_t i = 0; i < ref.size(); ++i)
  {
    c.maxDiff = std::max(c.maxDiff, double(std::fabs(std::fabs(a[i]) - std::fabs(ref[i]))));
    const bool wrong = (a[i] < 0) != (ref[i] < 0);
    const bool far = std::fabs(ref[i]) > 1.0f;
    c.far += far;
    c.signWrongAll += wrong;
    c.signWrongFar += wrong && far;
  }
  return c;
}

std::string pct(std::int64_t n, std::int64_t d) { return bench::fmt(d ? 100.0 * double(n) / double(d) : 0, 3) + " %"; }

// OpenVDB's signed distance field of the mesh on our grid (index space = our
// voxel indices), densely copied; returns the seconds of meshToVolume and of the copy.
std::vector<float> openvdbDense(const TriangleMesh& mesh, const GridGeometry& g, float exBand, float inBand,
  double& volumeSec, double& copySec, std::size_t& activeVoxels)
{
  auto xform = openvdb::math::Transform::createLinearTransform(g.spacing[0]);
  xform->postTranslate(openvdb::Vec3d(g.origin[0], g.origin[1], g.origin[2]));
  std::vector<openvdb::Vec3s> pts;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  for (const auto& p : mesh.points) pts.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles) tris.emplace_back(t[0], t[1], t[2]);
  bench::Stopwatch w;
  auto grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(*xform, pts, tris, quads, exBand, inBand);
  volumeSec = w.seconds();
  activeVoxels = grid->activeVoxelCount();
  w.reset();
  const openvdb::CoordBBox box(openvdb::Coord(0, 0, 0),
    openvdb::Coord(int(g.dims[0] - 1), int(g.dims[1] - 1), int(g.dims[2] - 1)));
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, out.data());
  openvdb::tools::copyToDense(*grid, dense);
  copySec = w.seconds();
  const float toVoxel = static_cast<float>(1.0 / g.spacing[0]);
  for (float& v : out) v *= toVoxel; // OpenVDB stores world units
  return out;
}

std::vector<float> ours(const TriangleMesh& mesh, const GridGeometry& g, SignMode s, double& sec, float band)
{
  std::vector<float> out(static_cast<std::size_t>(g.count()), 0.0f);
  MeshToSdfOptions o;
  o.sign = s;
  o.device = Device::Cpu;
  o.bandWidth = band;
  bench::Stopwatch w;
  meshToSdf(mesh, FloatGridView{ out.data(), g }, o);
  sec = w.seconds();
  return out;
}

} // namespace

static int benchMain(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s MESH [RES=256] [VTKRES=64] [THREADS=2] [OPEN_MESH]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const std::int64_t res = argc > 2 ? std::atoll(argv[2]) : 256;
  const std::int64_t vtkRes = argc > 3 ? std::atoll(argv[3]) : 64;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
  const std::string openPath = argc > 5 ? argv[5] : "";
  omp_set_num_threads(threads);
  tbb::global_control tbbThreads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  vtkSMPTools::Initialize(threads);
  openvdb::initialize();
  const float inf = std::numeric_limits<float>::infinity();
  const TriangleMesh mesh = loadMesh(path);
  const GridGeometry g = fitGridToMesh(mesh, res, 2.0);
  std::printf("machine: %s; OpenMP %d threads, TBB (OpenVDB) %d, vtkSMPTools backend %s %d threads\n",
    bench::machineDescription().c_str(), threads, threads, vtkSMPTools::GetBackend(),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("mesh %s: %zu points, %zu triangles; grid %lldx%lldx%lld (%lld voxels)\n", path.c_str(),
    mesh.points.size(), mesh.triangles.size(), (long long)g.dims[0], (long long)g.dims[1], (long long)g.dims[2],
    (long long)g.count());

  double tWn = 0, tPn = 0, tWnBand = 0;
  // process CPU time (all threads) beside the wall time: on a shared machine
  // it is far less sensitive to the other processes' load
  auto cpuNow = [] { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; };
  double c0 = cpuNow();
  const std::vector<float> wn = ours(mesh, g, SignMode::WindingNumber, tWn, inf);
  const double cpuWn = cpuNow() - c0;
  c0 = cpuNow();
  const std::vector<float> pn = ours(mesh, g, SignMode::PseudoNormal, tPn, inf);
  const double cpuPn = cpuNow() - c0;
  ours(mesh, g, SignMode::WindingNumber, tWnBand, 3.0f);
  float maxDist = 0;
  for (float v : wn) maxDist = std::max(maxDist, std::fabs(v));
  // OpenVDB: exterior band just covering the grid's farthest voxel; interior unbounded (fills it all).
  const float exBand = std::ceil(maxDist) + 1.0f;
  double vdbSec = 0, vdbCopy = 0, vdbNbSec = 0, vdbNbCopy = 0;
  std::size_t active = 0, activeNb = 0;
  c0 = cpuNow();
  const std::vector<float> vdb = openvdbDense(mesh, g, exBand, inf, vdbSec, vdbCopy, active);
  const double cpuVdb = cpuNow() - c0;
  openvdbDense(mesh, g, 3.0f, 3.0f, vdbNbSec, vdbNbCopy, activeNb);
  // vtkImplicitPolyDataDistance at vtkRes (per voxel, extrapolated), with ours at the same resolution.
  const GridGeometry gv = fitGridToMesh(mesh, vtkRes, 2.0);
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> vp;
  vtkNew<vtkCellArray> cells;
  for (const auto& p : mesh.points) vp->InsertNextPoint(p[0], p[1], p[2]);
  for (const auto& t : mesh.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    cells->InsertNextCell(3, ids);
  }
  pd->SetPoints(vp);
  pd->SetPolys(cells);
  // vtkImplicitPolyDataDistance is not thread-safe (its locator and cell
  // scratch are shared): vtkSampleFunction's SMP threads crashed it once
  // ("realloc(): invalid next size"), so it is sampled here in a plain loop
  // on ONE thread, on the same points vtkSampleFunction would use.
  bench::Stopwatch wv;
  vtkNew<vtkImplicitPolyDataDistance> ipd;
  ipd->SetInput(pd);
  std::vector<float> vtkField(static_cast<std::size_t>(gv.count()));
  for (std::int64_t k = 0, i = 0; k < gv.dims[2]; ++k)
    for (std::int64_t j = 0; j < gv.dims[1]; ++j)
      for (std::int64_t x = 0; x < gv.dims[0]; ++x, ++i)
      {
        double q[3] = { gv.origin[0] + x * gv.spacing[0], gv.origin[1] + j * gv.spacing[1],
          gv.origin[2] + k * gv.spacing[2] };
        vtkField[static_cast<std::size_t>(i)] = static_cast<float>(ipd->EvaluateFunction(q) / gv.spacing[0]);
      }
  const double vtkSec = wv.seconds();
  double tWnLow = 0;
  const std::vector<float> wnLow = ours(mesh, gv, SignMode::WindingNumber, tWnLow, inf);

  const Compare cPn = compare(pn, wn), cVdb = compare(vdb, wn), cVtk = compare(vtkField, wnLow);
  const double perVoxelVtk = vtkSec / double(gv.count());
  const double vtkExtrap = perVoxelVtk * double(g.count());
  std::vector<std::vector<std::string>> rows;
  rows.push_back({ "ours WindingNumber (BVH), no band", bench::fmt(tWn, 3), "1.00", "reference", "reference",
    "reference", "-" });
  rows.push_back({ "ours PseudoNormal (BVH), no band", bench::fmt(tPn, 3), bench::fmt(tPn / tWn, 2),
    bench::fmt(cPn.maxDiff, 4), pct(cPn.signWrongFar, cPn.far), pct(cPn.signWrongAll, g.count()), "-" });
  rows.push_back({ "OpenVDB meshToSignedDistanceField (ex " + bench::fmt(exBand, 0) + ", in inf) + dense copy",
    bench::fmt(vdbSec + vdbCopy, 3) + " (" + bench::fmt(vdbCopy, 3) + " copy)", bench::fmt((vdbSec + vdbCopy) / tWn, 2),
    bench::fmt(cVdb.maxDiff, 4), pct(cVdb.signWrongFar, cVdb.far), pct(cVdb.signWrongAll, g.count()),
    std::to_string(active) + " active" });
  rows.push_back({ "ours WindingNumber, band 3 (narrow band, every voxel written)", bench::fmt(tWnBand, 3),
    bench::fmt(tWnBand / tWn, 2), "-", "-", "-", "-" });
  rows.push_back({ "OpenVDB meshToSignedDistanceField, band 3/3 (sparse) + dense copy",
    bench::fmt(vdbNbSec + vdbNbCopy, 3), bench::fmt((vdbNbSec + vdbNbCopy) / tWn, 2), "-", "-", "-",
    std::to_string(activeNb) + " active" });
  rows.push_back({ "vtkImplicitPolyDataDistance (1 thread, plain loop) at " + std::to_string(vtkRes) + " (" +
                     std::to_string(gv.count()) + " voxels), extrapolated x" + bench::fmt(double(g.count()) / gv.count(), 1),
    bench::fmt(vtkExtrap, 1) + " (measured " + bench::fmt(vtkSec, 3) + ")", bench::fmt(vtkExtrap / tWn, 1),
    bench::fmt(cVtk.maxDiff, 4) + " (at " + std::to_string(vtkRes) + ")", pct(cVtk.signWrongFar, cVtk.far),
    pct(cVtk.signWrongAll, gv.count()), "ours at same res: " + bench::fmt(tWnLow, 3) + " s, ratio " +
      bench::fmt(vtkSec / tWnLow, 1) });
  std::printf("process CPU seconds (all threads): ours WindingNumber %.2f, ours PseudoNormal %.2f, OpenVDB dense "
              "(with copy) %.2f; OpenVDB / ours: %.2f (WN), %.2f (PN)\n",
    cpuWn, cpuPn, cpuVdb, cpuVdb / cpuWn, cpuVdb / cpuPn);
  bench::printTable({ "method", "seconds", "time / ours WN", "max |d| diff (voxels)", "sign != WN (far)",
                      "sign != WN (all)", "notes" },
    rows);

  if (!openPath.empty())
  {
    const TriangleMesh open = loadMesh(openPath);
    const GridGeometry go = fitGridToMesh(open, res, 2.0);
    double t1 = 0, t2 = 0, t3 = 0, t4 = 0;
    std::size_t a1 = 0, a2 = 0;
    const std::vector<float> wnOpen = ours(open, go, SignMode::WindingNumber, t1, inf);
    float md = 0;
    for (float v : wnOpen) md = std::max(md, std::fabs(v));
    const std::vector<float> vdbOpen = openvdbDense(open, go, std::ceil(md) + 1.0f, inf, t2, t3, a1);
    const std::vector<float> vdbOpenNb = openvdbDense(open, go, 3.0f, 3.0f, t4, t3, a2);
    std::int64_t insideWn = 0, insideVdb = 0, insideNb = 0;
    for (std::size_t i = 0; i < wnOpen.size(); ++i)
      insideWn += wnOpen[i] < 0, insideVdb += vdbOpen[i] < 0, insideNb += vdbOpenNb[i] < 0;
    const Compare c1 = compare(vdbOpen, wnOpen), c2 = compare(vdbOpenNb, wnOpen);
    std::printf("\nopen mesh %s (%zu triangles), grid %lldx%lldx%lld: inside voxels by our WindingNumber %lld\n",
      openPath.c_str(), open.triangles.size(), (long long)go.dims[0], (long long)go.dims[1], (long long)go.dims[2],
      (long long)insideWn);
    bench::printTable({ "OpenVDB meshToSignedDistanceField", "inside voxels", "sign != WN (far)", "sign != WN (all)" },
      { { "dense (ex " + bench::fmt(std::ceil(md) + 1, 0) + ", in inf)", std::to_string(insideVdb),
          pct(c1.signWrongFar, c1.far), pct(c1.signWrongAll, go.count()) },
        { "level set band 3 (background sign)", std::to_string(insideNb), pct(c2.signWrongFar, c2.far),
          pct(c2.signWrongAll, go.count()) } });
  }
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
