// Meshes damaged on purpose for the sign-quality study (docs/SIGN_QUALITY.md),
// and an independent brute-force winding number used as its reference.
// Every damage is seeded, so the study is reproducible bit for bit.
#pragma once

#include "lvdif/TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <cstdint>
#include <random>
#include <string>
#include <unordered_map>
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

/// Reverses whole patches: round regions (radius 4 % of the diagonal) around
/// random triangles are reversed until `fraction` of the faces are, the way a
/// broken export flips whole parts of a surface rather than single faces.
inline TriangleMesh flipPatches(const TriangleMesh& m, double fraction, unsigned seed = 5)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  const double r2 = std::pow(0.04 * diagonal(m), 2);
  std::vector<std::array<double, 3>> c(m.triangles.size());
  for (std::size_t t = 0; t < c.size(); ++t) c[t] = centroid(m, t);
  std::vector<char> flipped(m.triangles.size(), 0);
  std::size_t count = 0;
  const auto want = static_cast<std::size_t>(fraction * static_cast<double>(m.triangles.size()));
  for (int tries = 0; count < want && tries < 100000; ++tries)
  {
    const auto h = c[pick(rng)];
    for (std::size_t t = 0; t < c.size() && count < want; ++t)
    {
      const double d2 = (c[t][0] - h[0]) * (c[t][0] - h[0]) + (c[t][1] - h[1]) * (c[t][1] - h[1]) +
        (c[t][2] - h[2]) * (c[t][2] - h[2]);
      if (d2 <= r2 && !flipped[t]) flipped[t] = 1, ++count;
    }
  }
  TriangleMesh out = m;
  out.normals.clear();
  for (std::size_t t = 0; t < c.size(); ++t)
    if (flipped[t]) std::swap(out.triangles[t][1], out.triangles[t][2]);
  return out;
}

/// Appends a copy of a random fraction of the faces, every second copy
/// reversed: a reversed copy cancels its original (the chain has a one-face
/// hole there), a same-orientation copy doubles it.
inline TriangleMesh duplicateHalfReversed(const TriangleMesh& m, double fraction, unsigned seed = 6)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  TriangleMesh out = m;
  out.normals.clear();
  bool reverse = false;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (u(rng) < fraction)
    {
      auto f = m.triangles[t];
      if (reverse) std::swap(f[1], f[2]);
      reverse = !reverse;
      out.triangles.push_back(f);
    }
  return out;
}

/// Non-manifold fins: on `count` random faces, a thin triangle standing on
/// the face's first edge (a third face on that edge), pointing along the
/// face normal by `heightFrac` of the diagonal, as stray sheets in CAD
/// exports. Each fin adds two boundary edges and one non-manifold edge.
inline TriangleMesh addFins(const TriangleMesh& m, int count, double heightFrac = 0.01, unsigned seed = 7)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  const double h = heightFrac * diagonal(m);
  TriangleMesh out = m;
  out.normals.clear();
  std::vector<char> used(m.triangles.size(), 0); // one fin per face (two would be duplicates)
  for (int i = 0; i < count; ++i)
  {
    std::size_t f = pick(rng);
    while (used[f]) f = pick(rng);
    used[f] = 1;
    const auto t = m.triangles[f];
    const auto& a = m.points[t[0]];
    const auto& b = m.points[t[1]];
    const auto& c = m.points[t[2]];
    double n[3] = { double(b[1] - a[1]) * (c[2] - a[2]) - double(b[2] - a[2]) * (c[1] - a[1]),
      double(b[2] - a[2]) * (c[0] - a[0]) - double(b[0] - a[0]) * (c[2] - a[2]),
      double(b[0] - a[0]) * (c[1] - a[1]) - double(b[1] - a[1]) * (c[0] - a[0]) };
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) continue;
    std::array<float, 3> tip;
    for (int k = 0; k < 3; ++k) tip[k] = static_cast<float>(0.5 * (double(a[k]) + b[k]) + h * n[k] / len);
    out.points.push_back(tip);
    out.triangles.push_back({ t[0], t[1], static_cast<std::uint32_t>(out.points.size() - 1) });
  }
  return out;
}

