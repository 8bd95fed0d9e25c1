// The brushes that read neighbouring voxels (smooth, grab, pinch): per group
// of dabs, every new value is computed from the volume as the previous group
// left it, then written. Planned by Brush.cpp (planGroups).
#include "BrushKernel.h"

#include "lvdif/Error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

namespace lvdif
{
namespace
{
// Pinch's pull at q (the base dab's frame): q minus the nearest point of the
// dab's centre (line), without its component along the stroke direction.
void pinchOffset(const Dab& d, const double q[3], double r[3])
{
  double c[3] = { d.center[0], d.center[1], d.center[2] };
  double dir[3] = { d.vec[0], d.vec[1], d.vec[2] };
  if (d.shape == BrushShape::Capsule)
  {
    const double ba[3] = { d.end[0] - d.center[0], d.end[1] - d.center[1], d.end[2] - d.center[2] };
    const double bb = ba[0] * ba[0] + ba[1] * ba[1] + ba[2] * ba[2];
    double t = bb > 0 ? ((q[0] - c[0]) * ba[0] + (q[1] - c[1]) * ba[1] + (q[2] - c[2]) * ba[2]) / bb : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    for (int a = 0; a < 3; ++a)
      c[a] += t * ba[a];
    if (dir[0] == 0 && dir[1] == 0 && dir[2] == 0)
      dir[0] = ba[0], dir[1] = ba[1], dir[2] = ba[2];
  }
  for (int a = 0; a < 3; ++a)
    r[a] = q[a] - c[a];
  const double dd = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
  if (dd > 0)
  {
    const double k = (r[0] * dir[0] + r[1] * dir[1] + r[2] * dir[2]) / dd;
    for (int a = 0; a < 3; ++a)
      r[a] -= k * dir[a];
  }
}

} // namespace

namespace detail::edit
{
// Smooth, Grab and Pinch: per group, every new value is computed from the
// volume as the previous group left it, then written.
EditResult applyGather(
  DictionaryVolume& volume, const detail::edit::DabPlan& plan, ChunkWriteObserver* observer, const Interrupter* interrupter)
{
  const detail::edit::BrushContext& c = plan.ctx;
  const float* table = volume.sdfDictionary().table();
  const Index3& n = volume.dims();
  const bool grab = c.op == static_cast<int>(BrushOp::Grab);
  const bool pinch = c.op == static_cast<int>(BrushOp::Pinch);
  EditResult result;
  std::map<std::int64_t, VoxelBox> changedChunks; // and the box of each one's changed voxels
  const int g = c.groupSize;
  const int groups = static_cast<int>(plan.dabs.size()) / g;
  struct Change
  {
    std::int64_t x, y, z;
    Voxel v;
  };
  for (int gi = 0; gi < groups; ++gi)
  {
    if (interrupter && interrupter->wasInterrupted())
    {
      result.interrupted = true;
      break;
    }
    VoxelBox box;
    for (int k = gi * g; k < (gi + 1) * g; ++k)
      box = box.unite(plan.boxes[static_cast<std::size_t>(k)]);
    std::vector<std::vector<Change>> perSlice(static_cast<std::size_t>(box.hi[2] - box.lo[2] + 1));
    const std::int64_t nz = static_cast<std::int64_t>(perSlice.size());
#pragma omp parallel for schedule(dynamic, 1) if (nz > 4)
    for (std::int64_t iz = 0; iz < nz; ++iz)
    {
      const std::int64_t z = box.lo[2] + iz;
      std::vector<Change>& out = perSlice[static_cast<std::size_t>(iz)];
      for (std::int64_t y = box.lo[1]; y <= box.hi[1]; ++y)
        for (std::int64_t x = box.lo[0]; x <= box.hi[0]; ++x)
        {
          double s = 0, t = 0, disp[3] = { 0, 0, 0 };
          bool in = false;
          const Dab& base = plan.dabs[static_cast<std::size_t>(gi * g)];
          for (int k = gi * g; k < (gi + 1) * g; ++k)
          {
            const Dab& d = plan.dabs[static_cast<std::size_t>(k)];
            if (!plan.boxes[static_cast<std::size_t>(k)].contains(x, y, z))
              continue;
            double p[3] = { double(x), double(y), double(z) };
            detail::edit::reflectForMember(c, k - gi * g, p);
            const double sk = dabDistance(base, p[0], p[1], p[2], c.rounding);
            const double tk = dabRadialFraction(base, p[0], p[1], p[2]);
            if (!in || sk < s)
              s = sk;
            if (!in || tk < t)
              t = tk;
            in = true;
            if (grab && sk <= 0)
            {
              const double wk = c.strength * falloffCurve(c.falloff, tk);
              for (int a = 0; a < 3; ++a)
                disp[a] += wk * d.vec[a];
            }
            if (pinch && sk <= 0)
            {
              // in the base dab's frame, then reflected back (negation is exact,
              // so mirror images stay mirror images bit for bit)
              const double wk = (c.invert ? -1.0 : 1.0) * c.strength * falloffCurve(c.falloff, tk);
              double r[3];
              pinchOffset(base, p, r);
              double m[3] = { 1, 1, 1 };
              for (int i = 0; (1 << i) < c.groupSize; ++i)
                if (((k - gi * g) >> i) & 1)
                  m[c.mirrorAxis[i]] = -1;
              for (int a = 0; a < 3; ++a)
                disp[a] -= m[a] * wk * r[a]; // sampled at p - disp
            }
          }
          if (!in || s > 0)
            continue;
          const Voxel old = volume.get(x, y, z);
          const double d = table[old.sdf];
          double dn = d;
          if (grab || pinch)
          {
            if (disp[0] == 0 && disp[1] == 0 && disp[2] == 0)
              continue;
            dn = trilinear(volume, table, double(x) - disp[0], double(y) - disp[1], double(z) - disp[2]);
          }
          else
          {
            const double w = c.strength * falloffCurve(c.falloff, t);
            if (!(w > 0) || !(d > -c.band && d < c.band))
              continue;
            const std::int64_t nb[6][3] = { { x - 1, y, z }, { x + 1, y, z }, { x, y - 1, z }, { x, y + 1, z },
              { x, y, z - 1 }, { x, y, z + 1 } };
            double v6[6];
            for (int i = 0; i < 6; ++i)
            {
              const std::int64_t* q = nb[i];
              const bool inside = q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[0] < n[0] && q[1] < n[1] && q[2] < n[2];
              v6[i] = inside ? table[volume.get(q[0], q[1], q[2]).sdf] : d;
            }
            // summed by axis pairs, so a mirror image of the volume gives the mirror image bit for bit
            const double sum = (v6[0] + v6[1]) + (v6[2] + v6[3]) + (v6[4] + v6[5]);
            dn = d + w * (sum / 6 - d);
          }
          Voxel v = old;
          v.sdf = volume.encode(static_cast<float>(dn));
          if (v != old)
            out.push_back(Change{ x, y, z, v });
        }
    }
    std::set<std::int64_t> touched;
    for (const auto& slice : perSlice)
      for (const Change& ch : slice)
      {
        const std::int64_t id = volume.chunkOf(ch.x, ch.y, ch.z);
        if (touched.insert(id).second && observer)
          observer->beforeChunkWrite(volume, id);
        volume.set(ch.x, ch.y, ch.z, ch.v);
        ++result.changedVoxels;
        result.changedBox.include(ch.x, ch.y, ch.z);
        changedChunks[id].include(ch.x, ch.y, ch.z);
      }
    for (std::int64_t id : touched)
      if (!volume.isUniform(id))
        volume.tryCollapseChunk(id);
  }
  for (const auto& c : changedChunks)
  {
    result.changedChunks.push_back(c.first);
    result.changedChunkBoxes.push_back(c.second);
  }
  return result;
}
} // namespace detail::edit
} // namespace lvdif
