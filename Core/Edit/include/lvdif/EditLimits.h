// One set of rules for every number an edit takes, whoever sends it (scripts,
// recordings, socket samples, the Python/VTK API, the Qt editor), and the
// budgets of what one edit may generate. Everything is checked before the
// work starts and refused with one Error(InvalidArgument) naming the value.
//
// Why these bounds: brush loops turn coordinates and reaches (radius + blend +
// band) into 64-bit voxel indices and square them; with |coordinate| <= 1e9
// and every size <= 1e7 all of that stays exact and finite, and no real
// volume (at most 2^21 voxels a side) needs more.
#pragma once

#include "lvdif/Brush.h"
#include "lvdif/Stroke.h"

#include <cstdint>
#include <string>

namespace lvdif
{

struct EditLimits
{
  /// Largest |coordinate| of a dab centre, capsule end or sample position (voxels).
  static constexpr double MaxCoordinate = 1e9;
  /// Largest radius, blend, rounding, colour offset, spacing or minimum radius (voxels).
  static constexpr double MaxSize = 1e7;
  /// Smallest stroke spacing (voxels): finer adds nothing a voxel grid can show.
  static constexpr double MinSpacing = 1e-3;

  /// Dabs one stroke, line or edit may generate (checked before generating them).
  std::uint64_t maxDabsPerEdit = 1'000'000;
  /// Dabs one editor may apply in all (a script run, a playback, a session).
  std::uint64_t maxTotalDabs = 100'000'000;
  /// Chunk visits of one edit (sum over its dabs of the chunks their boxes meet).
  std::uint64_t maxChunkVisitsPerEdit = std::uint64_t(1) << 27;
};

/// Finite and in [lo, hi], or Error(InvalidArgument) "<what> must be ... (got v)".
double checkedNumber(double v, double lo, double hi, const std::string& what);
/// Finite and in (0, hi], or Error(InvalidArgument) "<what> must be a finite number in (0, hi] (got v)".
double checkedPositive(double v, double hi, const std::string& what);

void validate(const BrushSettings& s);
/// `index` names the dab in the message (e.g. its position in a list).
void validate(const Dab& d, std::size_t index);
void validate(const BrushSample& s);

/// How many dabs a stroke resampled at `spacing` makes along `length` voxels of
/// path (the count StrokeBuilder produces, plus one for the last sample).
double strokeDabEstimate(double length, double spacing);

} // namespace lvdif
