#include "lvdif/AnalyticFill.h"

#include <cmath>

namespace lvdif
{

void fillFromFunction(DictionaryVolume& volume, const SdfFunction& f, ColorKey color, Interrupter& interrupter)
{
  interrupter.start("analytic fill");
  const float band = volume.bandWidth();
  const std::int64_t n = volume.chunkCount();
  std::int64_t done = 0;
  bool cancelled = false;
#pragma omp parallel for schedule(dynamic, 8)
  for (std::int64_t id = 0; id < n; ++id)
  {
    if (cancelled)
    {
      continue;
    }
    const VoxelBox b = volume.chunkBox(id);
    const double c[3] = { 0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2]) };
    double h2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double h = 0.5 * (b.hi[a] - b.lo[a]);
      h2 += h * h;
    }
    const double dc = f(c[0], c[1], c[2]);
    if (std::isfinite(band) && std::fabs(dc) - std::sqrt(h2) > band)
    {
      volume.fillChunk(id, Voxel{ volume.encode(dc > 0 ? band : -band), color });
    }
    else
    {
      Voxel* d = volume.expandChunk(id);
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
            d[volume.localIndex(x, y, z)] = Voxel{ volume.encode(f(double(x), double(y), double(z))), color };
      volume.markDirty(id);
      volume.tryCollapseChunk(id);
    }
#pragma omp critical(lvdif_fill_progress)
    {
      ++done;
      if (interrupter.wasInterrupted())
      {
        cancelled = true;
      }
      else if ((done & 255) == 0)
      {
        // progress from whichever thread holds the lock; the interrupter sees one caller at a time
        interrupter.progress(static_cast<double>(done) / static_cast<double>(n));
      }
    }
  }
  if (cancelled)
  {
    interrupter.checkInterrupt();
  }
  interrupter.progress(1.0);
  interrupter.end();
}

SdfFunction sphereSdf(double cx, double cy, double cz, double radius)
{
  return [=](double x, double y, double z) {
    const double dx = x - cx, dy = y - cy, dz = z - cz;
    return static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz) - radius);
  };
}

} // namespace lvdif
