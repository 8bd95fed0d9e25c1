// Independent oracles for the mesh-to-SDF tests: brute-force distance by
// projection on the plane plus the three edge segments (a different method
// from the Voronoi-region routine under test), exact winding numbers by the
// sum of solid angles in long double, and the test meshes.
#pragma once

#include "lvdif/TriangleMesh.h"

#include <cmath>
#include <random>

namespace oracle
{

using R = long double;
struct P
{
  R x, y, z;
};
inline P sub(P a, P b) { return { a.x - b.x, a.y - b.y, a.z - b.z }; }
inline R dot(P a, P b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline P cross(P a, P b) { return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x }; }
inline P pt(const lvdif::Vec3f& v) { return { v[0], v[1], v[2] }; }

inline R segmentDist2(P p, P a, P b)
{
  const P ab = sub(b, a), ap = sub(p, a);
  R t = dot(ap, ab) / dot(ab, ab);
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const P q{ a.x + t * ab.x - p.x, a.y + t * ab.y - p.y, a.z + t * ab.z - p.z };
  return dot(q, q);
}

/// Squared distance from p to triangle abc: the plane projection if it falls
/// inside (all three edge tests agree), else the nearest edge.
inline R triangleDist2(P p, P a, P b, P c)
{
  const P n = cross(sub(b, a), sub(c, a));
  const R nn = dot(n, n);
  const R s = dot(sub(p, a), n) / nn;
  const P q{ p.x - s * n.x, p.y - s * n.y, p.z - s * n.z };
  const R e0 = dot(cross(sub(b, a), sub(q, a)), n), e1 = dot(cross(sub(c, b), sub(q, b)), n),
          e2 = dot(cross(sub(a, c), sub(q, c)), n);
  if (e0 >= 0 && e1 >= 0 && e2 >= 0)
  {
    return s * s * nn;
  }
  return std::min(segmentDist2(p, a, b), std::min(segmentDist2(p, b, c), segmentDist2(p, c, a)));
}

inline bool degenerate(const lvdif::TriangleMesh& m, const std::array<std::uint32_t, 3>& t)
{
  const P n = cross(sub(pt(m.points[t[1]]), pt(m.points[t[0]])), sub(pt(m.points[t[2]]), pt(m.points[t[0]])));
  return dot(n, n) == 0;
}

inline double distance(const lvdif::TriangleMesh& m, P p)
{
  R best = 1e300L;
  for (const auto& t : m.triangles)
  {
    if (degenerate(m, t)) continue;
    best = std::min(best, triangleDist2(p, pt(m.points[t[0]]), pt(m.points[t[1]]), pt(m.points[t[2]])));
  }
  return static_cast<double>(std::sqrt(best));
}

/// Generalized winding number: sum of signed solid angles (Van Oosterom &
/// Strackee 1983) over 4 pi, in long double.
inline double winding(const lvdif::TriangleMesh& m, P p)
{
  R sum = 0;
  for (const auto& t : m.triangles)
  {
    const P a = sub(pt(m.points[t[0]]), p), b = sub(pt(m.points[t[1]]), p), c = sub(pt(m.points[t[2]]), p);
    const R la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    const R num = dot(a, cross(b, c));
    const R den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    sum += 2 * std::atan2(num, den);
  }
  return static_cast<double>(sum / (4 * 3.14159265358979323846264338327950288L));
}

/// a and b in one mesh (b's indices shifted past a's points).
inline lvdif::TriangleMesh merge(const lvdif::TriangleMesh& a, const lvdif::TriangleMesh& b)
{
  lvdif::TriangleMesh m = a;
  const std::uint32_t off = static_cast<std::uint32_t>(a.points.size());
  m.points.insert(m.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.triangles) m.triangles.push_back({ t[0] + off, t[1] + off, t[2] + off });
  return m;
}

inline lvdif::TriangleMesh randomSoup(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1), s(-0.4f, 0.4f);
  lvdif::TriangleMesh m;
  for (int i = 0; i < n; ++i)
  {
    const float cx = u(rng), cy = u(rng), cz = u(rng);
    for (int k = 0; k < 3; ++k)
    {
      m.points.push_back({ cx + s(rng), cy + s(rng), cz + s(rng) });
    }
    m.triangles.push_back({ std::uint32_t(3 * i), std::uint32_t(3 * i + 1), std::uint32_t(3 * i + 2) });
  }
  return m;
}

} // namespace oracle
