// Import of the original LVDIF recorder's CSV (original-code-spec.md section 6.2).
// Columns: time stamp, frame ID, input method, brush shape, input radius,
// eraser mode, color type, start time, end time, cursorVoxelPos. The points are
// "x-y-z-w" joined by '_', in kernel order (volume z, y, x), voxel units of the
// original volume. We also accept a minus sign where a number starts (the
// original's '-' separator cannot write negative numbers, so none occur).
#include "lvdif/Recording.h"
#include "lvdif/CNumbers.h"

#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"

#include <cmath>
#include <cstdlib>
#include <istream>
#include <sstream>

namespace lvdif
{

const std::vector<Rgba>& defaultCsvPalette()
{
  static const std::vector<Rgba> p{ { 230, 230, 230, 255 }, { 120, 190, 255, 255 }, { 255, 90, 90, 255 },
    { 90, 220, 120, 255 }, { 255, 150, 200, 255 }, { 255, 210, 60, 255 }, { 160, 110, 255, 255 },
    { 255, 140, 40, 255 }, { 60, 200, 200, 255 }, { 120, 80, 50, 255 } };
  return p;
}

namespace
{
bool parseInt(const std::string& s, int& out)
{
  std::size_t b = s.find_first_not_of(" \t");
  std::size_t e = s.find_last_not_of(" \t\r");
  if (b == std::string::npos)
    return false;
  const std::string t = s.substr(b, e - b + 1);
  char* end = nullptr;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (*end != '\0' || v < -1000000 || v > 1000000)
    return false;
  out = static_cast<int>(v);
  return true;
}

// "x-y-z-w": numbers separated by '-'; a '-' directly at a number's start is its sign.
bool parsePoint(const std::string& s, double v[4])
{
  std::size_t i = 0;
  for (int k = 0; k < 4; ++k)
  {
    if (k > 0)
    {
      if (i >= s.size() || s[i] != '-')
        return false;
      ++i;
    }
    const char* start = s.c_str() + i;
    char* end = nullptr;
    v[k] = strtodC(start, &end);
    if (end == start || !std::isfinite(v[k]))
      return false;
    i += static_cast<std::size_t>(end - start);
  }
  return i == s.size() || (i + 1 == s.size() && s[i] == '\r');
}
} // namespace

CsvImportResult importOriginalCsv(std::istream& in, const CsvImportOptions& options)
{
  require(std::isfinite(options.originalSize) && options.originalSize > 0, "original volume size must be > 0");
  require(std::isfinite(options.targetSize) && options.targetSize > 0, "target volume size must be > 0");
  const std::vector<Rgba>& palette = options.palette.empty() ? defaultCsvPalette() : options.palette;
  const double scale = options.targetSize / options.originalSize;
  require(std::isfinite(scale) && scale > 0, "target / original volume size must be a finite ratio > 0");
  const EditLimits limits;
  std::uint64_t totalDabs = 0;
  CsvImportResult result;
  std::string line;
  std::size_t no = 0;
  double time = 0;
  auto skip = [&](const std::string& why) {
    if (result.skippedRows++ == 0)
      result.firstProblem = "line " + std::to_string(no) + ": " + why;
  };
  while (std::getline(in, line))
  {
    ++no;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty() || line.rfind("time stamp", 0) == 0)
      continue; // header
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');)
      f.push_back(cell);
    if (f.size() != 10)
    {
      skip("expected 10 comma-separated fields, got " + std::to_string(f.size()));
      continue;
    }
    int method, shape, radius, eraser, color;
    if (!parseInt(f[2], method) || !parseInt(f[3], shape) || !parseInt(f[4], radius) || !parseInt(f[5], eraser) ||
      !parseInt(f[6], color) || method < 0 || method > 3 || shape < 0 || shape > 1 || color < 0)
    {
      skip("bad input method, shape, radius, eraser or colour field");
      continue;
    }
    EditRecord e;
    e.type = EditRecord::Type::Edit;
    e.kind = static_cast<BrushKind>(method);
    e.brush.op = eraser ? BrushOp::Subtract : BrushOp::Add;
    e.brush.color = palette[static_cast<std::size_t>(color) % palette.size()];
    e.brush.colorOffset = 1.5 * scale;
    e.spacing = 1.6 * scale;
    e.time = time;
    time += 1.0; // the original's time stamps are 12-hour local times; we keep the order only
    bool ok = true;
    std::stringstream pts(f[9]);
    for (std::string p; std::getline(pts, p, '_');)
    {
      double v[4];
      if (!parsePoint(p, v))
      {
        ok = false;
        break;
      }
      Dab d;
      d.shape = shape == 1 ? BrushShape::Cube : BrushShape::Sphere;
      // kernel order (z, y, x) -> volume (x, y, z)
      d.center = { v[2] * scale, v[1] * scale, v[0] * scale };
      d.radius = v[3] * scale;
      e.dabs.push_back(d);
      if (e.dabs.size() > limits.maxDabsPerEdit)
      {
        ok = false;
        break;
      }
    }
    if (!ok || e.dabs.empty())
    {
      skip(e.dabs.size() > limits.maxDabsPerEdit
          ? "more than " + std::to_string(limits.maxDabsPerEdit) + " points in one row"
          : "bad point list (expected x-y-z-w joined by '_')");
      continue;
    }
    try
    {
      // the rules of every other edit input (lvdif/EditLimits.h), row by row
      validate(e.brush);
      checkedNumber(e.spacing, EditLimits::MinSpacing, EditLimits::MaxSize, "spacing");
      for (std::size_t i = 0; i < e.dabs.size(); ++i)
        validate(e.dabs[i], i);
    }
    catch (const Error& x)
    {
      skip(x.what());
      continue;
    }
    totalDabs += e.dabs.size();
    if (totalDabs > limits.maxTotalDabs)
      throw Error(ErrorCode::InvalidArgument, "line " + std::to_string(no) + ": the CSV has more than " +
          std::to_string(limits.maxTotalDabs) + " points in all");
    result.recording.records.push_back(std::move(e));
  }
  return result;
}

} // namespace lvdif
