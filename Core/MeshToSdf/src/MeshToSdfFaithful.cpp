// The paper's acceleration structure for mesh to SDF (Sect. 3.1, "octree of
// overlapping chunks", spec section 1.7): a uniform grid of M^3 cells, each
// listing the triangles that overlap the cell scaled by 2 about its centre.
// Differences from the original code, on purpose: every cell is built (the
// original never processed the last one), and the query is exact (the
// original searched one list only and missed the nearest triangle far from
// the mesh).
#include "MeshToSdfInternal.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace lvdif
{
namespace detail::meshtosdf
{

bool triangleBoxOverlap(const V3 tri[3], const double centre[3], const double half[3])
{
  // Akenine-Moeller, "Fast 3D triangle-box overlap testing", JGT 2001: the
  // two are disjoint iff one of 13 axes separates them (3 box normals, the
  // triangle normal, 9 edge x box-axis products). Written as one loop.
  const V3 c{ centre[0], centre[1], centre[2] };
  const V3 v[3] = { tri[0] - c, tri[1] - c, tri[2] - c };
  const double h[3] = { half[0] * (1 + 1e-9), half[1] * (1 + 1e-9), half[2] * (1 + 1e-9) };
  const V3 e[3] = { v[1] - v[0], v[2] - v[1], v[0] - v[2] };
  const V3 axes[3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  auto separated = [&](V3 L) {
    const double p0 = dot(L, v[0]), p1 = dot(L, v[1]), p2 = dot(L, v[2]);
    const double mn = std::min(p0, std::min(p1, p2)), mx = std::max(p0, std::max(p1, p2));
    const double r = h[0] * std::fabs(L.x) + h[1] * std::fabs(L.y) + h[2] * std::fabs(L.z);
    const double slack = 1e-12 * (std::fabs(mn) + std::fabs(mx) + r);
    return mn > r + slack || mx < -r - slack;
  };
  for (const V3& a : axes)
  {
    if (separated(a)) return false;
  }
  if (separated(cross(e[0], e[1]))) return false;
  for (const V3& ed : e)
  {
    for (const V3& a : axes)
    {
      const V3 L = cross(ed, a);
      if (dot(L, L) > 0 && separated(L)) return false;
    }
  }
  return true;
}

FaithfulGrid::FaithfulGrid(const TriList& tris, const double lo[3], const double hi[3], int m, double scale)
  : Tris(tris)
  , M(m)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Lo[a] = lo[a];
    this->Step[a] = std::max(hi[a] - lo[a], 1e-300) / m;
  }
  const std::int64_t cells = static_cast<std::int64_t>(m) * m * m;
  std::vector<std::vector<std::int32_t>> lists(static_cast<std::size_t>(cells));
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    int r0[3], r1[3];
    for (int a = 0; a < 3; ++a)
    {
      const double tlo = std::min(tris[t].v[0][a], std::min(tris[t].v[1][a], tris[t].v[2][a]));
      const double thi = std::max(tris[t].v[0][a], std::max(tris[t].v[1][a], tris[t].v[2][a]));
      // cell i's scaled box spans centre +- scale/2 * step
      const double ext = 0.5 * (scale - 1);
      r0[a] = std::max(0, static_cast<int>(std::floor((tlo - lo[a]) / this->Step[a] - ext)) - 1);
      r1[a] = std::min(m - 1, static_cast<int>(std::floor((thi - lo[a]) / this->Step[a] + ext)) + 1);
    }
    for (int k = r0[2]; k <= r1[2]; ++k)
      for (int j = r0[1]; j <= r1[1]; ++j)
        for (int i = r0[0]; i <= r1[0]; ++i)
        {
          const double centre[3] = { lo[0] + (i + 0.5) * this->Step[0], lo[1] + (j + 0.5) * this->Step[1],
            lo[2] + (k + 0.5) * this->Step[2] };
          const double half[3] = { 0.5 * scale * this->Step[0], 0.5 * scale * this->Step[1],
            0.5 * scale * this->Step[2] };
          if (triangleBoxOverlap(tris[t].v, centre, half))
          {
            lists[static_cast<std::size_t>(this->cellIndex(i, j, k))].push_back(static_cast<std::int32_t>(t));
          }
        }
  }
  this->Start.assign(static_cast<std::size_t>(cells + 1), 0);
  for (std::int64_t c = 0; c < cells; ++c)
  {
    this->Start[c + 1] = this->Start[c] + static_cast<std::int64_t>(lists[c].size());
  }
  this->Entries.reserve(static_cast<std::size_t>(this->Start[cells]));
  for (auto& l : lists)
  {
    this->Entries.insert(this->Entries.end(), l.begin(), l.end());
  }
  // For each cell, a nearby cell with triangles (breadth-first over faces):
  // the start of the search. The original scanned all M^3 box centres per
  // voxel instead; the start only sets the first bound, exactness comes from
  // the expansion in nearest().
  this->NearestFull.assign(static_cast<std::size_t>(cells), -1);
  std::deque<std::int64_t> queue;
  for (std::int64_t c = 0; c < cells; ++c)
  {
    if (this->Start[c + 1] > this->Start[c])
    {
      this->NearestFull[c] = static_cast<std::int32_t>(c);
      queue.push_back(c);
    }
  }
  while (!queue.empty())
  {
    const std::int64_t c = queue.front();
    queue.pop_front();
    const int i = static_cast<int>(c % m), j = static_cast<int>((c / m) % m), k = static_cast<int>(c / (static_cast<std::int64_t>(m) * m));
    const int nb[6][3] = { { i - 1, j, k }, { i + 1, j, k }, { i, j - 1, k }, { i, j + 1, k }, { i, j, k - 1 }, { i, j, k + 1 } };
    for (const auto& q : nb)
    {
      if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= m || q[1] >= m || q[2] >= m) continue;
      const std::int64_t n = this->cellIndex(q[0], q[1], q[2]);
      if (this->NearestFull[n] < 0)
      {
        this->NearestFull[n] = this->NearestFull[c];
        queue.push_back(n);
      }
    }
  }
}

