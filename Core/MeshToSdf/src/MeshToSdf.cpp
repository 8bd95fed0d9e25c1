// Mesh to SDF calls: the device of a call (the CPU engine, MeshToSdfEngine.h,
// or the CUDA session), its output (a float extent, or a dictionary volume:
// stored by MeshToSdfVolumeStore.h), its warnings (composed by MeshToSdfWarnings.h),
// and the preparation of a mesh. Algorithms: MeshToSdf.h; structures: MeshToSdfInternal.h.
#include "lvdif/MeshToSdf.h"

#include "MeshToSdfCuda.h"
#include "MeshToSdfEngine.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfSolidSigns.h"
#include "MeshToSdfSolid.h"
#include "MeshToSdfVolumeStore.h"
#include "MeshToSdfNearest.h" // the prepared mesh owns one (destroyed here)
#include "MeshToSdfWarnings.h"
#include "lvdif/Memory.h"
#include "lvdif/ParallelFailure.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <numeric>
#include <sstream>
#include <utility>

namespace lvdif
{

using namespace detail::meshtosdf;

namespace
{
/// Says (with --trace) which winding construction the GPU runs.
void traceWindingPath(const WindingSigner& w, bool reoriented)
{
  const DipoleTree* s = w.cpuCorrection(reoriented);
  const std::string what = !w.gpuTakesCpuClosure(reoriented)
    ? "winding sign on the GPU: cone over the boundary (the older construction)"
    : s ? "winding sign on the GPU: the CPU's closure, correction s over " + std::to_string(s->size()) +
          " faces (caps, reversed, removed) in the dipole tree"
        : std::string("winding sign on the GPU: closed mesh, crossings only");
  trace(what.c_str(), 0);
}

/// The CUDA session of a call, on the prepared mesh's device copy (uploaded
/// on first use; the upload counts as build time). Winding structures not
/// built yet (the one-call API) are built and uploaded by the session right
/// after it queues the first distance kernel, overlapping it; that host time
/// is added to the build time too.
std::unique_ptr<detail::meshtosdf_cuda::Session> openCuda(const MeshToSdfPrepared& prepared, const Engine& e,
  const MeshToSdfOptions& opts, MeshToSdfStats& stats)
{
  const double t0 = now();
  double unused = 0;
  MeshToSdfPrepared::Impl& impl = prepared.impl();
  const bool winding = opts.sign == SignMode::WindingNumber;
  const bool normals = opts.sign == SignMode::Normal || opts.sign == SignMode::PseudoNormal;
  const bool reoriented = winding && opts.reorientFaces; // chooseDevice built the structures
  const bool built = impl.hasWindingSigner();
  const detail::meshtosdf_cuda::DeviceMesh& dm =
    impl.deviceMesh(winding && built, normals, unused, winding && !built, reoriented);
  trace("upload: the device copy of the mesh (or its reuse)", now() - t0);
  std::function<void()> ensure;
  if (winding && built) traceWindingPath(impl.windingSigner(unused), reoriented);
  if (winding)
  {
    ensure = [&impl, &stats, reoriented]() {
      const double t1 = now();
      double s = 0;
      impl.deviceMesh(true, false, s, false, reoriented);
      stats.buildSeconds += now() - t1;
      trace("winding structures built and uploaded, overlapping the distance kernel", now() - t1);
      traceWindingPath(impl.windingSigner(s), reoriented);
    };
  }
  auto session = detail::meshtosdf_cuda::openSession(dm, e.geom, opts, e.toOut, e.band, stats, std::move(ensure));
  stats.buildSeconds += now() - t0;
  trace("upload and session", now() - t0);
  return session;
}

/// The device of a call on a prepared mesh. Auto prefers CUDA for every mesh:
/// the CUDA sign kernel takes the CPU's winding construction (orientation
/// pass, local caps, the dipole tree over caps, reversed and removed faces; or
/// those of the re-oriented mesh M+) and decides every voxel as the CPU does
/// (MeshToSdfCudaDipole.cuh). The one exception: the re-oriented winding
/// number (reorientFaces) stays on the CPU when M+ could not be closed by
/// local caps (its closure has a cone, which the GPU takes only for M as
/// given). Builds the winding structures for that check: the GPU session then
/// uploads them before its first kernel (no overlap).
Device chooseDevice(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats)
{
  const Device d = resolveDevice(options.device);
  if (d != Device::Cuda || options.sign != SignMode::WindingNumber || !options.reorientFaces) return d;
  double seconds = 0;
  const bool capped = mesh.impl().windingSigner(seconds).gpuTakesCpuClosure(true);
  stats.buildSeconds += seconds;
  return capped ? d : Device::Cpu;
}


/// On CUDA the host mostly waits while the GPU computes the distances, so the
/// connected parts that warnIfPartsVanish reads (about 0.3 s for 13M
/// triangles on 16 threads, once per prepared mesh) are found then, on a
/// thread of their own, instead of after the result. `needed`: the call
/// will check for vanishing parts (a signed field over the whole grid). The
/// caller get()s the future before the check (an error there is the call's).
std::future<void> partsBesideGpu(const MeshToSdfPrepared& mesh, bool needed)
{
  if (!needed) return {};
  return std::async(std::launch::async, [&mesh] { mesh.impl().partBounds(); });
}

bool wholeGrid(const GridGeometry& grid, const VoxelBox& extent)
{
  for (int a = 0; a < 3; ++a)
    if (extent.lo[a] != 0 || extent.hi[a] != grid.dims[a] - 1) return false;
  return true;
}

MeshToSdfStats gridPass(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& given, const MeshToSdfOptions& options, MeshToSdfStats& stats, Interrupter& interrupter,
  SolidCheckBesideGpu* check);
MeshToSdfStats volumePass(const MeshToSdfPrepared& mesh, DictionaryVolume& volume, const MeshToSdfOptions& given,
  const MeshToSdfOptions& options, MeshToSdfStats& stats, Interrupter& interrupter, SolidCheckBesideGpu* check);

} // namespace

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent,
  float* out, const MeshToSdfOptions& given, Interrupter& interrupter)
{
  const PhaseTraceScope tracing(given.tracePhases);
  validateGrid(grid);
  require(out != nullptr, "mesh to SDF: output pointer is null");
  require(!extent.empty(), "mesh to SDF: the requested extent is empty");
  for (int a = 0; a < 3; ++a)
  {
    require(extent.lo[a] >= 0 && extent.hi[a] < grid.dims[a], "mesh to SDF: the extent lies outside the grid");
  }
  const BuildInterruptScope cancel(interrupter);
  interrupter.start("mesh to SDF"); // the solid check below may take seconds
  if (resolveDevice(given.device) == Device::Cuda && SolidCheckBesideGpu::applies(mesh, given, grid, extent))
  {
    SolidCheckBesideGpu check(mesh, given, grid, extent, interrupter);
    try
    {
      MeshToSdfStats stats;
      const MeshToSdfOptions options = check.windingOptions(stats);
      return gridPass(mesh, grid, extent, out, given, options, stats, interrupter, &check);
    }
    catch (const SolidCheckBesideGpu::NotASolid&)
    {
      trace("solid check beside the GPU: not a solid, the call again on the sign's own path", 0);
    }
  }
  MeshToSdfStats stats;
  const MeshToSdfOptions options = signOfSolids(mesh, given, stats, grid, extent);
  return gridPass(mesh, grid, extent, out, given, options, stats, interrupter, nullptr);
}

