// Mesh to SDF signs against exact winding numbers (sum of solid angles,
// Van Oosterom & Strackee, long double) on closed, holed, partly flipped,
// duplicated and intersecting meshes. Prints the wrong-sign fraction of each
// mode; WindingNumber must be right on every voxel farther than 1 voxel.
#include "../src/MeshToSdfGeometry.h"
#include "ErrorTestUtil.h"
#include "MeshToSdfOracle.h"
#include "lvdif/Error.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
using oracle::merge;

struct Case
{
  std::string name;
  TriangleMesh mesh;
};

std::vector<Case> cases()
{
  std::vector<Case> cs;
  const TriangleMesh sphere = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 10, 20);
  cs.push_back({ "closed sphere", sphere });
  cs.push_back({ "closed box", makeBoxMesh({ -0.9f, -0.7f, -0.8f }, { 0.8f, 0.9f, 0.6f }) });
  {
    // holes: drop the polar cap (a wide opening, w crosses 0.5 far from the
    // mesh) and a few scattered triangles
    TriangleMesh h = sphere;
    std::vector<std::array<std::uint32_t, 3>> kept;
    for (std::size_t t = 0; t < h.triangles.size(); ++t)
    {
      const bool cap = t < 20 * 3; // pole fan and two rings
      if (!cap && t % 29 != 5) kept.push_back(h.triangles[t]);
    }
    h.triangles = kept;
    cs.push_back({ "sphere with holes", h });
  }
  {
    TriangleMesh f = sphere;
    std::mt19937 rng(7);
    for (auto& t : f.triangles)
    {
      if (rng() % 5 == 0) std::swap(t[1], t[2]); // ~20% flipped
    }
    cs.push_back({ "20% faces flipped", f });
  }
  {
    TriangleMesh d = sphere;
    for (std::size_t t = 0; t < sphere.triangles.size(); t += 3) d.triangles.push_back(sphere.triangles[t]);
    cs.push_back({ "duplicated faces", d });
  }
  cs.push_back({ "two intersecting spheres",
    merge(makeSphereMesh(-0.35f, 0, 0, 0.8f, 8, 16), makeSphereMesh(0.4f, 0.1f, 0.05f, 0.75f, 8, 16)) });
  return cs;
}
} // namespace

TEST(MeshToSdfSign, ClosestPointMatchesOracle)
{
  // 200k random point/triangle pairs: covers every Voronoi region, including
  // the edge-AB region the original code got wrong (spec 1.4)
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  using namespace detail::meshtosdf;
  double worst = 0;
  int featureCount[7] = {};
  for (int n = 0; n < 200000; ++n)
  {
    const V3 a{ u(rng), u(rng), u(rng) }, b{ u(rng), u(rng), u(rng) }, c{ u(rng), u(rng), u(rng) },
      p{ u(rng), u(rng), u(rng) };
    const Closest cl = closestPointOnTriangle(p, a, b, c);
    ++featureCount[cl.feature];
    const double d = norm(cl.point - p);
    const double ref = static_cast<double>(std::sqrt(oracle::triangleDist2(
      { p.x, p.y, p.z }, { a.x, a.y, a.z }, { b.x, b.y, b.z }, { c.x, c.y, c.z })));
    worst = std::max(worst, std::fabs(d - ref) / std::max(ref, 1e-9));
    // the barycentric weights reproduce the point
    const V3 q = (1 - cl.b1 - cl.b2) * a + cl.b1 * b + cl.b2 * c;
    ASSERT_LT(norm(q - cl.point), 1e-9);
  }
  EXPECT_LT(worst, 1e-9);
  for (int f = 0; f < 7; ++f) EXPECT_GT(featureCount[f], 100) << "feature " << f;
}

