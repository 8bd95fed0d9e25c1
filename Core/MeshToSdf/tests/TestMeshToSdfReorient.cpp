// MeshToSdfOptions::reorientFaces (WindingNumber on meshes whose face
// orientation cannot be trusted): the sign must be that of the exact winding
// number of the ORIGINAL, consistently oriented mesh (brute-force long-double
// solid angles of the undamaged mesh, MeshToSdfOracle.h) on every voxel
// farther than 1 voxel, after reversing 30 % / 70 % of the faces at random
// and duplicating some; and without the option the mesh as given is used
// (30 % reversed: the exact winding number is ~0.4 inside, so the inside is
// mostly lost: that is what the option is for). Also closed meshes whose
// faces all have reversed copies (every edge cancelled): the option gives
// their solid back, and every sign's warning names it.
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

namespace
{
/// `clean` with a reversed copy of every face: a closed mesh (every oriented
/// edge cancels) whose winding number is 0 everywhere, as exporters of
/// double-sided surfaces write it. firstCopies: every third face's copy comes
/// before the face itself (the faces kept once are then not all the original's).
TriangleMesh withReversedCopies(const TriangleMesh& clean, bool firstCopies)
{
  TriangleMesh m = clean;
  m.triangles.clear();
  for (std::size_t t = 0; t < clean.triangles.size(); ++t)
  {
    auto f = clean.triangles[t], r = f;
    std::swap(r[1], r[2]);
    const bool before = firstCopies && t % 3 == 0;
    m.triangles.push_back(before ? r : f);
    m.triangles.push_back(before ? f : r);
  }
  return m;
}

std::size_t faces(const TriangleMesh& m)
{
  std::size_t n = 0;
  for (const auto& t : m.triangles) n += !oracle::degenerate(m, t);
  return n;
}
} // namespace

// A closed sphere whose every face has a reversed copy: every oriented edge
// cancels, so the orientation pass did not run and --reorient computed the
// winding number of the mesh as given, 0 everywhere: nothing inside, with
// the warning that re-orienting "cannot help". Now the pass runs for M+ when
// some edge has more than two faces (each edge here has four), M+ keeps each
// pair once, and the field is the undamaged sphere's (brute-force winding
// numbers) on every voxel farther than 1 voxel; as given, the warning names
// the option instead of denying it, and says the mesh is closed once each
// pair is kept once.
TEST(MeshToSdfReorient, AClosedMeshWhoseFacesAllHaveReversedCopiesGetsItsSolidBack)
{
  const TriangleMesh clean = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  for (const bool firstCopies : { false, true })
  {
    const TriangleMesh m = withReversedCopies(clean, firstCopies);
    MeshToSdfStats st;
    const Count fixed = compareWith(clean, m, true, grid(), st);
    EXPECT_EQ(st.boundaryEdges, 0u); // the premise: closed as given
    EXPECT_GT(fixed.far, grid().count() / 2);
    EXPECT_EQ(fixed.wrong, 0) << fixed.wrong << " of " << fixed.far << " far voxels wrong";
    EXPECT_TRUE(st.warnings.empty()) << st.warnings[0];
    const Count given = compareWith(clean, m, false, grid(), st);
    EXPECT_GT(given.wrong, given.far / 10); // w = 0: the inside is lost as given
    ASSERT_EQ(st.warnings.size(), 1u);
    EXPECT_NE(st.warnings[0].find("--reorient"), std::string::npos) << st.warnings[0];
    EXPECT_EQ(st.warnings[0].find("cannot help"), std::string::npos) << st.warnings[0];
    // kept once, the pairs close the sphere whichever copy comes first (it
    // said "still has 512 boundary edges" when some copies came first)
    EXPECT_NE(st.warnings[0].find("closed once each is kept once"), std::string::npos) << st.warnings[0];
  }
}

// The same closed double-sided sphere beside a clean box, in every sign: the
// box keeps voxels inside, so the "nothing inside" warning does not speak,
// and the duplicates of a closed mesh were not looked for (to keep clean
// closed meshes' calls free): the winding sign dropped the sphere (w = 0) and
// the normal and pseudo-normal signs read cancelled normals at its edges and
// corners, without a word. Now one warning counts the cancelled faces (every
// face of the sphere and its copy) and names --reorient, which gives both
// solids (brute-force winding numbers of the undamaged mesh). A closed mesh
// with edges of more than two faces but no duplicates (two boxes sharing an
// edge), or whose sphere is doubled in one orientation (w = 2 inside, the
// same field), is not warned about.
TEST(MeshToSdfReorient, ReversedCopiesOfAClosedPartAreNamedInEverySign)
{
  const TriangleMesh sphere = makeSphereMesh(-0.45f, -0.03f, 0.02f, 0.7f, 10, 20);
  const TriangleMesh box = makeBoxMesh({ 0.3f, -0.5f, -0.45f }, { 0.9f, 0.2f, 0.5f });
  const TriangleMesh clean = oracle::merge(sphere, box);
  const TriangleMesh m = oracle::merge(withReversedCopies(sphere, true), box);
  const std::size_t cancelled = 2 * faces(sphere);
  GridGeometry g;
  g.dims = { 27, 16, 16 };
  g.origin = { -1.3, -0.8, -0.7 };
  g.spacing = { 0.1, 0.1, 0.1 };
  for (const SignMode s : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Normal })
  {
    MeshToSdfOptions o;
    o.sign = s;
    o.device = Device::Cpu;
    std::vector<float> sdf(static_cast<std::size_t>(g.count()));
    const MeshToSdfStats st = meshToSdf(m, FloatGridView{ sdf.data(), g }, o);
    ASSERT_EQ(st.warnings.size(), 1u) << toString(s);
    const std::string& w = st.warnings[0];
    EXPECT_NE(w.find(std::to_string(cancelled) + " faces are cancelled by exact duplicates of opposite orientation"),
      std::string::npos) << w;
    EXPECT_NE(w.find("--reorient"), std::string::npos) << w;
    // the clean mesh, one-orientation doubling and a shared edge: no word
    for (const TriangleMesh& quiet : { clean, oracle::merge(clean, sphere),
           oracle::merge(box, makeBoxMesh({ 0.9f, 0.2f, -0.45f }, { 1.2f, 0.5f, 0.5f })) })
    {
      const MeshToSdfStats q = meshToSdf(quiet, FloatGridView{ sdf.data(), g }, o);
      EXPECT_TRUE(q.warnings.empty()) << toString(s) << ": " << q.warnings[0];
    }
  }
  MeshToSdfStats st;
  const Count fixed = compareWith(clean, m, true, g, st);
  EXPECT_GT(fixed.far, g.count() / 2);
  EXPECT_EQ(fixed.wrong, 0) << fixed.wrong << " of " << fixed.far << " far voxels wrong";
  EXPECT_TRUE(st.warnings.empty());
}