namespace
{
/// The float grid call after its sign's route is chosen: `check` (CUDA only)
/// is the solid check still running beside the pass, confirmed after it.
MeshToSdfStats gridPass(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& given, const MeshToSdfOptions& options, MeshToSdfStats& stats, Interrupter& interrupter,
  SolidCheckBesideGpu* check)
{
  stats.device = chooseDevice(mesh, options, stats);
  auto engine = makeEngine(mesh, grid, options, options.bandWidth, stats.device, stats);
  const bool sharp = given.sign == SignMode::Normal && stats.signByWinding;
  std::future<SharpRegionVoxels> regions;
  auto startRegions = [&](bool onGpu) {
    if (sharp)
      regions = sharpRegions(mesh, grid, extent, outputScale(grid, options), options.bandWidth,
        check ? check->regionsInterrupter() : interrupter, onGpu, given.tracePhases);
  };
  if (stats.device == Device::Cuda)
  {
    std::future<void> parts = partsBesideGpu(mesh, wholeGrid(grid, extent) && options.sign != SignMode::Unsigned);
    const auto session = openCuda(mesh, *engine, options, stats);
    startRegions(true); // after the session: its step 2 reads the device copy of the mesh
    session->compute(extent, out, stats, interrupter);
    if (check) check->confirm(stats); // else `out` is computed again, whole
    if (parts.valid()) parts.get();
  }
  else
  {
    if (check) check->confirm(stats); // (only CUDA calls go ahead)
    startRegions(false);
    computeBox(*engine, extent, out, stats, interrupter, 0.0, 1.0);
  }
  if (sharp)
  {
    const SharpRegionVoxels r = regions.get();
    r.warnIfMoved(stats);
    const std::vector<SharpVoxel>& voxels = r.voxels;
    const std::int64_t nx = extent.hi[0] - extent.lo[0] + 1, ny = extent.hi[1] - extent.lo[1] + 1;
    for (const SharpVoxel& v : voxels)
      out[(v.i - extent.lo[0]) + nx * ((v.j - extent.lo[1]) + ny * (v.k - extent.lo[2]))] = v.value;
    stats.sharpVoxels = static_cast<std::int64_t>(voxels.size());
  }
  if (options.svfFilters != 0)
  {
    const double t0 = now();
    FloatGridView view;
    view.data = out;
    view.geometry.dims = { extent.hi[0] - extent.lo[0] + 1, extent.hi[1] - extent.lo[1] + 1,
      extent.hi[2] - extent.lo[2] + 1 };
    SignVoxelFilterParams p = options.svf;
    p.filters = options.svfFilters;
    if (p.device == Device::Auto) p.device = options.device; // "--device cpu" holds for the filters too
    stats.svfFlips = signVoxelFilter(view, p, interrupter).totalFlips();
    stats.svfSeconds = now() - t0;
  }
  bool duplicatesSaid = false;
  if (wholeGrid(grid, extent) && options.sign != SignMode::Unsigned)
  {
    // a piece of a larger grid may rightly have nothing inside: whole grids
    // only. Inside voxels within 1 voxel of the surface do not count: a
    // curved open sheet has a film of them (|w| just above 1/2), and
    // meshing them gives slivers at best
    const double h = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
    const float deep = deepInsideLimit(options.unit == DistanceUnit::World ? static_cast<float>(h) : 1.0f, options.bandWidth);
    std::int64_t inside = 0;
    const std::int64_t n = extent.voxelCount();
#pragma omp parallel for reduction(+ : inside)
    for (std::int64_t i = 0; i < n; ++i) inside += out[i] < deep;
    duplicatesSaid = warnIfNothingInside(mesh, grid, options, inside, stats);
  }
  warnIfFacesReversed(mesh, options, stats);
  warnIfFacesDuplicated(mesh, options, stats, duplicatesSaid);
  interrupter.end();
  return stats;
}
} // namespace

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  VoxelBox all;
  all.hi = { out.geometry.dims[0] - 1, out.geometry.dims[1] - 1, out.geometry.dims[2] - 1 };
  return meshToSdf(mesh, out.geometry, all, out.data, options, interrupter);
}

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, DictionaryVolume& volume, const MeshToSdfOptions& given,
  Interrupter& interrupter)
{
  const PhaseTraceScope tracing(given.tracePhases);
  const GridGeometry grid = gridOf(volume.options());
  MeshToSdfStats stats;
  VoxelBox whole;
  whole.hi = { grid.dims[0] - 1, grid.dims[1] - 1, grid.dims[2] - 1 };
  // a chunk region keeps the Normal path: its sharp regions may leave it
  MeshToSdfOptions forSolids = given;
  if (!given.chunkRegion.empty() && given.sign == SignMode::Normal) forSolids.solidsByWinding = false;
  const BuildInterruptScope cancel(interrupter);
  interrupter.start("mesh to SDF"); // the solid check below may take seconds
  if (given.chunkRegion.empty() && resolveDevice(given.device) == Device::Cuda &&
    SolidCheckBesideGpu::applies(mesh, forSolids, grid, whole))
  {
    SolidCheckBesideGpu check(mesh, forSolids, grid, whole, interrupter);
    try
    {
      const MeshToSdfOptions options = check.windingOptions(stats);
      return volumePass(mesh, volume, given, options, stats, interrupter, &check);
    }
    catch (const SolidCheckBesideGpu::NotASolid&)
    {
      trace("solid check beside the GPU: not a solid, the call again on the sign's own path", 0);
      stats = MeshToSdfStats();
    }
  }
  const MeshToSdfOptions options = signOfSolids(mesh, forSolids, stats, grid, whole);
  return volumePass(mesh, volume, given, options, stats, interrupter, nullptr);
}

