// Sign voxel filters: the paper's Fig. 2 cases built by hand (expected values
// worked out on paper), the threshold, boundaries, the iteration cap, flip
// counts against an independent count of changed voxels, determinism, and a
// plain per-plane reference (SvfReference.h) on random volumes.
#include "ErrorTestUtil.h"
#include "SvfReference.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/SignVoxelFilter.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <random>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace lvdif;

namespace
{

struct Vol
{
  std::int64_t nx, ny, nz;
  std::vector<float> v;
  Vol(std::int64_t x, std::int64_t y, std::int64_t z, float fill)
    : nx(x), ny(y), nz(z), v(static_cast<size_t>(x * y * z), fill)
  {
  }
  float& at(std::int64_t x, std::int64_t y, std::int64_t z) { return v[static_cast<size_t>(x + nx * (y + ny * z))]; }
  FloatGridView view()
  {
    FloatGridView g;
    g.data = v.data();
    g.geometry.dims = { nx, ny, nz };
    return g;
  }
};

SignVoxelFilterParams params(unsigned filters, int axis = 0, SvfBoundary b = SvfBoundary::Free)
{
  SignVoxelFilterParams p;
  p.filters = filters;
  p.axis = axis;
  p.boundary = b;
  p.device = Device::Cpu;
  return p;
}

Vol randomVol(std::int64_t x, std::int64_t y, std::int64_t z, unsigned seed)
{
  // blobs of one sign with sprinkled wrong signs: more realistic than white
  // noise (which SVF2/3 barely touch) and it exercises all four filters
  Vol g(x, y, z, 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> mag(0.0f, 6.0f);
  std::uniform_int_distribution<int> coin(0, 99);
  for (std::int64_t k = 0; k < z; ++k)
    for (std::int64_t j = 0; j < y; ++j)
      for (std::int64_t i = 0; i < x; ++i)
      {
        const double d = std::sqrt(double((i - x / 2) * (i - x / 2) + (j - y / 2) * (j - y / 2) +
                           (k - z / 2) * (k - z / 2))) - 0.3 * double(std::min({ x, y, z }));
        float val = static_cast<float>(d) + mag(rng) * 0.2f;
        const int c = coin(rng);
        if (c < 12)
          val = -val; // wrong sign
        else if (c < 14)
          val = 0.0f;
        g.at(i, j, k) = val;
      }
  return g;
}

svfref::Grid toRef(const Vol& g)
{
  return svfref::Grid{ { g.nx, g.ny, g.nz }, g.v };
}

} // namespace

// ---- SVF1 (Fig. 2a) ---------------------------------------------------------
TEST(SignVoxelFilter, Svf1PropagatesAlongEveryAxis)
{
  const float row[8] = { 3, -3, -4, 1.5f, -1, -3, 0, -5 };
  // hand-derived: the far -3, -4 follow the +3 before them; -1 is near and
  // keeps its sign, so the far -3 after it is right; after the 0 nothing opposes.
  const float want[8] = { 3, 3, 4, 1.5f, -1, -3, 0, -5 };
  for (int axis = 0; axis < 3; ++axis)
  {
    std::int64_t d[3] = { 2, 3, 2 };
    d[axis] = 8;
    Vol g(d[0], d[1], d[2], 1.0f);
    for (int a = 0; a < 8; ++a)
    {
      std::int64_t c[3] = { 1, 2, 1 };
      c[axis] = a;
      g.at(c[0], c[1], c[2]) = row[a];
    }
    const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(Svf1, axis));
    EXPECT_EQ(st.flips[0], 2) << "axis " << axis;
    for (int a = 0; a < 8; ++a)
    {
      std::int64_t c[3] = { 1, 2, 1 };
      c[axis] = a;
      EXPECT_EQ(g.at(c[0], c[1], c[2]), want[a]) << "axis " << axis << " a " << a;
    }
  }
}

TEST(SignVoxelFilter, Svf1ThresholdAndOutsideBoundary)
{
  Vol g(4, 1, 1, 0);
  const float in[4] = { -3, -2, 3, -2.5f };
  std::memcpy(g.v.data(), in, sizeof(in));
  // Outside boundary: the far -3 at x = 0 follows the virtual outside voxel;
  // -2 equals T and stays; 3 is far and follows -2's minus; -2.5 then agrees.
  signVoxelFilter(g.view(), params(Svf1, 0, SvfBoundary::Outside));
  EXPECT_EQ(g.v, (std::vector<float>{ 3, -2, -3, -2.5f }));
  std::memcpy(g.v.data(), in, sizeof(in));
  signVoxelFilter(g.view(), params(Svf1, 0, SvfBoundary::Free));
  EXPECT_EQ(g.v, (std::vector<float>{ -3, -2, -3, -2.5f }));
}

