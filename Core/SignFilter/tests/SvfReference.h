// A deliberately plain reference of the sign voxel filters for the tests:
// plane by plane, explicit coordinates, each plane iterated on its own until
// it stops changing (the library sweeps the whole volume and tracks active
// planes instead). It encodes the documented rules (docs/SVF.md), not the
// library's code.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace svfref
{

struct Grid
{
  std::int64_t n[3];
  std::vector<float> v;
  std::int64_t index(std::int64_t x, std::int64_t y, std::int64_t z) const { return x + n[0] * (y + n[1] * z); }
};

inline int sgn(float x)
{
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}

struct Result
{
  std::array<std::int64_t, 4> flips{ 0, 0, 0, 0 };
  std::array<int, 4> iterations{ 0, 0, 0, 0 };
};

/// filters: bit mask as lvdif::SvfBits; bsign: +1 (Outside) or 0 (Free).
inline Result run(Grid& g, float t, int axis, unsigned filters, int cap, int bsign)
{
  Result res;
  const int ua = axis == 0 ? 1 : 0, va = axis == 2 ? 1 : 2;
  // voxel at (u, v, a) in the axis frame
  auto id = [&](std::int64_t u, std::int64_t v, std::int64_t a) {
    std::int64_t c[3];
    c[ua] = u;
    c[va] = v;
    c[axis] = a;
    return g.index(c[0], c[1], c[2]);
  };
  const std::int64_t nu = g.n[ua], nv = g.n[va], na = g.n[axis];
  auto inPlane = [&](std::int64_t u, std::int64_t v) { return u >= 0 && v >= 0 && u < nu && v < nv; };
  auto countDiff = [&](const std::vector<float>& before) {
    std::int64_t c = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
      c += (before[i] < 0) != (g.v[i] < 0) ? 1 : 0;
    return c;
  };

  if (filters & 1u)
  {
    const std::vector<float> before = g.v;
    for (std::int64_t v = 0; v < nv; ++v)
      for (std::int64_t u = 0; u < nu; ++u)
        for (std::int64_t a = 0; a < na; ++a)
        {
          const int prev = a == 0 ? bsign : sgn(g.v[id(u, v, a - 1)]);
          float& c = g.v[id(u, v, a)];
          if (std::fabs(c) > t && prev == -sgn(c))
            c = -c;
        }
    res.flips[0] = countDiff(before);
    res.iterations[0] = 1;
  }
  for (int filter = 2; filter <= 3; ++filter)
  {
    if (!(filters & (1u << (filter - 1))))
      continue;
    const std::vector<float> before = g.v;
    int maxIt = 0;
    for (std::int64_t a = 0; a < na; ++a)
    {
      int it = 0;
      bool changed = true;
      while (changed && it < cap)
      {
        changed = false;
        ++it;
        const int colours = filter == 2 ? 4 : 2;
        for (int col = 0; col < colours; ++col)
          for (std::int64_t v = 0; v < nv; ++v)
            for (std::int64_t u = 0; u < nu; ++u)
            {
              const int c0 = filter == 2 ? int((u % 2) + 2 * (v % 2)) : int((u + v) % 2);
              if (c0 != col)
                continue;
              float& c = g.v[id(u, v, a)];
              if (!(std::fabs(c) > t))
                continue;
              const int sc = sgn(c);
              bool flip = false;
              if (filter == 2)
              {
                int sum = sc;
                bool flow = false;
                for (int dv = -1; dv <= 1; ++dv)
                  for (int du = -1; du <= 1; ++du)
                  {
                    if (!du && !dv)
                      continue;
                    if (!inPlane(u + du, v + dv))
                    {
                      sum += bsign;
                      continue;
                    }
                    const float n = g.v[id(u + du, v + dv, a)];
                    sum += sgn(n);
                    flow = flow || (sgn(n) == -sc && std::fabs(n) > std::fabs(c));
                  }
                flip = flow && sum * sc < 0;
              }
              else
              {
                const std::int64_t du[4] = { 1, -1, 0, 0 }, dv[4] = { 0, 0, 1, -1 };
                flip = true;
                for (int q = 0; q < 4; ++q)
                {
                  const int s = inPlane(u + du[q], v + dv[q]) ? sgn(g.v[id(u + du[q], v + dv[q], a)]) : bsign;
                  flip = flip && s == -sc;
                }
              }
              if (flip)
              {
                c = -c;
                changed = true;
              }
            }
      }
      maxIt = it > maxIt ? it : maxIt;
    }
    res.flips[filter - 1] = countDiff(before);
    res.iterations[filter - 1] = maxIt;
  }
  if (filters & 8u)
  {
    const std::vector<float> in = g.v;
    for (std::int64_t z = 0; z < g.n[2]; ++z)
      for (std::int64_t y = 0; y < g.n[1]; ++y)
        for (std::int64_t x = 0; x < g.n[0]; ++x)
        {
          const std::int64_t c3[3] = { x, y, z };
          const int sc = sgn(in[g.index(x, y, z)]);
          if (sc == 0)
            continue;
          int opposite = 0;
          for (int ax = 0; ax < 3; ++ax)
            for (int d = -1; d <= 1; d += 2)
            {
              std::int64_t q[3] = { c3[0], c3[1], c3[2] };
              q[ax] += d;
              const bool inside = q[ax] >= 0 && q[ax] < g.n[ax];
              const int s = inside ? sgn(in[g.index(q[0], q[1], q[2])]) : bsign;
              opposite += s == -sc ? 1 : 0;
            }
          if (opposite >= 4)
          {
            g.v[g.index(x, y, z)] = -in[g.index(x, y, z)];
            ++res.flips[3];
          }
        }
    res.iterations[3] = 1;
  }
  return res;
}

} // namespace svfref
