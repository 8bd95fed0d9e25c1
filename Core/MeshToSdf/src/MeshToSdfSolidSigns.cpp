// The normal and pseudo-normal signs of solids by the winding path
// (MeshToSdfSolidSigns.h).
#include "MeshToSdfSolidSigns.h"

#include "MeshToSdfCuda.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfSolid.h"
#include "lvdif/ParallelFailure.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>
#include <string>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
bool normalsSign(const MeshToSdfOptions& options)
{
  return options.sign == SignMode::Normal || options.sign == SignMode::PseudoNormal;
}

bool meshInsideGrid(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent)
{
  const PreparedMesh& m = mesh.impl().mesh;
  return insideExtent(V3{ m.lo[0], m.lo[1], m.lo[2] }, grid, extent) &&
    insideExtent(V3{ m.hi[0], m.hi[1], m.hi[2] }, grid, extent);
}

/// The route's conditions other than the solid check, for a solid.
bool routeApplies(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats,
  const GridGeometry& grid, const VoxelBox& extent)
{
  if (options.sign != SignMode::Normal) return true;
  // the sharp features' voxels take the CPU's queries of the BVH path
  if (options.useVertexNormals || options.accel != MeshToSdfAccel::Bvh) return false;
  // every sharp feature must lie inside the grid. A mesh inside it needs
  // no search here: the regions' thread finds them (beside the GPU's pass)
  if (meshInsideGrid(mesh, grid, extent)) return true;
  const double t1 = now();
  const SharpFeatures& sharp = mesh.impl().sharpFeatures();
  stats.buildSeconds += now() - t1;
  if (sharpFeaturesInside(sharp, grid, extent)) return true;
  trace("normal sign on its own path: a sharp feature lies outside the grid", 0);
  return false;
}

MeshToSdfOptions byWinding(const MeshToSdfOptions& options, MeshToSdfStats& stats)
{
  MeshToSdfOptions o = options;
  o.sign = SignMode::WindingNumber;
  o.reorientFaces = false;
  stats.signByWinding = true;
  return o;
}
} // namespace

MeshToSdfOptions signOfSolids(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats,
  const GridGeometry& grid, const VoxelBox& extent)
{
  if (!normalsSign(options)) return options;
  const double t0 = now();
  const SolidBoundary& solid = mesh.impl().solidBoundary();
  stats.buildSeconds += now() - t0;
  if (solid.inwardParts > 0)
  {
    std::ostringstream m;
    m << "mesh to SDF: " << solid.inwardParts << " of the mesh's " << solid.parts
      << " connected parts face inwards (closed, but their faces point into the solid), so the "
      << (options.sign == SignMode::Normal ? "normal" : "pseudo-normal")
      << " sign is inside out there; reverse their faces, or use the winding-number sign, which is right either way";
    stats.warnings.push_back(m.str());
  }
  if (!options.solidsByWinding) return options;
  if (!solid.solid)
  {
    trace(((options.sign == SignMode::Normal ? "normal" : "pseudo-normal") + std::string(" sign on its own path: ") +
            solid.why)
            .c_str(),
      0);
    return options;
  }
  return routeApplies(mesh, options, stats, grid, extent) ? byWinding(options, stats) : options;
}

bool SolidCheckBesideGpu::applies(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options,
  const GridGeometry& grid, const VoxelBox& extent)
{
  MeshToSdfPrepared::Impl& impl = mesh.impl();
  // a mesh with a boundary is no solid, and its winding structures may take
  // seconds (the orientation pass, caps): only closed meshes go ahead; nor is
  // one with an edge of more than two faces (the check's first step fails on
  // it, and its winding structures run the orientation pass: reversed copies)
  return normalsSign(options) && options.solidsByWinding && impl.mesh.boundaryEdges == 0 &&
    impl.mesh.crowdedEdges == 0 && !impl.solidBoundaryKnown() &&
    (options.sign != SignMode::Normal ||
      (!options.useVertexNormals && options.accel == MeshToSdfAccel::Bvh && meshInsideGrid(mesh, grid, extent)));
}

SolidCheckBesideGpu::SolidCheckBesideGpu(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options,
  const GridGeometry& grid, const VoxelBox& extent, Interrupter& interrupter)
  : Mesh(mesh)
  , Options(options)
  , Grid(grid)
  , Extent(extent)
{
  this->Stop.caller = &interrupter;
  trace("solid check beside the GPU's pass: started", 0);
  this->Check = std::async(std::launch::async, [this] {
    const PhaseTraceScope tracing(this->Options.tracePhases); // this thread's own
    const BuildInterruptScope cancel(this->Stop);
    this->Mesh.impl().solidBoundary();
  });
}

SolidCheckBesideGpu::~SolidCheckBesideGpu()
{
  // a pass that failed before confirm(): the check is not waited for to its end
  this->Stop.dropped.store(true);
  if (this->Check.valid()) this->Check.wait();
}

MeshToSdfOptions SolidCheckBesideGpu::windingOptions(MeshToSdfStats& stats) const
{
  return byWinding(this->Options, stats);
}

