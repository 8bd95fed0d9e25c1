#include "DemoScene.h"

#include "lvdif/AnalyticFill.h"

#include <algorithm>
#include <cmath>

DemoResult BuildDemoVolume(long size, const std::string&, lvdif::Interrupter& progress)
{
  lvdif::VolumeOptions o;
  o.dims = { size, size, size };
  DemoResult r;
  r.volume = std::make_unique<lvdif::DictionaryVolume>(o);
  const double c = 0.5 * size, rad = 0.3 * size;
  // a sphere with a cubic bite taken out (max of the sphere and the negated box)
  const auto sphere = lvdif::sphereSdf(c, c, c, rad);
  lvdif::fillFromFunction(*r.volume, [&](double x, double y, double z) {
    const double q[3] = { std::fabs(x - c - 0.5 * rad) - 0.45 * rad, std::fabs(y - c - 0.5 * rad) - 0.45 * rad,
      std::fabs(z - c - 0.5 * rad) - 0.45 * rad };
    const double outside = std::sqrt(std::pow(std::max(q[0], 0.0), 2) + std::pow(std::max(q[1], 0.0), 2) +
      std::pow(std::max(q[2], 0.0), 2));
    const double box = outside + std::min(std::max(q[0], std::max(q[1], q[2])), 0.0);
    return static_cast<float>(std::max<double>(sphere(x, y, z), -box));
  }, 0, progress);
  r.source = "analytic sphere minus box (embedded)";
  return r;
}