// ---- SVF2 (Fig. 2b) ---------------------------------------------------------
namespace
{
Vol svf2Plane(float flowValue, float centre)
{
  // one plane (x = 0) of 5x5 in (y, z); outer ring near +1
  Vol g(1, 5, 5, 1.0f);
  g.at(0, 1, 1) = 1;
  g.at(0, 2, 1) = 1;
  g.at(0, 3, 1) = 1;
  g.at(0, 1, 2) = -1;
  g.at(0, 3, 2) = flowValue;
  g.at(0, 1, 3) = -1;
  g.at(0, 2, 3) = -1;
  g.at(0, 3, 3) = 1;
  g.at(0, 2, 2) = centre;
  return g; // window signs around the centre: 5 plus, 4 minus (centre included)
}
} // namespace

TEST(SignVoxelFilter, Svf2FlipsWithMajorityAndSignFlow)
{
  Vol g = svf2Plane(4.0f, -3.0f);
  const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(Svf2));
  EXPECT_EQ(st.flips[1], 1);
  EXPECT_EQ(g.at(0, 2, 2), 3.0f); // sign inverted, magnitude kept (the code, not Fig. 2b's copy of +4)
  EXPECT_EQ(g.at(0, 3, 2), 4.0f);
  EXPECT_EQ(st.iterations[1], 2); // one pass flips, the next finds nothing
}

TEST(SignVoxelFilter, Svf2NeedsALargerOppositeNeighbour)
{
  Vol g = svf2Plane(2.0f, -3.0f); // majority but the opposite neighbours are all smaller
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf2)).flips[1], 0);
  EXPECT_EQ(g.at(0, 2, 2), -3.0f);
}

TEST(SignVoxelFilter, Svf2NeedsTheOppositeMajority)
{
  Vol g = svf2Plane(4.0f, -3.0f);
  g.at(0, 3, 3) = -1; // window now 4 plus, 5 minus: same sign as the centre
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf2)).flips[1], 0);
  EXPECT_EQ(g.at(0, 2, 2), -3.0f);
}

TEST(SignVoxelFilter, Svf2RespectsTheThreshold)
{
  Vol g = svf2Plane(4.0f, -2.0f); // |centre| == T
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf2)).flips[1], 0);
  EXPECT_EQ(g.at(0, 2, 2), -2.0f);
}

// ---- SVF3 (Fig. 2c) ---------------------------------------------------------
TEST(SignVoxelFilter, Svf3FlipsAnIsolatedVoxelInItsPlane)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    Vol g(5, 5, 5, 1.0f);
    g.at(2, 2, 2) = -3;
    // the neighbours along the axis are wrong too: SVF3 only looks in-plane
    std::int64_t c[3] = { 2, 2, 2 };
    c[axis] = 1;
    g.at(c[0], c[1], c[2]) = -1;
    c[axis] = 3;
    g.at(c[0], c[1], c[2]) = -1;
    const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(Svf3, axis));
    EXPECT_EQ(st.flips[2], 1) << axis;
    EXPECT_EQ(g.at(2, 2, 2), 3.0f);
  }
}

TEST(SignVoxelFilter, Svf3ZeroNeighbourAndThresholdBlock)
{
  Vol g(1, 5, 5, 1.0f);
  g.at(0, 2, 2) = -3;
  g.at(0, 2, 3) = 0; // a zero neighbour is not "opposite"
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf3)).flips[2], 0);
  g.at(0, 2, 3) = 1;
  g.at(0, 2, 2) = -2; // |centre| == T
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf3)).flips[2], 0);
  EXPECT_EQ(g.at(0, 2, 2), -2.0f);
}

TEST(SignVoxelFilter, Svf3BoundaryModes)
{
  Vol g(1, 4, 4, 5.0f);
  g.at(0, 0, 0) = -3; // corner: 2 in-plane neighbours, 2 virtual
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf3, 0, SvfBoundary::Free)).flips[2], 0);
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf3, 0, SvfBoundary::Outside)).flips[2], 1);
  EXPECT_EQ(g.at(0, 0, 0), 3.0f);
}

// ---- SVF4 (Fig. 2d) ---------------------------------------------------------
TEST(SignVoxelFilter, Svf4MajorityOfSixIsOnePassWithoutThreshold)
{
  Vol g(5, 5, 5, 3.0f);
  g.at(2, 2, 2) = -0.5f; // near the surface: SVF4 has no threshold
  g.at(2, 2, 1) = -3;
  g.at(2, 2, 3) = -3;
  // centre: 4 of 6 opposite -> flips; (2,2,1) and (2,2,3): 5 of 6 -> flip.
  // All decisions read the input (a Jacobi pass).
  SignVoxelFilterStats st = signVoxelFilter(g.view(), params(Svf4));
  EXPECT_EQ(st.flips[3], 3);
  EXPECT_EQ(g.at(2, 2, 2), 0.5f);
  EXPECT_EQ(g.at(2, 2, 1), 3.0f);

  Vol h(5, 5, 5, 3.0f);
  h.at(2, 2, 2) = -0.5f;
  h.at(2, 2, 1) = -3;
  h.at(2, 2, 3) = -3;
  h.at(1, 2, 2) = -3; // centre now 3 of 6 opposite: stays; the three others flip
  st = signVoxelFilter(h.view(), params(Svf4));
  EXPECT_EQ(st.flips[3], 3);
  EXPECT_EQ(h.at(2, 2, 2), -0.5f);
  EXPECT_EQ(h.at(1, 2, 2), 3.0f);
}