void SolidCheckBesideGpu::conclude(MeshToSdfStats& stats)
{
  this->Concluded = true; // before get(): a future is read once, and a cancel comes out of get()
  this->Check.get();
  MeshToSdfStats checked;
  signOfSolids(this->Mesh, this->Options, checked, this->Grid, this->Extent); // found: its warnings and route
  stats.warnings.insert(stats.warnings.end(), checked.warnings.begin(), checked.warnings.end());
  if (checked.signByWinding) return;
  this->Stop.dropped.store(true); // the sharp regions' thread stops at its next poll
  throw NotASolid{};
}

void SolidCheckBesideGpu::stopIfNotASolid(MeshToSdfStats& stats)
{
  if (!this->Concluded && this->Check.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    this->conclude(stats);
}

void SolidCheckBesideGpu::confirm(MeshToSdfStats& stats)
{
  if (this->Concluded) return;
  const double t0 = now();
  this->conclude(stats);
  stats.buildSeconds += now() - t0; // the part of the check the GPU's pass did not hide
  trace("solid check beside the GPU's pass: waited for", now() - t0);
}

std::future<SharpRegionVoxels> sharpRegions(const MeshToSdfPrepared& mesh, const GridGeometry& grid,
  const VoxelBox& extent, double toOut, double band, Interrupter& interrupter, bool onGpu, bool tracePhases)
{
  return std::async(onGpu ? std::launch::async : std::launch::deferred,
    [&mesh, grid, extent, toOut, band, &interrupter, onGpu, tracePhases] {
      const PhaseTraceScope tracing(tracePhases); // this thread's own
      const double t0 = now();
      MeshToSdfPrepared::Impl& impl = mesh.impl();
      const std::shared_ptr<const Bvh> bvh = impl.meshBvh(); // built by the solid check
      const SharpFeatures& sharp = impl.sharpFeatures();
      const std::vector<SharpBrick> bricks = sharpRegionBricks(sharp, *bvh, grid, extent, interrupter);
      trace(("sharp features' regions: " + std::to_string(bricks.size()) + " bricks").c_str(), now() - t0);
      const double t1 = now();
      SharpRegionVoxels r;
      bool onCpu = !onGpu;
      if (onGpu)
      {
        try
        {
          double unused = 0;
          r.voxels = meshtosdf_cuda::sharpRegionVoxelsOnDevice(
            impl.deviceMesh(false, false, unused), sharp, bricks, grid, extent, toOut, band);
        }
        catch (const Error& e)
        {
          // the CPU's step 2 computes the same voxels (tested): a GPU that
          // fails here (out of memory beside the pass) costs time, not the call
          if (e.code() == ErrorCode::Cancelled) throw;
          r.gpuFailure = e.what();
          r.voxels.clear();
          onCpu = true;
        }
        interrupter.checkInterrupt();
      }
      if (onCpu) r.voxels = sharpRegionVoxels(impl.mesh, sharp, *bvh, bricks, grid, extent, toOut, band, interrupter);
      trace(("sharp features' regions: " + std::to_string(r.voxels.size()) + " voxels" + (onCpu ? "" : " (GPU)"))
              .c_str(),
        now() - t1);
      return r;
    });
}

void SharpRegionVoxels::warnIfMoved(MeshToSdfStats& stats) const
{
  if (this->gpuFailure.empty()) return;
  stats.warnings.push_back("mesh to SDF: the sharp features' regions were computed on the CPU (the same values, "
                           "more time): their GPU step failed: " +
    this->gpuFailure);
}

void storeSharpVoxels(DictionaryVolume& volume, std::vector<SharpVoxel>& voxels)
{
  auto chunkOf = [&](const SharpVoxel& v) { return volume.chunkOf(v.i, v.j, v.k); };
  std::sort(voxels.begin(), voxels.end(),
    [&](const SharpVoxel& x, const SharpVoxel& y) { return chunkOf(x) < chunkOf(y); });
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < voxels.size(); ++i)
    if (i == 0 || chunkOf(voxels[i]) != chunkOf(voxels[i - 1])) starts.push_back(i);
  starts.push_back(voxels.size());
  ParallelFailure failure;
  const auto groups = static_cast<std::int64_t>(starts.size()) - 1;
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t g = 0; g < groups; ++g)
  {
    failure.run([&] {
      bool changed = false;
      for (std::size_t i = starts[static_cast<std::size_t>(g)]; i < starts[static_cast<std::size_t>(g) + 1]; ++i)
      {
        const SharpVoxel& v = voxels[i];
        Voxel voxel = volume.get(v.i, v.j, v.k);
        const SdfKey key = volume.encode(v.value);
        if (voxel.sdf == key) continue;
        voxel.sdf = key;
        volume.set(v.i, v.j, v.k, voxel);
        changed = true;
      }
      if (!changed) return;
      const std::int64_t id = chunkOf(voxels[starts[static_cast<std::size_t>(g)]]);
      volume.markDirty(id);
      volume.tryCollapseChunk(id);
    });
  }
  failure.rethrow();
}

} // namespace detail::meshtosdf
} // namespace lvdif
