#include "lvdif/Brush.h"

#include "BrushKernel.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
  }
  return "unknown";
}

namespace
{

double reachOf(const DictionaryVolume& volume, const BrushSettings& s)
{
  const double k = s.blend > 0 ? s.blend : 0.0;
  if (s.op == BrushOp::Paint)
  {
    return 0.0;
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

void validate(const std::vector<Dab>& dabs, const BrushSettings& s)
{
  require(std::isfinite(s.blend) && s.blend >= 0, "brush blend radius must be finite and >= 0");
  require(std::isfinite(s.colorOffset) && s.colorOffset >= 0, "brush colour offset must be finite and >= 0");
  require(std::isfinite(s.rounding) && s.rounding >= 0, "cube rounding must be finite and >= 0");
  require(s.op == BrushOp::Add || s.op == BrushOp::Subtract || s.op == BrushOp::Paint, "unknown brush operation");
  for (size_t i = 0; i < dabs.size(); ++i)
  {
    const Dab& d = dabs[i];
    bool ok = std::isfinite(d.radius) && d.radius < 1e7;
    for (int a = 0; a < 3; ++a)
    {
      ok = ok && std::isfinite(d.center[a]) && std::fabs(d.center[a]) < 1e9;
      if (d.shape == BrushShape::Capsule)
        ok = ok && std::isfinite(d.end[a]) && std::fabs(d.end[a]) < 1e9;
    }
    ok = ok && (d.shape == BrushShape::Sphere || d.shape == BrushShape::Cube || d.shape == BrushShape::Capsule);
    if (!ok)
    {
      std::ostringstream msg;
      msg << "dab " << i << " has a non-finite, absurd or unknown position, radius or shape";
      throw Error(ErrorCode::InvalidArgument, msg.str());
    }
  }
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

namespace detail::edit
{
DabPlan planDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings)
{
  validate(dabs, settings);
  DabPlan plan;
  BrushContext& ctx = plan.ctx;
  ctx.op = static_cast<int>(settings.op);
  ctx.blend = settings.blend;
  ctx.colorOffset = settings.colorOffset;
  ctx.rounding = settings.rounding;
  ctx.reach = reachOf(volume, settings);
  if (settings.op != BrushOp::Subtract)
  {
    ctx.colorKey = volume.colors().add(settings.color);
  }
  for (const Dab& d : dabs)
  {
    if (!(d.radius > 0))
    {
      continue; // the original skips points with w <= 0
    }
    const VoxelBox b = boxFor(volume, d, ctx.reach);
    if (b.empty())
    {
      continue;
    }
    plan.dabs.push_back(d);
    plan.boxes.push_back(b);
    volume.forEachChunkInBox(b, [&](std::int64_t id) { plan.chunks.push_back(id); });
  }
  std::sort(plan.chunks.begin(), plan.chunks.end());
  plan.chunks.erase(std::unique(plan.chunks.begin(), plan.chunks.end()), plan.chunks.end());
  return plan;
}
} // namespace detail::edit

EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer)
{
  detail::edit::DabPlan plan = detail::edit::planDabs(volume, dabs, settings);
  EditResult result;
  const detail::edit::BrushContext& ctx = plan.ctx;
  const std::vector<Dab>& active = plan.dabs;
  const std::vector<VoxelBox>& boxes = plan.boxes;
  const std::vector<std::int64_t>& chunks = plan.chunks;
  const float* table = volume.sdfDictionary().table();
  const SdfDictionary& dict = volume.sdfDictionary();
  const float band = volume.bandWidth();
  auto encode = [&dict, band](double v) { return dict.encodeClamped(static_cast<float>(v), band); };
  const std::int64_t nChunks = static_cast<std::int64_t>(chunks.size());
  std::vector<std::int64_t> changedPerChunk(chunks.size(), 0);
  std::vector<VoxelBox> changedBoxPerChunk(chunks.size());
  const double reach = ctx.reach;
  bool failed = false;
  Error firstError(ErrorCode::InvalidArgument, "");

#pragma omp parallel for schedule(dynamic, 1) if (nChunks > 1)
  for (std::int64_t ci = 0; ci < nChunks; ++ci)
  {
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
      std::vector<int> mine;
      bool covered = false; // some dab is below -band over the whole chunk
      VoxelBox region;
      region.lo = cb.hi;
      region.hi = cb.lo;
      for (size_t k = 0; k < active.size(); ++k)
      {
        const VoxelBox ib = boxes[k].intersect(cb);
        if (ib.empty())
          continue;
        const double sc = dabDistance(active[k], cc[0], cc[1], cc[2], ctx.rounding);
        if (sc - halfDiag > reach)
          continue;
        covered = covered || sc + halfDiag <= -double(band);
        mine.push_back(static_cast<int>(k));
        for (int a = 0; a < 3; ++a)
        {
          region.lo[a] = std::min(region.lo[a], ib.lo[a]);
          region.hi[a] = std::max(region.hi[a], ib.hi[a]);
        }
      }
      if (mine.empty())
        continue;
      if (covered && ctx.blend <= 0 && ctx.op != static_cast<int>(BrushOp::Paint))
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
      for (std::int64_t z = region.lo[2]; z <= region.hi[2]; ++z)
        for (std::int64_t y = region.lo[1]; y <= region.hi[1]; ++y)
        {
          // per row, the x range each dab can reach (a sphere trims it analytically)
          std::int64_t x0 = region.hi[0] + 1, x1 = region.lo[0] - 1;
          for (int k : mine)
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
          }
          for (std::int64_t x = x0; x <= x1; ++x)
          {
            const std::int64_t li = volume.localIndex(x, y, z);
            const Voxel old = writeData ? writeData[li] : (readData ? readData[li] : uniformValue);
            Voxel v = old;
            for (int k : mine)
            {
              const VoxelBox& b = boxes[static_cast<size_t>(k)];
              if (!b.contains(x, y, z))
                continue;
              const double s =
                dabDistance(active[static_cast<size_t>(k)], double(x), double(y), double(z), ctx.rounding);
              if (s > reach)
                continue;
              detail::edit::combineVoxel(v.sdf, v.color, s, ctx, table, encode);
            }
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
  for (size_t i = 0; i < chunks.size(); ++i)
  {
    if (changedPerChunk[i] > 0)
    {
      result.changedChunks.push_back(chunks[i]);
      result.changedVoxels += changedPerChunk[i];
      result.changedBox = result.changedBox.unite(changedBoxPerChunk[i]);
    }
  }
  return result;
}

} // namespace lvdif
