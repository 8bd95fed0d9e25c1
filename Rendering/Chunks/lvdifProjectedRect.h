// The pixel rectangle that projected points reach: the one projection of
// vtkPartialRedrawCuller (a prop's, a declared box's or declared points'
// rectangle) and vtkTetrahedralColorMapper's draw ranges (a range's box
// against the GL scissor box). Not a VTK class: a private header of the module.
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>

namespace lvdif
{
namespace render
{

/// The pixels that n points may reach, window coordinates, half-open:
/// rect = { x0, y0, x1, y1 } = [floor(lo) - pad, ceil(hi) + 1 + pad) where lo
/// and hi bound the points projected by `m` (row-major 4x4, model to clip
/// coordinates) into the viewport { x, y, width, height }. point(i, p) writes
/// the i-th point's x, y, z into p[0..2]. False (rect unset) when a point lies
/// on or behind the eye plane (w <= 1e-12): the projection does not bound it.
/// The rectangle is not clamped (it may be far outside the viewport).
template <class Point>
bool projectedPixelRect(const double* m, const int viewport[4], std::size_t n, int pad, Point&& point, double rect[4])
{
  double lo[2] = { DBL_MAX, DBL_MAX }, hi[2] = { -DBL_MAX, -DBL_MAX };
  for (std::size_t i = 0; i < n; ++i)
  {
    double p[3];
    point(i, p);
    double q[4];
    for (int r = 0; r < 4; ++r)
    {
      q[r] = p[0] * m[4 * r] + p[1] * m[4 * r + 1] + p[2] * m[4 * r + 2] + m[4 * r + 3];
    }
    if (!(q[3] > 1e-12))
    {
      return false;
    }
    for (int a = 0; a < 2; ++a)
    {
      const double d = (q[a] / q[3] + 1.0) * 0.5 * viewport[2 + a] + viewport[a];
      lo[a] = std::min(lo[a], d);
      hi[a] = std::max(hi[a], d);
    }
  }
  rect[0] = std::floor(lo[0]) - pad;
  rect[1] = std::floor(lo[1]) - pad;
  rect[2] = std::ceil(hi[0]) + 1 + pad;
  rect[3] = std::ceil(hi[1]) + 1 + pad;
  return true;
}

/// The same for the 8 corners of a box { xmin, xmax, ymin, ymax, zmin, zmax }.
inline bool projectedBoxPixelRect(const double* m, const int viewport[4], const double box[6], int pad, double rect[4])
{
  return projectedPixelRect(m, viewport, 8, pad,
    [box](std::size_t c, double* p) {
      p[0] = box[c & 1];
      p[1] = box[2 + ((c >> 1) & 1)];
      p[2] = box[4 + ((c >> 2) & 1)];
    },
    rect);
}

} // namespace render
} // namespace lvdif
