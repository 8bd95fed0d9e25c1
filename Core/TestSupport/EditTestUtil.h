// Helpers shared by the editing tests: whole-volume comparisons against a
// clone and brute-force oracles.
#pragma once

#include "lvdif/DictionaryVolume.h"

#include <cstdint>
#include <functional>
#include <set>

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

} // namespace edittest
