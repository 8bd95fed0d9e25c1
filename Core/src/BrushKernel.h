// The per-voxel CSG rule shared by the CPU brush loop (Brush.cpp). Kept in one
// place so every path (single dab, stroke, player, script) computes the same
// bits. See lvdif/Brush.h for the semantics.
#pragma once

#include "lvdif/Brush.h"

#include <cmath>

namespace lvdif
{
namespace detail
{

struct BrushContext
{
  BrushOp op = BrushOp::Add;
  double blend = 0;
  double colorOffset = 1.5;
  ColorKey colorKey = 0;
  float band = 8;
  const SdfDictionary* dictionary = nullptr;
  /// The largest primitive distance s at which the op can change a voxel.
  double reach = 0;
};

inline SdfKey encodeBand(const BrushContext& c, double value)
{
  return c.dictionary->encodeClamped(static_cast<float>(value), c.band);
}

/// Combines one voxel with one primitive distance s; returns the new voxel.
inline Voxel combineVoxel(Voxel v, double s, const BrushContext& c)
{
  const double d = c.dictionary->decode(v.sdf);
  switch (c.op)
  {
    case BrushOp::Add:
    {
      bool fillet = false;
      if (c.blend <= 0)
      {
        if (s < d)
        {
          v.sdf = encodeBand(c, s);
        }
      }
      else if (s - d < c.blend)
      {
        const double dn = smoothMin(d, s, c.blend);
        if (dn != d)
        {
          v.sdf = encodeBand(c, dn);
          fillet = dn <= c.colorOffset;
        }
      }
      if (s <= c.colorOffset || fillet)
      {
        v.color = c.colorKey;
      }
      return v;
    }
    case BrushOp::Subtract:
    {
      if (c.blend <= 0)
      {
        if (-s > d)
        {
          v.sdf = encodeBand(c, -s);
        }
      }
      else if (d + s < c.blend)
      {
        const double dn = -smoothMin(-d, s, c.blend);
        if (dn != d)
        {
          v.sdf = encodeBand(c, dn);
        }
      }
      return v;
    }
    case BrushOp::Paint:
    default:
      if (s <= 0 && std::fabs(d) <= c.colorOffset)
      {
        v.color = c.colorKey;
      }
      return v;
  }
}

} // namespace detail
} // namespace lvdif