namespace
{
/// The volume call after its sign's route is chosen: `check` (CUDA only) is
/// the solid check still running beside the pass, polled between its groups
/// and confirmed after it.
MeshToSdfStats volumePass(const MeshToSdfPrepared& mesh, DictionaryVolume& volume, const MeshToSdfOptions& given,
  const MeshToSdfOptions& options, MeshToSdfStats& stats, Interrupter& interrupter, SolidCheckBesideGpu* check)
{
  const GridGeometry grid = gridOf(volume.options());
  VoxelBox whole;
  whole.hi = { grid.dims[0] - 1, grid.dims[1] - 1, grid.dims[2] - 1 };
  MeshToSdfOptions opts = options;
  opts.unit = DistanceUnit::Voxel;
  stats.device = chooseDevice(mesh, options, stats);
  auto engine = makeEngine(mesh, grid, opts, volume.bandWidth(), stats.device, stats);
  const bool sharp = given.sign == SignMode::Normal && stats.signByWinding;
  std::future<SharpRegionVoxels> regions;
  auto startRegions = [&](bool onGpu) {
    if (sharp)
      regions = sharpRegions(mesh, grid, whole, outputScale(grid, opts), volume.bandWidth(),
        check ? check->regionsInterrupter() : interrupter, onGpu, given.tracePhases);
  };
  const bool region = !options.chunkRegion.empty();
  require(!region || options.svfFilters == 0,
    "mesh to SDF: a chunk region cannot be combined with the sign voxel filters (they need the whole volume)");
  if (check && stats.device != Device::Cuda) check->confirm(stats); // (only CUDA calls go ahead)
  if (region)
  {
    std::unique_ptr<detail::meshtosdf_cuda::Session> cuda;
    if (stats.device == Device::Cuda) cuda = openCuda(mesh, *engine, opts, stats);
    startRegions(cuda != nullptr);
    volumeRegion(volume, options.chunkRegion, opts.cpuBandBytes, stats, interrupter,
      [&](const VoxelBox& box, float* out, double p0, double dp) {
        if (cuda)
          cuda->compute(box, out, stats, interrupter);
        else
          computeBox(*engine, box, out, stats, interrupter, p0, dp);
      });
  }
  else if (stats.device == Device::Cuda)
  {
    std::future<void> parts = partsBesideGpu(mesh, options.sign != SignMode::Unsigned);
    const auto session = openCuda(mesh, *engine, opts, stats);
    startRegions(true); // after the session: its step 2 reads the device copy of the mesh
    // a pass beside the solid check stores as it goes, and stops at the next
    // group once the check has found no solid (the call then runs again on
    // the sign's own path, which writes every chunk: nothing of this pass stays)
    volumeOnCuda(*session, volume, opts, stats, interrupter, [&] {
      if (check) check->stopIfNotASolid(stats);
    });
    if (check) check->confirm(stats);
    if (parts.valid()) parts.get();
  }
  else
  {
    startRegions(false);
    VoxelBox everyChunk;
    everyChunk.hi = { volume.chunkCounts()[0] - 1, volume.chunkCounts()[1] - 1, volume.chunkCounts()[2] - 1 };
    volumeRegion(volume, everyChunk, opts.cpuBandBytes, stats, interrupter,
      [&](const VoxelBox& box, float* out, double p0, double dp) {
        computeBox(*engine, box, out, stats, interrupter, p0, dp);
      });
  }
  if (sharp)
  {
    SharpRegionVoxels r = regions.get();
    r.warnIfMoved(stats);
    std::vector<SharpVoxel>& voxels = r.voxels;
    const double t0 = now();
    storeSharpVoxels(volume, voxels);
    stats.sharpVoxels = static_cast<std::int64_t>(voxels.size());
    trace("sharp features' regions stored", now() - t0);
  }
  if (options.svfFilters != 0)
  {
    const double t0 = now();
    SignVoxelFilterParams p = options.svf;
    p.filters = options.svfFilters;
    if (p.device == Device::Auto) p.device = options.device; // "--device cpu" holds for the filters too
    stats.svfFlips = signVoxelFilter(volume, p, interrupter).totalFlips();
    stats.svfSeconds = now() - t0;
  }
  bool duplicatesSaid = false;
  if (options.sign != SignMode::Unsigned && !region) // a region may rightly have nothing inside
  {
    // voxels deep inside (as for float grids): uniform chunks by their
    // value, the others voxel by voxel until the first one
    const SdfKey zero = volume.encode(deepInsideLimit(1.0f, volume.bandWidth()));
    std::int64_t inside = 0;
    for (std::int64_t c = 0; c < volume.chunkCount() && inside == 0; ++c)
    {
      if (volume.isUniform(c))
      {
        inside += volume.uniformValue(c).sdf < zero;
        continue;
      }
      const VoxelBox b = volume.chunkBox(c);
      for (std::int64_t z = b.lo[2]; z <= b.hi[2] && inside == 0; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1] && inside == 0; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0] && inside == 0; ++x) inside += volume.get(x, y, z).sdf < zero;
    }
    duplicatesSaid = warnIfNothingInside(mesh, grid, options, inside, stats);
  }
  warnIfFacesReversed(mesh, options, stats);
  warnIfFacesDuplicated(mesh, options, stats, duplicatesSaid);
  interrupter.end();
  return stats;
}
} // namespace

