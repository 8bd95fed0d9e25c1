// The normal and pseudo-normal signs of a mesh that bounds a solid, by the
// winding path (docs/MESH_TO_SDF.md, "Pseudo-normal signs of solids",
// "Normal signs of solids"): which calls take it, and the Normal sign's
// sharp regions computed beside the winding pass and stored after it.
#pragma once

#include "MeshToSdfSharpFeatures.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MeshToSdf.h"

#include <future>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// PseudoNormal on a mesh that bounds a solid: the winding sign, the same
/// function there (MeshToSdfSolid.h) and faster, since it needs exact
/// distances only in the band, where the pseudo-normal far field needs the
/// planes of every nearby triangle (docs/MESH_TO_SDF.md, "Pseudo-normal signs
/// of solids"). Normal on such a mesh: the winding sign too, then the voxels
/// of the sharp features' regions recomputed (sharpRegions;
/// "Normal signs of solids"), when the sharp features lie inside `extent` of
/// `grid` (their regions are walked through its voxels). The checks run once
/// per prepared mesh (their time is build time). A closed part whose faces
/// point inwards makes either sign inside out there, silently: a warning.
MeshToSdfOptions signOfSolids(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats,
  const GridGeometry& grid, const VoxelBox& extent);

/// Normal by the winding path (signOfSolids): the voxels of the sharp
/// features' regions with the Normal path's values. Step 1 (the bricks) runs
/// on the CPU; step 2 (the voxels' queries, exact, ties to the lowest index
/// like every accelerator) on the GPU for a call on CUDA (onGpu: a thread of
/// its own beside the session's kernels; the device copy of the mesh must
/// exist, so open the session first), else on the CPU when get() is called,
/// after the CPU's pass (both use every thread). A GPU step that fails
/// (not a cancel) is done again on the CPU, with a warning (gpuFailure).
struct SharpRegionVoxels
{
  std::vector<SharpVoxel> voxels;
  std::string gpuFailure; // why step 2 left the GPU for the CPU (empty: it did not)
  /// A warning in stats when step 2 moved to the CPU.
  void warnIfMoved(MeshToSdfStats& stats) const;
};
std::future<SharpRegionVoxels> sharpRegions(const MeshToSdfPrepared& mesh, const GridGeometry& grid,
  const VoxelBox& extent, double toOut, double band, Interrupter& interrupter, bool onGpu, bool tracePhases);

/// The sharp regions' voxels into the volume, chunk by chunk on the threads
/// (a far chunk that a region crosses is expanded: thousands at 1024^3), each
/// chunk collapsed again if it became uniform; only changed keys are written.
void storeSharpVoxels(DictionaryVolume& volume, std::vector<SharpVoxel>& voxels);

} // namespace detail::meshtosdf
} // namespace lvdif
