// A second triangulation of lvdif's marching cubes loops, built independently
// of the table's own triangulation: each loop (recovered from the table's
// directed boundary) is fanned from its vertex with the LARGEST edge id. Used
// to test MarchingCubesOptions::triangleTable (it differs from lvdif's table in
// many cases, and is a valid table: same loops, same orientation).
#pragma once

#include "lvdif/MarchingCubesTables.h"

#include <algorithm>
#include <map>
#include <vector>

namespace mctest
{

/// The directed loops of case cs (boundary edges of its triangles, i.e. those whose reverse is absent).
inline std::vector<std::vector<int>> caseLoops(const lvdif::MarchingCubesTables& t, int cs)
{
  std::map<std::pair<int, int>, int> directed;
  for (int k = 0; k < 3 * t.triangleCount[cs]; k += 3)
    for (int i = 0; i < 3; ++i) ++directed[{ t.triangles[cs][k + i], t.triangles[cs][k + (i + 1) % 3] }];
  int next[12];
  for (int& n : next) n = -1;
  for (const auto& d : directed)
    if (!directed.count({ d.first.second, d.first.first })) next[d.first.first] = d.first.second;
  std::vector<std::vector<int>> loops;
  bool seen[12] = {};
  for (int e = 0; e < 12; ++e)
  {
    if (next[e] < 0 || seen[e]) continue;
    std::vector<int> loop;
    for (int x = e; !seen[x]; x = next[x])
    {
      seen[x] = true;
      loop.push_back(x);
    }
    loops.push_back(loop);
  }
  return loops;
}

inline lvdif::MarchingCubesTriangleTable fanFromLargestEdge()
{
  const lvdif::MarchingCubesTables& t = lvdif::marchingCubesTables();
  lvdif::MarchingCubesTriangleTable r;
  for (auto& row : r) row.fill(-1);
  for (int cs = 0; cs < 256; ++cs)
  {
    int k = 0;
    for (std::vector<int> loop : caseLoops(t, cs))
    {
      std::rotate(loop.begin(), std::max_element(loop.begin(), loop.end()), loop.end());
      for (std::size_t i = 1; i + 1 < loop.size(); ++i)
      {
        r[cs][k++] = static_cast<std::int8_t>(loop[0]);
        r[cs][k++] = static_cast<std::int8_t>(loop[i]);
        r[cs][k++] = static_cast<std::int8_t>(loop[i + 1]);
      }
    }
  }
  return r;
}

} // namespace mctest