TEST(SignVoxelFilter, Svf4BoundaryModes)
{
  Vol g(4, 4, 4, 2.0f);
  g.at(0, 0, 0) = -5; // corner: 3 grid neighbours, 3 virtual
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf4, 0, SvfBoundary::Free)).flips[3], 0);
  EXPECT_EQ(signVoxelFilter(g.view(), params(Svf4, 0, SvfBoundary::Outside)).flips[3], 1);
  EXPECT_EQ(g.at(0, 0, 0), 5.0f);
}

// ---- cap, threshold, counts, determinism ------------------------------------
TEST(SignVoxelFilter, IterationCapIsHonoured)
{
  // a 2-voxel-wide wrong streak erodes only from its ends under SVF2
  Vol g(1, 40, 8, 6.0f);
  for (std::int64_t y = 5; y < 35; ++y)
  {
    g.at(0, y, 3) = -5;
    g.at(0, y, 4) = -5;
  }
  Vol capped = g;
  SignVoxelFilterParams p = params(Svf2);
  p.maxIterations = 1;
  const SignVoxelFilterStats sc = signVoxelFilter(capped.view(), p);
  EXPECT_EQ(sc.iterations[1], 1);
  EXPECT_EQ(sc.planesAtCap[1], 1);
  EXPECT_GT(sc.flips[1], 0);
  EXPECT_LT(sc.flips[1], 60);
  svfref::Grid r = toRef(g);
  svfref::run(r, 2.0f, 0, Svf2, 1, 0);
  EXPECT_EQ(capped.v, r.v);

  const SignVoxelFilterStats sf = signVoxelFilter(g.view(), params(Svf2));
  EXPECT_EQ(sf.flips[1], 60); // the whole streak repaired
  EXPECT_GT(sf.iterations[1], 2);
  EXPECT_EQ(sf.planesAtCap[1], 0);
  for (float x : g.v)
    EXPECT_GT(x, 0.0f);
}

TEST(SignVoxelFilter, NearVoxelsNeverFlipUnderSvf1To3)
{
  Vol g = randomVol(23, 19, 17, 7);
  const Vol before = g;
  const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(Svf1 | Svf2 | Svf3, 1, SvfBoundary::Outside));
  EXPECT_GT(st.totalFlips(), 0);
  for (size_t i = 0; i < g.v.size(); ++i)
  {
    if (std::fabs(before.v[i]) <= 2.0f)
      ASSERT_EQ(g.v[i], before.v[i]) << i;
    else
      ASSERT_EQ(std::fabs(g.v[i]), std::fabs(before.v[i])) << i; // magnitude kept
  }
}

TEST(SignVoxelFilter, FlipCountsEqualChangedVoxels)
{
  const Vol start = randomVol(31, 26, 21, 11);
  for (int axis = 0; axis < 3; ++axis)
  {
    Vol all = start;
    const SignVoxelFilterStats st = signVoxelFilter(all.view(), params(SvfAll, axis, SvfBoundary::Outside));
    Vol prev = start;
    for (int n = 1; n <= 4; ++n)
    {
      Vol cur = start;
      signVoxelFilter(cur.view(), params(svfCumulative(n), axis, SvfBoundary::Outside));
      std::int64_t changed = 0;
      for (size_t i = 0; i < cur.v.size(); ++i)
        changed += cur.v[i] != prev.v[i] ? 1 : 0;
      EXPECT_EQ(st.flips[n - 1], changed) << "axis " << axis << " SVF" << n;
      EXPECT_GT(changed, 0) << "axis " << axis << " SVF" << n;
      prev = cur;
    }
    EXPECT_EQ(all.v, prev.v);
  }
}

TEST(SignVoxelFilter, MatchesThePlainReference)
{
  for (int axis = 0; axis < 3; ++axis)
    for (SvfBoundary b : { SvfBoundary::Outside, SvfBoundary::Free })
    {
      Vol g = randomVol(29, 24, 18, 100u + static_cast<unsigned>(axis));
      svfref::Grid r = toRef(g);
      const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(SvfAll, axis, b));
      const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
      const std::int64_t dims[3] = { 29, 24, 18 };
      const int cap = static_cast<int>(std::max(dims[u], dims[v]));
      const svfref::Result want = svfref::run(r, 2.0f, axis, SvfAll, cap, b == SvfBoundary::Outside ? 1 : 0);
      EXPECT_EQ(g.v, r.v) << "axis " << axis;
      for (int f = 0; f < 4; ++f)
      {
        EXPECT_EQ(st.flips[f], want.flips[f]) << "axis " << axis << " SVF" << f + 1;
        EXPECT_EQ(st.iterations[f], want.iterations[f]) << "axis " << axis << " SVF" << f + 1;
      }
    }
}

