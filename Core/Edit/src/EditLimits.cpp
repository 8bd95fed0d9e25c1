#include "lvdif/EditLimits.h"
#include "lvdif/CNumbers.h"

#include "lvdif/Error.h"

#include <cmath>
#include <cstdio>

namespace lvdif
{

namespace
{
std::string str(double v)
{
  char b[40];
  formatDoubleC(b, sizeof(b), "%.6g", v);
  return b;
}
} // namespace

double checkedNumber(double v, double lo, double hi, const std::string& what)
{
  if (!(std::isfinite(v) && v >= lo && v <= hi))
    throw Error(ErrorCode::InvalidArgument,
      what + " must be a finite number in [" + str(lo) + ", " + str(hi) + "] (got " + str(v) + ")");
  return v;
}

double checkedPositive(double v, double hi, const std::string& what)
{
  if (!(std::isfinite(v) && v > 0 && v <= hi))
    throw Error(ErrorCode::InvalidArgument, what + " must be a finite number in (0, " + str(hi) + "] (got " + str(v) + ")");
  return v;
}

void validate(const BrushSettings& s)
{
  checkedNumber(s.blend, 0, EditLimits::MaxSize, "brush blend radius");
  checkedNumber(s.colorOffset, 0, EditLimits::MaxSize, "brush colour offset");
  checkedNumber(s.rounding, 0, EditLimits::MaxSize, "cube rounding");
  require(static_cast<int>(s.op) >= 0 && static_cast<int>(s.op) <= static_cast<int>(BrushOp::Pinch),
    "unknown brush operation");
  require(std::isfinite(s.strength) && s.strength > 0 && s.strength <= 1, "brush strength must be in (0, 1]");
  require(static_cast<int>(s.falloff) >= 0 && static_cast<int>(s.falloff) <= static_cast<int>(Falloff::Sharp),
    "unknown brush falloff");
  for (int a = 0; a < 3; ++a)
    if (s.symmetry.mirror[a])
      checkedNumber(s.symmetry.plane[a], -EditLimits::MaxCoordinate, EditLimits::MaxCoordinate, "symmetry plane");
}

void validate(const Dab& d, std::size_t index)
{
  const std::string name = "dab " + std::to_string(index);
  require(d.shape == BrushShape::Sphere || d.shape == BrushShape::Cube || d.shape == BrushShape::Capsule,
    name + " has an unknown shape");
  // radius <= 0 is allowed: such dabs are skipped (the original skips w <= 0)
  checkedNumber(d.radius, -EditLimits::MaxSize, EditLimits::MaxSize, name + " radius");
  for (int a = 0; a < 3; ++a)
  {
    checkedNumber(d.center[a], -EditLimits::MaxCoordinate, EditLimits::MaxCoordinate, name + " position");
    checkedNumber(d.vec[a], -EditLimits::MaxSize, EditLimits::MaxSize, name + " grab displacement or pinch direction");
    if (d.shape == BrushShape::Capsule)
      checkedNumber(d.end[a], -EditLimits::MaxCoordinate, EditLimits::MaxCoordinate, name + " capsule end");
  }
}

void validate(const BrushSample& s)
{
  for (int a = 0; a < 3; ++a)
    checkedNumber(s.position[a], -EditLimits::MaxCoordinate, EditLimits::MaxCoordinate, "brush sample position");
  require(std::isfinite(s.pressure), "brush sample pressure must be finite");
}

double strokeDabEstimate(double length, double spacing)
{
  return std::floor(length / spacing) + 2;
}

} // namespace lvdif
