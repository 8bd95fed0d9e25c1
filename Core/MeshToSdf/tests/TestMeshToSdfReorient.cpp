// MeshToSdfOptions::reorientFaces (WindingNumber on meshes whose face
// orientation cannot be trusted): the sign must be that of the exact winding
// number of the ORIGINAL, consistently oriented mesh (brute-force long-double
// solid angles of the undamaged mesh, MeshToSdfOracle.h) on every voxel
// farther than 1 voxel, after reversing 30 % / 70 % of the faces at random
// and duplicating some; and without the option the mesh as given is used
// (30 % reversed: the exact winding number is ~0.4 inside, so the inside is
// mostly lost: that is what the option is for).
#include "MeshToSdfOracle.h"
#include "lvdif/Cuda.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
TriangleMesh damaged(const TriangleMesh& clean, double flipFraction, double dupFraction, unsigned seed)
{
  TriangleMesh m = clean;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::size_t n = m.triangles.size();
  for (std::size_t t = 0; t < n; ++t)
  {
    if (u(rng) < flipFraction) std::swap(m.triangles[t][1], m.triangles[t][2]);
    if (u(rng) < dupFraction) m.triangles.push_back(m.triangles[t]);
  }
  return m;
}

struct Count
{
  std::int64_t far = 0, wrong = 0;
};

Count compareWith(const TriangleMesh& reference, const TriangleMesh& mesh, bool reorient, const GridGeometry& g,
  MeshToSdfStats& st)
{
  MeshToSdfOptions o;
  o.sign = SignMode::WindingNumber;
  o.reorientFaces = reorient;
  o.device = Device::Auto; // reorientFaces runs on the GPU when there is one (the same field as the CPU)
  std::vector<float> sdf(static_cast<std::size_t>(g.count()));
  st = meshToSdf(mesh, FloatGridView{ sdf.data(), g }, o);
  const double h = g.spacing[0];
  Count c;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
      {
        const oracle::P p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
        if (oracle::distance(reference, p) <= h) continue;
        ++c.far;
        const bool in = std::fabs(oracle::winding(reference, p)) >= 0.5;
        c.wrong += (sdf[static_cast<std::size_t>(g.index(i, j, k))] < 0) != in;
      }
  return c;
}

GridGeometry grid()
{
  GridGeometry g;
  g.dims = { 17, 18, 16 };
  g.origin = { -1.25, -1.3, -1.2 };
  g.spacing = { 0.15, 0.15, 0.15 };
  return g;
}
} // namespace

TEST(MeshToSdfReorient, MatchesTheUndamagedMeshAfterReversalsAndDuplicates)
{
  const TriangleMesh clean = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  for (double flip : { 0.3, 0.7 })
  {
    const TriangleMesh m = damaged(clean, flip, 0.1, 5);
    MeshToSdfStats st;
    const Count c = compareWith(clean, m, true, grid(), st);
    EXPECT_EQ(st.device, cuda::available() ? Device::Cuda : Device::Cpu);
    EXPECT_GT(c.far, grid().count() / 2);
    EXPECT_EQ(c.wrong, 0) << flip * 100 << " % reversed: " << c.wrong << " of " << c.far << " far voxels wrong";
  }
}

TEST(MeshToSdfReorient, ReversedPatchesMatchTheUndamagedMesh)
{
  // patches reversed (more faces than rim edges: the CPU's own closure is
  // M with caps over dM, the option needs M+ closed by its own caps): the
  // patches of MeshToSdfWindingFlip.ReversedPatchesClosedByCapsOverTheirRimsAreExact,
  // which checks that the CPU closes M itself there
  const TriangleMesh clean = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 16, 32);
  TriangleMesh m = clean;
  std::size_t n = 0;
  for (auto& t : m.triangles)
  {
    std::array<float, 3> c{};
    for (const std::uint32_t v : t)
      for (int k = 0; k < 3; ++k) c[k] += m.points[v][k] / 3;
    for (const std::array<float, 3>& q : { std::array<float, 3>{ 0.85f, 0.3f, 0.45f }, std::array<float, 3>{ -0.4f, -0.6f, -0.7f } })
    {
      const float d2 = (c[0] - q[0]) * (c[0] - q[0]) + (c[1] - q[1]) * (c[1] - q[1]) + (c[2] - q[2]) * (c[2] - q[2]);
      if (d2 <= 0.6f * 0.6f)
      {
        std::swap(t[1], t[2]);
        ++n;
        break;
      }
    }
  }
  ASSERT_GT(n, 40u);
  for (const bool reorient : { true, false })
  {
    MeshToSdfStats st;
    const Count c = compareWith(clean, m, reorient, grid(), st);
    EXPECT_GT(c.far, grid().count() / 2);
    if (reorient) EXPECT_EQ(c.wrong, 0) << c.wrong << " of " << c.far << " far voxels wrong";
    else EXPECT_GT(c.wrong, 0) << "as given, the patches' neighbourhood differs from the undamaged mesh";
  }
}

TEST(MeshToSdfReorient, TwoComponentsAndHolesKeepTheirOwnOrientation)
{
  // two disjoint spheres, the second one entirely inside out plus 30 % of the
  // first reversed, and a hole in the first: each component is oriented on
  // its own (|w| >= 1/2 inside either way), the hole closed by the cone
  TriangleMesh a = makeSphereMesh(-0.6f, 0, 0, 0.5f, 10, 20);
  const TriangleMesh b = makeSphereMesh(0.6f, 0, 0, 0.45f, 10, 20);
  TriangleMesh clean = oracle::merge(a, b);
  TriangleMesh m = clean;
  std::mt19937 rng(9);
  for (std::size_t t = 0; t < a.triangles.size(); ++t)
    if (rng() % 10 < 3) std::swap(m.triangles[t][1], m.triangles[t][2]);
  for (std::size_t t = a.triangles.size(); t < m.triangles.size(); ++t) std::swap(m.triangles[t][1], m.triangles[t][2]);
  m.triangles.erase(m.triangles.begin() + 40, m.triangles.begin() + 44); // a hole in the first sphere
  clean.triangles.erase(clean.triangles.begin() + 40, clean.triangles.begin() + 44);
  GridGeometry g;
  g.dims = { 26, 12, 12 };
  g.origin = { -1.25, -0.6, -0.6 };
  g.spacing = { 0.1, 0.1, 0.1 };
  MeshToSdfStats st;
  const Count c = compareWith(clean, m, true, g, st);
  EXPECT_GT(c.far, g.count() / 2);
  EXPECT_EQ(c.wrong, 0) << c.wrong << " of " << c.far << " far voxels wrong";
}

TEST(MeshToSdfReorient, WithoutTheOptionTheMeshAsGivenDecides)
{
  // the guard that the option changes something: 30 % reversed, as given,
  // loses much of the inside (w ~ 0.4 there)
  const TriangleMesh clean = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  const TriangleMesh m = damaged(clean, 0.3, 0.0, 5);
  MeshToSdfStats st;
  const Count c = compareWith(clean, m, false, grid(), st);
  EXPECT_GT(c.wrong, c.far / 50) << "as given, " << c.wrong << " of " << c.far << " far voxels differ from the undamaged mesh";
}
