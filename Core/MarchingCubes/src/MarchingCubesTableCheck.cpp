// Validation of a caller's marching cubes triangle table against our loops
// (see marchingCubesTablesWith in MarchingCubesTables.h).
#include "lvdif/MarchingCubesTables.h"

#include "lvdif/Error.h"

#include <string>

namespace lvdif
{
namespace
{
[[noreturn]] void reject(int cs, const std::string& why)
{
  throw Error(ErrorCode::InvalidArgument,
    "marching cubes triangle table: case " + std::to_string(cs) + " " + why +
      " (it must triangulate the same contour loops as lvdif's own table; see MarchingCubesTables.h)");
}

/// Directed edge counts a->b of a case's triangles, and the loop of each cut edge (-1: not cut).
struct CaseShape
{
  int directed[12][12] = {};
  int loopOf[12];
  int loopSize[12] = {};
  int loops = 0;
};

/// Our case: loops are the connected components of its triangles' vertices
/// (each loop is triangulated on its own).
CaseShape ourShape(const MarchingCubesTables& t, int cs)
{
  CaseShape s;
  for (int& l : s.loopOf) l = -1;
  int parent[12];
  for (int e = 0; e < 12; ++e) parent[e] = e;
  auto find = [&](int e) {
    while (parent[e] != e) e = parent[e] = parent[parent[e]];
    return e;
  };
  bool used[12] = {};
  for (int k = 0; k < 3 * t.triangleCount[cs]; k += 3)
    for (int i = 0; i < 3; ++i)
    {
      const int a = t.triangles[cs][k + i], b = t.triangles[cs][k + (i + 1) % 3];
      ++s.directed[a][b];
      used[a] = true;
      parent[find(a)] = find(b);
    }
  int id[12];
  for (int& x : id) x = -1;
  for (int e = 0; e < 12; ++e)
  {
    if (!used[e]) continue;
    const int r = find(e);
    if (id[r] < 0) id[r] = s.loops++;
    s.loopOf[e] = id[r];
    ++s.loopSize[id[r]];
  }
  return s;
}
} // namespace

MarchingCubesTables marchingCubesTablesWith(const MarchingCubesTriangleTable& triangles)
{
  const MarchingCubesTables& ours = marchingCubesTables();
  MarchingCubesTables t = ours;
  for (int cs = 0; cs < 256; ++cs)
  {
    const auto& row = triangles[static_cast<std::size_t>(cs)];
    int n = 0;
    while (n < 16 && row[static_cast<std::size_t>(n)] >= 0) ++n;
    for (int k = n; k < 16; ++k)
      if (row[static_cast<std::size_t>(k)] != -1) reject(cs, "has an entry other than -1 after its last triangle");
    if (n % 3 != 0) reject(cs, "has " + std::to_string(n) + " edge ids, not a multiple of 3");
    if (n / 3 != ours.triangleCount[cs])
      reject(cs, "has " + std::to_string(n / 3) + " triangles instead of " + std::to_string(ours.triangleCount[cs]));
    const CaseShape s = ourShape(ours, cs);
    int directed[12][12] = {};
    int perLoop[12] = {};
    for (int k = 0; k < n; k += 3)
    {
      const int v[3] = { row[static_cast<std::size_t>(k)], row[static_cast<std::size_t>(k + 1)],
        row[static_cast<std::size_t>(k + 2)] };
      for (int x : v)
        if (x > 11 || s.loopOf[x] < 0) reject(cs, "uses edge " + std::to_string(x) + ", which this case does not cut");
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) reject(cs, "has a triangle with a repeated edge id");
      if (s.loopOf[v[0]] != s.loopOf[v[1]] || s.loopOf[v[0]] != s.loopOf[v[2]])
        reject(cs, "has a triangle joining two different contour loops");
      ++perLoop[s.loopOf[v[0]]];
      for (int i = 0; i < 3; ++i)
        if (++directed[v[i]][v[(i + 1) % 3]] > 1) reject(cs, "uses a directed edge twice (not a manifold triangulation)");
    }
    for (int l = 0; l < s.loops; ++l)
      if (perLoop[l] != s.loopSize[l] - 2)
        reject(cs, "triangulates a loop of " + std::to_string(s.loopSize[l]) + " vertices with " +
            std::to_string(perLoop[l]) + " triangles");
    // boundary: net flow a->b (1 on a loop segment, 0 on a diagonal) equals ours
    for (int a = 0; a < 12; ++a)
      for (int b = a + 1; b < 12; ++b)
        if (directed[a][b] - directed[b][a] != s.directed[a][b] - s.directed[b][a])
          reject(cs, "does not have the same directed loop segments (edges " + std::to_string(a) + ", " +
              std::to_string(b) + "): other loops or the opposite orientation");
    for (int k = 0; k < 16; ++k) t.triangles[cs][k] = row[static_cast<std::size_t>(k)];
  }
  return t;
}

MarchingCubesTriangleTable marchingCubesTriangleTable()
{
  const MarchingCubesTables& ours = marchingCubesTables();
  MarchingCubesTriangleTable r{};
  for (int cs = 0; cs < 256; ++cs)
    for (int k = 0; k < 16; ++k) r[static_cast<std::size_t>(cs)][static_cast<std::size_t>(k)] = ours.triangles[cs][k];
  return r;
}

} // namespace lvdif
