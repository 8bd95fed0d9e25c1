// Sign voxel filters SVF1..SVF4 (Wang et al. 2023, "LVDIF", Sect. 3.2,
// Figs. 2-5): repair the wrong signs that a fast, normal-based mesh-to-SDF
// sign (the paper's Algorithm 1) leaves far from the surface.
//
//   SVF1  along the filter axis, a far voxel (|d| > T) whose predecessor has
//         the opposite sign is flipped (a sequential scan per row).
//   SVF2  a far voxel flips when the 3x3 in-plane window (centre included)
//         sums to the opposite sign AND an in-plane neighbour of the opposite
//         sign has a larger magnitude ("sign flow").
//   SVF3  a far voxel flips when its 4 in-plane neighbours all have the
//         opposite sign.
//   SVF4  any voxel flips when at least 4 of its 6 neighbours have the
//         opposite sign (one pass, no threshold).
//
// Planes are perpendicular to the filter axis. A flip negates the value (the
// magnitude is kept, as the authors' code does). Everything is deterministic:
// SVF2/SVF3 update in place in a fixed colour order (4 colours of the 3x3
// stencil, 2 of the 4-neighbour stencil), so no voxel is written while a
// voxel that reads it is evaluated; SVF4 is a Jacobi pass (all decisions read
// the input). CPU with any thread count and CUDA give bit-identical results.
// docs/SVF.md explains every rule and where this follows the code or paper.
#pragma once

#include "lvdif/Cuda.h"
#include "lvdif/DenseGrid.h"
#include "lvdif/Interrupter.h"

#include <array>
#include <cstdint>
#include <vector>

