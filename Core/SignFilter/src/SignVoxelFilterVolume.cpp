// Sign voxel filters on a DictionaryVolume, streamed plane slab by plane slab
// along the filter axis. Why this equals the dense filter on the whole grid:
//  * SVF1 scans rows along the axis; its only state is the sign of the last
//    filtered voxel of each row, carried from slab to slab (entry signs).
//  * SVF2/SVF3 read and write one plane only (per-plane convergence), so a
//    slab of whole planes gives each plane exactly its dense result.
//  * SVF4 is one Jacobi pass over the SVF3 result with 6 neighbours: a plane
//    needs the SVF3 result of the planes on each side, kept unflipped in the
//    buffer (the last two planes of a slab move to the front of the next).
// The slab buffer holds the planes in the axis frame (u fastest, the axis
// slowest); the SVF2/SVF3 rules and colour classes depend on (u, v) only, so
// the dense filter with axis z on that buffer is the same function.
#include "SignVoxelFilterImpl.h"
#include "SignVoxelFilterRules.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "lvdif/ParallelFailure.h"
#include "lvdif/SignVoxelFilter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <vector>

namespace lvdif
{

namespace
{
using detail::svf::signOf;

/// The volume seen from the filter axis.
struct Frame
{
  int a = 0, u = 1, v = 2; // volume axes of the axis and the in-plane u, v
  std::int64_t nU = 0, nV = 0, nA = 0, nUV = 0;
};

Frame frameOf(const DictionaryVolume& vol, int axis)
{
  Frame f;
  f.a = axis;
  f.u = detail::svf::axisU(axis);
  f.v = detail::svf::axisV(axis);
  f.nU = vol.dims()[f.u];
  f.nV = vol.dims()[f.v];
  f.nA = vol.dims()[f.a];
  f.nUV = f.nU * f.nV;
  return f;
}

VoxelBox planeBox(const DictionaryVolume& vol, const Frame& f, std::int64_t p0, std::int64_t p1)
{
  VoxelBox box = vol.bounds();
  box.lo[f.a] = p0;
  box.hi[f.a] = p1;
  return box;
}

/// Calls fn(x, y, z, offset in `out`) for every voxel of chunk `id` in the
/// planes [p0, p1], where plane p0 sits at out + 0.
template <typename Fn>
void forChunkVoxels(const DictionaryVolume& vol, const Frame& f, std::int64_t id, const VoxelBox& box, Fn&& fn)
{
  const VoxelBox b = vol.chunkBox(id).intersect(box);
  Index3 stride{ 0, 0, 0 };
  stride[f.u] = 1;
  stride[f.v] = f.nU;
  stride[f.a] = f.nUV;
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
    {
      std::int64_t o = (z - (f.a == 2 ? box.lo[2] : 0)) * stride[2] + (y - (f.a == 1 ? box.lo[1] : 0)) * stride[1] +
        (b.lo[0] - (f.a == 0 ? box.lo[0] : 0)) * stride[0];
      for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x, o += stride[0])
      {
        fn(x, y, z, o);
      }
    }
}

/// Decodes the planes [p0, p1] into out (plane p at out + (p - p0) * nUV).
void decodePlanes(const DictionaryVolume& vol, const Frame& f, std::int64_t p0, std::int64_t p1, float* out)
{
  const VoxelBox box = planeBox(vol, f, p0, p1);
  const std::vector<std::int64_t> ids = vol.chunksInBox(box);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(ids.size()); ++i)
  {
    const std::int64_t id = ids[static_cast<std::size_t>(i)];
    const Voxel* d = vol.chunkData(id);
    if (!d)
    {
      const float value = vol.decode(vol.uniformValue(id).sdf);
      forChunkVoxels(vol, f, id, box, [&](std::int64_t, std::int64_t, std::int64_t, std::int64_t o) { out[o] = value; });
    }
    else
    {
      forChunkVoxels(vol, f, id, box, [&](std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t o) {
        out[o] = vol.decode(d[vol.localIndex(x, y, z)].sdf);
      });
    }
  }
}

/// SVF1 over one plane (the next along the axis): returns the flips.
std::int64_t svf1Plane(float* plane, std::int64_t nUV, std::vector<std::int8_t>& entry, float threshold)
{
  std::int64_t flips = 0;
#pragma omp parallel for schedule(static) reduction(+ : flips)
  for (std::int64_t r = 0; r < nUV; ++r)
  {
    float c = plane[r];
    if (detail::svf::svf1Flips(c, entry[static_cast<std::size_t>(r)], threshold))
    {
      c = -c;
      plane[r] = c;
      ++flips;
    }
    entry[static_cast<std::size_t>(r)] = static_cast<std::int8_t>(signOf(c));
  }
  return flips;
}

