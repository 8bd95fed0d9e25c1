#include "lvdif/Brush.h"
#include "lvdif/EditLimits.h"

#include "BrushKernel.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace lvdif
{

const char* toString(BrushShape s)
{
  switch (s)
  {
    case BrushShape::Sphere: return "sphere";
    case BrushShape::Cube: return "cube";
    case BrushShape::Capsule: return "capsule";
  }
  return "unknown";
}

const char* toString(BrushOp op)
{
  switch (op)
  {
    case BrushOp::Add: return "add";
    case BrushOp::Subtract: return "subtract";
    case BrushOp::Paint: return "paint";
    case BrushOp::Smooth: return "smooth";
    case BrushOp::Inflate: return "inflate";
    case BrushOp::Grab: return "grab";
    case BrushOp::Flatten: return "flatten";
    case BrushOp::Crease: return "crease";
    case BrushOp::Pinch: return "pinch";
  }
  return "unknown";
}

const char* toString(Falloff f)
{
  switch (f)
  {
    case Falloff::Constant: return "constant";
    case Falloff::Linear: return "linear";
    case Falloff::Smooth: return "smooth";
    case Falloff::Sharp: return "sharp";
  }
  return "unknown";
}

std::vector<Dab> mirrorDabs(const std::vector<Dab>& dabs, const Symmetry& sym)
{
  std::vector<Dab> out;
  int axes[3], n = 0;
  for (int a = 0; a < 3; ++a)
    if (sym.mirror[a])
      axes[n++] = a;
  out.reserve(dabs.size() << n);
  for (const Dab& d : dabs)
    for (int m = 0; m < (1 << n); ++m)
    {
      Dab c = d;
      for (int i = 0; i < n; ++i)
        if (m & (1 << i))
        {
          const int a = axes[i];
          const double p = sym.plane[a];
          c.center[a] = 2 * p - c.center[a];
          c.end[a] = 2 * p - c.end[a];
          c.vec[a] = -c.vec[a];
        }
      out.push_back(c);
    }
  return out;
}

namespace
{

double reachOf(const DictionaryVolume& volume, const BrushSettings& s)
{
  const double k = s.blend > 0 ? s.blend : 0.0;
  if (s.op != BrushOp::Add && s.op != BrushOp::Subtract)
  {
    return 0.0; // the other operations act inside the primitive only
  }
  const double band = volume.bandWidth();
  const double colour = s.op == BrushOp::Add ? s.colorOffset : 0.0;
  return std::max(band, colour) + k;
}

// Bounding box of the primitive itself (continuous, voxel coordinates).
void primitiveBounds(const Dab& d, double lo[3], double hi[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (d.shape == BrushShape::Capsule)
    {
      lo[a] = std::min(d.center[a], d.end[a]) - d.radius;
      hi[a] = std::max(d.center[a], d.end[a]) + d.radius;
    }
    else
    {
      // a cube's half edge reaches sqrt(3)*h only at corners, but its box is +-h
      lo[a] = d.center[a] - d.radius;
      hi[a] = d.center[a] + d.radius;
    }
  }
}

VoxelBox boxFor(const DictionaryVolume& volume, const Dab& d, double reach)
{
  if (!std::isfinite(reach))
  {
    return volume.bounds();
  }
  double lo[3], hi[3];
  primitiveBounds(d, lo, hi);
  VoxelBox b;
  for (int a = 0; a < 3; ++a)
  {
    // clamp before converting so far-away dabs cannot overflow the integer
    const double l = std::max(-1.0, std::min(std::floor(lo[a] - reach), double(volume.dims()[a])));
    const double h = std::max(-1.0, std::min(std::ceil(hi[a] + reach), double(volume.dims()[a])));
    b.lo[a] = static_cast<std::int64_t>(l);
    b.hi[a] = static_cast<std::int64_t>(h);
  }
  return b.intersect(volume.bounds());
}

void validateAll(const std::vector<Dab>& dabs, const BrushSettings& s)
{
  validate(s);
  for (size_t i = 0; i < dabs.size(); ++i)
    validate(dabs[i], i);
}


// A hard add or subtract whose primitive lies below -band over a whole chunk
// sets every voxel's distance to the band's extreme key (add: -band and the
// brush colour; subtract: +band, colours kept), whatever the other dabs of the
// call do, provided no stored key is beyond the band. Then the chunk is
// written in one go instead of voxel by voxel; the bits are the same as the
// per-voxel rule's (the CUDA path, which has no such shortcut, checks it).
bool coverChunk(DictionaryVolume& volume, std::int64_t id, const detail::edit::BrushContext& ctx,
  ChunkWriteObserver* observer, std::int64_t& changed)
{
  const float band = volume.bandWidth();
  const bool add = ctx.op == static_cast<int>(BrushOp::Add);
  const SdfKey extreme = volume.encode(add ? -band : band);
  const std::pair<SdfKey, SdfKey> range = volume.chunkRange(id);
  if (add ? range.first < extreme : range.second > extreme)
    return false; // keys beyond the band: leave it to the per-voxel rule
  const VoxelBox b = volume.chunkBox(id);
  changed = 0;
  if (volume.isUniform(id))
  {
    const Voxel u = volume.uniformValue(id);
    const Voxel target{ extreme, add ? ctx.colorKey : u.color };
    if (u != target)
    {
      changed = b.voxelCount();
      if (observer)
        observer->beforeChunkWrite(volume, id);
      volume.fillChunk(id, target);
    }
    return true;
  }
  if (add)
  {
    const Voxel target{ extreme, ctx.colorKey };
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          changed += volume.get(x, y, z) != target;
    if (changed > 0)
    {
      if (observer)
        observer->beforeChunkWrite(volume, id);
      volume.fillChunk(id, target);
    }
    return true;
  }
  bool touched = false;
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
      for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
      {
        Voxel v = volume.get(x, y, z);
        if (v.sdf == extreme)
          continue;
        if (!touched && observer)
          observer->beforeChunkWrite(volume, id);
        touched = true;
        v.sdf = extreme;
        volume.set(x, y, z, v);
        ++changed;
      }
  if (touched)
    volume.tryCollapseChunk(id);
  return true;
}

} // namespace

VoxelBox dabInfluenceBox(const DictionaryVolume& volume, const Dab& dab, const BrushSettings& settings)
{
  return boxFor(volume, dab, reachOf(volume, settings));
}

void requireChunkVisitBudget(const DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings)
{
  const std::uint64_t maxVisits = EditLimits().maxChunkVisitsPerEdit;
  const double edge = volume.chunkEdge();
  const double reach = reachOf(volume, settings);
  const std::vector<Dab> all = mirrorDabs(dabs, settings.symmetry);
  double visits = 0;
  for (const Dab& d : all)
  {
    if (!(d.radius > 0))
      continue; // skipped by every brush
    const VoxelBox b = boxFor(volume, d, reach);
    if (b.empty())
      continue;
    double n = 1;
    for (int a = 0; a < 3; ++a)
      n *= std::floor(double(b.hi[a]) / edge) - std::floor(double(b.lo[a]) / edge) + 1;
    visits += n;
    if (visits > double(maxVisits))
      throw Error(ErrorCode::InvalidArgument, "the edit's " + std::to_string(all.size()) +
          " dabs would visit more than " + std::to_string(maxVisits) + " chunks (radius, blend or dab count too large)");
  }
}

namespace detail::edit
{
double trilinear(const DictionaryVolume& v, const float* table, double x, double y, double z)
{
  const Index3& n = v.dims();
  const double p[3] = { std::min(std::max(x, 0.0), double(n[0] - 1)), std::min(std::max(y, 0.0), double(n[1] - 1)),
    std::min(std::max(z, 0.0), double(n[2] - 1)) };
  std::int64_t i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    i0[a] = static_cast<std::int64_t>(std::floor(p[a]));
    i1[a] = std::min(i0[a] + 1, n[a] - 1);
    f[a] = p[a] - double(i0[a]);
  }
  double r = 0;
  for (int c = 0; c < 8; ++c)
  {
    const double w = ((c & 1) ? f[0] : 1 - f[0]) * ((c & 2) ? f[1] : 1 - f[1]) * ((c & 4) ? f[2] : 1 - f[2]);
    if (w == 0)
      continue;
    r += w * table[v.get((c & 1) ? i1[0] : i0[0], (c & 2) ? i1[1] : i0[1], (c & 4) ? i1[2] : i0[2]).sdf];
  }
  return r;
}
} // namespace detail::edit