TEST(SignVoxelFilter, ColourOrderOnCheckerboards)
{
  // On a checkerboard every far voxel is a candidate at once, so the update
  // order decides the result: the fixed colour order must match the reference.
  for (int axis = 0; axis < 3; ++axis)
    for (unsigned f : { unsigned(Svf2), unsigned(Svf3) })
    {
      // SVF3: a checkerboard; SVF2 (which a checkerboard never triggers): white sign noise
      Vol g(13, 11, 9, 0);
      std::mt19937 rng(17);
      for (std::int64_t k = 0; k < 9; ++k)
        for (std::int64_t j = 0; j < 11; ++j)
          for (std::int64_t i = 0; i < 13; ++i)
            g.at(i, j, k) = f == Svf3 ? ((i + j + k) % 2 ? 5.0f : -4.0f) + 0.01f * float(i)
                                      : (rng() % 2 ? 1.0f : -1.0f) * (2.5f + float(rng() % 100) * 0.05f);
      svfref::Grid r = toRef(g);
      const SignVoxelFilterStats st = signVoxelFilter(g.view(), params(f, axis));
      const svfref::Result want = svfref::run(r, 2.0f, axis, f, 13, 0);
      EXPECT_EQ(g.v, r.v) << "axis " << axis << " filters " << f;
      EXPECT_EQ(st.flips, want.flips);
      EXPECT_GT(st.totalFlips(), 0);
    }
}

