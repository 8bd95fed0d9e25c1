// Sign voxel filters on the CPU (OpenMP). Each parallel loop writes only
// voxels whose inputs no other iteration of that loop writes, so the result
// does not depend on the thread count or schedule:
//  * SVF1: one thread owns a whole row along the axis (a sequential scan).
//  * SVF2/SVF3: one colour class per sweep (see SignVoxelFilterRules.h).
//  * SVF4: decisions go to a bit mask first, then are applied.
#include "SignVoxelFilterImpl.h"
#include "SignVoxelFilterRules.h"

#include "lvdif/Memory.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <vector>

namespace lvdif
{
namespace detail::svf
{
namespace
{

using detail::svf::AxisFrame;

struct Dense
{
  float* d;
  std::int64_t nx, ny, nz;
  AxisFrame frame(int axis) const
  {
    const std::int64_t n[3] = { nx, ny, nz };
    const std::int64_t s[3] = { 1, nx, nx * ny };
    const int u = detail::svf::axisU(axis), v = detail::svf::axisV(axis);
    return AxisFrame{ n[u], n[v], n[axis], s[u], s[v], s[axis] };
  }
};

/// Runs body(r) for every row r = j + ny*k in slabs, polling the interrupter
/// between slabs (exceptions may not leave an OpenMP region).
template <typename Body>
void forRows(const Dense& g, Interrupter& it, unsigned filters, int f, Body&& body)
{
  const std::int64_t rows = g.ny * g.nz;
  const std::int64_t slab = std::max<std::int64_t>(1, rows / 16);
  for (std::int64_t r0 = 0; r0 < rows; r0 += slab)
  {
    it.checkInterrupt();
    const std::int64_t r1 = std::min(rows, r0 + slab);
#pragma omp parallel for schedule(static)
    for (std::int64_t r = r0; r < r1; ++r)
    {
      body(r);
    }
    it.progress(svfProgress(filters, f, double(r1) / double(rows)));
  }
}

// ---- SVF1: a sequential scan along the axis, rows in parallel ---------------
std::int64_t runSvf1(const Dense& g, const SvfSetup& s, Interrupter& it)
{
  const AxisFrame f = g.frame(s.axis);
  std::int64_t flips = 0;
  // Parallel over a dimension that is not the axis, so each thread owns whole
  // rows; inner loops run along x (contiguous) where x is not the axis.
  const std::int64_t outer = s.axis == 2 ? g.ny : g.nz;
  const std::int64_t slab = std::max<std::int64_t>(1, outer / 16);
  for (std::int64_t o0 = 0; o0 < outer; o0 += slab)
  {
    it.checkInterrupt();
    const std::int64_t o1 = std::min(outer, o0 + slab);
#pragma omp parallel for schedule(static) reduction(+ : flips)
    for (std::int64_t o = o0; o < o1; ++o)
    {
      if (s.axis == 0)
      {
        for (std::int64_t j = 0; j < g.ny; ++j)
        {
          float* row = g.d + g.nx * (j + g.ny * o);
          int prev = s.boundarySign;
          for (std::int64_t i = 0; i < g.nx; ++i)
          {
            float c = row[i];
            if (detail::svf::svf1Flips(c, prev, s.threshold))
            {
              c = -c;
              row[i] = c;
              ++flips;
            }
            prev = detail::svf::signOf(c);
          }
        }
      }
      else
      {
        // axis y: o = k, scan j; axis z: o = j, scan k. The predecessor is the
        // previous row along the axis, already final (same thread).
        for (std::int64_t a = 0; a < f.nA; ++a)
        {
          const std::int64_t base = s.axis == 1 ? g.nx * (a + g.ny * o) : g.nx * (o + g.ny * a);
          for (std::int64_t i = 0; i < g.nx; ++i)
          {
            const std::int64_t idx = base + i;
            const float c = g.d[idx];
            const int prev = a > 0 ? detail::svf::signOf(g.d[idx - f.sA]) : s.boundarySign;
            if (detail::svf::svf1Flips(c, prev, s.threshold))
            {
              g.d[idx] = -c;
              ++flips;
            }
          }
        }
      }
    }
    it.progress(svfProgress(s.filters, 0, double(o1) / double(outer)));
  }
  return flips;
}

// ---- sign masks (net change counting for SVF2/SVF3) ------------------------
std::vector<std::uint64_t> signMask(const Dense& g)
{
  const std::int64_t n = g.nx * g.ny * g.nz;
  const std::int64_t words = (n + 63) / 64;
  requireMemory(static_cast<std::uint64_t>(words) * 8, "sign voxel filter sign mask");
  std::vector<std::uint64_t> mask(static_cast<std::size_t>(words));
#pragma omp parallel for schedule(static)
  for (std::int64_t w = 0; w < words; ++w)
  {
    std::uint64_t bits = 0;
    const std::int64_t end = std::min<std::int64_t>(64, n - 64 * w);
    for (std::int64_t b = 0; b < end; ++b)
    {
      bits |= static_cast<std::uint64_t>(g.d[64 * w + b] < 0.0f) << b;
    }
    mask[static_cast<std::size_t>(w)] = bits;
  }
  return mask;
}

std::int64_t countChanged(const Dense& g, const std::vector<std::uint64_t>& before)
{
  const std::vector<std::uint64_t> after = signMask(g);
  std::int64_t changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
  for (std::int64_t w = 0; w < static_cast<std::int64_t>(after.size()); ++w)
  {
    changed += __builtin_popcountll(after[static_cast<std::size_t>(w)] ^ before[static_cast<std::size_t>(w)]);
  }
  return changed;
}

// ---- SVF2 / SVF3: coloured in-place sweeps, per-plane convergence ---------
/// The neighbours of the voxels of one x-row (j, k) in the plane of the
/// filter axis: neighbour q of voxel i is Row[q][i + Off[q]], or virtual (the
/// boundary) when Row[q] is null or i + Off[q] leaves [0, nx). Hoisting the
/// bounds tests out of the inner loop is what makes the CPU sweeps fast.
struct RowNeighbours
{
  const float* Row[8];
  int Off[8];
  bool Interior; // every Row[q] present: only i = 0 and nx-1 need care