namespace
{
using detail::edit::trilinear;

// Flatten's plane for a dab: tangent to the surface nearest the centre.
void measurePlane(const DictionaryVolume& v, Dab& d)
{
  const float* table = v.sdfDictionary().table();
  const double cx = d.center[0], cy = d.center[1], cz = d.center[2];
  double g[3] = { trilinear(v, table, cx + 1, cy, cz) - trilinear(v, table, cx - 1, cy, cz),
    trilinear(v, table, cx, cy + 1, cz) - trilinear(v, table, cx, cy - 1, cz),
    trilinear(v, table, cx, cy, cz + 1) - trilinear(v, table, cx, cy, cz - 1) };
  const double len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (!(len > 1e-9))
  {
    g[0] = 0, g[1] = 0, g[2] = 1; // flat field (deep inside or far outside): any plane
  }
  else
  {
    for (double& c : g)
      c /= len;
  }
  const double dc = trilinear(v, table, cx, cy, cz);
  d.vec = { g[0], g[1], g[2] };
  d.value = g[0] * (cx - dc * g[0]) + g[1] * (cy - dc * g[1]) + g[2] * (cz - dc * g[2]);
}

// Soft paint: every colour key the plan's boxes hold where the skin may be
// painted, and its mixes with the brush colour in eighths.
void buildMixTable(DictionaryVolume& volume, detail::edit::DabPlan& plan, const BrushSettings& settings)
{
  const float* table = volume.sdfDictionary().table();
  std::set<std::uint16_t> keys;
  VoxelBox all;
  for (const VoxelBox& b : plan.boxes)
    all = all.unite(b);
  for (std::int64_t id : plan.chunks)
  {
    if (volume.isUniform(id))
    {
      keys.insert(volume.uniformValue(id).color);
      continue;
    }
    const VoxelBox b = volume.chunkBox(id).intersect(all);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          const Voxel v = volume.get(x, y, z);
          if (std::fabs(table[v.sdf]) <= settings.colorOffset)
            keys.insert(v.color);
        }
  }
  const Rgba brush = settings.color;
  for (std::uint16_t k : keys)
  {
    plan.mixFrom.push_back(k);
    const Rgba old = volume.colors().color(k);
    for (int q = 1; q < detail::edit::PaintLevels; ++q)
    {
      const int L = detail::edit::PaintLevels;
      auto mix = [&](std::uint8_t a, std::uint8_t b) {
        return static_cast<std::uint8_t>((int(a) * (L - q) + int(b) * q + L / 2) / L);
      };
      plan.mixTo.push_back(
        volume.colors().add(Rgba{ mix(old.r, brush.r), mix(old.g, brush.g), mix(old.b, brush.b), mix(old.a, brush.a) }));
    }
  }
  plan.ctx.mixFrom = plan.mixFrom.data();
  plan.ctx.mixTo = plan.mixTo.data();
  plan.ctx.mixCount = static_cast<int>(plan.mixFrom.size());
}

