// lvdif::pieceTilingProblem, the rule for the pieces of a .lvdvp index and of
// a .vti: pieces that share one boundary layer (as VTK's extent translator and
// the distributed writer split a volume) tile; a duplicate, an overlap, a piece
// outside and a hole are each named. Oracle for the holes: every point of small
// grids enumerated against random piece sets.
#include "lvdif/PieceTiling.h"

#include <gtest/gtest.h>

#include <random>

using namespace lvdif;

namespace
{
VoxelBox box(std::int64_t x0, std::int64_t x1, std::int64_t y0, std::int64_t y1, std::int64_t z0, std::int64_t z1)
{
  return VoxelBox{ { x0, y0, z0 }, { x1, y1, z1 } };
}
} // namespace

TEST(PieceTiling, SplitsThatShareALayerTile)
{
  const VoxelBox whole = box(0, 40, -2, 31, 5, 41);
  EXPECT_EQ(pieceTilingProblem(whole, { whole }), "");
  // two slabs sharing x = 20, and four blocks sharing x = 20 and y = 10
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 20, -2, 31, 5, 41), box(20, 40, -2, 31, 5, 41) }), "");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 20, -2, 10, 5, 41), box(20, 40, -2, 10, 5, 41),
                                        box(0, 20, 10, 31, 5, 41), box(20, 40, 10, 31, 5, 41) }),
    "");
  // the writer's last chunk of one voxel: a piece one layer thick, the other's shared layer
  EXPECT_EQ(pieceTilingProblem(box(0, 32, 0, 7, 0, 7), { box(0, 32, 0, 7, 0, 7), box(32, 32, 0, 7, 0, 7) }), "");
  // pieces that share no point at all also tile
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 19, -2, 31, 5, 41), box(20, 40, -2, 31, 5, 41) }), "");
  // a flat volume (one point on z): its pieces share that layer everywhere
  EXPECT_EQ(pieceTilingProblem(box(0, 9, 0, 9, 3, 3), { box(0, 5, 0, 9, 3, 3), box(5, 9, 0, 9, 3, 3) }), "");
}

TEST(PieceTiling, DuplicatesAndOverlapsAreNamed)
{
  const VoxelBox whole = box(0, 40, 0, 30, 0, 20);
  const VoxelBox a = box(0, 20, 0, 30, 0, 20), b = box(20, 40, 0, 30, 0, 20);
  EXPECT_EQ(pieceTilingProblem(whole, { a, b, a }), "piece 1 and piece 3 have the same extent 0 20 0 30 0 20");
  EXPECT_EQ(pieceTilingProblem(whole, { a, box(19, 40, 0, 30, 0, 20) }),
    "piece 1 (extent 0 20 0 30 0 20) and piece 2 (extent 19 40 0 30 0 20) overlap: neighbouring pieces share at "
    "most one boundary layer of points");
  // one layer, but inside the other piece (not its boundary)
  EXPECT_NE(pieceTilingProblem(whole, { a, b, box(10, 10, 0, 30, 0, 20) }).find("overlap"), std::string::npos);
  // the same thin layer twice
  EXPECT_NE(pieceTilingProblem(box(0, 32, 0, 7, 0, 7),
              { box(0, 32, 0, 7, 0, 7), box(32, 32, 0, 7, 0, 7), box(32, 32, 0, 7, 0, 7) })
              .find("the same extent"),
    std::string::npos);
  // two thin pieces overlapping each other, each sharing only layers with the pieces listed before
  EXPECT_EQ(pieceTilingProblem(box(0, 5, 0, 10, 0, 10), { box(0, 0, 0, 10, 0, 10), box(1, 5, 0, 10, 0, 10),
                                                          box(0, 1, 0, 10, 0, 10), box(0, 1, 0, 9, 0, 10) }),
    "piece 3 (extent 0 1 0 10 0 10) and piece 4 (extent 0 1 0 9 0 10) overlap: neighbouring pieces share at most "
    "one boundary layer of points");
  // a flat volume: two pieces sharing a 2 x 2 patch of its one layer overlap
  EXPECT_NE(pieceTilingProblem(box(0, 9, 0, 9, 0, 0), { box(0, 5, 0, 9, 0, 0), box(4, 9, 0, 9, 0, 0) }).find("overlap"),
    std::string::npos);
}