/// Bytes of decoded planes to hold at once: 128 MiB, less under a low memory limit.
std::uint64_t slabBudget()
{
  return std::min<std::uint64_t>(128u << 20, memoryLimitBytes() / 8);
}

/// True when a uniform chunk keeps its stored value: every buffer value of its
/// voxels in `box` and of their 6 neighbours (inside the volume; the buffer
/// holds the planes box.lo[a] - 1 .. box.hi[a] + 1 where they exist) has the
/// stored sign, so SVF4 finds no opposite neighbour (a virtual one opposes a
/// negative chunk with the Outside boundary, at most 3 of them when every
/// dimension is 2 or more) and no sign changed. `at` points at plane box.lo[a].
bool quietChunk(const DictionaryVolume& vol, const Frame& f, std::int64_t id, const VoxelBox& box, const float* at,
  SdfKey zero, int bsign)
{
  if (!vol.isUniform(id))
  {
    return false;
  }
  const SdfKey key = vol.uniformValue(id).sdf;
  const int s = key < zero ? -1 : 1;
  if (key == zero || (s != bsign && bsign != 0 && (f.nU < 2 || f.nV < 2 || f.nA < 2)))
  {
    return false;
  }
  const VoxelBox b = vol.chunkBox(id).intersect(box);
  VoxelBox g = b; // grown by one voxel, clipped to the volume
  for (int k = 0; k < 3; ++k)
  {
    g.lo[k] = std::max<std::int64_t>(g.lo[k] - 1, 0);
    g.hi[k] = std::min<std::int64_t>(g.hi[k] + 1, vol.dims()[k] - 1);
  }
  Index3 lo{ g.lo[0], g.lo[1], g.lo[2] }, hi{ g.hi[0], g.hi[1], g.hi[2] };
  for (std::int64_t pa = lo[f.a]; pa <= hi[f.a]; ++pa)
    for (std::int64_t pv = lo[f.v]; pv <= hi[f.v]; ++pv)
    {
      const float* row = at + (pa - box.lo[f.a]) * f.nUV + pv * f.nU;
      for (std::int64_t pu = lo[f.u]; pu <= hi[f.u]; ++pu)
      {
        if (signOf(row[pu]) != s)
        {
          return false;
        }
      }
    }
  return true;
}

int boundarySign(const SignVoxelFilterParams& p)
{
  return p.boundary == SvfBoundary::Outside ? 1 : 0;
}

/// SVF2 then SVF3 on whole planes (the dense filter, axis z of the buffer).
SignVoxelFilterStats planar(float* planes, const Frame& f, std::int64_t n, const SignVoxelFilterParams& params)
{
  SignVoxelFilterParams q = params;
  q.axis = 2;
  q.filters = params.filters & (Svf2 | Svf3);
  FloatGridView view;
  view.data = planes;
  view.geometry.dims = { f.nU, f.nV, n };
  return signVoxelFilter(view, q, nullInterrupter());
}

/// The sign every value of [p, p + n) has, or 0 when they differ (or one has no sign).
int commonSign(const float* p, std::int64_t n)
{
  const int s = signOf(p[0]);
  bool same = s != 0;
#pragma omp parallel for schedule(static) reduction(&& : same)
  for (std::int64_t i = 1; i < n; ++i)
  {
    same = same && signOf(p[i]) == s;
  }
  return same ? s : 0;
}

/// True when SVF2/SVF3 cannot flip anything in a plane whose values all have
/// sign s: every neighbour then has sign s, except virtual ones, which oppose
/// only a negative plane with the Outside boundary; SVF2 needs an opposite
/// neighbour of larger magnitude (a virtual one has 0), SVF3 four opposite
/// neighbours (a voxel has at most 2 virtual ones when the plane is 2 x 2 or more).
bool planeIsQuiet(int s, const Frame& f, int bsign)
{
  return s != 0 && (s == bsign || bsign == 0 || (f.nU >= 2 && f.nV >= 2));
}

