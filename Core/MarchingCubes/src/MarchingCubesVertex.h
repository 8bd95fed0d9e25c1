// Edge-vertex arithmetic shared by the CPU and CUDA marching cubes, written
// with explicitly rounded operations on the device (no fused multiply-add), so
// both compute bit-identical vertices and a chunk boundary vertex is the same
// number from either side.
#pragma once

#include "lvdif/HostDevice.h"

#include <cstdint>


namespace lvdif
{
namespace detail::mc
{

#if defined(__CUDA_ARCH__)
LVDIF_HD float fmul(float a, float b) { return __fmul_rn(a, b); }
LVDIF_HD float fadd(float a, float b) { return __fadd_rn(a, b); }
LVDIF_HD float fsub(float a, float b) { return __fsub_rn(a, b); }
LVDIF_HD float fdiv(float a, float b) { return __fdiv_rn(a, b); }
LVDIF_HD float fsqrt(float a) { return __fsqrt_rn(a); }
LVDIF_HD double dmul(double a, double b) { return __dmul_rn(a, b); }
LVDIF_HD double dadd(double a, double b) { return __dadd_rn(a, b); }
#else
LVDIF_HD float fmul(float a, float b) { return a * b; }
LVDIF_HD float fadd(float a, float b) { return a + b; }
LVDIF_HD float fsub(float a, float b) { return a - b; }
LVDIF_HD float fdiv(float a, float b) { return a / b; }
LVDIF_HD float fsqrt(float a) { return __builtin_sqrtf(a); }
LVDIF_HD double dmul(double a, double b) { return a * b; }
LVDIF_HD double dadd(double a, double b) { return a + b; }
#endif

/// Parameter of the iso crossing on the edge from value a (lower point) to b.
LVDIF_HD float edgeT(float iso, float a, float b) { return fdiv(fsub(iso, a), fsub(b, a)); }

/// World coordinate of point index i (+ t) along one axis.
LVDIF_HD float coord(double origin, double spacing, std::int64_t i, float t)
{
  return static_cast<float>(dadd(origin, dmul(spacing, dadd(static_cast<double>(i), static_cast<double>(t)))));
}

/// Gradient component from the neighbours (central inside, one-sided at the border).
/// lo, mid, hi are the values at i-1, i, i+1 (lo/hi unused at the border).
LVDIF_HD float gradient(float lo, float mid, float hi, std::int64_t i, std::int64_t n, float invSpacing)
{
  const float d = i == 0 ? fsub(hi, mid) : (i == n - 1 ? fsub(mid, lo) : fmul(fsub(hi, lo), 0.5f));
  return fmul(d, invSpacing);
}

LVDIF_HD float lerp(float a, float b, float t) { return fadd(a, fmul(t, fsub(b, a))); }

LVDIF_HD void normalize(float& x, float& y, float& z)
{
  const float l = fsqrt(fadd(fadd(fmul(x, x), fmul(y, y)), fmul(z, z)));
  if (l > 0.0f)
  {
    x = fdiv(x, l);
    y = fdiv(y, l);
    z = fdiv(z, l);
  }
}

LVDIF_HD std::uint8_t lerpChannel(std::uint8_t a, std::uint8_t b, float t)
{
  const float v = lerp(static_cast<float>(a), static_cast<float>(b), t);
  const int r = static_cast<int>(fadd(v, 0.5f));
  return static_cast<std::uint8_t>(r < 0 ? 0 : (r > 255 ? 255 : r));
}

} // namespace detail::mc
} // namespace lvdif
