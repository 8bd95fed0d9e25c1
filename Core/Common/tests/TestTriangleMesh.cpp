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
  try
  {
    m.validate();
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("triangle 3"), std::string::npos);
  }
  m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
  m.points[2][1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(m.validate(), Error);
  EXPECT_THROW(TriangleMesh().validate(), Error);
  m = makeBoxMesh({ 0, 0, 0 }, { 1, 1, 1 });
  m.triangles.push_back({ 0, 0, 1 });
  EXPECT_EQ(m.degenerateCount(), 1u);
}