/// SVF2/SVF3 on the planes [0, n) of `planes`: on each run of planes that hold
/// more than one sign; a plane of one sign is left alone (it would take one
/// iteration that changes nothing).
SignVoxelFilterStats planarRuns(float* planes, const Frame& f, std::int64_t n, const SignVoxelFilterParams& params)
{
  SignVoxelFilterStats st;
  const int bsign = params.boundary == SvfBoundary::Outside ? 1 : 0;
  bool skipped = false;
  for (std::int64_t p = 0; p < n;)
  {
    if (planeIsQuiet(commonSign(planes + p * f.nUV, f.nUV), f, bsign))
    {
      skipped = true;
      ++p;
      continue;
    }
    std::int64_t q = p + 1;
    while (q < n && !planeIsQuiet(commonSign(planes + q * f.nUV, f.nUV), f, bsign))
    {
      ++q;
    }
    const SignVoxelFilterStats r = planar(planes + p * f.nUV, f, q - p, params);
    for (int k = 1; k <= 2; ++k)
    {
      st.flips[k] += r.flips[k];
      st.iterations[k] = std::max(st.iterations[k], r.iterations[k]);
      st.planesAtCap[k] += r.planesAtCap[k];
    }
    st.device = r.device;
    st.deviceMs += r.deviceMs;
    p = q;
  }
  for (int k = 1; k <= 2; ++k)
  {
    if (skipped && (params.filters & (1u << k)))
    {
      st.iterations[k] = std::max(st.iterations[k], 1); // the pass that found nothing
    }
  }
  return st;
}

void validate(const SignVoxelFilterParams& params)
{
  // the dense filter's rules (it sees only the SVF2/SVF3 slabs)
  checkSignVoxelFilterParams(params);
}

} // namespace

std::vector<std::int8_t> svf1BoundarySigns(const DictionaryVolume& volume, const SignVoxelFilterParams& params)
{
  validate(params);
  const Frame f = frameOf(volume, params.axis);
  return std::vector<std::int8_t>(static_cast<std::size_t>(f.nUV), static_cast<std::int8_t>(boundarySign(params)));
}

std::vector<std::int8_t> svf1Continue(const std::vector<std::int8_t>& entry, const std::vector<std::int8_t>& exits)
{
  require(exits.size() == 3 * entry.size(), "svf1Continue: the exit signs must hold 3 values per row");
  std::vector<std::int8_t> out(entry.size());
  const std::size_t n = entry.size();
  for (std::size_t r = 0; r < n; ++r)
  {
    require(entry[r] >= -1 && entry[r] <= 1, "svf1Continue: a sign must be -1, 0 or +1");
    out[r] = exits[static_cast<std::size_t>(entry[r] + 1) * n + r];
  }
  return out;
}

std::vector<std::int8_t> svf1ExitSigns(const DictionaryVolume& volume, const SignVoxelFilterParams& params,
  std::int64_t first, std::int64_t last, Interrupter& interrupter)
{
  validate(params);
  const Frame f = frameOf(volume, params.axis);
  require(first >= 0 && first <= last && last < f.nA, "svf1ExitSigns: the planes must lie in the volume");
  std::vector<std::int8_t> exits(static_cast<std::size_t>(3 * f.nUV));
  for (int k = 0; k < 3; ++k)
  {
    std::fill(exits.begin() + k * f.nUV, exits.begin() + (k + 1) * f.nUV, static_cast<std::int8_t>(k - 1));
  }
  const std::uint64_t planeBytes = static_cast<std::uint64_t>(f.nUV) * sizeof(float);
  const std::int64_t slab = std::clamp<std::int64_t>(static_cast<std::int64_t>(slabBudget() / planeBytes), 1, last - first + 1);
  requireMemory(slab * planeBytes, "sign voxel filter planes");
  std::vector<float> buf(static_cast<std::size_t>(slab * f.nUV));
  for (std::int64_t p0 = first; p0 <= last; p0 += slab)
  {
    interrupter.checkInterrupt();
    const std::int64_t p1 = std::min(last, p0 + slab - 1);
    decodePlanes(volume, f, p0, p1, buf.data());
    for (std::int64_t p = p0; p <= p1; ++p)
    {
      const float* plane = buf.data() + (p - p0) * f.nUV;
#pragma omp parallel for schedule(static)
      for (std::int64_t r = 0; r < f.nUV; ++r)
      {
        for (int k = 0; k < 3; ++k)
        {
          std::int8_t& s = exits[static_cast<std::size_t>(k * f.nUV + r)];
          const float c = plane[r];
          s = static_cast<std::int8_t>(signOf(detail::svf::svf1Flips(c, s, params.threshold) ? -c : c));
        }
      }
    }
  }
  return exits;
}