// A .vti's pieces may repeat points (VTK's writer repeats the whole extent in
// each piece of an input it cannot split): only holes and pieces outside count.
TEST(PieceTiling, OverlapsAllowedForVti)
{
  const VoxelBox whole = box(0, 7, 0, 7, 0, 7);
  EXPECT_EQ(pieceTilingProblem(whole, { whole, whole, whole }, "piece", true), "");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 5, 0, 7, 0, 7), box(2, 7, 0, 7, 0, 7) }, "piece", true), "");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 7, 0, 7, 0, 6), box(0, 7, 0, 7, 0, 6) }, "piece", true),
    "no piece holds the point (0, 0, 7) of the whole extent 0 7 0 7 0 7");
  EXPECT_EQ(pieceTilingProblem(whole, { whole, box(0, 8, 0, 7, 0, 7) }, "piece", true),
    "piece 2's extent 0 8 0 7 0 7 lies outside the whole extent 0 7 0 7 0 7");
}

TEST(PieceTiling, OutsideEmptyAndHolesAreNamed)
{
  const VoxelBox whole = box(0, 9, 0, 9, 0, 10);
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 9, 0, 9, 0, 9) }),
    "the whole extent 0 9 0 9 0 10 is larger than its piece's extent 0 9 0 9 0 9: the points outside it would be "
    "made up");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 9, 0, 9, 0, 11) }),
    "piece 1's extent 0 9 0 9 0 11 lies outside the whole extent 0 9 0 9 0 10");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 9, 0, 9, 5, 4) }), "piece 1's extent 0 9 0 9 5 4 is empty");
  EXPECT_EQ(pieceTilingProblem(whole, {}), "no piece for the whole extent 0 9 0 9 0 10");
  // an empty whole extent is named as such (it was blamed on its piece of the same extent)
  EXPECT_EQ(pieceTilingProblem(box(0, 3, 0, 3, 3, 0), { box(0, 3, 0, 3, 3, 0) }), "the whole extent 0 3 0 3 3 0 is empty");
  EXPECT_EQ(pieceTilingProblem(whole, { box(0, 9, 0, 9, 0, 4), box(0, 9, 0, 9, 6, 10) }, "Piece element"),
    "no Piece element holds the point (0, 0, 5) of the whole extent 0 9 0 9 0 10");
}

// Oracle: each point of the whole extent looked up in every piece.
TEST(PieceTiling, HolesAgreeWithEveryPointCounted)
{
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> coord(0, 7);
  int holes = 0, tilings = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const VoxelBox whole = box(0, 7, 0, 7, 0, 7);
    // disjoint pieces: slabs along a random axis, cut at random points (some skipped: holes)
    const int axis = trial % 3;
    std::vector<VoxelBox> pieces;
    int from = 0;
    while (from <= 7)
    {
      const int to = std::max(from, std::min(7, coord(rng)));
      VoxelBox p = whole;
      p.lo[axis] = from;
      p.hi[axis] = to;
      if (coord(rng) != 0) pieces.push_back(p);
      from = to + 1;
    }
    bool everyPoint = true;
    for (int z = 0; z <= 7; ++z)
      for (int y = 0; y <= 7; ++y)
        for (int x = 0; x <= 7; ++x)
        {
          bool held = false;
          for (const VoxelBox& p : pieces) held = held || p.contains(x, y, z);
          everyPoint = everyPoint && held;
        }
    const std::string problem = pieceTilingProblem(whole, pieces);
    EXPECT_EQ(problem.empty(), everyPoint) << problem;
    (everyPoint ? tilings : holes)++;
  }
  EXPECT_GT(holes, 20);
  EXPECT_GT(tilings, 20);
}
