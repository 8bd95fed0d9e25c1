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

/// Runs the selected filters in place on a dense float grid (negative inside,
/// voxel units). Throws Error(InvalidArgument) for a bad parameter or an empty
/// grid, Error(Cancelled) when the interrupter asks (the grid then holds a
/// partially filtered state). NaN voxels are never flipped and have no sign.
SignVoxelFilterStats signVoxelFilter(const FloatGridView& grid, const SignVoxelFilterParams& params = {},
  Interrupter& interrupter = nullInterrupter());

/// The same on a dictionary volume: decodes it into a dense float grid (4 bytes
/// a voxel, checked with requireMemory first), filters that, and writes back
/// only the voxels whose sign changed, as the key of the negated decoded value
/// (colour kept; chunks marked dirty, collapsed again where they became
/// uniform). Because keys are ordered like values, the filters see exactly
/// the signs the volume stores; magnitudes are those of the dictionary.
/// Cancelling leaves the volume unchanged (the write-back starts after the
/// filters); an error during the write-back (OutOfMemory) leaves part of it.
SignVoxelFilterStats signVoxelFilter(DictionaryVolume& volume, const SignVoxelFilterParams& params = {},
  Interrupter& interrupter = nullInterrupter());

} // namespace lvdif