  RowNeighbours(const Dense& g, int axis, std::int64_t j, std::int64_t k, bool diagonals)
  {
    int q = 0;
    Interior = true;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du)
      {
        if ((du == 0 && dv == 0) || (!diagonals && du != 0 && dv != 0))
          continue;
        // (dj, dk, di) of this in-plane step for the axis
        std::int64_t dj = 0, dk = 0;
        int di = 0;
        if (axis == 0)
        {
          dj = du;
          dk = dv;
        }
        else if (axis == 1)
        {
          di = du;
          dk = dv;
        }
        else
        {
          di = du;
          dj = dv;
        }
        const std::int64_t jj = j + dj, kk = k + dk;
        const bool in = jj >= 0 && kk >= 0 && jj < g.ny && kk < g.nz;
        Row[q] = in ? g.d + g.nx * (jj + g.ny * kk) : nullptr;
        Off[q] = di;
        Interior = Interior && in;
        ++q;
      }
  }

  /// Signs and magnitudes of the neighbours of voxel i (n = 8 or 4).
  void gather(std::int64_t i, std::int64_t nx, int n, int bsign, int* s, float* m) const
  {
    const bool safe = Interior && i > 0 && i + 1 < nx;
    for (int q = 0; q < n; ++q)
    {
      const std::int64_t ii = i + Off[q];
      if (safe || (Row[q] && ii >= 0 && ii < nx))
      {
        const float x = Row[q][ii];
        s[q] = detail::svf::signOf(x);
        m[q] = std::fabs(x);
      }
      else
      {
        s[q] = bsign;
        m[q] = 0.0f;
      }
    }
  }
};

/// One sweep over colour `col` of the planes marked active; sets changed[a]
/// for every plane where a voxel flipped.
void sweep(const Dense& g, const SvfSetup& s, int filter, int col, const std::vector<std::uint8_t>& active,
  std::atomic<std::uint8_t>* changed)
{
  const std::int64_t rows = g.ny * g.nz;
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    const std::int64_t j = r % g.ny, k = r / g.ny;
    std::int64_t iStart = 0, iStep = 1;
    if (s.axis == 0)
    {
      // (u, v) = (j, k): the whole row has one colour
      const int c = filter == 2 ? detail::svf::colourSvf2(j, k) : detail::svf::colourSvf3(j, k);
      if (c != col)
        continue;
    }
    else
    {
      // u = i; the plane index a and v are fixed by the row
      const std::int64_t a = s.axis == 1 ? j : k;
      const std::int64_t v = s.axis == 1 ? k : j;
      if (!active[static_cast<std::size_t>(a)])
        continue;
      if (filter == 2)
      {
        if (((v & 1) << 1) != (col & 2))
          continue;
        iStart = col & 1;
      }
      else
      {
        iStart = (col - v) & 1;
      }
      iStep = 2;
    }
    const RowNeighbours nb(g, s.axis, j, k, filter == 2);
    float* row = g.d + g.nx * r;
    for (std::int64_t i = iStart; i < g.nx; i += iStep)
    {
      if (s.axis == 0 && !active[static_cast<std::size_t>(i)])
        continue;
      const float c = row[i];
      if (!detail::svf::isFar(c, s.threshold))
        continue;
      int sg[8];
      float mg[8];
      bool flip;
      if (filter == 2)
      {
        nb.gather(i, g.nx, 8, s.boundarySign, sg, mg);
        flip = detail::svf::svf2Flips(c, sg, mg, s.threshold);
      }
      else
      {
        nb.gather(i, g.nx, 4, s.boundarySign, sg, mg);
        flip = detail::svf::svf3Flips(c, sg, s.threshold);
      }
      if (flip)
      {
        row[i] = -c;
        const std::int64_t a = s.axis == 0 ? i : (s.axis == 1 ? j : k);
        changed[a].store(1, std::memory_order_relaxed);
      }
    }
  }
}

/// filter = 2 or 3. Returns the net flips; fills iterations and planesAtCap.
std::int64_t runPlanar(const Dense& g, const SvfSetup& s, int filter, Interrupter& it, int& iterations,
  std::int64_t& atCap)
{
  const AxisFrame f = g.frame(s.axis);
  const std::vector<std::uint64_t> before = signMask(g);
  std::vector<std::uint8_t> active(static_cast<std::size_t>(f.nA), 1);
  std::unique_ptr<std::atomic<std::uint8_t>[]> changed(new std::atomic<std::uint8_t>[f.nA]);
  const int colours = filter == 2 ? 4 : 2;
  iterations = 0;
  std::int64_t live = f.nA;
  while (live > 0 && iterations < s.cap)
  {
    it.checkInterrupt();
    for (std::int64_t a = 0; a < f.nA; ++a)
    {
      changed[a].store(0);
    }
    for (int col = 0; col < colours; ++col)
    {
      sweep(g, s, filter, col, active, changed.get());
    }
    ++iterations;
    live = 0;
    for (std::int64_t a = 0; a < f.nA; ++a)
    {
      const bool go = active[static_cast<std::size_t>(a)] && changed[a].load();
      active[static_cast<std::size_t>(a)] = go ? 1 : 0;
      live += go ? 1 : 0;
    }
    it.progress(svfProgress(s.filters, filter - 1, 1.0 - double(live) / double(f.nA)));
  }
  atCap = live;
  return countChanged(g, before);
}

// ---- SVF4: one Jacobi pass through a flip mask ------------------------------
std::int64_t runSvf4(const Dense& g, const SvfSetup& s, Interrupter& it)
{
  const std::int64_t wordsPerRow = (g.nx + 63) / 64;
  const std::int64_t rows = g.ny * g.nz;
  requireMemory(static_cast<std::uint64_t>(wordsPerRow * rows) * 8, "SVF4 flip mask");
  std::vector<std::uint64_t> mask(static_cast<std::size_t>(wordsPerRow * rows), 0);
  // The 6-neighbourhood is the same for every axis: the 4 neighbours in the
  // x-row's (y, z) plane come from RowNeighbours of axis x, the 2 along x are in the row.
  forRows(g, it, s.filters, 3, [&](std::int64_t r) {
    const std::int64_t j = r % g.ny, k = r / g.ny;
    const RowNeighbours nb(g, 0, j, k, false);
    const float* row = g.d + g.nx * r;
    for (std::int64_t i = 0; i < g.nx; ++i)
    {
      int sg[6];
      float mg[4];
      nb.gather(i, g.nx, 4, s.boundarySign, sg, mg);
      sg[4] = i + 1 < g.nx ? detail::svf::signOf(row[i + 1]) : s.boundarySign;
      sg[5] = i > 0 ? detail::svf::signOf(row[i - 1]) : s.boundarySign;
      if (detail::svf::svf4Flips(row[i], sg))
      {
        mask[static_cast<std::size_t>(r * wordsPerRow + i / 64)] |= std::uint64_t(1) << (i % 64);
      }
    }
  });
  std::int64_t flips = 0;
#pragma omp parallel for schedule(static) reduction(+ : flips)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    for (std::int64_t w = 0; w < wordsPerRow; ++w)
    {
      std::uint64_t bits = mask[static_cast<std::size_t>(r * wordsPerRow + w)];
      flips += __builtin_popcountll(bits);
      while (bits)
      {
        const int b = __builtin_ctzll(bits);
        bits &= bits - 1;
        float& x = g.d[g.nx * r + 64 * w + b];
        x = -x;
      }
    }
  }
  return flips;
}

} // namespace

SignVoxelFilterStats signVoxelFilterCpu(const FloatGridView& grid, const SvfSetup& s, Interrupter& it)
{
  const Dense g{ grid.data, grid.geometry.dims[0], grid.geometry.dims[1], grid.geometry.dims[2] };
  SignVoxelFilterStats st;
  st.device = Device::Cpu;
  if (s.filters & Svf1)
  {
    st.flips[0] = runSvf1(g, s, it);
    st.iterations[0] = 1;
  }
  if (s.filters & Svf2)
  {
    st.flips[1] = runPlanar(g, s, 2, it, st.iterations[1], st.planesAtCap[1]);
  }
  if (s.filters & Svf3)
  {
    st.flips[2] = runPlanar(g, s, 3, it, st.iterations[2], st.planesAtCap[2]);
  }
  if (s.filters & Svf4)
  {
    st.flips[3] = runSvf4(g, s, it);
    st.iterations[3] = 1;
  }
  it.progress(1.0);
  return st;
}

} // namespace detail::svf
} // namespace lvdif
