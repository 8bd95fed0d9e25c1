// The per-voxel rules of the sign voxel filters, shared verbatim by the CPU
// (SignVoxelFilterCpu.cpp) and CUDA (SignVoxelFilter.cu) paths so that both
// compute the same function. Only comparisons and negations touch the
// values, so results are bit-exact on both.
//
// A neighbour is given as (sign, magnitude). Inside the grid that is
// (signOf(v), |v|); a virtual neighbour outside the grid is (boundarySign, 0).
// "Opposite" means strictly opposite: a zero (or NaN) sign never opposes.
#pragma once

#include "lvdif/HostDevice.h"

#include <cmath>
#include <cstdint>


namespace lvdif
{
namespace detail::svf
{

LVDIF_HD int signOf(float v)
{
  return (v > 0.0f) - (v < 0.0f); // 0 for +-0 and NaN
}

/// |v| > t; false for NaN.
LVDIF_HD bool isFar(float v, float t)
{
  return fabsf(v) > t;
}

/// SVF1: a far voxel takes the sign of its (already filtered) predecessor.
LVDIF_HD bool svf1Flips(float c, int prevSign, float t)
{
  return isFar(c, t) && prevSign == -signOf(c);
}

/// SVF2: n[0..7] are the 8 in-plane neighbours (signs s, magnitudes m).
/// Flip when the sum of the 9 signs (centre included) has the opposite sign
/// and some neighbour of the opposite sign is larger in magnitude.
LVDIF_HD bool svf2Flips(float c, const int s[8], const float m[8], float t)
{
  if (!isFar(c, t))
  {
    return false;
  }
  const int sc = signOf(c);
  int sum = sc;
  bool flow = false;
  const float mc = fabsf(c);
  for (int q = 0; q < 8; ++q)
  {
    sum += s[q];
    flow = flow || (s[q] == -sc && m[q] > mc);
  }
  return flow && (sc > 0 ? sum < 0 : sum > 0);
}

/// SVF3: all four in-plane 4-neighbours have the opposite sign.
LVDIF_HD bool svf3Flips(float c, const int s[4], float t)
{
  if (!isFar(c, t))
  {
    return false;
  }
  const int sc = signOf(c);
  return s[0] == -sc && s[1] == -sc && s[2] == -sc && s[3] == -sc;
}

/// SVF4: at least 4 of the 6 neighbours have the opposite sign; no threshold.
LVDIF_HD bool svf4Flips(float c, const int s[6])
{
  const int sc = signOf(c);
  if (sc == 0)
  {
    return false;
  }
  int opposite = 0;
  for (int q = 0; q < 6; ++q)
  {
    opposite += (s[q] == -sc) ? 1 : 0;
  }
  return opposite >= 4;
}

/// In-plane axes for a filter axis: (u, v) = (y, z) for x, (x, z) for y, (x, y) for z.
LVDIF_HD int axisU(int a)
{
  return a == 0 ? 1 : 0;
}
LVDIF_HD int axisV(int a)
{
  return a == 2 ? 1 : 2;
}

/// Colour classes making in-place updates order-independent: SVF2's 3x3
/// stencil needs 4 colours (parities of u and v), SVF3's plus-shaped one 2.
LVDIF_HD int colourSvf2(std::int64_t u, std::int64_t v)
{
  return static_cast<int>((u & 1) | ((v & 1) << 1));
}
LVDIF_HD int colourSvf3(std::int64_t u, std::int64_t v)
{
  return static_cast<int>((u + v) & 1);
}

} // namespace detail::svf
} // namespace lvdif

namespace lvdif
{
namespace detail::svf
{

/// Strides and sizes of a grid seen from a filter axis.
struct AxisFrame
{
  std::int64_t nU, nV, nA; // sizes along u, v and the filter axis
  std::int64_t sU, sV, sA; // linear-index strides
};

/// Gathers the 8 in-plane neighbours of the voxel at idx (coordinates u, v).
LVDIF_HD void gather8(const float* d, std::int64_t idx, std::int64_t u, std::int64_t v, const AxisFrame& f,
  int bsign, int s[8], float m[8])
{
  int q = 0;
  for (int dv = -1; dv <= 1; ++dv)
  {
    for (int du = -1; du <= 1; ++du)
    {
      if (du == 0 && dv == 0)
      {
        continue;
      }
      const std::int64_t uu = u + du, vv = v + dv;
      if (uu < 0 || vv < 0 || uu >= f.nU || vv >= f.nV)
      {
        s[q] = bsign;
        m[q] = 0.0f;
      }
      else
      {
        const float x = d[idx + du * f.sU + dv * f.sV];
        s[q] = signOf(x);
        m[q] = fabsf(x);
      }
      ++q;
    }
  }
}

/// Signs of the 4 in-plane neighbours (u+1, u-1, v+1, v-1).
LVDIF_HD void gather4(const float* d, std::int64_t idx, std::int64_t u, std::int64_t v, const AxisFrame& f,
  int bsign, int s[4])
{
  s[0] = u + 1 < f.nU ? signOf(d[idx + f.sU]) : bsign;
  s[1] = u > 0 ? signOf(d[idx - f.sU]) : bsign;
  s[2] = v + 1 < f.nV ? signOf(d[idx + f.sV]) : bsign;
  s[3] = v > 0 ? signOf(d[idx - f.sV]) : bsign;
}

/// Signs of the 6 neighbours (in-plane 4, then a+1, a-1).
LVDIF_HD void gather6(const float* d, std::int64_t idx, std::int64_t u, std::int64_t v, std::int64_t a,
  const AxisFrame& f, int bsign, int s[6])
{
  gather4(d, idx, u, v, f, bsign, s);
  s[4] = a + 1 < f.nA ? signOf(d[idx + f.sA]) : bsign;
  s[5] = a > 0 ? signOf(d[idx - f.sA]) : bsign;
}

} // namespace detail::svf
} // namespace lvdif
