#include "lvdif/Stroke.h"

#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cmath>

namespace lvdif
{

const char* toString(BrushKind k)
{
  switch (k)
  {
    case BrushKind::Single: return "single";
    case BrushKind::Basic: return "basic";
    case BrushKind::Dynamic: return "dynamic";
    case BrushKind::Drill: return "drill";
  }
  return "unknown";
}

void validate(const StrokeSettings& s)
{
  require(s.radius > 0, "stroke radius must be > 0");
  checkedNumber(s.radius, 0, EditLimits::MaxSize, "stroke radius");
  checkedNumber(s.spacing, EditLimits::MinSpacing, EditLimits::MaxSize, "stroke sample spacing");
  require(s.minRadius > 0, "stroke minimum radius must be > 0");
  checkedNumber(s.minRadius, 0, EditLimits::MaxSize, "stroke minimum radius");
  require(s.shape == BrushShape::Sphere || s.shape == BrushShape::Cube, "stroke dabs must be spheres or cubes");
  require(static_cast<int>(s.kind) >= 0 && static_cast<int>(s.kind) <= 3, "unknown brush kind");
}

StrokeBuilder::StrokeBuilder(const StrokeSettings& settings, std::uint64_t maxDabs)
  : Settings(settings)
  , MaxDabs(maxDabs)
{
  validate(settings);
}

void StrokeBuilder::addDab(const std::array<double, 3>& p, double radius, double arc)
{
  Dab d;
  d.shape = this->Settings.shape;
  d.center = p;
  d.radius = radius;
  this->Pending.push_back(d);
  this->PendingArc.push_back(arc);
  this->LastEmit = arc;
}

void StrokeBuilder::add(const BrushSample& sample)
{
  require(!this->Finished, "stroke already finished");
  validate(sample);
  double r = this->Settings.radius;
  if (this->Settings.pressureDrivesRadius && sample.pressure >= 0 && std::isfinite(sample.pressure))
  {
    r = std::max(this->Settings.minRadius, r * std::min(sample.pressure, 1.0));
  }
  if (this->Samples == 0)
  {
    this->Samples = 1;
    this->Last = sample.position;
    this->LastRadius = r;
    this->addDab(sample.position, r, 0.0);
    this->NextAt = this->Settings.spacing;
    return;
  }
  ++this->Samples;
  if (this->Settings.kind == BrushKind::Single)
  {
    return; // a stamp uses only its first sample
  }
  const std::array<double, 3>& q = this->Last;
  const double dx = sample.position[0] - q[0], dy = sample.position[1] - q[1], dz = sample.position[2] - q[2];
  const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(len > 0))
  {
    return; // repeated position
  }
  // the budget, before making any dab of this segment (the +1 keeps room for
  // the dab finish() adds at the last sample)
  const double segmentDabs = std::floor((this->Arc + len - this->NextAt) / this->Settings.spacing) + 1;
  if (double(this->Pending.size()) + std::max(0.0, segmentDabs) + 1 > double(this->MaxDabs))
    throw Error(ErrorCode::InvalidArgument,
      "the stroke would make " + std::to_string(static_cast<std::uint64_t>(double(this->Pending.size()) + segmentDabs)) +
        " dabs (" + std::to_string(len) + " voxels of path at spacing " + std::to_string(this->Settings.spacing) +
        "), more than the limit of " + std::to_string(this->MaxDabs));
  while (this->NextAt <= this->Arc + len)
  {
    const double t = (this->NextAt - this->Arc) / len;
    this->addDab({ q[0] + t * dx, q[1] + t * dy, q[2] + t * dz }, this->LastRadius + t * (r - this->LastRadius),
      this->NextAt);
    this->NextAt += this->Settings.spacing;
  }
  this->Arc += len;
  this->Last = sample.position;
  this->LastRadius = r;
}

std::vector<Dab> StrokeBuilder::takeReady()
{
  std::vector<Dab> out;
  const bool live = this->Settings.kind == BrushKind::Drill ||
    (this->Settings.kind == BrushKind::Basic && this->Settings.applyAsItGoes);
  if (!live)
  {
    return out;
  }
  out.assign(this->Pending.begin() + static_cast<std::ptrdiff_t>(this->Taken), this->Pending.end());
  this->Taken = this->Pending.size();
  return out;
}

std::vector<Dab> StrokeBuilder::finish()
{
  require(!this->Finished, "stroke already finished");
  this->Finished = true;
  if (this->Samples > 0 && this->Settings.kind != BrushKind::Single && this->Arc - this->LastEmit > 1e-9)
  {
    this->addDab(this->Last, this->LastRadius, this->Arc); // keep the last sample
  }
  if (this->Settings.kind == BrushKind::Dynamic && this->Arc > 0)
  {
    for (std::size_t i = this->Taken; i < this->Pending.size(); ++i)
    {
      const double t = this->PendingArc[i] / this->Arc;
      this->Pending[i].radius = this->Pending[i].radius * (1.0 - t) + this->Settings.minRadius * t;
    }
  }
  std::vector<Dab> out(this->Pending.begin() + static_cast<std::ptrdiff_t>(this->Taken), this->Pending.end());
  this->Taken = this->Pending.size();
  return out;
}

std::vector<Dab> strokeDabs(const std::vector<BrushSample>& samples, const StrokeSettings& settings,
  std::uint64_t maxDabs)
{
  StrokeBuilder b(settings, maxDabs);
  for (const BrushSample& s : samples)
  {
    b.add(s);
  }
  return b.finish();
}

} // namespace lvdif