TEST(MeshToSdfSign, WrongSignFractionsAgainstExactWindingNumbers)
{
  GridGeometry g;
  g.dims = { 24, 23, 22 };
  g.origin = { -1.55, -1.45, -1.5 };
  g.spacing = { 0.135, 0.135, 0.135 };
  const SignMode modes[3] = { SignMode::Normal, SignMode::PseudoNormal, SignMode::WindingNumber };
  for (const Case& c : cases())
  {
    // the oracle: exact winding number and distance at every voxel
    std::vector<double> w(static_cast<std::size_t>(g.count())), dist(w.size());
    for (std::int64_t k = 0; k < g.dims[2]; ++k)
      for (std::int64_t j = 0; j < g.dims[1]; ++j)
        for (std::int64_t i = 0; i < g.dims[0]; ++i)
        {
          const oracle::P p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1],
            g.origin[2] + k * g.spacing[2] };
          w[g.index(i, j, k)] = oracle::winding(c.mesh, p);
          dist[g.index(i, j, k)] = oracle::distance(c.mesh, p) / g.spacing[0];
        }
    std::string line = c.name + ":";
    for (SignMode mode : modes)
    {
      for (MeshToSdfAccel accel : { MeshToSdfAccel::Bvh, MeshToSdfAccel::Faithful })
      {
        if (accel == MeshToSdfAccel::Faithful && mode != SignMode::Normal) continue;
        MeshToSdfOptions o;
        o.sign = mode;
        o.accel = accel;
        o.device = Device::Cpu;
        std::vector<float> sdf(w.size());
        const MeshToSdfStats st = meshToSdf(c.mesh, FloatGridView{ sdf.data(), g }, o);
        std::int64_t far = 0, wrongFar = 0, ambiguous = 0;
        for (std::size_t v = 0; v < w.size(); ++v)
        {
          if (dist[v] <= 1.0) continue;
          const double aw = std::fabs(w[v]);
          if (std::fabs(aw - 0.5) < 1e-6)
          {
            ++ambiguous; // the oracle itself cannot decide
            continue;
          }
          ++far;
          const bool inside = aw >= 0.5;
          if ((sdf[v] < 0) != inside) ++wrongFar;
          ASSERT_NEAR(std::fabs(sdf[v]), dist[v], 1e-4 * std::max(1.0, dist[v]));
        }
        char buf[160];
        std::snprintf(buf, sizeof(buf), " %s%s %.4f%%", toString(mode),
          accel == MeshToSdfAccel::Faithful ? "(faithful)" : "", 100.0 * wrongFar / std::max<std::int64_t>(far, 1));
        line += buf;
        EXPECT_EQ(ambiguous, 0) << c.name;
        if (mode == SignMode::WindingNumber)
        {
          EXPECT_EQ(wrongFar, 0) << c.name << ": winding number wrong on voxels farther than 1 voxel"
                                 << " (evaluations " << st.windingEvaluations << ", exact " << st.windingExact << ")";
        }
        if (mode == SignMode::PseudoNormal && (c.name == "closed sphere" || c.name == "closed box"))
        {
          EXPECT_EQ(wrongFar, 0) << c.name << ": pseudo-normals are right on closed meshes";
        }
      }
    }
    std::printf("[ wrong-sign fraction, voxels > 1 voxel from the mesh ] %s\n", line.c_str());
  }
}

TEST(MeshToSdfSign, WindingNumberOnEveryVoxelOfAClosedMeshWithExactEvaluation)
{
  // the scan-line carry on a closed mesh: the sign must equal the exact
  // winding number everywhere, even on voxels within 1 voxel of the surface
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 10, 20);
  GridGeometry g;
  g.dims = { 25, 25, 25 };
  g.origin = { -1.3, -1.3, -1.3 };
  g.spacing = { 0.11, 0.11, 0.11 };
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  std::vector<float> sdf(static_cast<std::size_t>(g.count()));
  meshToSdf(m, FloatGridView{ sdf.data(), g }, o);
  std::int64_t wrong = 0;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
      {
        const double w = oracle::winding(m, { g.origin[0] + i * 0.11, g.origin[1] + j * 0.11, g.origin[2] + k * 0.11 });
        if (std::fabs(std::fabs(w) - 0.5) < 1e-6) continue;
        if ((sdf[g.index(i, j, k)] < 0) != (std::fabs(w) >= 0.5)) ++wrong;
      }
  EXPECT_EQ(wrong, 0);
}

TEST(MeshToSdfSign, SignVoxelFilterHookEqualsFilteringAfterwards)
{
  // the hook must be exactly "mesh to SDF, then signVoxelFilter" (composition)
  TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 10, 20);
  std::mt19937 rng(5);
  for (auto& t : m.triangles)
  {
    if (rng() % 6 == 0) std::swap(t[1], t[2]);
  }
  GridGeometry g;
  g.dims = { 26, 25, 24 };
  g.origin = { -1.4, -1.4, -1.4 };
  g.spacing = { 0.115, 0.115, 0.115 };
  MeshToSdfOptions o;
  o.sign = SignMode::Normal;
  o.device = Device::Cpu;
  std::vector<float> plain(static_cast<std::size_t>(g.count())), hooked(plain.size());
  meshToSdf(m, FloatGridView{ plain.data(), g }, o);
  o.svfFilters = SvfAll;
  const MeshToSdfStats st = meshToSdf(m, FloatGridView{ hooked.data(), g }, o);
  SignVoxelFilterParams p;
  p.filters = SvfAll;
  p.device = Device::Cpu;
  const SignVoxelFilterStats ref = signVoxelFilter(FloatGridView{ plain.data(), g }, p);
  EXPECT_EQ(hooked, plain);
  EXPECT_EQ(st.svfFlips, ref.totalFlips());
  EXPECT_GT(st.svfFlips, 0);
}

