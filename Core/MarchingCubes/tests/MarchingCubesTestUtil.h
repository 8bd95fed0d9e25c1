// Independent checks on merged marching cubes meshes: area, enclosed volume
// (divergence theorem in double), edge manifoldness and a canonical triangle
// set for comparing two extractions.
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace mctest
{

struct Topology
{
  std::size_t boundaryEdges = 0;    // undirected edges used once
  std::size_t nonManifoldEdges = 0; // used more than twice
  std::size_t misorientedEdges = 0; // a directed edge used twice (neighbours disagree)
  long euler = 0;                   // V - E + F over referenced points
};

inline Topology topology(const lvdif::TriangleMesh& m)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::vector<char> used(m.points.size(), 0);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
    {
      directed[{ t[k], t[(k + 1) % 3] }]++;
      used[t[k]] = 1;
    }
  Topology r;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> undirected;
  for (const auto& d : directed)
  {
    if (d.second > 1) r.misorientedEdges++;
    undirected[{ std::min(d.first.first, d.first.second), std::max(d.first.first, d.first.second) }] += d.second;
  }
  for (const auto& u : undirected)
  {
    if (u.second == 1) r.boundaryEdges++;
    if (u.second > 2) r.nonManifoldEdges++;
  }
  long v = 0;
  for (char c : used) v += c;
  r.euler = v - static_cast<long>(undirected.size()) + static_cast<long>(m.triangles.size());
  return r;
}

inline double area(const lvdif::TriangleMesh& m)
{
  double a = 0;
  for (const auto& t : m.triangles)
  {
    const auto &p = m.points[t[0]], &q = m.points[t[1]], &r = m.points[t[2]];
    const double u[3] = { double(q[0]) - p[0], double(q[1]) - p[1], double(q[2]) - p[2] };
    const double w[3] = { double(r[0]) - p[0], double(r[1]) - p[1], double(r[2]) - p[2] };
    const double c[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
    a += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  return a;
}

/// Signed enclosed volume; positive for a closed surface with outward, counter-clockwise triangles.
inline double signedVolume(const lvdif::TriangleMesh& m)
{
  double v = 0;
  for (const auto& t : m.triangles)
  {
    const auto &p = m.points[t[0]], &q = m.points[t[1]], &r = m.points[t[2]];
    v += (double(p[0]) * (double(q[1]) * r[2] - double(q[2]) * r[1]) -
           double(p[1]) * (double(q[0]) * r[2] - double(q[2]) * r[0]) +
           double(p[2]) * (double(q[0]) * r[1] - double(q[1]) * r[0])) /
      6.0;
  }
  return v;
}

using TriKey = std::array<float, 9>;

/// Triangles as coordinate triples, rotated to start at the smallest point (orientation kept), sorted.
inline std::vector<TriKey> triangleSet(const lvdif::TriangleMesh& m)
{
  std::vector<TriKey> s;
  s.reserve(m.triangles.size());
  for (const auto& t : m.triangles)
  {
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (m.points[t[k]] < m.points[t[first]]) first = k;
    TriKey key;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) key[3 * k + a] = m.points[t[(first + k) % 3]][a];
    s.push_back(key);
  }
  std::sort(s.begin(), s.end());
  return s;
}

} // namespace mctest