TEST(SignVoxelFilter, DeterministicForAnyThreadCount)
{
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
  const Vol start = randomVol(67, 45, 39, 5);
  for (int axis = 0; axis < 3; ++axis)
  {
    omp_set_num_threads(1);
    Vol one = start;
    const SignVoxelFilterStats s1 = signVoxelFilter(one.view(), params(SvfAll, axis, SvfBoundary::Outside));
    for (int threads : { 2, 3, 8 })
    {
      omp_set_num_threads(threads);
      Vol many = start;
      const SignVoxelFilterStats sn = signVoxelFilter(many.view(), params(SvfAll, axis, SvfBoundary::Outside));
      EXPECT_EQ(std::memcmp(one.v.data(), many.v.data(), one.v.size() * sizeof(float)), 0) << threads;
      EXPECT_EQ(s1.flips, sn.flips);
      EXPECT_EQ(s1.iterations, sn.iterations);
    }
  }
  omp_set_num_threads(saved);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(SignVoxelFilter, CumulativeSettingAndBadParameters)
{
  EXPECT_EQ(svfCumulative(0), 0u);
  EXPECT_EQ(svfCumulative(2), unsigned(Svf1 | Svf2));
  EXPECT_EQ(svfCumulative(4), unsigned(SvfAll));
  EXPECT_THROW(svfCumulative(5), Error);
  Vol g(4, 4, 4, 1.0f);
  auto refusal = [&](SignVoxelFilterParams p) {
    return errortest::errorMessageOf([&] { signVoxelFilter(g.view(), p); }, ErrorCode::InvalidArgument);
  };
  SignVoxelFilterParams p = params(SvfAll);
  p.threshold = -1;
  EXPECT_NE(refusal(p).find("threshold"), std::string::npos) << refusal(p);
  p = params(SvfAll, 3);
  EXPECT_NE(refusal(p).find("axis"), std::string::npos) << refusal(p);
  p = params(16u);
  EXPECT_NE(refusal(p).find("filter mask"), std::string::npos) << refusal(p);
  p = params(SvfAll);
  p.maxIterations = -2;
  EXPECT_NE(refusal(p).find("maxIterations"), std::string::npos) << refusal(p);
  FloatGridView empty;
  EXPECT_THROW(signVoxelFilter(empty, params(SvfAll)), Error);
}

TEST(SignVoxelFilter, ParamsRuleNamesTheParameterAndTheValueGiven)
{
  // the one rule the VTK filter's settings check uses (no clamp anywhere)
  auto message = [](SignVoxelFilterParams p) {
    return errortest::errorMessageOf([&] { checkSignVoxelFilterParams(p); }, ErrorCode::InvalidArgument);
  };
  SignVoxelFilterParams p;
  EXPECT_NO_THROW(checkSignVoxelFilterParams(p));
  p.threshold = -0.5f;
  EXPECT_EQ(message(p), "signVoxelFilter: the threshold must be finite and >= 0, not -0.5");
  p = {};
  p.axis = 3;
  EXPECT_EQ(message(p), "signVoxelFilter: the axis must be 0 (x), 1 (y) or 2 (z), not 3");
  p = {};
  p.filters = 16u;
  EXPECT_EQ(message(p), "signVoxelFilter: the filter mask may only contain Svf1..Svf4 bits (0..15), not 16");
  p = {};
  p.maxIterations = -2;
  EXPECT_EQ(message(p), "signVoxelFilter: maxIterations must be >= 0 (0 = automatic), not -2");
  // the edges of each range are accepted
  p = {};
  p.threshold = 0.0f;
  p.axis = 2;
  p.filters = 0u;
  p.maxIterations = 0;
  EXPECT_NO_THROW(checkSignVoxelFilterParams(p));
}

TEST(SignVoxelFilter, CancelStops)
{
  Vol g = randomVol(20, 20, 20, 3);
  CancelFlagInterrupter it;
  it.cancel();
  errortest::errorMessageOf([&] { signVoxelFilter(g.view(), params(SvfAll), it); }, ErrorCode::Cancelled);
}

TEST(SignVoxelFilter, MatchesTheReferenceOnTheCudaTestCases)
{
  // the cases of SignVoxelFilterCuda.BitIdenticalToCpu, against the reference
  // (its 130x97x64 shape too when LVDIF_SLOW_TESTS is set: ~45 s on 2 cores)
  struct Shape
  {
    std::int64_t x, y, z;
  };
  std::vector<Shape> shapes{ { 29, 24, 18 }, { 67, 45, 39 }, { 1, 50, 70 } };
  if (std::getenv("LVDIF_SLOW_TESTS"))
    shapes.push_back({ 130, 97, 64 });
  for (Shape s : shapes)
    for (int axis = 0; axis < 3; ++axis)
      for (SvfBoundary b : { SvfBoundary::Outside, SvfBoundary::Free })
        for (unsigned filters : { unsigned(SvfAll), unsigned(Svf2), unsigned(Svf3 | Svf4) })
        {
          Vol g = randomVol(s.x, s.y, s.z, static_cast<unsigned>(s.x + axis));
          svfref::Grid r = toRef(g);
          signVoxelFilter(g.view(), params(filters, axis, b));
          const std::int64_t dims[3] = { s.x, s.y, s.z };
          const int cap = static_cast<int>(std::max({ dims[axis == 0 ? 1 : 0], dims[axis == 2 ? 1 : 2], std::int64_t(2) }));
          svfref::run(r, 2.0f, axis, filters, cap, b == SvfBoundary::Outside ? 1 : 0);
          ASSERT_EQ(g.v, r.v) << s.x << "x" << s.y << "x" << s.z << " axis " << axis << " filters " << filters;
        }
}

TEST(SignVoxelFilter, ProgressRisesToOne)
{
  struct Recorder : Interrupter
  {
    std::vector<double> values;
    int starts = 0;
    void start(const char*) override { ++starts; }
    void progress(double f) override { values.push_back(f); }
  } rec;
  Vol g = randomVol(30, 20, 20, 4);
  signVoxelFilter(g.view(), params(SvfAll, 1), rec);
  EXPECT_EQ(rec.starts, 1);
  ASSERT_GT(rec.values.size(), 8u);
  for (size_t i = 1; i < rec.values.size(); ++i)
    EXPECT_GE(rec.values[i], rec.values[i - 1]) << i;
  EXPECT_EQ(rec.values.back(), 1.0);
  EXPECT_GE(rec.values.front(), 0.0);
}

// ---- CUDA: bit-identical to the CPU -----------------------------------------
TEST(SignVoxelFilterCuda, BitIdenticalToCpu)
{
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  struct Shape
  {
    std::int64_t x, y, z;
  };
  for (Shape s : { Shape{ 29, 24, 18 }, Shape{ 67, 45, 39 }, Shape{ 130, 97, 64 }, Shape{ 1, 50, 70 } })
    for (int axis = 0; axis < 3; ++axis)
      for (SvfBoundary b : { SvfBoundary::Outside, SvfBoundary::Free })
        for (unsigned filters : { unsigned(SvfAll), unsigned(Svf2), unsigned(Svf3 | Svf4) })
        {
          const Vol start = randomVol(s.x, s.y, s.z, static_cast<unsigned>(s.x + axis));
          Vol cpu = start, gpu = start;
          SignVoxelFilterParams p = params(filters, axis, b);
          const SignVoxelFilterStats sc = signVoxelFilter(cpu.view(), p);
          p.device = Device::Cuda;
          const SignVoxelFilterStats sg = signVoxelFilter(gpu.view(), p);
          ASSERT_EQ(sg.device, Device::Cuda);
          EXPECT_EQ(std::memcmp(cpu.v.data(), gpu.v.data(), cpu.v.size() * sizeof(float)), 0)
            << s.x << "x" << s.y << "x" << s.z << " axis " << axis << " filters " << filters;
          EXPECT_EQ(sc.flips, sg.flips);
          EXPECT_EQ(sc.iterations, sg.iterations);
          EXPECT_EQ(sc.planesAtCap, sg.planesAtCap);
        }
}

TEST(SignVoxelFilterCuda, CapAndRepeatedRuns)
{
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  const Vol start = randomVol(90, 80, 70, 9);
  SignVoxelFilterParams p = params(SvfAll, 2, SvfBoundary::Outside);
  p.maxIterations = 1;
  Vol cpu = start;
  signVoxelFilter(cpu.view(), p);
  p.device = Device::Cuda;
  for (int rep = 0; rep < 3; ++rep)
  {
    Vol gpu = start;
    signVoxelFilter(gpu.view(), p);
    EXPECT_EQ(std::memcmp(cpu.v.data(), gpu.v.data(), cpu.v.size() * sizeof(float)), 0) << rep;
  }
}

// ---- DictionaryVolume entry point -------------------------------------------

TEST(SignVoxelFilterVolume, RepairsAStoredSphere)
{
  VolumeOptions o;
  o.dims = { 64, 48, 40 };
  o.chunkEdge = 16;
  DictionaryVolume vol(o);
  const double cx = 31.5, cy = 23.5, cz = 19.5, r = 14.0;
  fillFromFunction(vol, sphereSdf(cx, cy, cz, r));
  auto truthInside = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) < r;
  };
  // wrong signs: a streak inside, one outside (saturated, uniform chunks), isolated voxels
  int injected = 0;
  auto flip = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const float v = vol.sdf(x, y, z);
    if (std::fabs(v) > 2.0f)
    {
      vol.setSdf(x, y, z, -v);
      ++injected;
    }
  };
  for (std::int64_t x = 26; x < 36; ++x)
    flip(x, 24, 20);
  for (std::int64_t x = 3; x < 12; ++x)
    flip(x, 5, 33);
  flip(50, 40, 5);
  flip(30, 22, 18);
  ASSERT_GT(injected, 15);
  vol.takeDirtyChunks();
  const std::unique_ptr<DictionaryVolume> before = vol.clone();

  SignVoxelFilterParams p;
  p.device = Device::Cpu;
  const SignVoxelFilterStats st = signVoxelFilter(vol, p);
  std::int64_t wrong = 0, changed = 0;
  for (std::int64_t z = 0; z < 40; ++z)
    for (std::int64_t y = 0; y < 48; ++y)
      for (std::int64_t x = 0; x < 64; ++x)
      {
        const float v = vol.sdf(x, y, z);
        wrong += (v < 0) != truthInside(x, y, z) ? 1 : 0;
        const Voxel a = vol.get(x, y, z), b = before->get(x, y, z);
        changed += a != b ? 1 : 0;
        ASSERT_EQ(a.color, b.color);
      }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(st.totalFlips(), changed);
  EXPECT_GE(changed, injected);
  const std::vector<std::int64_t> dirty = vol.takeDirtyChunks();
  EXPECT_NE(std::find(dirty.begin(), dirty.end(), vol.chunkOf(30, 24, 20)), dirty.end());
  EXPECT_NE(std::find(dirty.begin(), dirty.end(), vol.chunkOf(5, 5, 33)), dirty.end());
}

