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
  double strength = 1;
  int falloff = 0; // Falloff
  int invert = 0;
  double band = 8;
  /// Strength 1 and the Constant falloff: the paper's CSG bit for bit, no t needed.
  int unitWeight = 1;
  /// Dabs per symmetry group (1, 2, 4 or 8), see Brush.h. Member m of a group is
  /// the group's first dab seen from the voxel reflected on the axes of m's set
  /// bits (bit i: axis mirrorAxis[i], p -> twicePlane - p): exact for integer
  /// voxels and planes on whole or half voxels, so mirror images are bit-exact.
  int groupSize = 1;
  int mirrorAxis[3] = { 0, 1, 2 };
  double twicePlane[3] = { 0, 0, 0 };
  /// Soft paint: the sorted colour keys the dab may meet (mixCount of them) and,
  /// per key, the keys of its mixes with the brush colour at 1/8 .. 7/8.
  const std::uint16_t* mixFrom = nullptr;
  const std::uint16_t* mixTo = nullptr;
  int mixCount = 0;
};

constexpr int PaintLevels = 8;

/// Crease depth (voxels) at full weight.
constexpr double CreaseDepth = 1.5;

LVDIF_HD std::uint16_t mixedColor(std::uint16_t color, int q, const BrushContext& c)
{
  int lo = 0, hi = c.mixCount - 1;
  while (lo <= hi)
  {
    const int mid = (lo + hi) / 2;
    if (c.mixFrom[mid] == color)
      return c.mixTo[mid * (PaintLevels - 1) + (q - 1)];
    if (c.mixFrom[mid] < color)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return color; // not met by the plan: cannot happen
}

/// Combines one voxel (sdf key, colour key) at (x, y, z) with one dab group:
/// its primitive distance s, radial fraction t and the member `dab` nearest in t.
/// `table` decodes keys; `encode(double)` is the band-clamped encoder.
// The CPU brush calls combineVoxel per voxel from two loops; inlined into both
// (CUDA inlines LVDIF_HD functions anyway).
#if !defined(__CUDACC__) && (defined(__GNUC__) || defined(__clang__))
#define LVDIF_EDIT_ALWAYS_INLINE __attribute__((always_inline))
#else
#define LVDIF_EDIT_ALWAYS_INLINE
#endif

template <typename Encode>
LVDIF_HD LVDIF_EDIT_ALWAYS_INLINE void combineVoxel(std::uint16_t& sdf, std::uint16_t& color, double s, double t, const Dab& dab, double x,
  double y, double z, const BrushContext& c, const float* table, const Encode& encode)
{
  const double d = table[sdf];
  const bool full = c.unitWeight != 0;
  if (c.op == static_cast<int>(BrushOp::Add))
  {
    const double w = full ? 1.0 : c.strength * falloffCurve(c.falloff, t < 1 ? t : 1);
    bool own = false; // the brush lowered the distance: its surface owns the voxel
    if (c.blend <= 0)
    {
      if (s < d)
      {
        const double dn = full ? s : d + w * (s - d);
        if (dn < d)
        {
          sdf = encode(dn);
          own = dn <= c.colorOffset;
        }
      }
    }
    else if (s - d < c.blend)
    {
      const double m = smoothMin(d, s, c.blend);
      const double dn = full ? m : d + w * (m - d);
      if (dn != d)
      {
        sdf = encode(dn);
        own = dn <= c.colorOffset;
      }
    }
    if (own || (full && s <= 0))
      color = c.colorKey;
  }
  else if (c.op == static_cast<int>(BrushOp::Subtract))
  {
    const double w = full ? 1.0 : c.strength * falloffCurve(c.falloff, t < 1 ? t : 1);
    if (c.blend <= 0)
    {
      if (-s > d)
        sdf = encode(full ? -s : d + w * (-s - d));
    }
    else if (d + s < c.blend)
    {
      const double m = -smoothMin(-d, s, c.blend);
      const double dn = full ? m : d + w * (m - d);
      if (dn != d)
        sdf = encode(dn);
    }
  }
  else if (c.op == static_cast<int>(BrushOp::Paint))
  {
    if (s <= 0 && (d < 0 ? -d : d) <= c.colorOffset)
    {
      if (full)
        color = c.colorKey;
      else
      {
        const int q = static_cast<int>(c.strength * falloffCurve(c.falloff, t) * PaintLevels + 0.5);
        if (q >= PaintLevels)
          color = c.colorKey;
        else if (q > 0)
          color = mixedColor(color, q, c);
      }
    }
  }
  else if (s <= 0 && d > -c.band && d < c.band)
  {
    const double f = falloffCurve(c.falloff, t);
    const double w = c.strength * f;
    if (!(w > 0))
      return;
    double dn = d;
    if (c.op == static_cast<int>(BrushOp::Inflate))
      dn = c.invert ? d + w : d - w;
    else if (c.op == static_cast<int>(BrushOp::Crease))
      dn = d + (c.invert ? -1.0 : 1.0) * c.strength * f * f * f * CreaseDepth;
    else if (c.op == static_cast<int>(BrushOp::Flatten))
      dn = d + w * (dab.vec[0] * x + dab.vec[1] * y + dab.vec[2] * z - dab.value - d);
    sdf = encode(dn);
  }
}

/// Applies dab group `g` (dabs [g * groupSize, (g + 1) * groupSize)) to one voxel:
/// the members whose box holds it act as the union of their primitives.
/// The voxel position member m of a group sees (see BrushContext::groupSize).
LVDIF_HD void reflectForMember(const BrushContext& c, int m, double p[3])
{
  for (int i = 0; (1 << i) < c.groupSize; ++i)
    if ((m >> i) & 1)
    {
      const int a = c.mirrorAxis[i];
      p[a] = c.twicePlane[a] - p[a];
    }
}

template <typename Box, typename Encode>
LVDIF_HD void applyGroupToVoxel(std::uint16_t& sdf, std::uint16_t& color, long long x, long long y, long long z,
  const Dab* dabs, const Box* boxes, int g, const BrushContext& c, const float* table, const Encode& encode)
{
  double s = 0, t = 0;
  int best = -1;
  const Dab& base = dabs[g * c.groupSize];
  for (int m = 0; m < c.groupSize; ++m)
  {
    const int k = g * c.groupSize + m;
    const Box& b = boxes[k];
    if (x < b.lo[0] || x > b.hi[0] || y < b.lo[1] || y > b.hi[1] || z < b.lo[2] || z > b.hi[2])
      continue;
    double p[3] = { double(x), double(y), double(z) };
    reflectForMember(c, m, p);
    const double sk = dabDistance(base, p[0], p[1], p[2], c.rounding);
    const double tk = c.unitWeight ? 0.0 : dabRadialFraction(base, p[0], p[1], p[2]);
    if (best < 0 || sk < s)
      s = sk;
    if (best < 0 || tk < t)
    {
      t = tk;
      best = k;
    }
  }
  if (best < 0 || s > c.reach)
    return;
  combineVoxel(sdf, color, s, t, dabs[best], double(x), double(y), double(z), c, table, encode);
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
  /// Whole symmetry groups (ctx.groupSize dabs each) of which some member can act.
  std::vector<Dab> dabs;
  /// Each dab's influence box (empty for a member outside the volume).
  std::vector<VoxelBox> boxes;
  std::vector<std::int64_t> chunks;
  /// Soft paint's table (ctx.mixFrom/mixTo point into these on the host).
  std::vector<std::uint16_t> mixFrom, mixTo;
};

/// Validates (Error InvalidArgument), checks the chunk and memory budgets
/// (Error InvalidArgument / OutOfMemory; the undo snapshots count when an
/// observer is given) and plans; adds the brush colour (and soft paint's
/// mixes) to the dictionary; Flatten's planes are measured here. Refuses
/// Smooth, Grab and Pinch (they are not per-voxel rules).
DabPlan planDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  const ChunkWriteObserver* observer = nullptr);

/// The volume's SDF at a continuous point (trilinear, clamped to the volume).
double trilinear(const DictionaryVolume& v, const float* table, double x, double y, double z);

/// Applies a plan of a brush that reads neighbours (BrushGather.cpp); checks
/// `interrupter` between groups.
EditResult applyGather(
  DictionaryVolume& volume, const DabPlan& plan, ChunkWriteObserver* observer, const Interrupter* interrupter);

} // namespace detail::edit
} // namespace lvdif
