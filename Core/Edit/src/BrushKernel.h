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
namespace detail::edit
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
LVDIF_HD void combineVoxel(
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

/// SdfDictionary::encodeClamped for host and device code: the dictionary's
/// own encodeWith on its constants, after clamping to the band (TestBrushCuda
/// checks it against encodeClamped for every key midpoint).
struct EncodeParams
{
  SdfDictionary::EncodeConstants c;
  float band = 8;

  static EncodeParams of(const SdfDictionary& d, float band) { return { d.encodeConstants(), band }; }

  LVDIF_HD std::uint16_t operator()(double value) const
  {
    float v = static_cast<float>(value);
    if (v > band)
      v = band;
    if (v < -band)
      v = -band;
    return SdfDictionary::encodeWith(c, v);
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

} // namespace detail::edit
} // namespace lvdif