// Plans groups of dabs (any operation); shared by the per-voxel rule and the gather brushes.
detail::edit::DabPlan planGroups(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  const ChunkWriteObserver* observer = nullptr)
{
  validateAll(dabs, settings);
  detail::edit::DabPlan plan;
  detail::edit::BrushContext& ctx = plan.ctx;
  ctx.op = static_cast<int>(settings.op);
  ctx.blend = settings.blend;
  ctx.colorOffset = settings.colorOffset;
  ctx.rounding = settings.rounding;
  ctx.reach = reachOf(volume, settings);
  ctx.strength = settings.strength;
  ctx.falloff = static_cast<int>(settings.falloff);
  ctx.invert = settings.invert ? 1 : 0;
  ctx.band = volume.bandWidth();
  const bool csg = settings.op == BrushOp::Add || settings.op == BrushOp::Subtract || settings.op == BrushOp::Paint;
  ctx.unitWeight = csg && settings.strength == 1 && settings.falloff == Falloff::Constant ? 1 : 0;
  ctx.groupSize = 1;
  int nMirror = 0;
  for (int a = 0; a < 3; ++a)
  {
    ctx.twicePlane[a] = 2 * settings.symmetry.plane[a];
    if (settings.symmetry.mirror[a])
    {
      ctx.groupSize *= 2;
      ctx.mirrorAxis[nMirror++] = a; // mirrorDabs' bit order
    }
  }
  if (settings.op == BrushOp::Add || settings.op == BrushOp::Paint)
  {
    ctx.colorKey = volume.colors().add(settings.color);
  }
  // Budgets, counted before any chunk is visited or written: the chunk visits
  // of all boxes, then (below) the memory the edit may allocate (uniform chunks
  // it expands, plus the undo snapshots of expanded ones).
  requireChunkVisitBudget(volume, dabs, settings);
  const std::vector<Dab> all = mirrorDabs(dabs, settings.symmetry);
  const std::size_t g = static_cast<std::size_t>(ctx.groupSize);
  for (std::size_t first = 0; first < all.size(); first += g)
  {
    if (!(all[first].radius > 0))
    {
      continue; // the original skips points with w <= 0
    }
    std::vector<VoxelBox> boxes(g);
    bool any = false;
    for (std::size_t k = 0; k < g; ++k)
    {
      boxes[k] = boxFor(volume, all[first + k], ctx.reach);
      any = any || !boxes[k].empty();
    }
    if (!any)
    {
      continue;
    }
    for (std::size_t k = 0; k < g; ++k)
    {
      Dab d = all[first + k];
      if (settings.op == BrushOp::Flatten)
        measurePlane(volume, d);
      plan.dabs.push_back(d);
      plan.boxes.push_back(boxes[k]);
    }
  }
  std::vector<bool> seen(static_cast<std::size_t>(volume.chunkCount()), false);
  for (const VoxelBox& b : plan.boxes)
    volume.forEachChunkInBox(b, [&](std::int64_t id) {
      if (!seen[static_cast<std::size_t>(id)])
      {
        seen[static_cast<std::size_t>(id)] = true;
        plan.chunks.push_back(id);
      }
    });
  std::sort(plan.chunks.begin(), plan.chunks.end());
  const std::uint64_t chunkBytes = std::uint64_t(volume.chunkEdge()) * std::uint64_t(volume.chunkEdge()) *
    std::uint64_t(volume.chunkEdge()) * sizeof(Voxel);
  std::uint64_t newBytes = 0;
  for (std::int64_t id : plan.chunks)
    newBytes += volume.isUniform(id) ? chunkBytes : 0;
  // small edits (every interactive dab) skip the /proc/meminfo read
  const std::uint64_t need = newBytes + (observer ? plan.chunks.size() * chunkBytes : 0);
  if (need > (std::uint64_t(64) << 20))
    requireMemory(need, "an edit of " + std::to_string(plan.chunks.size()) + " chunks");
  if (settings.op == BrushOp::Paint && !ctx.unitWeight)
    buildMixTable(volume, plan, settings);
  return plan;
}


} // namespace