// ---- the streamed volume filter against the dense filter ---------------------

namespace
{
/// A dictionary volume holding randomVol's values (wrong signs everywhere,
/// uniform chunks far out), and the dense grid of its decoded values.
std::unique_ptr<DictionaryVolume> randomVolume(std::int64_t x, std::int64_t y, std::int64_t z, unsigned seed)
{
  VolumeOptions o;
  o.dims = { x, y, z };
  o.chunkEdge = 8;
  o.bandWidth = 4.0f; // saturates the far field: uniform chunks of both signs
  auto vol = std::make_unique<DictionaryVolume>(o);
  Vol g = randomVol(x, y, z, seed);
  for (std::int64_t k = 0; k < z; ++k)
    for (std::int64_t j = 0; j < y; ++j)
      for (std::int64_t i = 0; i < x; ++i) vol->setSdf(i, j, k, g.at(i, j, k));
  // a wrong-sign box far outside (saturated) crossing chunk and slab borders
  for (std::int64_t k = 1; k < 6; ++k)
    for (std::int64_t j = 1; j < 9; ++j)
      for (std::int64_t i = 1; i < 4; ++i) vol->setSdf(i, j, k, -4.0f);
  vol->collapseUniformChunks();
  return vol;
}

Vol decoded(const DictionaryVolume& v)
{
  Vol g(v.dims()[0], v.dims()[1], v.dims()[2], 0);
  for (std::int64_t k = 0; k < g.nz; ++k)
    for (std::int64_t j = 0; j < g.ny; ++j)
      for (std::int64_t i = 0; i < g.nx; ++i) g.at(i, j, k) = v.sdf(i, j, k);
  return g;
}

/// What the volume filter must store: the dense filter's result on the
/// decoded volume, written back as the key of each value whose sign changed.
std::vector<Voxel> expectedVoxels(const DictionaryVolume& v, const SignVoxelFilterParams& p, SignVoxelFilterStats& st)
{
  Vol g = decoded(v);
  st = signVoxelFilter(g.view(), p);
  const SdfKey zero = v.sdfDictionary().zeroKey();
  std::vector<Voxel> out;
  for (std::int64_t k = 0; k < g.nz; ++k)
    for (std::int64_t j = 0; j < g.ny; ++j)
      for (std::int64_t i = 0; i < g.nx; ++i)
      {
        Voxel old = v.get(i, j, k);
        const float f = g.at(i, j, k);
        if ((f < 0.0f) != (old.sdf < zero)) old.sdf = v.encode(f);
        out.push_back(old);
      }
  return out;
}

std::vector<Voxel> voxels(const DictionaryVolume& v)
{
  std::vector<Voxel> out;
  for (std::int64_t k = 0; k < v.dims()[2]; ++k)
    for (std::int64_t j = 0; j < v.dims()[1]; ++j)
      for (std::int64_t i = 0; i < v.dims()[0]; ++i) out.push_back(v.get(i, j, k));
  return out;
}

void expectSameStats(const SignVoxelFilterStats& a, const SignVoxelFilterStats& b)
{
  EXPECT_EQ(a.flips, b.flips);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.planesAtCap, b.planesAtCap);
}
} // namespace