// The Normal sign with useVertexNormals takes the mesh's vertex normals
// interpolated at the closest point (PreparedMesh::cornerNormals). On a sphere
// whose normals point outwards every voxel farther than a voxel from the
// surface gets the sphere's inside/outside; with the normals pointing inwards
// every sign flips, which the face normals alone (the control) do not do.
TEST(MeshToSdfSign, VertexNormalsAreInterpolatedAtTheClosestPoint)
{
  const float c[3] = { 0.1f, -0.05f, 0.02f }, r = 1.0f;
  TriangleMesh out = makeSphereMesh(c[0], c[1], c[2], r, 20, 40);
  out.normals.resize(out.points.size());
  for (std::size_t i = 0; i < out.points.size(); ++i)
  {
    const Vec3f& p = out.points[i];
    const float d[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
    const float l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    out.normals[i] = { d[0] / l, d[1] / l, d[2] / l };
  }
  TriangleMesh in = out;
  for (Vec3f& n : in.normals) n = { -n[0], -n[1], -n[2] };
  const GridGeometry g = fitGridToMesh(out, 28, 3);
  VoxelBox all;
  all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  auto run = [&](const TriangleMesh& m, bool vertexNormals) {
    std::vector<float> f(static_cast<std::size_t>(all.voxelCount()));
    MeshToSdfOptions o;
    o.sign = SignMode::Normal;
    o.useVertexNormals = vertexNormals;
    o.device = Device::Cpu;
    meshToSdf(m, g, all, f.data(), o);
    return f;
  };
  const std::vector<float> fOut = run(out, true), fIn = run(in, true), faceIn = run(in, false);
  const double h = g.spacing[0];
  std::size_t far = 0, wrongOut = 0, notFlipped = 0, faceWrong = 0;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
      {
        const std::size_t at = static_cast<std::size_t>(i + g.dims[0] * (j + g.dims[1] * k));
        const double x = g.origin[0] + i * h - c[0], y = g.origin[1] + j * g.spacing[1] - c[1],
                     z = g.origin[2] + k * g.spacing[2] - c[2];
        const double rho = std::sqrt(x * x + y * y + z * z);
        if (std::fabs(rho - r) < 2 * h) continue; // the tessellation lies within a voxel of the sphere
        ++far;
        const bool inside = rho < r;
        wrongOut += (fOut[at] < 0) != inside;
        notFlipped += (fIn[at] < 0) == (fOut[at] < 0);
        faceWrong += (faceIn[at] < 0) != inside;
      }
  ASSERT_GT(far, 10000u);
  EXPECT_EQ(wrongOut, 0u);
  EXPECT_EQ(notFlipped, 0u);
  EXPECT_EQ(faceWrong, 0u); // the control: without them the inward normals change nothing
}

// The one parser of the sign modes' command-line names (the CLI's --sign, the
// editor's --mesh-sign): every name reads back, anything else is one error in
// the same words (the editor had its own list and words).
TEST(SignModeNames, EveryNameReadsBackAndOthersAreOneError)
{
  EXPECT_EQ(signModeFromName("normal", "--sign"), SignMode::Normal);
  EXPECT_EQ(signModeFromName("pseudo", "--sign"), SignMode::PseudoNormal);
  EXPECT_EQ(signModeFromName("winding", "--sign"), SignMode::WindingNumber);
  for (const SignMode m : { SignMode::Normal, SignMode::PseudoNormal, SignMode::WindingNumber })
    EXPECT_EQ(signModeFromName(signModeName(m), "--sign"), m) << signModeName(m);
  for (const std::string bad : { "pseudonormal", "Winding", "", "unsigned", "winding " })
  {
    EXPECT_EQ(errortest::errorMessageOf([&] { signModeFromName(bad, "--mesh-sign"); }, ErrorCode::InvalidArgument),
      "--mesh-sign must be normal, pseudo or winding, not '" + bad + "'");
  }
}
