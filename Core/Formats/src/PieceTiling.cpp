#include "lvdif/PieceTiling.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

namespace lvdif
{

std::string extentText(const VoxelBox& b)
{
  std::string s;
  for (int a = 0; a < 3; ++a)
    s += (a ? " " : "") + std::to_string(b.lo[a]) + " " + std::to_string(b.hi[a]);
  return s;
}

namespace
{
constexpr std::uint64_t MaxCells = std::uint64_t(1) << 23;

bool inside(const VoxelBox& outer, const VoxelBox& inner)
{
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a])
      return false;
  return true;
}

/// Two intersecting pieces share only a boundary layer: on some axis of more
/// than one point their common points are one layer, the last of one piece and
/// the first of the other.
bool shareOnlyALayer(const VoxelBox& whole, const VoxelBox& p, const VoxelBox& q)
{
  for (int a = 0; a < 3; ++a)
  {
    if (whole.lo[a] == whole.hi[a])
      continue;
    const std::int64_t lo = std::max(p.lo[a], q.lo[a]), hi = std::min(p.hi[a], q.hi[a]);
    if (lo == hi && ((lo == p.hi[a] && lo == q.lo[a]) || (lo == p.lo[a] && lo == q.hi[a])))
      return true;
  }
  return false;
}
} // namespace

std::string pieceTilingProblem(
  const VoxelBox& whole, const std::vector<VoxelBox>& pieces, const std::string& what, bool overlapsAllowed)
{
  auto name = [&](std::size_t i) { return what + " " + std::to_string(i + 1); };
  if (whole.empty())
    return "the whole extent " + extentText(whole) + " is empty";
  if (pieces.empty())
    return "no " + what + " for the whole extent " + extentText(whole);
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    if (pieces[i].empty())
      return name(i) + "'s extent " + extentText(pieces[i]) + " is empty";
    if (!inside(whole, pieces[i]))
      return name(i) + "'s extent " + extentText(pieces[i]) + " lies outside the whole extent " + extentText(whole);
  }
  // the same extent twice (sorted, so equal extents are neighbours)
  std::vector<std::size_t> order(pieces.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto key = [&](std::size_t i) { return std::make_pair(pieces[i].lo, pieces[i].hi); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return key(a) != key(b) ? key(a) < key(b) : a < b;
  });
  for (std::size_t u = 0; !overlapsAllowed && u + 1 < order.size(); ++u)
    if (key(order[u]) == key(order[u + 1]))
      return name(order[u]) + " and " + name(order[u + 1]) + " have the same extent " + extentText(pieces[order[u]]);
  // the grid of the pieces' boundaries: each of its cells is held by whole pieces or none
  std::vector<std::int64_t> cuts[3];
  std::uint64_t cells = 1;
  for (int a = 0; a < 3; ++a)
  {
    cuts[a] = { whole.lo[a], whole.hi[a] + 1 };
    for (const VoxelBox& p : pieces)
    {
      cuts[a].push_back(p.lo[a]);
      cuts[a].push_back(p.hi[a] + 1);
    }
    std::sort(cuts[a].begin(), cuts[a].end());
    cuts[a].erase(std::unique(cuts[a].begin(), cuts[a].end()), cuts[a].end());
    cells *= cuts[a].size() - 1;
    if (cells > MaxCells)
      return "the " + std::to_string(pieces.size()) + " " + what + "s have too many distinct boundaries to check " +
        "that they tile the whole extent " + extentText(whole);
  }
  const std::size_t nx = cuts[0].size() - 1, ny = cuts[1].size() - 1;
  auto at = [&](int a, std::int64_t v) {
    return static_cast<std::size_t>(std::lower_bound(cuts[a].begin(), cuts[a].end(), v) - cuts[a].begin());
  };
  // (cell, piece) for every cell each piece holds; pieces that tile hold a cell
  // at most 8 times (a corner of 8 blocks), so a bound on the count is no limit for them
  const std::uint64_t maxMarks = std::min<std::uint64_t>(16 * cells + 64, MaxCells * 2);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> marks;
  bool tooMany = false;
  std::vector<char> held(overlapsAllowed ? static_cast<std::size_t>(cells) : 0, 0);
  for (std::size_t i = 0; i < pieces.size() && !tooMany; ++i)
  {
    const VoxelBox& p = pieces[i];
    const std::size_t x0 = at(0, p.lo[0]), x1 = at(0, p.hi[0] + 1), y0 = at(1, p.lo[1]), y1 = at(1, p.hi[1] + 1),
                      z0 = at(2, p.lo[2]), z1 = at(2, p.hi[2] + 1);
    for (std::size_t z = z0; z < z1 && !tooMany; ++z)
      for (std::size_t y = y0; y < y1 && !tooMany; ++y)
        for (std::size_t x = x0; x < x1 && !tooMany; ++x)
        {
          const std::size_t cell = (z * ny + y) * nx + x;
          if (overlapsAllowed)
          {
            if (!held[cell]) marks.emplace_back(static_cast<std::uint32_t>(cell), static_cast<std::uint32_t>(i));
            held[cell] = 1;
            continue;
          }
          marks.emplace_back(static_cast<std::uint32_t>((z * ny + y) * nx + x), static_cast<std::uint32_t>(i));
          tooMany = marks.size() > maxMarks;
        }
  }
  std::sort(marks.begin(), marks.end());
  // overlaps: every two pieces holding one cell (any two that overlap hold one)
  for (std::size_t g = 0; g < marks.size();)
  {
    std::size_t e = g;
    while (e < marks.size() && marks[e].first == marks[g].first)
      ++e;
    for (std::size_t u = g; u < e; ++u)
      for (std::size_t v = u + 1; v < e; ++v)
      {
        const std::size_t i = marks[u].second, j = marks[v].second;
        if (!shareOnlyALayer(whole, pieces[i], pieces[j]))
          return name(i) + " (extent " + extentText(pieces[i]) + ") and " + name(j) + " (extent " +
            extentText(pieces[j]) + ") overlap: neighbouring pieces share at most one boundary layer of points";
      }
    g = e;
  }
  if (tooMany)
    return "the " + what + "s overlap: they hold the points of the whole extent " + extentText(whole) +
      " more than 16 times over";
  // holes: a cell no piece holds
  std::uint64_t c = 0;
  for (std::size_t g = 0; g < marks.size() && marks[g].first == c; ++g)
    if (g + 1 == marks.size() || marks[g + 1].first != c)
      ++c;
  if (c == cells)
    return "";
  if (pieces.size() == 1)
    return "the whole extent " + extentText(whole) + " is larger than its " + what + "'s extent " +
      extentText(pieces[0]) + ": the points outside it would be made up";
  return "no " + what + " holds the point (" + std::to_string(cuts[0][c % nx]) + ", " +
    std::to_string(cuts[1][c / nx % ny]) + ", " + std::to_string(cuts[2][c / nx / ny]) + ") of the whole extent " +
    extentText(whole);
}

} // namespace lvdif
