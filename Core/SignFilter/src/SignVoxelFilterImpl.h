// Internal interface between the sign voxel filter dispatcher and its CPU and
// CUDA back ends (not installed).
#pragma once

#include "lvdif/SignVoxelFilter.h"

namespace lvdif
{
namespace detail::svf
{

/// Validated parameters with the automatic values resolved.
struct SvfSetup
{
  float threshold = 2.0f;
  int axis = 0;
  unsigned filters = SvfAll;
  int cap = 1;       // SVF2/SVF3 iterations per plane at most
  int boundarySign = 1; // +1 (Outside) or 0 (Free)
};

SignVoxelFilterStats signVoxelFilterCpu(const FloatGridView& grid, const SvfSetup& setup, Interrupter& interrupter);

/// Device bytes the CUDA path needs for this grid.
std::uint64_t signVoxelFilterCudaBytes(const GridGeometry& geometry);
/// Throws Error(Unsupported) in builds without CUDA.
SignVoxelFilterStats signVoxelFilterCuda(const FloatGridView& grid, const SvfSetup& setup, Interrupter& interrupter);

/// Progress over the selected filters: filter f (0..3) is `within` done.
double svfProgress(unsigned filters, int f, double within);

} // namespace detail::svf
} // namespace lvdif