/// prepareMeshToSdf; the winding structures only when sign is WindingNumber
/// (otherwise built on first use: on CUDA while the GPU computes distances).
/// The pseudo-normals only when `sign` reads them (Normal, PseudoNormal): the
/// others (e.g. the GPU's winding-number path) skip that work; a later call
/// with such a sign builds them then (Impl::pseudoNormals).
/// meshTreeNow (a call that will run on CUDA, whose distance kernel needs
/// the mesh BVH): for a large mesh the tree is built on its own thread as
/// soon as the triangle records are, beside the edge pass (boundary,
/// pseudo-normals) that only the signs need; the same tree as built
/// afterwards. Below TreeBesideEdgePassTriangles the new thread's OpenMP
/// team costs more than the overlap saves (H200 host: the 30k bunny's build
/// 18 -> 27 ms with it; the 832k armadillo's 190 -> 110 ms).
/// nearestIndex (a one-call run on the CPU with the Bvh accelerator): the
/// CPU's index will follow, so the memory check counts it too.
constexpr std::size_t TreeBesideEdgePassTriangles = std::size_t(1) << 18;
/// normalsLater (a PseudoNormal or Normal call that checks for a solid first): the
/// pseudo-normals are counted in the memory check but built only if the mesh
/// is not a solid's boundary (a solid's call never reads them).
static MeshToSdfPrepared prepareInternal(const TriangleMesh& mesh, SignMode sign, bool meshTreeNow = false,
  bool nearestIndex = false, bool normalsLater = false)
{
  // before anything is allocated: the whole preparation against the limit
  requirePreparedMemory(mesh, sign == SignMode::Normal || sign == SignMode::PseudoNormal, sign == SignMode::WindingNumber,
    nearestIndex);
  meshTreeNow = meshTreeNow && mesh.triangles.size() >= TreeBesideEdgePassTriangles;
  const bool winding = sign == SignMode::WindingNumber;
  const double t0 = now();
  auto impl = std::make_shared<MeshToSdfPrepared::Impl>();
  // declared after impl: destroyed (joined) first, also when the edge pass throws
  std::future<std::shared_ptr<const Bvh>> tree;
  const bool tracing = tracePhasesActive();
  std::function<void()> startTree;
  if (meshTreeNow)
  {
    startTree = [&tree, &impl, tracing]() {
      const PreparedMesh* m = &impl->mesh;
      // a new thread starts from the default thread count: pass the caller's on
      const int threads = omp_get_max_threads();
      tree = std::async(std::launch::async, [m, tracing, threads]() {
        omp_set_num_threads(threads);
        const PhaseTraceScope scope(tracing);
        const double tb = now();
        auto bvh = std::make_shared<const Bvh>(m->tris);
        trace("mesh BVH (beside the edge pass)", now() - tb);
        return bvh;
      });
    };
  }
  prepareMesh(mesh, impl->mesh, (sign == SignMode::Normal || sign == SignMode::PseudoNormal) && !normalsLater, startTree);
  if (tree.valid()) impl->bvh = tree.get();
  const double t2 = now();
  // the search structures are built on first use: the CPU's NearestIndex by
  // makeEngine, the GPU's Bvh by deviceMesh (each path needs only its own)
  double unused = 0;
  if (winding) impl->windingSigner(unused);
  impl->prepareSeconds = now() - t0;
  trace("prepareMesh", t2 - t0);
  if (winding) trace("winding structures", now() - t2);
  return MeshToSdfPrepared(std::move(impl));
}

