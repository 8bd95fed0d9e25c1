// Strokes: from device samples to a chain of dabs (paper Sect. 3.4.1: "smoothing
// is done via interpolation on the points with a fixed interval"; the original's
// interval is 1.6 voxels, original-code-spec.md section 5.4).
//
// Resampling: dabs are placed along the polyline of sample positions at a fixed
// arc-length spacing, starting at the first sample; the last sample always gets
// a dab too (the original loses it when the last segment is shorter than the
// interval). Repeated positions add nothing.
//
// Brush kinds (the original's input methods, same numbers):
//   Single  (0) one dab at the first sample (a click / stamp).
//   Basic   (1) constant radius; the stroke is applied when it ends.
//   Dynamic (2) the radius tapers linearly with arc length from the full radius
//               at the start to minRadius (default 1 voxel) at the end, as the
//               original's taper R -> 1; applied when it ends (the taper needs
//               the whole length).
//   Drill   (3) the cursor moves freely through the volume (not snapped to the
//               surface) and the stroke is applied in real time: takeReady()
//               returns the dabs of the path walked since the previous call,
//               the spacing continuing across calls (the original flushes every
//               5 samples in its VR drill mode).
// applyAsItGoes: a Basic stroke applied in real time as Drill is (takeReady() gives
// the path walked since the previous call), for a front end that shows the
// surface change under the cursor (the Qt editor); the dabs are the same, and the
// stroke stays Basic (its recording says kind=basic, not drill).
// Pressure: when pressureDrivesRadius and a sample has pressure >= 0, the radius
// at that sample is max(minRadius, radius * min(pressure, 1)); radii are
// interpolated linearly between samples (the taper multiplies on top).
#pragma once

#include "lvdif/Brush.h"

#include <array>
#include <cstdint>
#include <vector>

namespace lvdif
{

enum class BrushKind : int
{
  Single = 0,
  Basic = 1,
  Dynamic = 2,
  Drill = 3
};

const char* toString(BrushKind k);

/// One sample of an input device.
struct BrushSample
{
  std::array<double, 3> position{ 0, 0, 0 };       // voxel coordinates
  std::array<double, 4> orientation{ 1, 0, 0, 0 }; // unit quaternion (w, x, y, z)
  double pressure = -1;                            // [0, 1]; < 0 means "no pressure sensor"
  std::uint32_t buttons = 0;                       // bit 0: the draw button
  double time = 0;                                 // seconds
};

struct StrokeSettings
{
  BrushKind kind = BrushKind::Basic;
  BrushShape shape = BrushShape::Sphere; // Sphere or Cube dabs
  double radius = 3.0;                   // radius or cube half edge, voxels
  double spacing = 1.6;                  // fixed interpolation interval, voxels (> 0)
  double minRadius = 1.0;                // end radius of the taper, floor for pressure
  bool pressureDrivesRadius = true;
  bool applyAsItGoes = false;            // Basic only: applied as it goes, as Drill (see above)
};

/// Validates settings (Error InvalidArgument with the offending field).
void validate(const StrokeSettings& s);

/// Builds the dabs of one stroke incrementally.
class StrokeBuilder
{
public:
  /// maxDabs: the most dabs this stroke may make; add() refuses a sample that would
  /// pass it (Error InvalidArgument) before making any of its dabs.
  explicit StrokeBuilder(const StrokeSettings& settings, std::uint64_t maxDabs = 1'000'000);
  const StrokeSettings& settings() const { return this->Settings; }

  void add(const BrushSample& sample);
  /// Dabs that may be applied now (Drill, and Basic with applyAsItGoes: the path since
  /// the last call; others: none).
  std::vector<Dab> takeReady();
  /// Ends the stroke and returns every dab not yet taken (with the taper for Dynamic).
  std::vector<Dab> finish();
  std::size_t sampleCount() const { return this->Samples; }

private:
  void addDab(const std::array<double, 3>& p, double radius, double arc);

  StrokeSettings Settings;
  std::uint64_t MaxDabs;
  std::size_t Samples = 0;
  std::array<double, 3> Last{ 0, 0, 0 };
  double LastRadius = 0;
  double Arc = 0;      // arc length walked so far
  double NextAt = 0;   // arc length of the next dab
  double LastEmit = -1; // arc length of the last emitted dab
  std::vector<Dab> Pending;
  std::vector<double> PendingArc;
  std::size_t Taken = 0;
  bool Finished = false;
};

/// All dabs of a complete stroke.
std::vector<Dab> strokeDabs(const std::vector<BrushSample>& samples, const StrokeSettings& settings,
  std::uint64_t maxDabs = 1'000'000);

} // namespace lvdif
