#include "lvdif/ImageToVolume.h"

#include "lvdif/Brush.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lvdif
{

std::int64_t imageToVolume(DictionaryVolume& volume, const ImageView& image, const ImageToVolumeOptions& o,
  Interrupter& interrupter)
{
  require(image.width > 0 && image.height > 0 && image.rgba != nullptr, "image must have pixels");
  require(image.width <= (1 << 20) && image.height <= (1 << 20), "image is too large");
  require(std::isfinite(o.thickness) && o.thickness > 0, "slab thickness must be finite and > 0");
  require(std::isfinite(o.depthScale) && o.depthScale >= 0 && o.depthScale < 1e6, "depth scale must be in [0, 1e6)");
  require(o.window >= 1 && o.window <= 8, "image search window must be 1..8 pixels");
  const std::int64_t w = image.width, h = image.height;
  interrupter.start("image to volume");

  // per pixel: height of its column (0 = no column) and colour key
  std::vector<float> top(static_cast<size_t>(w * h), 0.0f);
  std::vector<ColorKey> key(static_cast<size_t>(w * h), 0);
  double maxTop = 0;
  for (std::int64_t r = 0; r < h; ++r)
    for (std::int64_t u = 0; u < w; ++u)
    {
      const std::uint8_t* p = image.rgba + 4 * (r * w + u);
      const size_t i = static_cast<size_t>(r * w + u);
      if (p[3] == 0 && !o.keepTransparent)
        continue;
      double d = image.depth ? image.depth[i] : 0.0;
      require(std::isfinite(d), "depth map values must be finite");
      d = std::min(1.0, std::max(0.0, d));
      top[i] = static_cast<float>(o.thickness + d * o.depthScale);
      maxTop = std::max(maxTop, double(top[i]));
      key[i] = volume.colors().add(Rgba{ p[0], p[1], p[2], p[3] });
    }
  // pixel (u, r) -> column at x = ox + u, y = oy + (h - 1 - r)
  const std::int64_t W = o.window;
  VoxelBox box;
  box.lo = { o.origin[0] - W, o.origin[1] - W, o.origin[2] - W };
  box.hi = { o.origin[0] + w - 1 + W, o.origin[1] + h - 1 + W,
    o.origin[2] + static_cast<std::int64_t>(std::ceil(maxTop)) + W };
  const std::vector<std::int64_t> chunks = volume.chunksInBox(box);
  const std::int64_t n = static_cast<std::int64_t>(chunks.size());
  std::int64_t solid = 0;
  bool cancelled = false;
  const float band = volume.bandWidth();

#pragma omp parallel for schedule(dynamic, 1) reduction(+ : solid)
  for (std::int64_t ci = 0; ci < n; ++ci)
  {
    if (cancelled)
      continue;
    const std::int64_t id = chunks[static_cast<size_t>(ci)];
    const VoxelBox b = volume.chunkBox(id).intersect(box);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          const std::int64_t u0 = x - o.origin[0], v0 = y - o.origin[1];
          double best = std::isfinite(band) ? double(band) : 1e30;
          ColorKey bestKey = 0;
          bool any = false;
          for (std::int64_t dv = -W; dv <= W; ++dv)
            for (std::int64_t du = -W; du <= W; ++du)
            {
              const std::int64_t u = u0 + du, v = v0 + dv;
              if (u < 0 || v < 0 || u >= w || v >= h)
                continue;
              const size_t i = static_cast<size_t>((h - 1 - v) * w + u);
              if (!(top[i] > 0))
                continue;
              // box [u-0.5, u+0.5] x [v-0.5, v+0.5] x [0, top] relative to the origin
              const double half = 0.5 * top[i];
              const double d = cubeDistanceBox(double(-du), double(-dv), double(z - o.origin[2]) - half, 0.5, 0.5, half);
              if (!any || d < best)
              {
                best = d;
                bestKey = key[i];
                any = true;
              }
            }
          const Voxel old = volume.get(x, y, z);
          Voxel v = old;
          if (any && best < volume.decode(old.sdf)) // union with what is there
            v = Voxel{ volume.encode(static_cast<float>(best)), bestKey };
          if (v != old)
            volume.set(x, y, z, v);
          solid += volume.decode(v.sdf) < 0;
        }
    if (interrupter.wasInterrupted())
      cancelled = true;
  }
  interrupter.checkInterrupt();
  interrupter.progress(1.0);
  interrupter.end();
  return solid;
}

} // namespace lvdif