TEST(SignVoxelFilterVolume, StreamedSlabsEqualTheDenseFilter)
{
  const auto start = randomVolume(21, 18, 25, 7);
  for (int axis = 0; axis < 3; ++axis)
    for (SvfBoundary b : { SvfBoundary::Outside, SvfBoundary::Free })
      for (std::int64_t slab : { 1, 2, 3, 7, 0 })
      {
        SCOPED_TRACE("axis " + std::to_string(axis) + " slab " + std::to_string(slab) +
          (b == SvfBoundary::Free ? " free" : " outside"));
        SignVoxelFilterParams p = params(SvfAll, axis, b);
        p.volumeSlabPlanes = slab;
        SignVoxelFilterStats want;
        const std::vector<Voxel> expected = expectedVoxels(*start, p, want);
        auto vol = start->clone();
        const SignVoxelFilterStats got = signVoxelFilter(*vol, p);
        ASSERT_GT(want.totalFlips(), 100);
        EXPECT_EQ(voxels(*vol), expected);
        expectSameStats(got, want);
        EXPECT_EQ(voxels(*start), voxels(*start->clone())); // (the clone left the start alone)
      }
}

TEST(SignVoxelFilterVolume, PlanesAndChunksOfOneSignEqualTheDenseFilter)
{
  // mostly uniform: a small sphere, whole planes outside (positive) and a slab
  // of whole planes inside (negative), wrong signs in both and at the border,
  // so that the filter's shortcuts for planes and chunks of one sign are taken
  VolumeOptions o;
  o.dims = { 36, 30, 44 };
  o.chunkEdge = 4;
  o.bandWidth = 4.0f;
  DictionaryVolume start(o);
  fillFromFunction(start, sphereSdf(18, 15, 12, 6));
  for (std::int64_t z = 28; z < 36; ++z)
    for (std::int64_t y = 0; y < 30; ++y)
      for (std::int64_t x = 0; x < 36; ++x) start.setSdf(x, y, z, -4.0f);
  for (const Index3 w : { Index3{ 3, 3, 40 }, Index3{ 20, 20, 31 }, Index3{ 0, 0, 30 }, Index3{ 35, 29, 43 },
         Index3{ 18, 15, 12 } })
    start.setSdf(w[0], w[1], w[2], -start.sdf(w[0], w[1], w[2]));
  start.collapseUniformChunks();
  for (int axis = 0; axis < 3; ++axis)
    for (SvfBoundary b : { SvfBoundary::Outside, SvfBoundary::Free })
      for (unsigned filters : { unsigned(SvfAll), unsigned(Svf2 | Svf3 | Svf4) })
      {
        SCOPED_TRACE("axis " + std::to_string(axis) + (b == SvfBoundary::Free ? " free" : " outside") +
          " filters " + std::to_string(filters));
        SignVoxelFilterParams p = params(filters, axis, b);
        p.volumeSlabPlanes = 5;
        SignVoxelFilterStats want;
        const std::vector<Voxel> expected = expectedVoxels(start, p, want);
        auto vol = start.clone();
        expectSameStats(signVoxelFilter(*vol, p), want);
        EXPECT_EQ(voxels(*vol), expected);
        EXPECT_GT(want.totalFlips(), 0);
      }
}

TEST(SignVoxelFilterVolume, EachFilterAloneEqualsTheDenseFilter)
{
  const auto start = randomVolume(17, 23, 19, 11);
  for (unsigned f : { unsigned(Svf1), unsigned(Svf2), unsigned(Svf3), unsigned(Svf4), unsigned(Svf1 | Svf4) })
  {
    SCOPED_TRACE("filters " + std::to_string(f));
    SignVoxelFilterParams p = params(f, 1, SvfBoundary::Outside);
    p.volumeSlabPlanes = 4;
    SignVoxelFilterStats want;
    const std::vector<Voxel> expected = expectedVoxels(*start, p, want);
    auto vol = start->clone();
    expectSameStats(signVoxelFilter(*vol, p), want);
    EXPECT_EQ(voxels(*vol), expected);
  }
}

