// Sign voxel filters on CUDA: the same rules (SignVoxelFilterRules.h) and the
// same update order as SignVoxelFilterCpu.cpp, hence bit-identical output.
//  * SVF1: one thread per row along the axis (a sequential scan).
//  * SVF2/SVF3: one launch per colour class; planes that stopped changing
//    are skipped through a per-plane activity flag, as on the CPU.
//  * SVF4 and the net flip counts: warp ballots into bit masks.
// The whole grid lives on the device (plus a 1/32 bit mask); the dispatcher
// falls back to the CPU when it does not fit.
#include "SignVoxelFilterImpl.h"
#include "SignVoxelFilterRules.h"

#include "lvdif/CudaCheck.cuh"

#include <algorithm>
#include <vector>

namespace lvdif
{
namespace detail::svf
{
namespace
{

using detail::svf::AxisFrame;

template <typename T>
struct DeviceArray
{
  T* p = nullptr;
  explicit DeviceArray(std::size_t n) { LVDIF_CUDA_CHECK(cudaMalloc(&p, std::max<std::size_t>(n, 1) * sizeof(T))); }
  ~DeviceArray() { cudaFree(p); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
};

constexpr int Block = 128;

__device__ void addWarpCount(unsigned long long* counter, unsigned long long mine)
{
  for (int o = 16; o > 0; o >>= 1)
  {
    mine += __shfl_down_sync(0xffffffffu, mine, o);
  }
  if ((threadIdx.x & 31) == 0 && mine)
  {
    atomicAdd(counter, mine);
  }
}

// ---- SVF1 --------------------------------------------------------------------
__global__ void svf1Kernel(float* d, AxisFrame f, float t, int bsign, unsigned long long* count)
{
  unsigned long long flips = 0;
  const std::int64_t u = static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  for (std::int64_t v = blockIdx.y; v < f.nV; v += gridDim.y)
  {
    if (u < f.nU)
    {
      const std::int64_t base = u * f.sU + v * f.sV;
      int prev = bsign;
      for (std::int64_t a = 0; a < f.nA; ++a)
      {
        const std::int64_t idx = base + a * f.sA;
        float c = d[idx];
        if (detail::svf::svf1Flips(c, prev, t))
        {
          c = -c;
          d[idx] = c;
          ++flips;
        }
        prev = detail::svf::signOf(c);
      }
    }
  }
  addWarpCount(count, flips);
}

// ---- SVF2 / SVF3 colour sweep ------------------------------------------------
// Threads cover (a, u/2, v) when the axis is x (x = a stays the fastest thread
// index, for coalescing) and (u/2, v, a) otherwise (u = x then).
template <int Filter, bool AxisX>
__global__ void sweepKernel(float* d, AxisFrame f, int col, float t, int bsign, const std::uint8_t* active,
  unsigned* changed)
{
  const std::int64_t halfU = (f.nU + 1) / 2;
  const std::int64_t t0 = static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  const std::int64_t n0 = AxisX ? f.nA : halfU;
  const std::int64_t n1 = AxisX ? halfU : f.nV;
  const std::int64_t n2 = AxisX ? f.nV : f.nA;
  if (t0 >= n0)
  {
    return;
  }
  for (std::int64_t t2 = blockIdx.z; t2 < n2; t2 += gridDim.z)
  {
    for (std::int64_t t1 = blockIdx.y; t1 < n1; t1 += gridDim.y)
    {
      const std::int64_t a = AxisX ? t0 : t2;
      const std::int64_t uh = AxisX ? t1 : t0;
      const std::int64_t v = AxisX ? t2 : t1;
      if (!active[a])
      {
        continue;
      }
      std::int64_t u;
      if (Filter == 2)
      {
        if ((v & 1) != (col >> 1))
        {
          continue;
        }
        u = 2 * uh + (col & 1);
      }
      else
      {
        u = 2 * uh + ((col - v) & 1);
      }
      if (u >= f.nU)
      {
        continue;
      }
      const std::int64_t idx = u * f.sU + v * f.sV + a * f.sA;
      const float c = d[idx];
      if (!detail::svf::isFar(c, t))
      {
        continue;
      }
      bool flip;
      if (Filter == 2)
      {
        int sg[8];
        float mg[8];
        detail::svf::gather8(d, idx, u, v, f, bsign, sg, mg);
        flip = detail::svf::svf2Flips(c, sg, mg, t);
      }
      else
      {
        int sg[4];
        detail::svf::gather4(d, idx, u, v, f, bsign, sg);
        flip = detail::svf::svf3Flips(c, sg, t);
      }
      if (flip)
      {
        d[idx] = -c;
        changed[a] = 1u;
      }
    }
  }
}

// ---- bit masks over the linear index (one warp = one 32-bit word) ------------
struct Lin
{
  std::int64_t nx, ny, n;
};

__global__ void svf4MaskKernel(const float* d, Lin g, AxisFrame f, int axis, int bsign, unsigned* mask)
{
  const int lane = threadIdx.x & 31;
  const std::int64_t warp0 = (static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x) >> 5;
  const std::int64_t warps = (static_cast<std::int64_t>(gridDim.x) * blockDim.x) >> 5;
  for (std::int64_t w = warp0; w * 32 < g.n; w += warps)
  {
    const std::int64_t idx = w * 32 + lane;
    bool flip = false;
    if (idx < g.n)
    {
      const std::int64_t i = idx % g.nx, r = idx / g.nx;
      const std::int64_t c3[3] = { i, r % g.ny, r / g.ny };
      int sg[6];
      detail::svf::gather6(d, idx, c3[detail::svf::axisU(axis)], c3[detail::svf::axisV(axis)], c3[axis], f, bsign, sg);
      flip = detail::svf::svf4Flips(d[idx], sg);
    }
    const unsigned bits = __ballot_sync(0xffffffffu, flip);
    if (lane == 0)
    {
      mask[w] = bits;
    }
  }
}

__global__ void applyMaskKernel(float* d, Lin g, const unsigned* mask, unsigned long long* count)
{
  const int lane = threadIdx.x & 31;
  const std::int64_t warp0 = (static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x) >> 5;
  const std::int64_t warps = (static_cast<std::int64_t>(gridDim.x) * blockDim.x) >> 5;
  for (std::int64_t w = warp0; w * 32 < g.n; w += warps)
  {
    const unsigned bits = mask[w];
    const std::int64_t idx = w * 32 + lane;
    if ((bits >> lane) & 1u)
    {
      d[idx] = -d[idx];
    }
    if (lane == 0 && bits)
    {
      atomicAdd(count, static_cast<unsigned long long>(__popc(bits)));
    }
  }
}

/// count == nullptr: store the negative-sign mask; otherwise count the voxels
/// whose negativity differs from the stored mask.
__global__ void signMaskKernel(const float* d, Lin g, unsigned* mask, unsigned long long* count)
{
  const int lane = threadIdx.x & 31;
  const std::int64_t warp0 = (static_cast<std::int64_t>(blockIdx.x) * blockDim.x + threadIdx.x) >> 5;
  const std::int64_t warps = (static_cast<std::int64_t>(gridDim.x) * blockDim.x) >> 5;
  for (std::int64_t w = warp0; w * 32 < g.n; w += warps)
  {
    const std::int64_t idx = w * 32 + lane;
    const unsigned bits = __ballot_sync(0xffffffffu, idx < g.n && d[idx] < 0.0f);
    if (lane == 0)
    {
      if (count)
      {
        const unsigned diff = bits ^ mask[w];
        if (diff)
        {
          atomicAdd(count, static_cast<unsigned long long>(__popc(diff)));
        }
      }
      else
      {
        mask[w] = bits;
      }
    }
  }
}

unsigned linearBlocks(std::int64_t n)
{
  const std::int64_t warps = (n + 31) / 32;
  return static_cast<unsigned>(std::min<std::int64_t>((warps * 32 + Block - 1) / Block, 1 << 20));
}

unsigned clampGrid(std::int64_t n)
{
  return static_cast<unsigned>(std::clamp<std::int64_t>(n, 1, 65535));
}

struct Context
{
  float* d;
  Lin lin;
  AxisFrame f;
  const SvfSetup& s;
  unsigned* mask;
  unsigned long long* counter;
  Interrupter& it;