namespace detail::edit
{
DabPlan planDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  const ChunkWriteObserver* observer)
{
  if (readsNeighbours(settings.op))
    throw Error(ErrorCode::Unsupported,
      std::string("the ") + toString(settings.op) + " brush reads neighbouring voxels and runs on the CPU only");
  return planGroups(volume, dabs, settings, observer);
}
} // namespace detail::edit

EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer, const Interrupter* interrupter)
{
  if (readsNeighbours(settings.op))
    return detail::edit::applyGather(volume, planGroups(volume, dabs, settings, observer), observer, interrupter);
  detail::edit::DabPlan plan = detail::edit::planDabs(volume, dabs, settings, observer);
  EditResult result;
  const detail::edit::BrushContext& ctx = plan.ctx;
  const std::vector<Dab>& active = plan.dabs;
  const std::vector<VoxelBox>& boxes = plan.boxes;
  const std::vector<std::int64_t>& chunks = plan.chunks;
  const float* table = volume.sdfDictionary().table();
  const SdfDictionary& dict = volume.sdfDictionary();
  const float band = volume.bandWidth();
  // encodeClamped with the two saturated keys looked up once: most of a large
  // dab's interior (and far side) encodes to them
  const SdfKey belowBand = dict.encode(-band), aboveBand = dict.encode(band);
  auto encode = [&dict, band, belowBand, aboveBand](double v) {
    const float f = static_cast<float>(v);
    return f <= -band ? belowBand : (f >= band ? aboveBand : dict.encode(f));
  };
  const std::int64_t nChunks = static_cast<std::int64_t>(chunks.size());
  std::vector<std::int64_t> changedPerChunk(chunks.size(), 0);
  std::vector<VoxelBox> changedBoxPerChunk(chunks.size());
  const double reach = ctx.reach;
  bool failed = false;
  Error firstError(ErrorCode::InvalidArgument, "");
  std::atomic<bool> stopped{ false };

#pragma omp parallel for schedule(dynamic, 1) if (nChunks > 1)
  for (std::int64_t ci = 0; ci < nChunks; ++ci)
  {
    // each chunk is written whole or not at all: a cancel leaves no half chunk
    if (interrupter && (stopped.load(std::memory_order_relaxed) || interrupter->wasInterrupted()))
    {
      stopped.store(true, std::memory_order_relaxed);
      continue;
    }
    try
    {
      const std::int64_t id = chunks[static_cast<size_t>(ci)];
      const VoxelBox cb = volume.chunkBox(id);
      // The dabs (in order) whose box meets this chunk and that can reach it, and the
      // union of their boxes. SDFs are 1-Lipschitz, so the distance at the chunk's
      // centre +- its half diagonal bounds every voxel's.
      const double cc[3] = { 0.5 * (cb.lo[0] + cb.hi[0]), 0.5 * (cb.lo[1] + cb.hi[1]), 0.5 * (cb.lo[2] + cb.hi[2]) };
      const double halfDiag = 0.5 * std::sqrt(double((cb.hi[0] - cb.lo[0]) * (cb.hi[0] - cb.lo[0]) +
                                                (cb.hi[1] - cb.lo[1]) * (cb.hi[1] - cb.lo[1]) +
                                                (cb.hi[2] - cb.lo[2]) * (cb.hi[2] - cb.lo[2])));
      std::vector<int> mine; // groups that can reach this chunk
      bool covered = false; // some dab is below -band over the whole chunk
      VoxelBox region;
      region.lo = cb.hi;
      region.hi = cb.lo;
      const int g = ctx.groupSize;
      for (size_t k = 0; k < active.size(); ++k)
      {
        const VoxelBox ib = boxes[k].intersect(cb);
        if (ib.empty())
          continue;
        const double sc = dabDistance(active[k], cc[0], cc[1], cc[2], ctx.rounding);
        if (sc - halfDiag > reach)
          continue;
        covered = covered || sc + halfDiag <= -double(band);
        const int group = static_cast<int>(k) / g;
        if (mine.empty() || mine.back() != group)
          mine.push_back(group);
        for (int a = 0; a < 3; ++a)
        {
          region.lo[a] = std::min(region.lo[a], ib.lo[a]);
          region.hi[a] = std::max(region.hi[a], ib.hi[a]);
        }
      }
      if (mine.empty())
        continue;
      if (covered && ctx.blend <= 0 && ctx.unitWeight && ctx.op != static_cast<int>(BrushOp::Paint))
      {
        std::int64_t n = 0;
        if (coverChunk(volume, id, ctx, observer, n))
        {
          changedPerChunk[static_cast<size_t>(ci)] = n;
          if (n > 0)
            changedBoxPerChunk[static_cast<size_t>(ci)] = cb;
          continue;
        }
      }
      bool touched = false;
      std::int64_t changed = 0;
      VoxelBox changedBox;
      // Read through the chunk's own storage; after the first change (volume.set expands
      // the chunk and marks it dirty and its range stale) write straight into its data:
      // this thread owns the chunk for the whole call.
      const Voxel* readData = volume.chunkData(id);
      const Voxel uniformValue = volume.uniformValue(id);
      Voxel* writeData = nullptr;
      // without symmetry or weights, each dab's distances are computed a row at a time
      const bool perDabRows = g == 1 && ctx.unitWeight;
      const bool add = ctx.op == static_cast<int>(BrushOp::Add);
      const bool hardCsg = perDabRows && ctx.blend <= 0 && (add || ctx.op == static_cast<int>(BrushOp::Subtract));
      std::vector<Voxel> rowOld, rowNew;
      std::vector<double> rowS;
      // Hard add, row path: a voxel's distance lowered by a dab is kept as the
      // exact s ("pending") and encoded once after the row's last dab; the
      // sequence of the per-voxel rule is reproduced exactly (see below).
      const bool pendingAdd = hardCsg && add;
      std::vector<double> rowPend;
      std::vector<std::pair<std::int64_t, std::int64_t>> rowRange(perDabRows ? active.size() : 0);
      for (std::int64_t z = region.lo[2]; z <= region.hi[2]; ++z)
        for (std::int64_t y = region.lo[1]; y <= region.hi[1]; ++y)
        {
          // per row, the x range each dab can reach (a sphere trims it analytically)
          std::int64_t x0 = region.hi[0] + 1, x1 = region.lo[0] - 1;
          if (perDabRows)
            for (int k : mine)
              rowRange[static_cast<size_t>(k)] = { 1, 0 }; // empty unless the row meets the dab
          for (int gi : mine)
          {
            for (int k = gi * g; k < (gi + 1) * g; ++k)
            {
              const VoxelBox& b = boxes[static_cast<size_t>(k)];
              if (y < b.lo[1] || y > b.hi[1] || z < b.lo[2] || z > b.hi[2])
                continue;
              std::int64_t lo = std::max(b.lo[0], region.lo[0]), hi = std::min(b.hi[0], region.hi[0]);
              const Dab& d = active[static_cast<size_t>(k)];
              if (d.shape == BrushShape::Sphere && std::isfinite(reach))
              {
                const double rr = d.radius + reach, dy = y - d.center[1], dz = z - d.center[2];
                const double q = rr * rr - dy * dy - dz * dz;
                if (q < 0)
                  continue;
                const double w = std::sqrt(q);
                lo = std::max(lo, static_cast<std::int64_t>(std::floor(d.center[0] - w)));
                hi = std::min(hi, static_cast<std::int64_t>(std::ceil(d.center[0] + w)));
              }
              x0 = std::min(x0, lo);
              x1 = std::max(x1, hi);
              if (perDabRows)
                rowRange[static_cast<size_t>(k)] = { lo, hi };
            }
          }
          if (x1 < x0)
            continue;
          const std::int64_t li0 = volume.localIndex(x0, y, z); // a row is contiguous in the chunk
          const std::int64_t m = x1 - x0 + 1;
          rowOld.resize(static_cast<std::size_t>(m));
          if (writeData || readData)
            std::copy_n((writeData ? writeData : readData) + li0, m, rowOld.begin());
          else
            std::fill(rowOld.begin(), rowOld.end(), uniformValue);
          rowNew = rowOld;
          if (pendingAdd)
            rowPend.assign(static_cast<std::size_t>(m), std::numeric_limits<double>::infinity());
          if (perDabRows)
          {
            // Dab by dab over the row (voxels are independent, so this is the
            // per-voxel order): each dab's s over its own trimmed x range (the
            // union's other voxels are beyond its reach) in one tight loop, then
            // the same combine as applyGroupToVoxel with t = 0.
            for (int k : mine)
            {
              const VoxelBox& b = boxes[static_cast<size_t>(k)];
              if (y < b.lo[1] || y > b.hi[1] || z < b.lo[2] || z > b.hi[2])
                continue;
              const std::int64_t a0 = rowRange[static_cast<size_t>(k)].first, a1 = rowRange[static_cast<size_t>(k)].second;
              if (a1 < a0)
                continue;
              const Dab& d = active[static_cast<size_t>(k)];
              Voxel* rv = rowNew.data() - x0;
              std::pair<std::int64_t, std::int64_t> rest[2] = { { a0, a1 }, { 1, 0 } }; // what is left voxel by voxel
              int nRest = 1;
              if (hardCsg && d.shape == BrushShape::Sphere)
              {
                // Whole spans settled without a distance per voxel (the same bits as
                // the per-voxel rule). s(x) below is sphereDistance's arithmetic; it
                // grows with |x - cx| op by op, so its extremes over [a0, a1] are at
                // the ends and at the integers around cx.
                const double py = double(y) - d.center[1], pz = double(z) - d.center[2];
                const double yy = py * py, zz = pz * pz, cx = d.center[0], r = d.radius;
                auto sAt = [&](std::int64_t x) {
                  const double px = double(x) - cx;
                  return std::sqrt(px * px + yy + zz) - r;
                };
                const std::int64_t xn = std::min(a1, std::max(a0, static_cast<std::int64_t>(std::floor(cx))));
                const double sMin = std::min(sAt(xn), sAt(std::min(a1, xn + 1)));
                if (sMin > 0)
                {
                  // outside the primitive: add changes a voxel only where s < d,
                  // subtract only where -s > d; neither can happen when the row's
                  // largest (smallest) distance is at most sMin (at least -sMin)
                  SdfKey lo = rv[a0].sdf, hi = rv[a0].sdf;
                  for (std::int64_t x = a0 + 1; x <= a1; ++x)
                  {
                    lo = std::min(lo, rv[x].sdf);
                    hi = std::max(hi, rv[x].sdf);
                  }
                  if (add ? double(table[hi]) <= sMin : double(table[lo]) >= -sMin)
                    continue;
                }
                // [i0, i1]: where s <= -band (an interval: s falls to xn, then rises)
                const double deep = -double(band);
                std::int64_t i0 = a1 + 1, i1 = a1;
                if (std::min(sAt(xn), sAt(std::min(a1, xn + 1))) <= deep)
                {
                  const std::int64_t turn = sAt(xn) <= deep ? xn : xn + 1;
                  // s <= deep is monotone on each side of turn: start at the
                  // analytic boundary (|x - cx| <= sqrt((r - band)^2 - yy - zz))
                  // and step to the exact one with sAt, which gives the same x as
                  // a bisection with sAt, in about two square roots instead of ~12
                  const double rd = r + deep, w2 = rd * rd - yy - zz;
                  const double w = w2 > 0 ? std::sqrt(w2) : 0.0;
                  auto clampTo = [](double v, std::int64_t l, std::int64_t h) {
                    return v <= double(l) ? l : (v >= double(h) ? h : static_cast<std::int64_t>(v));
                  };
                  std::int64_t g = clampTo(std::ceil(cx - w), a0, turn); // first x in [a0, turn] with s <= deep
                  while (g > a0 && sAt(g - 1) <= deep)
                    --g;
                  while (g < turn && !(sAt(g) <= deep))
                    ++g;
                  i0 = g;
                  g = clampTo(std::floor(cx + w), turn, a1); // last x in [turn, a1] with s <= deep
                  while (g < a1 && sAt(g + 1) <= deep)
                    ++g;
                  while (g > turn && !(sAt(g) <= deep))
                    --g;
                  i1 = g;
                }
                bool inBand = true; // every key of the span within the band (else: voxel by voxel)
                for (std::int64_t x = i0; x <= i1 && inBand; ++x)
                  inBand = add ? rv[x].sdf >= belowBand : rv[x].sdf <= aboveBand;
                if (i0 <= i1 && inBand)
                {
                  // s <= -band there: add sets the distance to the key of -band
                  // (and the brush colour), subtract to that of +band, for every key
                  // within the band (encode(-band) is the nearest key to -band)
                  for (std::int64_t x = i0; x <= i1; ++x)
                  {
                    Voxel& w = rv[x];
                    w.sdf = add ? belowBand : aboveBand;
                    if (add)
                      w.color = ctx.colorKey;
                    if (pendingAdd)
                      rowPend[static_cast<std::size_t>(x - x0)] = std::numeric_limits<double>::infinity();
                  }
                  // the rest of the range, voxel by voxel below
                  if (i0 == a0 && i1 == a1)
                    continue;
                  rest[0] = { a0, i0 - 1 };
                  rest[1] = { i1 + 1, a1 };
                  nRest = 2;
                }
              }
              for (int part = 0; part < nRest; ++part)
              {
                const std::int64_t b0 = rest[part].first, b1 = rest[part].second;
                if (b1 < b0)
                  continue;
                rowS.resize(static_cast<std::size_t>(b1 - b0 + 1));
                double* sv = rowS.data();
                if (d.shape == BrushShape::Sphere)
                {
                  // sphereDistance's arithmetic in its order (bit-identical), vectorisable
                  const double py = double(y) - d.center[1], pz = double(z) - d.center[2];
                  const double yy = py * py, zz = pz * pz, cx = d.center[0], r = d.radius, x0d = double(b0);
                  const int n = static_cast<int>(b1 - b0 + 1);
                  // x0d + i is exactly double(x) (integers far below 2^53); an int
                  // index lets the loop vectorise
                  for (int i = 0; i < n; ++i)
                  {
                    const double px = (x0d + double(i)) - cx;
                    sv[i] = std::sqrt(px * px + yy + zz) - r;
                  }
                }
                else
                  for (std::int64_t x = b0; x <= b1; ++x)
                    sv[x - b0] = dabDistance(d, double(x), double(y), double(z), ctx.rounding);
                if (pendingAdd)
                {
                  // combineVoxel's hard add (s < d: key = encode(s), colour if
                  // s <= colorOffset; colour if s <= 0) with the key of a voxel
                  // this call already lowered left as its exact s = p. encode is
                  // monotone and encode(table[k]) == k for the band's keys
                  // (Brush.PendingEncodeIsExact), so for k = encode(p):
                  // s >= p: table[k] <= s would leave the voxel, table[k] > s
                  //   gives encode(s) == k and a colour p already gave: no-op;
                  // s < p: the key becomes encode(s) either way (table[k] <= s
                  //   < p), the colour as the rule says (table[k] only there).
                  const double co = ctx.colorOffset;
                  double* pend = rowPend.data() - x0;
                  for (std::int64_t x = b0; x <= b1; ++x)
                  {
                    const double sx = sv[x - b0];
                    if (sx > reach)
                      continue;
                    Voxel& w = rv[x];
                    double& p = pend[x];
                    if (p != std::numeric_limits<double>::infinity())
                    {
                      if (sx >= p)
                        continue;
                      if (w.color != ctx.colorKey && (sx <= 0 || (sx <= co && sx < double(table[encode(p)]))))
                        w.color = ctx.colorKey;
                      p = sx;
                    }
                    else if (sx < double(table[w.sdf]))
                    {
                      p = sx;
                      if (sx <= co || sx <= 0)
                        w.color = ctx.colorKey;
                    }
                    else if (sx <= 0)
                      w.color = ctx.colorKey;
                  }
                  continue;
                }
                for (std::int64_t x = b0; x <= b1; ++x)
                {
                  const double sx = sv[x - b0];
                  if (sx > reach)
                    continue;
                  detail::edit::combineVoxel(rv[x].sdf, rv[x].color, sx, 0.0, d, double(x), double(y), double(z), ctx, table, encode);
                }
              }
            }
          }
          else
            for (std::int64_t x = x0; x <= x1; ++x)
            {
              Voxel& v = rowNew[static_cast<std::size_t>(x - x0)];
              for (int gi : mine)
                detail::edit::applyGroupToVoxel(v.sdf, v.color, x, y, z, active.data(), boxes.data(), gi, ctx, table, encode);
            }
          if (pendingAdd)
            for (std::int64_t i = 0; i < m; ++i)
              if (rowPend[static_cast<std::size_t>(i)] != std::numeric_limits<double>::infinity())
                rowNew[static_cast<std::size_t>(i)].sdf = encode(rowPend[static_cast<std::size_t>(i)]);
          for (std::int64_t x = x0; x <= x1; ++x)
          {
            const std::int64_t li = li0 + (x - x0);
            const Voxel old = rowOld[static_cast<std::size_t>(x - x0)];
            const Voxel v = rowNew[static_cast<std::size_t>(x - x0)];
            if (v != old)
            {
              if (!touched)
              {
                touched = true;
                if (observer)
                  observer->beforeChunkWrite(volume, id);
                volume.set(x, y, z, v);
                writeData = volume.expandChunk(id); // already expanded by set: returns its data
              }
              else
              {
                writeData[li] = v;
              }
              ++changed;
              changedBox.include(x, y, z);
            }
          }
        }
      if (touched && !volume.isUniform(id))
      {
        volume.tryCollapseChunk(id);
      }
      changedPerChunk[static_cast<size_t>(ci)] = changed;
      changedBoxPerChunk[static_cast<size_t>(ci)] = changedBox;
    }
    catch (const Error& e)
    {
#pragma omp critical(lvdif_brush_error)
      {
        if (!failed)
          firstError = e;
        failed = true;
      }
    }
  }
  if (failed)
  {
    throw firstError;
  }
  result.interrupted = stopped.load();
  for (size_t i = 0; i < chunks.size(); ++i)
  {
    if (changedPerChunk[i] > 0)
    {
      result.changedChunks.push_back(chunks[i]);
      result.changedChunkBoxes.push_back(changedBoxPerChunk[i]);
      result.changedVoxels += changedPerChunk[i];
      result.changedBox = result.changedBox.unite(changedBoxPerChunk[i]);
    }
  }
  return result;
}

} // namespace lvdif
