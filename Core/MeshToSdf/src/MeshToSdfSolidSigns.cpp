// The normal and pseudo-normal signs of solids by the winding path
// (MeshToSdfSolidSigns.h).
#include "MeshToSdfSolidSigns.h"

#include "MeshToSdfCuda.h"
#include "MeshToSdfSolid.h"
#include "lvdif/ParallelFailure.h"

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>

namespace lvdif
{
namespace detail::meshtosdf
{

MeshToSdfOptions signOfSolids(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats,
  const GridGeometry& grid, const VoxelBox& extent)
{
  const bool normals = options.sign == SignMode::Normal || options.sign == SignMode::PseudoNormal;
  if (!normals) return options;
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
  const bool normal = options.sign == SignMode::Normal;
  if (!solid.solid)
  {
    trace(((normal ? "normal" : "pseudo-normal") + std::string(" sign on its own path: ") + solid.why).c_str(), 0);
    return options;
  }
  if (normal)
  {
    // the sharp features' voxels take the CPU's queries of the BVH path
    if (options.useVertexNormals || options.accel != MeshToSdfAccel::Bvh) return options;
    // every sharp feature must lie inside the grid. A mesh inside it needs
    // no search here: the regions' thread finds them (beside the GPU's pass)
    const PreparedMesh& m = mesh.impl().mesh;
    const bool meshInside = insideExtent(V3{ m.lo[0], m.lo[1], m.lo[2] }, grid, extent) &&
      insideExtent(V3{ m.hi[0], m.hi[1], m.hi[2] }, grid, extent);
    if (!meshInside)
    {
      const double t1 = now();
      const SharpFeatures& sharp = mesh.impl().sharpFeatures();
      stats.buildSeconds += now() - t1;
      if (!sharpFeaturesInside(sharp, grid, extent))
      {
        trace("normal sign on its own path: a sharp feature lies outside the grid", 0);
        return options;
      }
    }
  }
  MeshToSdfOptions o = options;
  o.sign = SignMode::WindingNumber;
  o.reorientFaces = false;
  stats.signByWinding = true;
  return o;
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