/// `levels` rounds of midpoint subdivision (each triangle into 4, edge
/// midpoints shared, so a closed mesh stays closed): large meshes with the
/// shape of a real one (the armadillo's 52k triangles: 832k after 2 levels).
inline TriangleMesh subdivide(const TriangleMesh& m, int levels)
{
  TriangleMesh cur = m;
  cur.normals.clear();
  for (int l = 0; l < levels; ++l)
  {
    TriangleMesh next;
    next.points = cur.points;
    std::unordered_map<std::uint64_t, std::uint32_t> mid;
    mid.reserve(cur.triangles.size() * 2);
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const auto& p = cur.points[a];
      const auto& q = cur.points[b];
      next.points.push_back({ 0.5f * (p[0] + q[0]), 0.5f * (p[1] + q[1]), 0.5f * (p[2] + q[2]) });
      const auto id = static_cast<std::uint32_t>(next.points.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    next.triangles.reserve(4 * cur.triangles.size());
    for (const auto& t : cur.triangles)
    {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.triangles.push_back({ t[0], ab, ca });
      next.triangles.push_back({ ab, t[1], bc });
      next.triangles.push_back({ ca, bc, t[2] });
      next.triangles.push_back({ ab, bc, ca });
    }
    cur = std::move(next);
  }
  return cur;
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

/// The damaged variant named by `damage` (seeded, reproducible): "" (none),
/// flipNN (NN % of the faces reversed, scattered), patchNN (NN % reversed in
/// patches), dupNN (NN % duplicated), duprevNN (NN % duplicated, every second
/// copy reversed), holes (8 round holes), holesNN (NN round holes), finsNN
/// (NN non-manifold fins), pair (two intersecting copies), subN (N levels of
/// midpoint subdivision: not damage, a larger mesh of the same shape).
inline TriangleMesh damaged(const TriangleMesh& m, const std::string& damage)
{
  auto num = [&](std::size_t prefix) { return std::atof(damage.c_str() + prefix); };
  if (damage.empty()) return m;
  if (damage.rfind("flip", 0) == 0) return flipFaces(m, num(4) / 100.0);
  if (damage.rfind("patch", 0) == 0) return flipPatches(m, num(5) / 100.0);
  if (damage.rfind("duprev", 0) == 0) return duplicateHalfReversed(m, num(6) / 100.0);
  if (damage.rfind("dup", 0) == 0) return duplicateFaces(m, num(3) / 100.0);
  if (damage == "holes") return punchHoles(m, 8, 0.03);
  if (damage.rfind("holes", 0) == 0) return punchHoles(m, static_cast<int>(num(5)), 0.015);
  if (damage.rfind("fins", 0) == 0) return addFins(m, static_cast<int>(num(4)));
  if (damage == "pair") return intersectingPair(m);
  if (damage.rfind("sub", 0) == 0) return subdivide(m, static_cast<int>(num(3)));
  throw std::invalid_argument("unknown damage '" + damage + "' (flipNN, patchNN, dupNN, duprevNN, holes[NN], finsNN, pair, subN)");
}

/// A benchmark's mesh argument "DAMAGE:...:PATH": the path and the damages in
/// the order written (applied from the right: patch10:sub2:m = patches on the
/// subdivided mesh). A colon inside the path (after its first '/') is kept.
struct DamagedPath
{
  std::string path;
  std::vector<std::string> damages;
  /// "patch10:sub2" ("" for none)
  std::string label() const
  {
    std::string s;
    for (const std::string& d : damages) s += (s.empty() ? "" : ":") + d;
    return s;
  }
  /// The mesh read from `path` (loader: a function of the path) with the damages applied.
  template <typename Load>
  TriangleMesh load(Load&& loader) const
  {
    TriangleMesh mesh = loader(path);
    for (auto d = damages.rbegin(); d != damages.rend(); ++d) mesh = damaged(mesh, *d);
    return mesh;
  }
};

inline DamagedPath parseDamagedPath(std::string path)
{
  DamagedPath r;
  for (auto colon = path.find(':'); colon != std::string::npos && path.find('/') > colon; colon = path.find(':'))
  {
    r.damages.push_back(path.substr(0, colon));
    path = path.substr(colon + 1);
  }
  r.path = path;
  return r;
}

} // namespace signquality
