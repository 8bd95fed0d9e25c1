// Sign voxel filter timing (the paper: 0.84 s at 256^3, 56.84 s at
// 1024^3 on an RTX 3090 for all four filters).
//
// Field: the analytic SDF of a torus (voxel units, negative inside) with
// wrong signs injected the way a normal-based sign goes wrong: streaks along
// the filter axis (a row segment beyond some point takes the wrong sign) and
// isolated voxels. Reported: time per filter and in all, flips, and the
// fraction of voxels whose sign disagrees with the analytic one before/after.
//
// usage: bench_sign_voxel_filter [--cpu 128,256] [--gpu 256,512,1024]
// CPU rows give the time also as a multiple of one std::copy of the grid
// (a peer measured in the same process); GPU rows give device time (data
// resident) and end-to-end time with the host<->device copies.
#include "BenchCommon.h"

#include "lvdif/Cuda.h"
#include "lvdif/SignVoxelFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{

std::vector<int> parseSizes(const char* s)
{
  std::vector<int> v;
  std::stringstream in(s);
  std::string tok;
  while (std::getline(in, tok, ','))
    if (!tok.empty())
      v.push_back(std::stoi(tok));
  return v;
}

struct Field
{
  std::int64_t n;
  std::vector<float> truth; // analytic SDF
  std::vector<float> noisy; // with injected wrong signs
};

Field makeField(std::int64_t n)
{
  Field f{ n, std::vector<float>(static_cast<size_t>(n * n * n)), {} };
  const double c = 0.5 * double(n - 1), R = 0.28 * double(n), r = 0.12 * double(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < n; ++k)
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t i = 0; i < n; ++i)
      {
        const double x = i - c, y = j - c, z = k - c;
        const double q = std::sqrt(x * x + z * z) - R; // torus around the y axis
        f.truth[static_cast<size_t>(i + n * (j + n * k))] = static_cast<float>(std::sqrt(q * q + y * y) - r);
      }
  f.noisy = f.truth;
  std::mt19937_64 rng(42);
  // streaks along x: n^2/32 row segments of length n/16..n/4 with far voxels flipped
  const std::int64_t streaks = n * n / 32;
  for (std::int64_t s = 0; s < streaks; ++s)
  {
    const std::int64_t j = rng() % n, k = rng() % n, len = n / 16 + rng() % (n / 4 - n / 16 + 1);
    const std::int64_t i0 = rng() % n;
    for (std::int64_t i = i0; i < std::min(n, i0 + len); ++i)
    {
      float& v = f.noisy[static_cast<size_t>(i + n * (j + n * k))];
      if (std::fabs(v) > 2.0f)
        v = -v;
    }
  }
  // isolated voxels: 1 in 1000 anywhere
  const std::int64_t isolated = n * n * n / 1000;
  for (std::int64_t s = 0; s < isolated; ++s)
  {
    float& v = f.noisy[static_cast<size_t>(rng() % static_cast<std::uint64_t>(n * n * n))];
    v = -v;
  }
  return f;
}

double wrongFraction(const std::vector<float>& v, const std::vector<float>& truth)
{
  std::int64_t wrong = 0, counted = 0;
#pragma omp parallel for schedule(static) reduction(+ : wrong, counted)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(v.size()); ++i)
  {
    if (truth[static_cast<size_t>(i)] == 0.0f)
      continue;
    ++counted;
    wrong += (v[static_cast<size_t>(i)] < 0) != (truth[static_cast<size_t>(i)] < 0) ? 1 : 0;
  }
  return counted ? double(wrong) / double(counted) : 0.0;
}

lvdif::FloatGridView view(std::vector<float>& v, std::int64_t n)
{
  lvdif::FloatGridView g;
  g.data = v.data();
  g.geometry.dims = { n, n, n };
  return g;
}

std::string pct(double f)
{
  return bench::fmt(100.0 * f, 3) + "%";
}

