#include "ErrorTestUtil.h"
#include "lvdif/Error.h"
#include "lvdif/TriangleMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>

using namespace lvdif;

// Signed volume by the divergence theorem: positive for outward-facing closed meshes.
static double signedVolume(const TriangleMesh& m)
{
  double v = 0;
  for (const auto& t : m.triangles)
  {
    const Vec3f &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    v += (a[0] * (double(b[1]) * c[2] - double(b[2]) * c[1]) - a[1] * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
           a[2] * (double(b[0]) * c[1] - double(b[1]) * c[0])) /
      6.0;
  }
  return v;
}

static bool everyEdgeSharedTwice(const TriangleMesh& m)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{ t[e], t[(e + 1) % 3] }];
  for (const auto& kv : edges)
    if (kv.second != 1 || edges.count({ kv.first.second, kv.first.first }) != 1) return false;
  return true;
}

TEST(TriangleMesh, PrimitivesAreClosedAndOutward)
{
  const TriangleMesh box = makeBoxMesh({ 0, 0, 0 }, { 1, 2, 3 });
  EXPECT_NEAR(signedVolume(box), 6.0, 1e-9);
  EXPECT_TRUE(everyEdgeSharedTwice(box));
  const TriangleMesh s = makeSphereMesh(0, 0, 0, 1, 48, 96);
  EXPECT_NEAR(signedVolume(s), 4.0 / 3.0 * M_PI, 0.02);
  EXPECT_TRUE(everyEdgeSharedTwice(s));
  EXPECT_NO_THROW(s.validate());
}

TEST(TriangleMesh, ValidateNamesTheProblem)
{
  TriangleMesh m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
  m.triangles[3][1] = 42;
  const std::string badIndex = errortest::errorMessageOf([&] { m.validate(); }, ErrorCode::InvalidArgument);
  EXPECT_NE(badIndex.find("triangle 3"), std::string::npos) << badIndex;
  m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
  m.points[2][1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(m.validate(), Error);
  EXPECT_THROW(TriangleMesh().validate(), Error);
  m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
  m.triangles.push_back({ 0, 0, 1 });
  EXPECT_EQ(m.degenerateCount(), 1u);
}

// Coordinates near float's limit (3e38 reads as a float) are refused by the
// mesh's own check with its bounds, before any grid is fitted (they failed
// later as "volume origin ... on axis x"); the limit itself still passes.
TEST(TriangleMesh, ValidateRefusesCoordinatesBeyondTheWorldRange)
{
  for (float far : { 3e38f, -3e38f, 2e30f, std::numeric_limits<float>::max() })
  {
    TriangleMesh m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
    m.points[5][2] = far;
    SCOPED_TRACE(far);
    const std::string what = errortest::errorMessageOf([&] { m.validate(); }, ErrorCode::InvalidArgument);
    EXPECT_NE(what.find("mesh coordinates span x [0, 1], y [0, 1], z ["), std::string::npos) << what;
    EXPECT_NE(what.find("within +-1e+30"), std::string::npos) << what;
    EXPECT_EQ(what.find("origin"), std::string::npos) << what;
  }
  TriangleMesh m = makeBoxMesh({ -1e30f, 0, 0 }, { 1e29f, 1, 1 });
  EXPECT_NO_THROW(m.validate()); // the limit as a float (1.00000002e30) passes
  EXPECT_TRUE(isWorldCoordinate(-1e30f));
  EXPECT_FALSE(isWorldCoordinate(std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(isWorldCoordinate(std::numeric_limits<float>::quiet_NaN()));
}
