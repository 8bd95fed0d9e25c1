// Sign voxel filters: parameter validation and the choice of back end.
#include "lvdif/SignVoxelFilter.h"

#include "SignVoxelFilterImpl.h"
#include "SignVoxelFilterRules.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace lvdif
{

unsigned svfCumulative(int n)
{
  require(n >= 0 && n <= 4, "svfCumulative: n must be in 0..4, got " + std::to_string(n));
  return (1u << n) - 1u;
}

void checkSignVoxelFilterParams(const SignVoxelFilterParams& params)
{
  // the value as given: a clamp would hide the mistake (docs/USER_GUIDE.md)
  std::ostringstream threshold;
  threshold << params.threshold;
  require(std::isfinite(params.threshold) && params.threshold >= 0.0f,
    "signVoxelFilter: the threshold must be finite and >= 0, not " + threshold.str());
  require(params.axis >= 0 && params.axis <= 2,
    "signVoxelFilter: the axis must be 0 (x), 1 (y) or 2 (z), not " + std::to_string(params.axis));
  require((params.filters & ~static_cast<unsigned>(SvfAll)) == 0,
    "signVoxelFilter: the filter mask may only contain Svf1..Svf4 bits (0..15), not " +
      std::to_string(static_cast<int>(params.filters)));
  require(params.maxIterations >= 0,
    "signVoxelFilter: maxIterations must be >= 0 (0 = automatic), not " + std::to_string(params.maxIterations));
}

namespace detail::svf
{
double svfProgress(unsigned filters, int f, double within)
{
  int total = 0, before = 0;
  for (int q = 0; q < 4; ++q)
  {
    if (filters & (1u << q))
    {
      ++total;
      before += q < f ? 1 : 0;
    }
  }
  return total == 0 ? 1.0 : (before + std::clamp(within, 0.0, 1.0)) / total;
}
} // namespace detail::svf

SignVoxelFilterStats signVoxelFilter(
  const FloatGridView& grid, const SignVoxelFilterParams& params, Interrupter& interrupter)
{
  const GridGeometry& g = grid.geometry;
  require(grid.data != nullptr, "signVoxelFilter: the grid has no data");
  require(g.dims[0] > 0 && g.dims[1] > 0 && g.dims[2] > 0,
    "signVoxelFilter: every grid dimension must be positive");
  checkSignVoxelFilterParams(params);

  detail::svf::SvfSetup s;
  s.threshold = params.threshold;
  s.axis = params.axis;
  s.filters = params.filters;
  s.boundarySign = params.boundary == SvfBoundary::Outside ? 1 : 0;
  const int u = detail::svf::axisU(params.axis), v = detail::svf::axisV(params.axis);
  const std::int64_t autoCap = std::max<std::int64_t>({ g.dims[u], g.dims[v], 2 });
  s.cap = params.maxIterations > 0 ? params.maxIterations : static_cast<int>(std::min<std::int64_t>(autoCap, 1 << 30));

  interrupter.start("sign voxel filters");
  SignVoxelFilterStats stats;
  if (resolveDevice(params.device) == Device::Cuda)
  {
    const std::uint64_t need = detail::svf::signVoxelFilterCudaBytes(g);
    // leave 5% of the free device memory for the runtime
    if (need <= cuda::freeMemory() / 20 * 19)
    {
      stats = detail::svf::signVoxelFilterCuda(grid, s, interrupter);
      interrupter.end();
      return stats;
    }
    std::fprintf(stderr, "lvdif: signVoxelFilter needs %s of device memory, %s free; using the CPU\n",
      formatBytes(need).c_str(), formatBytes(cuda::freeMemory()).c_str());
  }
  stats = detail::svf::signVoxelFilterCpu(grid, s, interrupter);
  interrupter.end();
  return stats;
}

} // namespace lvdif