TEST(SignVoxelFilterVolume, PiecesWithEntrySignsEqualTheWholeRun)
{
  // pieces of planes along the axis, each filtered on its own clone from the
  // original (as distributed ranks do), entry signs composed from the pieces before
  const auto start = randomVolume(19, 22, 26, 3);
  for (int axis = 0; axis < 3; ++axis)
  {
    SCOPED_TRACE("axis " + std::to_string(axis));
    SignVoxelFilterParams p = params(SvfAll, axis, SvfBoundary::Outside);
    p.volumeSlabPlanes = 3;
    SignVoxelFilterStats want;
    const std::vector<Voxel> expected = expectedVoxels(*start, p, want);
    const std::int64_t n = start->dims()[axis];
    const std::vector<std::int64_t> cuts{ 0, 5, 6, n / 2 + 1, n }; // a one-plane piece too
    std::vector<std::unique_ptr<DictionaryVolume>> parts;
    SignVoxelFilterStats sum;
    std::vector<std::int8_t> entry = svf1BoundarySigns(*start, p);
    std::vector<std::int8_t> unknown; // negative control: every piece enters with the boundary's signs
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
    {
      SvfPlanes planes;
      planes.first = cuts[k];
      planes.last = cuts[k + 1] - 1;
      planes.entrySigns = entry;
      parts.push_back(start->clone());
      const SignVoxelFilterStats st = signVoxelFilter(*parts.back(), p, planes);
      for (int q = 0; q < 4; ++q)
      {
        sum.flips[q] += st.flips[q];
        sum.iterations[q] = std::max(sum.iterations[q], st.iterations[q]);
        sum.planesAtCap[q] += st.planesAtCap[q];
      }
      entry = svf1Continue(entry, svf1ExitSigns(*start, p, planes.first, planes.last));
    }
    std::vector<Voxel> assembled;
    for (std::int64_t k = 0; k < start->dims()[2]; ++k)
      for (std::int64_t j = 0; j < start->dims()[1]; ++j)
        for (std::int64_t i = 0; i < start->dims()[0]; ++i)
        {
          const std::int64_t a = axis == 0 ? i : (axis == 1 ? j : k);
          std::size_t piece = 0;
          while (a >= cuts[piece + 1]) ++piece;
          assembled.push_back(parts[piece]->get(i, j, k));
        }
    EXPECT_EQ(assembled, expected);
    EXPECT_EQ(sum.flips, want.flips);
    EXPECT_EQ(sum.iterations, want.iterations);
    EXPECT_EQ(sum.planesAtCap, want.planesAtCap);
    // the same pieces entered with the boundary's signs: SVF1's rows are cut, results differ
    auto wrong = start->clone();
    SvfPlanes late;
    late.first = cuts[3];
    late.entrySigns = svf1BoundarySigns(*start, p);
    signVoxelFilter(*wrong, p, late);
    std::int64_t diff = 0;
    for (std::int64_t k = 0; k < start->dims()[2]; ++k)
      for (std::int64_t j = 0; j < start->dims()[1]; ++j)
        for (std::int64_t i = 0; i < start->dims()[0]; ++i)
          if ((axis == 0 ? i : (axis == 1 ? j : k)) >= cuts[3])
            diff += wrong->get(i, j, k) != parts[3]->get(i, j, k) ? 1 : 0;
    EXPECT_GT(diff, 0);
  }
  SignVoxelFilterParams p = params(SvfAll, 0, SvfBoundary::Outside);
  SvfPlanes bad;
  bad.first = 4;
  auto vol = start->clone();
  EXPECT_THROW(signVoxelFilter(*vol, p, bad), Error); // a later piece without entry signs
}

TEST(SignVoxelFilterVolume, NeedsOnlyASlabOfMemory)
{
  // 128 x 128 x 384: the dense float grid would be 24 MiB; a limit of 12 MiB
  // holds a slab, not the grid
  VolumeOptions o;
  o.dims = { 128, 128, 384 };
  o.chunkEdge = 32;
  DictionaryVolume vol(o);
  fillFromFunction(vol, sphereSdf(64, 64, 192, 50));
  vol.setSdf(64, 64, 192, 5.0f); // a wrong sign deep inside
  ::setenv("LVDIF_MEMORY_LIMIT", std::to_string(12u << 20).c_str(), 1);
  SignVoxelFilterParams p = params(SvfAll, 2, SvfBoundary::Outside);
  SignVoxelFilterStats st;
  EXPECT_NO_THROW(st = signVoxelFilter(vol, p));
  ::unsetenv("LVDIF_MEMORY_LIMIT");
  EXPECT_LT(vol.sdf(64, 64, 192), 0.0f);
  EXPECT_GE(st.totalFlips(), 1);
}

TEST(SignVoxelFilterCuda, StreamedVolumeEqualsTheCpu)
{
  // the streamed volume filter sends its SVF2/SVF3 slabs to the device: the
  // same voxels and statistics as on the CPU
  if (!cuda::available())
    GTEST_SKIP() << "no CUDA device";
  const auto start = randomVolume(37, 29, 41, 5);
  for (int axis = 0; axis < 3; ++axis)
    for (std::int64_t slab : { 3, 0 })
    {
      SCOPED_TRACE("axis " + std::to_string(axis) + " slab " + std::to_string(slab));
      SignVoxelFilterParams p = params(SvfAll, axis, SvfBoundary::Outside);
      p.volumeSlabPlanes = slab;
      auto cpu = start->clone();
      const SignVoxelFilterStats a = signVoxelFilter(*cpu, p);
      p.device = Device::Cuda;
      auto gpu = start->clone();
      const SignVoxelFilterStats b = signVoxelFilter(*gpu, p);
      EXPECT_EQ(b.device, Device::Cuda);
      EXPECT_EQ(voxels(*gpu), voxels(*cpu));
      expectSameStats(b, a);
    }
}