  unsigned long long takeCounter()
  {
    unsigned long long h = 0;
    LVDIF_CUDA_CHECK(cudaMemcpy(&h, this->counter, sizeof(h), cudaMemcpyDeviceToHost));
    LVDIF_CUDA_CHECK(cudaMemset(this->counter, 0, sizeof(h)));
    return h;
  }
};

std::int64_t runSvf1(Context& c)
{
  const dim3 grid((static_cast<unsigned>((c.f.nU + Block - 1) / Block)), clampGrid(c.f.nV));
  svf1Kernel<<<grid, Block>>>(c.d, c.f, c.s.threshold, c.s.boundarySign, c.counter);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  return static_cast<std::int64_t>(c.takeCounter());
}

void launchSweep(Context& c, int filter, int col, const std::uint8_t* active, unsigned* changed)
{
  const std::int64_t halfU = (c.f.nU + 1) / 2;
  const bool axisX = c.s.axis == 0;
  const std::int64_t n0 = axisX ? c.f.nA : halfU;
  const std::int64_t n1 = axisX ? halfU : c.f.nV;
  const std::int64_t n2 = axisX ? c.f.nV : c.f.nA;
  const dim3 grid(static_cast<unsigned>((n0 + Block - 1) / Block), clampGrid(n1), clampGrid(n2));
  const float t = c.s.threshold;
  const int b = c.s.boundarySign;
  if (filter == 2)
  {
    if (axisX)
      sweepKernel<2, true><<<grid, Block>>>(c.d, c.f, col, t, b, active, changed);
    else
      sweepKernel<2, false><<<grid, Block>>>(c.d, c.f, col, t, b, active, changed);
  }
  else
  {
    if (axisX)
      sweepKernel<3, true><<<grid, Block>>>(c.d, c.f, col, t, b, active, changed);
    else
      sweepKernel<3, false><<<grid, Block>>>(c.d, c.f, col, t, b, active, changed);
  }
  LVDIF_CUDA_CHECK(cudaGetLastError());
}

std::int64_t runPlanar(Context& c, int filter, int& iterations, std::int64_t& atCap)
{
  const unsigned blocks = linearBlocks(c.lin.n);
  signMaskKernel<<<blocks, Block>>>(c.d, c.lin, c.mask, nullptr);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  const std::size_t nA = static_cast<std::size_t>(c.f.nA);
  std::vector<std::uint8_t> active(nA, 1);
  std::vector<unsigned> changed(nA, 0);
  DeviceArray<std::uint8_t> dActive(nA);
  DeviceArray<unsigned> dChanged(nA);
  const int colours = filter == 2 ? 4 : 2;
  iterations = 0;
  std::int64_t live = c.f.nA;
  while (live > 0 && iterations < c.s.cap)
  {
    c.it.checkInterrupt();
    LVDIF_CUDA_CHECK(cudaMemcpy(dActive.p, active.data(), nA, cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemset(dChanged.p, 0, nA * sizeof(unsigned)));
    for (int col = 0; col < colours; ++col)
    {
      launchSweep(c, filter, col, dActive.p, dChanged.p);
    }
    LVDIF_CUDA_CHECK(cudaMemcpy(changed.data(), dChanged.p, nA * sizeof(unsigned), cudaMemcpyDeviceToHost));
    ++iterations;
    live = 0;
    for (std::size_t a = 0; a < nA; ++a)
    {
      const bool go = active[a] && changed[a];
      active[a] = go ? 1 : 0;
      live += go ? 1 : 0;
    }
    c.it.progress(svfProgress(c.s.filters, filter - 1, 1.0 - double(live) / double(c.f.nA)));
  }
  atCap = live;
  signMaskKernel<<<blocks, Block>>>(c.d, c.lin, c.mask, c.counter);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  return static_cast<std::int64_t>(c.takeCounter());
}

std::int64_t runSvf4(Context& c)
{
  const unsigned blocks = linearBlocks(c.lin.n);
  svf4MaskKernel<<<blocks, Block>>>(c.d, c.lin, c.f, c.s.axis, c.s.boundarySign, c.mask);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  applyMaskKernel<<<blocks, Block>>>(c.d, c.lin, c.mask, c.counter);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  return static_cast<std::int64_t>(c.takeCounter());
}

} // namespace

std::uint64_t signVoxelFilterCudaBytes(const GridGeometry& g)
{
  const std::uint64_t n = static_cast<std::uint64_t>(g.count());
  const std::uint64_t planes = static_cast<std::uint64_t>(std::max({ g.dims[0], g.dims[1], g.dims[2] }));
  return n * 4 + (n + 31) / 32 * 4 + planes * 5 + 64;
}

SignVoxelFilterStats signVoxelFilterCuda(const FloatGridView& grid, const SvfSetup& s, Interrupter& it)
{
  const GridGeometry& g = grid.geometry;
  const std::int64_t n = g.count();
  const std::int64_t nd[3] = { g.dims[0], g.dims[1], g.dims[2] };
  const std::int64_t sd[3] = { 1, nd[0], nd[0] * nd[1] };
  const int u = detail::svf::axisU(s.axis), v = detail::svf::axisV(s.axis);
  DeviceArray<float> d(static_cast<std::size_t>(n));
  DeviceArray<unsigned> mask(static_cast<std::size_t>((n + 31) / 32));
  DeviceArray<unsigned long long> counter(1);
  LVDIF_CUDA_CHECK(cudaMemset(counter.p, 0, sizeof(unsigned long long)));
  LVDIF_CUDA_CHECK(cudaMemcpy(d.p, grid.data, static_cast<std::size_t>(n) * sizeof(float), cudaMemcpyHostToDevice));

  cudaEvent_t e0, e1;
  LVDIF_CUDA_CHECK(cudaEventCreate(&e0));
  LVDIF_CUDA_CHECK(cudaEventCreate(&e1));
  Context c{ d.p, Lin{ nd[0], nd[1], n }, AxisFrame{ nd[u], nd[v], nd[s.axis], sd[u], sd[v], sd[s.axis] }, s,
    mask.p, counter.p, it };
  SignVoxelFilterStats st;
  st.device = Device::Cuda;
  try
  {
    LVDIF_CUDA_CHECK(cudaEventRecord(e0));
    if (s.filters & Svf1)
    {
      st.flips[0] = runSvf1(c);
      st.iterations[0] = 1;
      it.progress(svfProgress(s.filters, 0, 1.0));
    }
    if (s.filters & Svf2)
    {
      st.flips[1] = runPlanar(c, 2, st.iterations[1], st.planesAtCap[1]);
    }
    if (s.filters & Svf3)
    {
      st.flips[2] = runPlanar(c, 3, st.iterations[2], st.planesAtCap[2]);
    }
    if (s.filters & Svf4)
    {
      st.flips[3] = runSvf4(c);
      st.iterations[3] = 1;
    }
    LVDIF_CUDA_CHECK(cudaEventRecord(e1));
    LVDIF_CUDA_CHECK(cudaEventSynchronize(e1));
    float ms = 0;
    LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, e0, e1));
    st.deviceMs = ms;
  }
  catch (...)
  {
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    throw;
  }
  cudaEventDestroy(e0);
  cudaEventDestroy(e1);
  LVDIF_CUDA_CHECK(cudaMemcpy(grid.data, d.p, static_cast<std::size_t>(n) * sizeof(float), cudaMemcpyDeviceToHost));
  it.progress(1.0);
  return st;
}

} // namespace detail::svf
} // namespace lvdif
