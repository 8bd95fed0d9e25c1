// The per-voxel CSG rule shared by the CPU brush loop (Brush.cpp) and the CUDA
// kernel (Brush.cu), so both compute the same bits. See lvdif/Brush.h for the
// semantics. Also the edit plan (which dabs can act, their boxes, the chunks
// to visit) that both paths build the same way.
#pragma once

#include "lvdif/Brush.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail
{

struct BrushContext
{
  int op = 0; // BrushOp
  double blend = 0;
  double colorOffset = 1.5;
  double rounding = 0;
  std::uint16_t colorKey = 0;
  /// The largest primitive distance s at which the op can change a voxel.
  double reach = 0;
};

/// Combines one voxel (sdf key, colour key) with one primitive distance s.
/// `table` decodes keys; `encode(double)` is the band-clamped encoder.
template <typename Encode>
LVDIF_HD inline void combineVoxel(
  std::uint16_t& sdf, std::uint16_t& color, double s, const BrushContext& c, const float* table, const Encode& encode)
{
  const double d = table[sdf];
  if (c.op == static_cast<int>(BrushOp::Add))
  {
    bool fillet = false;
    if (c.blend <= 0)
    {
      if (s < d)
        sdf = encode(s);
    }
    else if (s - d < c.blend)
    {
      const double dn = smoothMin(d, s, c.blend);
      if (dn != d)
      {
        sdf = encode(dn);
        fillet = dn <= c.colorOffset;
      }
    }
    if (s <= c.colorOffset || fillet)
      color = c.colorKey;
  }
  else if (c.op == static_cast<int>(BrushOp::Subtract))
  {
    if (c.blend <= 0)
    {
      if (-s > d)
        sdf = encode(-s);
    }
    else if (d + s < c.blend)
    {
      const double dn = -smoothMin(-d, s, c.blend);
      if (dn != d)
        sdf = encode(dn);
    }
  }
  else
  {
    if (s <= 0 && (d < 0 ? -d : d) <= c.colorOffset)
      color = c.colorKey;
  }
}

/// The encoder of SdfDictionary::encodeClamped, restated from the dictionary's
/// public parameters so device code can run it (TestBrush checks it against
/// the dictionary for every key midpoint).
struct EncodeParams
{
  std::int64_t halfA = 0, zeroKey = 0;
  double invStepA = 0, invStepB = 0, firstB = 0, encodeALimit = 0;
  float band = 8;

  static EncodeParams of(const SdfDictionary& d, float band);

  LVDIF_HD static std::int64_t roundHalfDown(double x)
  {
    const double f = static_cast<double>(static_cast<std::int64_t>(x));
    return static_cast<std::int64_t>(x - f > 0.5 ? f + 1 : f);
  }
  LVDIF_HD std::uint16_t encodeFloat(float value) const
  {
    if (!(value == value))
      return 65535;
    const double a = value < 0 ? -static_cast<double>(value) : static_cast<double>(value);
    std::int64_t offset;
    if (a <= encodeALimit)
    {
      offset = roundHalfDown(a * invStepA);
      if (offset > halfA)
        offset = halfA;
    }
    else
    {
      const double t = (a - firstB) * invStepB;
      const double j = t > 1e6 ? 1e6 : static_cast<double>(roundHalfDown(t));
      offset = halfA + 1 + static_cast<std::int64_t>(j < 0 ? 0 : j);
    }
    if (value < 0)
      return offset > zeroKey ? 0 : static_cast<std::uint16_t>(zeroKey - offset);
    const std::int64_t k = zeroKey + offset;
    return k > 65535 ? 65535 : static_cast<std::uint16_t>(k);
  }
  LVDIF_HD std::uint16_t operator()(double value) const
  {
    float v = static_cast<float>(value);
    if (v > band)
      v = band;
    if (v < -band)
      v = -band;
    return encodeFloat(v);
  }
};

/// What an apply call will do: the dabs that can act (radius > 0, box meets the
/// volume), their influence boxes, and the sorted ids of the chunks they touch.
struct DabPlan
{
  BrushContext ctx;
  std::vector<Dab> dabs;
  std::vector<VoxelBox> boxes;
  std::vector<std::int64_t> chunks;
};

/// Validates (Error InvalidArgument) and plans; adds the brush colour to the dictionary.
DabPlan planDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings);

} // namespace detail
} // namespace lvdif
