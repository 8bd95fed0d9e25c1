// The normal and pseudo-normal signs of a mesh that bounds a solid, by the
// winding path (docs/MESH_TO_SDF.md, "Pseudo-normal signs of solids",
// "Normal signs of solids"): which calls take it, and the Normal sign's
// sharp regions computed beside the winding pass and stored after it.
#pragma once

#include "MeshToSdfSharpFeatures.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/MeshToSdf.h"

#include <atomic>
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

/// On CUDA the solid check, a large mesh's longest host step before the pass
/// (sub2: 62-80 ms of a 360-424 ms Normal call on 16 threads, 95-110 ms with
/// its parts), need not come first: a closed mesh whose check has not run
/// starts the pass on the winding route (signOfSolids's options for a solid)
/// while the check runs on a thread of its own. The pass stores as it goes;
/// between its groups stopIfNotASolid() stops it once the check has found no
/// solid, and confirm() after the pass waits for the check. A mesh that bounds
/// no solid throws NotASolid, after which the caller runs the call again on
/// the sign's own path (signOfSolids, now known), which writes every voxel of
/// the grid or every chunk of the volume: nothing of the first pass stays.
/// The result is signOfSolids's either way; a closed mesh that is no solid
/// pays the GPU's work until its check ends.
class SolidCheckBesideGpu
{
public:
  /// Thrown by confirm(): the mesh bounds no solid.
  struct NotASolid
  {
  };
  /// Whether a call may go ahead so: a normal or pseudo-normal sign that may
  /// take the route, a closed mesh whose check has not run, and for Normal a
  /// mesh inside the grid (no sharp-feature search first). The caller checks
  /// that the call runs on CUDA.
  static bool applies(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, const GridGeometry& grid,
    const VoxelBox& extent);
  /// Starts the check (cancelled by `interrupter`).
  SolidCheckBesideGpu(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, const GridGeometry& grid,
    const VoxelBox& extent, Interrupter& interrupter);
  /// Stops the check at its next poll if confirm() did not wait for it.
  ~SolidCheckBesideGpu();
  SolidCheckBesideGpu(const SolidCheckBesideGpu&) = delete;
  SolidCheckBesideGpu& operator=(const SolidCheckBesideGpu&) = delete;
  /// The winding route's options (sets stats.signByWinding).
  MeshToSdfOptions windingOptions(MeshToSdfStats& stats) const;
  /// What the sharp regions' thread polls: the caller's cancel, and a check
  /// that failed (its regions are not needed).
  Interrupter& regionsInterrupter() { return this->Stop; }
  /// Waits for the check; its warnings and the wait go into stats; throws
  /// NotASolid when the route does not apply after all.
  void confirm(MeshToSdfStats& stats);
  /// confirm() if the check has ended, else nothing: for between a pass's
  /// groups (a closed non-solid stops early).
  void stopIfNotASolid(MeshToSdfStats& stats);

private:
  struct Droppable : Interrupter
  {
    Interrupter* caller = nullptr;
    std::atomic<bool> dropped{ false };
    bool wasInterrupted() const override { return this->dropped.load() || this->caller->wasInterrupted(); }
  };
  const MeshToSdfPrepared& Mesh;
  const MeshToSdfOptions Options;
  const GridGeometry Grid;
  const VoxelBox Extent;
  Droppable Stop;
  std::future<void> Check;
  bool Concluded = false;
  void conclude(MeshToSdfStats& stats);
};

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
