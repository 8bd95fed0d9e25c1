// Helpers shared by the tests that mesh or filter dense float grids: a grid (values and,
// when painted, colours) filled from functions of the grid point, with its view.
#pragma once

#include "lvdif/AnalyticFill.h"
#include "lvdif/ColorDictionary.h"
#include "lvdif/DenseGrid.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace gridtest
{

struct Grid
{
  std::vector<float> data;
  std::vector<lvdif::Rgba> colors; // empty until paint()
  lvdif::FloatGridView view;

  Grid(std::int64_t nx, std::int64_t ny, std::int64_t nz, const lvdif::SdfFunction& f,
    std::array<double, 3> origin = { 0, 0, 0 }, std::array<double, 3> spacing = { 1, 1, 1 })
  {
    data.resize(static_cast<std::size_t>(nx * ny * nz));
    view.data = data.data();
    view.geometry.dims = { nx, ny, nz };
    view.geometry.origin = origin;
    view.geometry.spacing = spacing;
    fill(f);
  }
  Grid(const Grid&) = delete; // the view points into data
  Grid& operator=(const Grid&) = delete;

  /// Every value from f at the grid point (indices, not world coordinates).
  void fill(const lvdif::SdfFunction& f)
  {
    forEachPoint([&](std::int64_t x, std::int64_t y, std::int64_t z) { view.at(x, y, z) = f(double(x), double(y), double(z)); });
  }

  /// A colour for every grid point.
  void paint(const std::function<lvdif::Rgba(std::int64_t, std::int64_t, std::int64_t)>& c)
  {
    colors.resize(data.size());
    const auto& d = view.geometry.dims;
    forEachPoint([&](std::int64_t x, std::int64_t y, std::int64_t z) { colors[x + d[0] * (y + d[1] * z)] = c(x, y, z); });
  }

  /// The colours for ChunkedMarchingCubes, or nullptr when unpainted.
  const lvdif::Rgba* colorData() const { return colors.empty() ? nullptr : colors.data(); }

private:
  template <typename Fn>
  void forEachPoint(Fn fn) const
  {
    const auto& d = view.geometry.dims;
    for (std::int64_t z = 0; z < d[2]; ++z)
      for (std::int64_t y = 0; y < d[1]; ++y)
        for (std::int64_t x = 0; x < d[0]; ++x)
          fn(x, y, z);
  }
};

/// A torus around the z axis through (cx, cy, cz): major radius R, minor radius r.
inline lvdif::SdfFunction torusSdf(double cx, double cy, double cz, double R, double r)
{
  return [=](double x, double y, double z) {
    const double q = std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy)) - R;
    return static_cast<float>(std::sqrt(q * q + (z - cz) * (z - cz)) - r);
  };
}

} // namespace gridtest
