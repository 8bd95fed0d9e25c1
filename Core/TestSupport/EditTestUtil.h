// Helpers shared by the editing tests: whole-volume comparisons against a
// clone and brute-force oracles.
#pragma once

#include "lvdif/Brush.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Stroke.h"

#include <cstdint>
#include <functional>
#include <random>
#include <set>
#include <vector>

namespace edittest
{

inline lvdif::VolumeOptions options(std::int64_t n, int edge = 16, float band = 8.0f)
{
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = edge;
  o.bandWidth = band;
  return o;
}

/// Number of voxels whose 4 bytes differ.
inline std::int64_t countDifferences(const lvdif::DictionaryVolume& a, const lvdif::DictionaryVolume& b)
{
  std::int64_t n = 0;
  const auto& d = a.dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        if (a.get(x, y, z) != b.get(x, y, z))
          ++n;
  return n;
}

/// Ids of the chunks that hold at least one differing voxel.
inline std::set<std::int64_t> differingChunks(const lvdif::DictionaryVolume& a, const lvdif::DictionaryVolume& b)
{
  std::set<std::int64_t> ids;
  const auto& d = a.dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        if (a.get(x, y, z) != b.get(x, y, z))
          ids.insert(a.chunkOf(x, y, z));
  return ids;
}

inline void forEachVoxel(const lvdif::DictionaryVolume& v,
  const std::function<void(std::int64_t, std::int64_t, std::int64_t)>& fn)
{
  const auto& d = v.dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        fn(x, y, z);
}

/// The dabs of random edit number i: every seventh a dynamic stroke through four random
/// samples, the others one dab whose shape i picks; positions drawn from pos, radii from rad.
inline std::vector<lvdif::Dab> randomDabs(std::mt19937& rng, std::uniform_real_distribution<double>& pos,
  std::uniform_real_distribution<double>& rad, int i)
{
  std::vector<lvdif::Dab> dabs;
  if (i % 7 == 3)
  {
    lvdif::StrokeSettings st;
    st.kind = lvdif::BrushKind::Dynamic;
    st.radius = rad(rng) / 3 + 1;
    std::vector<lvdif::BrushSample> samples(4);
    for (auto& p : samples)
      p.position = { pos(rng), pos(rng), pos(rng) };
    return lvdif::strokeDabs(samples, st);
  }
  lvdif::Dab d;
  d.shape = static_cast<lvdif::BrushShape>(i % 3);
  d.center = { pos(rng), pos(rng), pos(rng) };
  d.end = { pos(rng), pos(rng), pos(rng) };
  d.radius = rad(rng);
  dabs.push_back(d);
  return dabs;
}

} // namespace edittest