namespace lvdif
{

class DictionaryVolume;

/// Bits selecting the filters; they always run in the order SVF1, 2, 3, 4.
enum SvfBits : unsigned
{
  Svf1 = 1u,
  Svf2 = 2u,
  Svf3 = 4u,
  Svf4 = 8u,
  SvfAll = 15u
};

/// The original's cumulative setting: n = 1..4 runs SVF1..SVFn (0 runs none).
unsigned svfCumulative(int n);

/// What the virtual neighbours just outside the grid read as.
enum class SvfBoundary
{
  /// Outside the object (positive sign, magnitude 0): the grid is assumed to
  /// enclose the object, as for a mesh bounding box with padding. Closest to
  /// the original, whose boundary layer reads as a tiny "outside" value.
  Outside,
  /// No sign: out-of-grid neighbours never vote (for crops of a larger field).
  Free
};

struct SignVoxelFilterParams
{
  /// Voxels with |d| <= threshold are never flipped by SVF1..SVF3 (voxel units).
  float threshold = 2.0f;
  /// Filter axis 0 = x, 1 = y, 2 = z: SVF1 scans along it, SVF2/3 work in the
  /// planes perpendicular to it. Default x, the paper's default ("y-z plane
  /// along the x axis").
  int axis = 0;
  /// Which filters run (SvfBits).
  unsigned filters = SvfAll;
  /// SVF2/SVF3 iterations per plane at most; 0 = automatic: the larger in-plane
  /// dimension (a wrong streak erodes at least one voxel per iteration).
  int maxIterations = 0;
  SvfBoundary boundary = SvfBoundary::Outside;
  Device device = Device::Auto;
  /// Dictionary volumes only: planes decoded per slab (0 = automatic, about
  /// 128 MiB). A test knob: the result does not depend on it.
  std::int64_t volumeSlabPlanes = 0;
};

struct SignVoxelFilterStats
{
  /// Voxels whose sign each filter changed (index 0 = SVF1). For SVF2/SVF3 a
  /// voxel flipped twice counts 0 (net change).
  std::array<std::int64_t, 4> flips{ 0, 0, 0, 0 };
  /// SVF2/SVF3: iterations of the slowest plane, the last one being the pass
  /// that found nothing (or the cap). SVF1 and SVF4 report 1 when run.
  std::array<int, 4> iterations{ 0, 0, 0, 0 };
  /// SVF2/SVF3: planes still changing when the cap stopped them.
  std::array<std::int64_t, 4> planesAtCap{ 0, 0, 0, 0 };
  /// Where it ran (Cpu or Cuda).
  Device device = Device::Cpu;
  /// CUDA only: milliseconds on the device without the host<->device copies.
  double deviceMs = 0;
  std::int64_t totalFlips() const { return flips[0] + flips[1] + flips[2] + flips[3]; }
};

/// The one rule of the parameters (every entry point and the VTK filter's
/// settings check): throws Error(InvalidArgument) naming the first parameter
/// outside its range (threshold finite and >= 0, axis 0..2, filters only
/// Svf1..Svf4 bits, maxIterations >= 0) and its value.
void checkSignVoxelFilterParams(const SignVoxelFilterParams& params);

/// Runs the selected filters in place on a dense float grid (negative inside,
/// voxel units). Throws Error(InvalidArgument) for a bad parameter or an empty
/// grid, Error(Cancelled) when the interrupter asks (the grid then holds a
/// partially filtered state). NaN voxels are never flipped and have no sign.
SignVoxelFilterStats signVoxelFilter(const FloatGridView& grid, const SignVoxelFilterParams& params = {},
  Interrupter& interrupter = nullInterrupter());

/// The planes [first, last] along the filter axis: a piece of a volume for the
/// sign voxel filters (distributed runs). SVF1's rows cross the volume along
/// the axis, SVF2/SVF3 work inside one plane, SVF4 reads one plane on each
/// side: a piece needs the sign each row enters it with and one ghost plane
/// on each side, nothing else.
struct SvfPlanes
{
  std::int64_t first = 0;
  /// Below first: through the volume's last plane.
  std::int64_t last = -1;
  /// The SVF1 sign (-1, 0, +1) each row enters plane `first` with: nU x nV
  /// values, u fastest, (u, v) the in-plane axes in order ((y, z) for axis x,
  /// (x, z) for y, (x, y) for z). Empty: the boundary's (first must be 0).
  /// Obtained by composing svf1ExitSigns of the pieces before (svf1Continue).
  std::vector<std::int8_t> entrySigns;
};

/// The same on a dictionary volume, streamed: planes perpendicular to the
/// filter axis are decoded a slab at a time into a float buffer (at most
/// 128 MiB or an eighth of the memory limit, but three planes at least), filtered there exactly as the dense grid
/// would be, and the voxels whose sign changed are written back as the key of
/// the negated decoded value (colour kept; chunks marked dirty, collapsed
/// again where they became uniform). Because keys are ordered like values,
/// the filters see exactly the signs the volume stores; magnitudes are those
/// of the dictionary. The result and the statistics equal the dense
/// filter's on the decoded volume. SVF1 and SVF4 run on the CPU; SVF2/SVF3
/// on params.device (their planes go through the dense filter).
///
/// With `planes`, only that piece is written; its ghost planes first-1 and
/// last+1 are read and must still hold unfiltered values. Cancelling (or an
/// OutOfMemory error) leaves the planes written so far filtered: filter a
/// clone (copy-on-write) to keep the original.
SignVoxelFilterStats signVoxelFilter(DictionaryVolume& volume, const SignVoxelFilterParams& params = {},
  Interrupter& interrupter = nullInterrupter());
SignVoxelFilterStats signVoxelFilter(DictionaryVolume& volume, const SignVoxelFilterParams& params,
  const SvfPlanes& planes, Interrupter& interrupter = nullInterrupter());

/// What SVF1 does to each row over the planes [first, last] (original,
/// unfiltered values): the sign it leaves with, for each sign it enters with.
/// 3 x nU x nV values: entering with -1, then 0, then +1 (layout of
/// SvfPlanes::entrySigns).
std::vector<std::int8_t> svf1ExitSigns(const DictionaryVolume& volume, const SignVoxelFilterParams& params,
  std::int64_t first, std::int64_t last, Interrupter& interrupter = nullInterrupter());

/// The signs rows enter the volume with (the boundary's), for the first piece.
std::vector<std::int8_t> svf1BoundarySigns(const DictionaryVolume& volume, const SignVoxelFilterParams& params);

/// The signs rows leave a piece with, given those they enter it with and the
/// piece's svf1ExitSigns.
std::vector<std::int8_t> svf1Continue(const std::vector<std::int8_t>& entry, const std::vector<std::int8_t>& exits);

} // namespace lvdif
