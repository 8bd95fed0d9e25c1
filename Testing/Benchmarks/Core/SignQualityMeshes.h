// Meshes damaged on purpose for the sign-quality study (docs/SIGN_QUALITY.md),
// and an independent brute-force winding number used as its reference.
// Every damage is seeded, so the study is reproducible bit for bit.
#pragma once

#include "lvdif/TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace signquality
{

using lvdif::TriangleMesh;

inline std::array<double, 3> centroid(const TriangleMesh& m, std::size_t t)
{
  std::array<double, 3> c{ 0, 0, 0 };
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a) c[a] += m.points[m.triangles[t][v]][a] / 3.0;
  return c;
}

inline double diagonal(const TriangleMesh& m)
{
  const auto b = m.bounds();
  double s = 0;
  for (int a = 0; a < 3; ++a) s += double(b[1][a] - b[0][a]) * double(b[1][a] - b[0][a]);
  return std::sqrt(s);
}

/// Removes every triangle whose centroid lies within radiusFrac * diagonal of
/// one of `count` centres picked on random triangles: round holes.
inline TriangleMesh punchHoles(const TriangleMesh& m, int count, double radiusFrac, unsigned seed = 1)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  std::vector<std::array<double, 3>> centres;
  for (int i = 0; i < count; ++i) centres.push_back(centroid(m, pick(rng)));
  const double r2 = std::pow(radiusFrac * diagonal(m), 2);
  TriangleMesh out;
  out.points = m.points;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    const auto c = centroid(m, t);
    bool keep = true;
    for (const auto& h : centres)
    {
      const double d2 = (c[0] - h[0]) * (c[0] - h[0]) + (c[1] - h[1]) * (c[1] - h[1]) + (c[2] - h[2]) * (c[2] - h[2]);
      keep = keep && d2 > r2;
    }
    if (keep) out.triangles.push_back(m.triangles[t]);
  }
  return out;
}

/// Reverses the orientation of a random fraction of the faces (scattered).
inline TriangleMesh flipFaces(const TriangleMesh& m, double fraction, unsigned seed = 2)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  TriangleMesh out = m;
  out.normals.clear();
  for (auto& t : out.triangles)
    if (u(rng) < fraction) std::swap(t[1], t[2]);
  return out;
}

/// Appends a copy of a random fraction of the faces (same vertices, same orientation).
inline TriangleMesh duplicateFaces(const TriangleMesh& m, double fraction, unsigned seed = 3)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  TriangleMesh out = m;
  out.normals.clear();
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (u(rng) < fraction) out.triangles.push_back(m.triangles[t]);
  return out;
}

/// The mesh plus a copy of itself shifted by (0.35, 0.2, 0.1) of its extent:
/// two closed meshes that intersect (the overlap has winding number 2).
inline TriangleMesh intersectingPair(const TriangleMesh& m)
{
  const auto b = m.bounds();
  const float shift[3] = { 0.35f * (b[1][0] - b[0][0]), 0.2f * (b[1][1] - b[0][1]), 0.1f * (b[1][2] - b[0][2]) };
  TriangleMesh out = m;
  out.normals.clear();
  const auto n = static_cast<std::uint32_t>(m.points.size());
  for (const auto& p : m.points) out.points.push_back({ p[0] + shift[0], p[1] + shift[1], p[2] + shift[2] });
  for (const auto& t : m.triangles) out.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  return out;
}

/// Generalized winding number at p by brute force: the sum over all triangles
/// of the signed solid angle (Van Oosterom & Strackee 1983) over 4 pi, in long
/// double. Written here, independently of Core/src, as the study's oracle.
inline long double bruteWinding(const TriangleMesh& m, const std::array<double, 3>& p)
{
  long double sum = 0;
  for (const auto& t : m.triangles)
  {
    long double v[3][3], len[3];
    for (int i = 0; i < 3; ++i)
    {
      for (int a = 0; a < 3; ++a) v[i][a] = static_cast<long double>(m.points[t[i]][a]) - p[a];
      len[i] = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    }
    auto dot = [](const long double* x, const long double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const long double det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
      v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) + v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
    const long double den = len[0] * len[1] * len[2] + dot(v[0], v[1]) * len[2] + dot(v[1], v[2]) * len[0] +
      dot(v[2], v[0]) * len[1];
    sum += 2 * std::atan2(det, den);
  }
  return sum / (4 * 3.14159265358979323846264338327950288L);
}

} // namespace signquality