void FaithfulGrid::scanCell(std::int64_t cell, V3 p, NearestResult& best) const
{
  for (std::int64_t e = this->Start[cell]; e < this->Start[cell + 1]; ++e)
  {
    const std::int32_t ti = this->Entries[e];
    const Tri& t = this->Tris[ti];
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 < best.dist2 || (d2 == best.dist2 && ti < best.tri)) // ties: lowest index, as the BVH
    {
      best.dist2 = d2;
      best.tri = ti;
      best.closest = c;
    }
  }
}

NearestResult FaithfulGrid::nearest(V3 p) const
{
  NearestResult best;
  best.dist2 = 1e300;
  int cell[3];
  for (int a = 0; a < 3; ++a)
  {
    const double f = std::floor((p[a] - this->Lo[a]) / this->Step[a]);
    cell[a] = f < 0 ? 0 : (f > this->M - 1 ? this->M - 1 : static_cast<int>(f));
  }
  const std::int64_t startCell = this->NearestFull[this->cellIndex(cell[0], cell[1], cell[2])];
  this->scanCell(startCell, p, best);
  // Exact expansion: the true closest point q* lies in some cell (the cells
  // tile the triangle bounds) and its triangle overlaps that cell, so it is
  // in that cell's list; that cell is within |p - q*| <= best of p.
  const double r = std::sqrt(best.dist2);
  int r0[3], r1[3];
  for (int a = 0; a < 3; ++a)
  {
    const double f0 = std::floor((p[a] - r - this->Lo[a]) / this->Step[a]);
    const double f1 = std::floor((p[a] + r - this->Lo[a]) / this->Step[a]);
    r0[a] = f0 < 0 ? 0 : (f0 > this->M - 1 ? this->M - 1 : static_cast<int>(f0));
    r1[a] = f1 < 0 ? 0 : (f1 > this->M - 1 ? this->M - 1 : static_cast<int>(f1));
  }
  for (int k = r0[2]; k <= r1[2]; ++k)
    for (int j = r0[1]; j <= r1[1]; ++j)
      for (int i = r0[0]; i <= r1[0]; ++i)
      {
        const std::int64_t c = this->cellIndex(i, j, k);
        if (c == startCell || this->Start[c + 1] == this->Start[c]) continue;
        const double lo[3] = { this->Lo[0] + i * this->Step[0], this->Lo[1] + j * this->Step[1],
          this->Lo[2] + k * this->Step[2] };
        const double hi[3] = { lo[0] + this->Step[0], lo[1] + this->Step[1], lo[2] + this->Step[2] };
        // slack: a point on a cell face may be attributed to either cell
        if (pointBoxDist2(p, lo, hi) <= best.dist2 * (1 + 1e-12) + 1e-300)
        {
          this->scanCell(c, p, best);
        }
      }
  return best;
}

} // namespace detail::meshtosdf
} // namespace lvdif