void runSize(std::int64_t n, bool cpu, bool gpu, std::vector<std::vector<std::string>>& rows)
{
  const Field f = makeField(n);
  const std::string size = std::to_string(n) + "^3";
  const double before = wrongFraction(f.noisy, f.truth);
  std::vector<float> work(f.noisy.size());

  // peer: one copy of the grid, median of 3
  const double copyMs = bench::medianMs(3, [&] { std::copy(f.noisy.begin(), f.noisy.end(), work.begin()); });

  for (lvdif::Device dev : { lvdif::Device::Cpu, lvdif::Device::Cuda })
  {
    if ((dev == lvdif::Device::Cpu && !cpu) || (dev == lvdif::Device::Cuda && !gpu))
      continue;
    // per-filter breakdown: each filter on the previous one's output
    std::copy(f.noisy.begin(), f.noisy.end(), work.begin());
    double perMs[4] = { 0, 0, 0, 0 }, perDev[4] = { 0, 0, 0, 0 };
    std::int64_t flips[4] = { 0, 0, 0, 0 };
    int iters[4] = { 0, 0, 0, 0 };
    for (int q = 0; q < 4; ++q)
    {
      lvdif::SignVoxelFilterParams p;
      p.filters = 1u << q;
      p.device = dev;
      bench::Stopwatch w;
      const lvdif::SignVoxelFilterStats st = lvdif::signVoxelFilter(view(work, n), p);
      perMs[q] = w.ms();
      perDev[q] = st.deviceMs;
      flips[q] = st.flips[q];
      iters[q] = st.iterations[q];
      if (dev == lvdif::Device::Cuda && st.device != lvdif::Device::Cuda)
        std::cout << "note: " << size << " fell back to the CPU\n";
    }
    const double after = wrongFraction(work, f.truth);
    const std::vector<float> split = work;
    // all four in one call
    std::copy(f.noisy.begin(), f.noisy.end(), work.begin());
    lvdif::SignVoxelFilterParams p;
    p.device = dev;
    bench::Stopwatch w;
    const lvdif::SignVoxelFilterStats all = lvdif::signVoxelFilter(view(work, n), p);
    const double allMs = w.ms();
    const bool same = std::memcmp(split.data(), work.data(), work.size() * sizeof(float)) == 0;
    const bool onGpu = all.device == lvdif::Device::Cuda;
    auto t = [&](int q) {
      return bench::fmt(onGpu ? perDev[q] : perMs[q], 1) + " (" + std::to_string(iters[q]) + " it, " +
        std::to_string(flips[q]) + ")";
    };
    rows.push_back({ size, onGpu ? "cuda" : "cpu", t(0), t(1), t(2), t(3),
      onGpu ? bench::fmt(all.deviceMs, 1) : bench::fmt(allMs, 1), bench::fmt(allMs, 1),
      onGpu ? "-" : bench::fmt(allMs / copyMs, 1) + "x", pct(before), pct(after), same ? "yes" : "NO" });
  }
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<int> cpuSizes{ 128, 256 }, gpuSizes{ 256, 512, 1024 };
  for (int a = 1; a + 1 < argc; a += 2)
  {
    if (!std::strcmp(argv[a], "--cpu"))
      cpuSizes = parseSizes(argv[a + 1]);
    else if (!std::strcmp(argv[a], "--gpu"))
      gpuSizes = parseSizes(argv[a + 1]);
  }
  if (!lvdif::cuda::available())
    gpuSizes.clear();
  else
    lvdif::cuda::freeMemory(); // creates the CUDA context outside the timings
  std::cout << "Sign voxel filters SVF1..SVF4 (T = 2, axis x, boundary outside), torus with injected wrong signs\n";
  std::cout << bench::machineDescription() << "\n\n";
  std::vector<int> sizes = cpuSizes;
  sizes.insert(sizes.end(), gpuSizes.begin(), gpuSizes.end());
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  std::vector<std::vector<std::string>> rows;
  for (int n : sizes)
  {
    const bool cpu = std::find(cpuSizes.begin(), cpuSizes.end(), n) != cpuSizes.end();
    const bool gpu = std::find(gpuSizes.begin(), gpuSizes.end(), n) != gpuSizes.end();
    try
    {
      runSize(n, cpu, gpu, rows);
    }
    catch (const std::exception& e)
    {
      std::cout << n << "^3: " << e.what() << "\n";
    }
  }
  std::cout << "SVFn columns: ms (iterations of the slowest plane, voxels flipped); device ms for cuda\n";
  bench::printTable({ "size", "device", "SVF1", "SVF2", "SVF3", "SVF4", "all ms (device)", "all ms (wall)",
                      "all / copy", "wrong before", "wrong after", "split == all" },
    rows);
  return 0;
}
