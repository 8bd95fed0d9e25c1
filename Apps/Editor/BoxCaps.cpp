#include "BoxCaps.h"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace BoxCaps
{
bool touchesBox(const lvdif::VoxelBox& cells, const lvdif::Index3& dims)
{
  if (cells.empty())
    return false;
  for (int a = 0; a < 3; ++a)
    if (cells.lo[a] == 0 || cells.hi[a] == dims[a] - 2)
      return true;
  return false;
}

namespace
{
struct CapPoint
{
  lvdif::Index3 lower{ 0, 0, 0 }; // the point, or the lower end of the face edge it lies on
  int axis = -1;        // the edge's axis, -1 for a voxel itself
  float t = 0;          // along the edge from `lower`
};
}

bool append(lvdif::ChunkMesh& m, const lvdif::DictionaryVolume& v, float iso)
{
  const lvdif::Index3& n = v.dims();
  if (!touchesBox(m.cells, n))
    return false;
  const auto& o = v.options();
  const auto& palette = v.colors().colors();
  // the arrays the mesh has; all of them when it is empty
  const bool fresh = m.points.empty() && m.triangles.empty();
  const bool withNormals = fresh || m.normals.size() == m.points.size();
  const bool withColors = fresh || (!m.colors.empty() && m.colors.size() == m.points.size());
  const bool withCells = fresh || (!m.cornerColors.empty() && m.cornerColors.size() == m.triangles.size() &&
                                    m.triangleCells.size() == m.triangles.size());
  const bool withEdgeIds = fresh || m.edgeIds.size() == m.points.size();
  const std::size_t trianglesBefore = m.triangles.size();

  auto addPoint = [&](const CapPoint& p, int faceAxis, int outward) {
    lvdif::Vec3f x;
    for (int a = 0; a < 3; ++a)
    {
      const double t = a == p.axis ? static_cast<double>(p.t) : 0.0;
      x[a] = static_cast<float>(o.origin[a] + o.spacing[a] * (static_cast<double>(p.lower[a]) + t));
    }
    m.points.push_back(x);
    if (withEdgeIds)
      m.edgeIds.push_back(std::numeric_limits<std::uint64_t>::max()); // on no cut edge of marching cubes
    if (withNormals)
    {
      lvdif::Vec3f nn{ 0.0f, 0.0f, 0.0f };
      nn[faceAxis] = static_cast<float>(outward);
      m.normals.push_back(nn);
    }
    if (withColors)
    {
      const lvdif::Rgba a = palette[v.get(p.lower[0], p.lower[1], p.lower[2]).color];
      lvdif::Rgba c = a;
      if (p.axis >= 0)
      {
        lvdif::Index3 q = p.lower;
        ++q[p.axis];
        const lvdif::Rgba b = palette[v.get(q[0], q[1], q[2]).color];
        auto mix = [&](std::uint8_t x0, std::uint8_t x1) {
          const float f = static_cast<float>(x0) + p.t * (static_cast<float>(x1) - static_cast<float>(x0)) + 0.5f;
          return static_cast<std::uint8_t>(f < 0 ? 0 : (f > 255 ? 255 : static_cast<int>(f)));
        };
        c = lvdif::Rgba{ mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b), mix(a.a, b.a) };
      }
      m.colors.push_back(c);
    }
    return static_cast<std::uint32_t>(m.points.size() - 1);
  };

  // one polygon of a face: `count` points, fanned by `fans`, on the boundary cell `cell`
  auto emit = [&](const CapPoint* poly, int count, const std::array<int, 3>* fans, int fanCount, int a, int outward,
                const lvdif::Index3& cell) {
    std::uint32_t ids[6];
    for (int k = 0; k < count; ++k)
      ids[k] = addPoint(poly[k], a, outward);
    std::array<lvdif::ColorKey, 8> keys{};
    if (withCells)
      for (int c = 0; c < 8; ++c)
        keys[c] = v.get(cell[0] + (c & 1), cell[1] + ((c >> 1) & 1), cell[2] + ((c >> 2) & 1)).color;
    for (int fi = 0; fi < fanCount; ++fi)
    {
      const std::array<int, 3>& f = fans[fi];
      // counter-clockwise seen from outside the box: as built seen from +a
      if (outward > 0)
        m.triangles.push_back({ ids[f[0]], ids[f[1]], ids[f[2]] });
      else
        m.triangles.push_back({ ids[f[0]], ids[f[2]], ids[f[1]] });
      if (withCells)
      {
        m.cornerColors.push_back(keys);
        m.triangleCells.push_back(cell[0] + n[0] * (cell[1] + n[1] * cell[2]));
      }
    }
  };

  for (int a = 0; a < 3; ++a)
  {
    const int u = (a + 1) % 3, w = (a + 2) % 3; // u x w = a
    for (int side = 0; side < 2; ++side)
    {
      if (side == 0 ? m.cells.lo[a] != 0 : m.cells.hi[a] != n[a] - 2)
        continue;
      const std::int64_t face = side == 0 ? 0 : n[a] - 1;   // the face's points along a
      const std::int64_t cellA = side == 0 ? 0 : n[a] - 2;  // the boundary cells along a
      const int outward = side == 0 ? -1 : 1;
      // the index (i, j) in the face's plane at `along` on axis a
      auto onFace = [&](std::int64_t along, std::int64_t i, std::int64_t j) {
        lvdif::Index3 p;
        p[a] = along;
        p[u] = i;
        p[w] = j;
        return p;
      };
      auto point = [&](std::int64_t i, std::int64_t j) { return onFace(face, i, j); };
      auto cellOf = [&](std::int64_t i, std::int64_t j) { return onFace(cellA, i, j); };
      // Squares wholly inside and of one colour are joined into rectangles
      // (a Full canvas's face is one quad per chunk, not two triangles per
      // voxel: 3.1 million triangles and 3 GB on a 512^3 canvas): runs along
      // u, and a run that repeats in the next row grows into it.
      struct Rect
      {
        std::int64_t i0, i1, j0, j1;
        lvdif::ColorKey key;
      };
      std::vector<Rect> open, next;
      auto flush = [&](const Rect& r) {
        const CapPoint quad[4] = { CapPoint{ point(r.i0, r.j0) }, CapPoint{ point(r.i1 + 1, r.j0) },
          CapPoint{ point(r.i1 + 1, r.j1 + 1) }, CapPoint{ point(r.i0, r.j1 + 1) } };
        const std::array<int, 3> fans[2] = { { 0, 1, 2 }, { 0, 2, 3 } };
        emit(quad, 4, fans, 2, a, outward, cellOf(r.i0, r.j0));
      };
      for (std::int64_t j = m.cells.lo[w]; j <= m.cells.hi[w]; ++j)
      {
        next.clear();
        auto endRun = [&](const Rect& run) {
          for (Rect& r : open)
            if (r.i0 == run.i0 && r.i1 == run.i1 && r.key == run.key && r.j1 == j - 1)
            {
              r.j1 = j; // grows into this row
              next.push_back(r);
              r.i0 = -1; // taken
              return;
            }
          next.push_back(run);
        };
        bool inRun = false;
        Rect run{};
        for (std::int64_t i = m.cells.lo[u]; i <= m.cells.hi[u]; ++i)
        {
          // the square's corners counter-clockwise seen from +a: (i,j) (i+1,j) (i+1,j+1) (i,j+1)
          static const int du[4] = { 0, 1, 1, 0 }, dw[4] = { 0, 0, 1, 1 };
          lvdif::Index3 corner[4];
          float value[4];
          bool in[4];
          lvdif::ColorKey key[4];
          int inside = 0;
          for (int k = 0; k < 4; ++k)
          {
            corner[k] = point(i + du[k], j + dw[k]);
            const lvdif::Voxel x = v.get(corner[k][0], corner[k][1], corner[k][2]);
            value[k] = v.decode(x.sdf);
            key[k] = x.color;
            in[k] = !(value[k] >= iso); // marching cubes: a point is outside when value >= iso
            inside += in[k] ? 1 : 0;
          }
          const bool whole = inside == 4 && key[1] == key[0] && key[2] == key[0] && key[3] == key[0];
          if (whole && inRun && run.key == key[0])
          {
            run.i1 = i;
            continue;
          }
          if (inRun)
            endRun(run);
          inRun = whole;
          if (whole)
          {
            run = Rect{ i, i, j, j, key[0] };
            continue;
          }
          if (inside == 0)
            continue;
          // the crossing on the side from corner k to k+1, from its lower point (as marching cubes' vertices)
          auto crossing = [&](int k) {
            const int k1 = (k + 1) % 4;
            const bool forward = k == 0 || k == 1; // (i,j)->(i+1,j) and (i+1,j)->(i+1,j+1) run up their axis
            const int lo = forward ? k : k1, hi = forward ? k1 : k;
            CapPoint p;
            p.lower = corner[lo];
            p.axis = (k == 0 || k == 2) ? u : w;
            p.t = (iso - value[lo]) / (value[hi] - value[lo]);
            return p;
          };
          auto cornerPoint = [&](int k) {
            CapPoint p;
            p.lower = corner[k];
            return p;
          };
          std::array<CapPoint, 6> poly;
          std::array<std::array<int, 3>, 4> fans;
          int count = 0, fanCount = 0;
          const bool saddle = inside == 2 && in[0] == in[2];
          if (saddle)
          {
            // two separate corners (the separated reading of the ambiguous face)
            for (int k = 0; k < 4; ++k)
              if (in[k])
              {
                const int base = count;
                poly[count++] = cornerPoint(k);
                poly[count++] = crossing(k);
                poly[count++] = crossing((k + 3) % 4);
                fans[fanCount++] = { base, base + 1, base + 2 };
              }
          }
          else
          {
            for (int k = 0; k < 4; ++k)
            {
              if (in[k])
                poly[count++] = cornerPoint(k);
              if (in[k] != in[(k + 1) % 4])
                poly[count++] = crossing(k);
            }
            for (int k = 1; k + 1 < count; ++k)
              fans[fanCount++] = { 0, k, k + 1 };
          }
          emit(poly.data(), count, fans.data(), fanCount, a, outward, cellOf(i, j));
        }
        if (inRun)
          endRun(run);
        for (const Rect& r : open)
          if (r.i0 >= 0)
            flush(r); // did not go on into this row
        open.swap(next);
      }
      for (const Rect& r : open)
        flush(r);
    }
  }
  return m.triangles.size() > trianglesBefore;
}
}