/// The one-call API's preparation: the mesh BVH at once for CUDA, the
/// nearest index counted in the memory check for the CPU.
static MeshToSdfPrepared prepareOneCall(const TriangleMesh& mesh, const MeshToSdfOptions& options)
{
  const bool cuda = resolveDevice(options.device) == Device::Cuda;
  // the signs that may take the winding path (signOfSolids)
  const bool mayWind = options.solidsByWinding &&
    (options.sign == SignMode::PseudoNormal ||
      (options.sign == SignMode::Normal && !options.useVertexNormals && options.accel == MeshToSdfAccel::Bvh));
  return prepareInternal(mesh, options.sign, cuda, !cuda && options.accel == MeshToSdfAccel::Bvh, mayWind);
}

/// The one-call API: prepare, then the prepared call (preparation counts as build time).
template <typename Out>
MeshToSdfStats prepareAndRun(const TriangleMesh& mesh, Out&& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  const BuildInterruptScope cancel(interrupter); // preparing a large mesh takes seconds
  const MeshToSdfPrepared prepared = prepareOneCall(mesh, options);
  MeshToSdfStats stats = meshToSdf(prepared, std::forward<Out>(out), options, interrupter);
  stats.buildSeconds += prepared.prepareSeconds();
  return stats;
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& options, Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  const BuildInterruptScope cancel(interrupter); // preparing a large mesh takes seconds
  const MeshToSdfPrepared prepared = prepareOneCall(mesh, options);
  MeshToSdfStats stats = meshToSdf(prepared, grid, extent, out, options, interrupter);
  stats.buildSeconds += prepared.prepareSeconds();
  return stats;
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  return prepareAndRun(mesh, out, options, interrupter);
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, DictionaryVolume& volume, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  requireVolumeFits(mesh, volume, options); // before any work
  return prepareAndRun(mesh, volume, options, interrupter);
}

MeshToSdfPrepared prepareMeshToSdf(const TriangleMesh& mesh, SignMode sign)
{
  return prepareInternal(mesh, sign);
}


} // namespace lvdif
