// The closed, painted test shape of the file benchmarks (bench_volume_file,
// bench_volume_file_vdb): a sphere fused with a torus, band 8, chunk edge 32,
// six colours in stripes on the shell (|d| < 3).
#pragma once

#include "lvdif/AnalyticFill.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sys/resource.h>

namespace bench
{

inline void paintShell(lvdif::DictionaryVolume& volume);

inline std::unique_ptr<lvdif::DictionaryVolume> makePaintedShape(std::int64_t n)
{
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = 32;
  o.memoryLimit = 0;
  auto v = std::make_unique<lvdif::DictionaryVolume>(o);
  const double c = 0.5 * double(n), r = 0.3 * double(n), R = 0.3 * double(n), t = 0.08 * double(n);
  const lvdif::SdfFunction sphere = lvdif::sphereSdf(c, c, c * 0.9, r);
  // union of a sphere and a horizontal torus through it (min of SDFs stays 1-Lipschitz)
  lvdif::fillFromFunction(*v, [=](double x, double y, double z) {
    const double dx = x - c, dy = y - c, dz = z - c * 1.2;
    const double q = std::sqrt(dx * dx + dy * dy) - R;
    return std::min(sphere(x, y, z), static_cast<float>(std::sqrt(q * q + dz * dz) - t));
  });
  paintShell(*v);
  return v;
}

/// Paints 6 colours in 16-voxel stripes on the shell (|d| < 3) of any volume.
inline void paintShell(lvdif::DictionaryVolume& volume)
{
  lvdif::DictionaryVolume* v = &volume;
  lvdif::ColorKey keys[6];
  for (int i = 0; i < 6; ++i)
    keys[i] = v->colors().add(lvdif::Rgba{ std::uint8_t(40 * i), std::uint8_t(255 - 30 * i), std::uint8_t(90 + 20 * i), 255 });
  const lvdif::SdfKey lo = v->encode(-3), hi = v->encode(3);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t id = 0; id < v->chunkCount(); ++id)
  {
    if (v->isUniform(id))
      continue;
    const lvdif::VoxelBox b = v->chunkBox(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          lvdif::Voxel w = v->get(x, y, z);
          if (w.sdf > lo && w.sdf < hi)
          {
            w.color = keys[((x + 2 * y) / 16 + z / 16) % 6];
            v->set(x, y, z, w);
          }
        }
  }
}

/// CPU seconds of the process (all threads), to read wall times on a shared machine.
inline double cpuSeconds()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

} // namespace bench