SignVoxelFilterStats signVoxelFilter(
  DictionaryVolume& volume, const SignVoxelFilterParams& params, Interrupter& interrupter)
{
  return signVoxelFilter(volume, params, SvfPlanes{}, interrupter);
}

SignVoxelFilterStats signVoxelFilter(
  DictionaryVolume& volume, const SignVoxelFilterParams& params, const SvfPlanes& planes, Interrupter& interrupter)
{
  validate(params);
  const Frame f = frameOf(volume, params.axis);
  const std::int64_t first = planes.first;
  const std::int64_t last = planes.last < planes.first ? f.nA - 1 : planes.last;
  require(first >= 0 && last < f.nA, "signVoxelFilter: the planes must lie in the volume");
  const bool svf1 = (params.filters & Svf1) != 0, svf23 = (params.filters & (Svf2 | Svf3)) != 0,
             svf4 = (params.filters & Svf4) != 0;
  std::vector<std::int8_t> entry = planes.entrySigns;
  if (entry.empty())
  {
    require(first == 0 || !svf1, "signVoxelFilter: a piece after the first plane needs its SVF1 entry signs");
    entry = svf1BoundarySigns(volume, params);
  }
  require(static_cast<std::int64_t>(entry.size()) == f.nUV, "signVoxelFilter: one entry sign per row of the plane");

  // the slab buffer: slots 0 and 1 hold the two planes before the slab
  // (SVF3 results, for SVF4), slots 2.. the slab
  const std::uint64_t planeBytes = static_cast<std::uint64_t>(f.nUV) * sizeof(float);
  const std::int64_t slab = params.volumeSlabPlanes > 0
    ? std::min(params.volumeSlabPlanes, f.nA)
    : std::clamp<std::int64_t>(static_cast<std::int64_t>(slabBudget() / planeBytes) - 2, 1, f.nA);
  requireMemory((slab + 2) * planeBytes, "sign voxel filter planes (" + std::to_string(slab + 2) + " planes of " +
      std::to_string(f.nU) + " x " + std::to_string(f.nV) + ")");
  std::vector<float> buf(static_cast<std::size_t>((slab + 2) * f.nUV));
  std::int64_t base = first - 2; // the plane in slot 0

  SignVoxelFilterStats st;
  st.device = Device::Cpu;
  auto addPlanar = [&](const SignVoxelFilterStats& s) {
    for (int k = 1; k <= 2; ++k)
    {
      st.flips[k] += s.flips[k];
      st.iterations[k] = std::max(st.iterations[k], s.iterations[k]);
      st.planesAtCap[k] += s.planesAtCap[k];
    }
    st.device = s.device;
    st.deviceMs += s.deviceMs;
  };

  interrupter.start("sign voxel filters");
  if (first > 0)
  {
    // the ghost plane before the piece: its SVF1 result is fixed by the signs
    // rows leave it with (a flip makes the voxel take the sign carried on)
    float* g = buf.data() + f.nUV;
    decodePlanes(volume, f, first - 1, first - 1, g);
    if (svf1)
    {
      for (std::int64_t r = 0; r < f.nUV; ++r)
      {
        const int e = entry[static_cast<std::size_t>(r)];
        g[r] = e != 0 && signOf(g[r]) == -e ? -g[r] : g[r];
      }
    }
    if (svf23)
    {
      planarRuns(g, f, 1, params);
    }
  }

  const SdfKey zero = volume.sdfDictionary().zeroKey();
  std::vector<std::uint8_t> written(static_cast<std::size_t>(volume.chunkCount()), 0);
  const std::int64_t lastA = std::min(last + 1, f.nA - 1); // SVF1-3 run through the ghost plane after
  std::int64_t next = first, due4 = first;
  std::int64_t collapsedThrough = first - 1;
  const detail::svf::AxisFrame af{ f.nU, f.nV, f.nA, 1, f.nU, f.nUV };
  const int bsign = boundarySign(params);
  while (next <= lastA)
  {
    interrupter.checkInterrupt();
    const std::int64_t b0 = next, b1 = std::min(lastA, b0 + slab - 1);
    // progress within the slab too, at its stages (a volume of one slab, the
    // usual case, reported nothing between 0 and 1), and a cancel honoured
    // between them, before the slab writes anything
    const double total = double(last - first + 1), done = double(std::min(b0, last + 1) - first),
                 own = double(std::max<std::int64_t>(0, std::min(b1, last) - b0 + 1));
    auto stage = [&](double within) {
      interrupter.progress((done + within * own) / total);
      interrupter.checkInterrupt();
    };
    float* at0 = buf.data() + (b0 - base) * f.nUV;
    decodePlanes(volume, f, b0, b1, at0);
    stage(0.1);
    if (svf1)
    {
      for (std::int64_t p = b0; p <= b1; ++p)
      {
        const std::int64_t flips = svf1Plane(buf.data() + (p - base) * f.nUV, f.nUV, entry, params.threshold);
        st.flips[0] += p <= last ? flips : 0;
      }
      st.iterations[0] = 1;
      stage(0.2);
    }
    if (svf23)
    {
      const std::int64_t own1 = std::min(b1, last);
      if (own1 >= b0)
      {
        addPlanar(planarRuns(at0, f, own1 - b0 + 1, params));
      }
      if (b1 > last)
      {
        planarRuns(buf.data() + (b1 - base) * f.nUV, f, 1, params); // the ghost plane after: not counted
      }
      stage(0.6);
    }

    // SVF4 (reading the unflipped SVF3 results) and the write-back of the planes whose neighbours are here
    const std::int64_t w0 = due4, w1 = std::min(last, b1 == f.nA - 1 ? b1 : b1 - 1);
    if (w1 >= w0)
    {
      const VoxelBox box = planeBox(volume, f, w0, w1);
      const std::vector<std::int64_t> ids = volume.chunksInBox(box);
      const float* slot0 = buf.data();
      std::int64_t flips4 = 0;
      ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : flips4)
      for (std::int64_t i = 0; i < static_cast<std::int64_t>(ids.size()); ++i)
      {
        const std::int64_t id = ids[static_cast<std::size_t>(i)];
        failure.run([&] {
          if (quietChunk(volume, f, id, box, slot0 + (w0 - base) * f.nUV, zero, bsign))
          {
            return;
          }
          bool wrote = false;
          const std::int64_t shift = (w0 - base) * f.nUV; // offset of plane w0 in the buffer
          forChunkVoxels(volume, f, id, box, [&](std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t o) {
            const std::int64_t idx = shift + o;
            float c = slot0[idx];
            if (svf4)
            {
              const Index3 p{ x, y, z };
              int s[6];
              detail::svf::gather6(slot0, idx, p[f.u], p[f.v], p[f.a], af, bsign, s);
              if (detail::svf::svf4Flips(c, s))
              {
                c = -c;
                ++flips4;
              }
            }
            Voxel old = volume.get(x, y, z);
            // the filters only negate, so a changed sign is a flipped voxel
            if ((c < 0.0f) != (old.sdf < zero))
            {
              old.sdf = volume.encode(c);
              volume.set(x, y, z, old);
              wrote = true;
            }
          });
          if (wrote)
          {
            written[static_cast<std::size_t>(id)] = 1;
          }
        });
      }
      failure.rethrow(); // the volume then holds part of the flips
      st.flips[3] += flips4;
      st.iterations[3] = svf4 ? 1 : 0;
      due4 = w1 + 1;
      // chunks whose planes are all written may have become uniform
      const std::int64_t edge = volume.chunkEdge();
      const std::int64_t through = w1 == last ? last : ((w1 + 1) / edge) * edge - 1;
      if (through > collapsedThrough)
      {
        const std::vector<std::int64_t> done = volume.chunksInBox(planeBox(volume, f, collapsedThrough + 1, through));
#pragma omp parallel for schedule(dynamic, 4)
        for (std::int64_t i = 0; i < static_cast<std::int64_t>(done.size()); ++i)
        {
          const std::int64_t id = done[static_cast<std::size_t>(i)];
          if (written[static_cast<std::size_t>(id)])
          {
            volume.tryCollapseChunk(id);
          }
        }
        collapsedThrough = through;
      }
    }

    // the last two planes go to slots 0 and 1 for the next slab's SVF4
    const std::int64_t keep = b1 - 1;
    std::memmove(buf.data(), buf.data() + (keep - base) * f.nUV, static_cast<std::size_t>(2 * f.nUV) * sizeof(float));
    base = keep;
    next = b1 + 1;
    interrupter.progress(double(std::min(next, last + 1) - first) / double(last - first + 1));
  }
  interrupter.end();
  return st;
}

} // namespace lvdif
