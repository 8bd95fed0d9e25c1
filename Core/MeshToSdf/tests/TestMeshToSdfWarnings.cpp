// Warnings when the field cannot be what the user expects: a signed field over
// the whole grid with no voxel inside (an open sheet that encloses no volume,
// or voxels larger than the mesh's parts). Checked against the output itself:
// a warning exactly when no voxel is deeper than 1 voxel inside, naming the
// cause and the option that helps (and the option is shown to help). And a
// warning when the winding sign met faces reversed against their neighbours
// or duplicates that cancel, with counts checked against the damage done.
#include "MeshToSdfDamagedMeshes.h"
#include "lvdif/Cuda.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace lvdif;

namespace
{
/// A flat tilted open sheet of n x n quads over [-1, 1]^2 (no volume enclosed).
TriangleMesh sheet(int n)
{
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
    {
      const float x = -1.0f + 2.0f * i / n, y = -1.0f + 2.0f * j / n;
      m.points.push_back({ x, y, 0.02f * x - 0.05f * y + 0.013f });
    }
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return m;
}

/// Two small closed boxes far apart.
TriangleMesh twoSmallBoxes()
{
  TriangleMesh a = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 0.5f, 0.5f, 0.5f });
  const TriangleMesh b = makeBoxMesh({ 10.0f, 10.0f, 10.0f }, { 10.5f, 10.5f, 10.5f });
  const auto n = static_cast<std::uint32_t>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.triangles) a.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  return a;
}

/// Voxels deeper than 1 voxel inside (voxel units): what the warnings are about.
std::int64_t deepInside(const std::vector<float>& v)
{
  std::int64_t n = 0;
  for (float x : v) n += x < -1.0f;
  return n;
}

struct Result
{
  MeshToSdfStats stats;
  std::int64_t inside = 0;
};

Result runFloat(const TriangleMesh& m, std::int64_t res, SignMode sign, unsigned svfFilters = 0)
{
  const GridGeometry g = fitGridToMesh(m, res, 2.0);
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  o.sign = sign;
  o.device = Device::Cpu;
  o.svfFilters = svfFilters;
  Result r;
  r.stats = meshToSdf(m, FloatGridView{ out.data(), g }, o);
  r.inside = deepInside(out);
  return r;
}

bool mentions(const MeshToSdfStats& s, const std::string& what)
{
  return s.warnings.size() == 1 && s.warnings[0].find(what) != std::string::npos;
}
} // namespace

TEST(MeshToSdfWarnings, OpenSheetEnclosesNoVolume)
{
  const TriangleMesh m = sheet(12);
  const Result w = runFloat(m, 40, SignMode::WindingNumber);
  EXPECT_EQ(w.inside, 0); // the premise: |w| < 1/2 except in a film near the sheet
  ASSERT_EQ(w.stats.warnings.size(), 1u);
  EXPECT_TRUE(mentions(w.stats, "encloses no volume")) << w.stats.warnings[0];
  EXPECT_TRUE(mentions(w.stats, "pseudo-normal"));
  // by the name of each front end's option (it named none: the CLI has no unsigned distance at all)
  EXPECT_TRUE(mentions(w.stats, "(--sign pseudo, lvdif-editor --mesh-sign pseudo, vtkMeshToSDF's PSEUDO_NORMAL, the editor's \"Pseudo-normal\""));
  // the option it names helps: each side of the sheet gets its own sign
  const Result pn = runFloat(m, 40, SignMode::PseudoNormal);
  EXPECT_GT(pn.inside, 0);
  EXPECT_TRUE(pn.stats.warnings.empty());
  // unsigned fields are never "inside"
  EXPECT_TRUE(runFloat(m, 40, SignMode::Unsigned).stats.warnings.empty());
  // into a dictionary volume too
  const GridGeometry g = fitGridToMesh(m, 40, 2.0);
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(mentions(meshToSdf(m, vol, o), "encloses no volume"));
}

// A part thinner than a voxel can still cross zero: a grid point inside it lies
// within a voxel of its surface. The warning that no voxel is deeper than one
// voxel inside said "the field has no zero crossing and meshing it gives no
// surface", while a new user's thin cylinder meshed to 976 triangles: it now
// says what is true, no surface or slivers at most.
TEST(MeshToSdfWarnings, AThinPartsWarningDoesNotDenyItsSlivers)
{
  const TriangleMesh m = makeBoxMesh({ 0.0f, -0.15f, -0.15f }, { 10.0f, 0.15f, 0.15f });
  GridGeometry g;
  g.dims = { 25, 5, 5 };
  g.spacing = { 0.5, 0.5, 0.5 };
  g.origin = { -1.0, -1.0, -1.0 }; // the row of points y = z = 0 runs inside the box
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  const MeshToSdfStats s = meshToSdf(m, FloatGridView{ out.data(), g }, o);
  EXPECT_LT(*std::min_element(out.begin(), out.end()), 0.0f) << "the premise: grid points inside the box";
  EXPECT_EQ(deepInside(out), 0);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("larger than the mesh's parts"), std::string::npos) << s.warnings[0];
  EXPECT_EQ(s.warnings[0].find("no zero crossing"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("at most slivers"), std::string::npos) << s.warnings[0];
}

TEST(MeshToSdfWarnings, VoxelsLargerThanTheParts)
{
  const TriangleMesh m = twoSmallBoxes();
  const Result coarse = runFloat(m, 8, SignMode::WindingNumber);
  EXPECT_EQ(coarse.inside, 0);
  EXPECT_TRUE(mentions(coarse.stats, "more voxels")) << (coarse.stats.warnings.empty() ? "" : coarse.stats.warnings[0]);
  // the option it names helps
  const Result fine = runFloat(m, 128, SignMode::WindingNumber);
  EXPECT_GT(fine.inside, 0);
  EXPECT_TRUE(fine.stats.warnings.empty());
}

// An explicit grid beside the mesh, or over a corner of its bounds that is
// outside it (a tiny spacing), has nothing inside for another reason than the
// voxels' size, which the warning named.
TEST(MeshToSdfWarnings, GridBesideTheMeshOrOverAPartOfItsBounds)
{
  const TriangleMesh sphere = makeSphereMesh(0, 0, 0, 1, 10, 20);
  auto warningOn = [&](std::array<double, 3> origin, double spacing) {
    GridGeometry g;
    g.dims = { 8, 8, 8 };
    g.origin = origin;
    g.spacing = { spacing, spacing, spacing };
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    MeshToSdfOptions o;
    o.device = Device::Cpu;
    const MeshToSdfStats st = meshToSdf(sphere, FloatGridView{ out.data(), g }, o);
    EXPECT_EQ(deepInside(out), 0);
    return st.warnings.empty() ? std::string() : st.warnings[0];
  };
  const std::string beside = warningOn({ 5, 5, 5 }, 0.1);
  EXPECT_NE(beside.find("the grid does not reach the mesh"), std::string::npos) << beside;
  EXPECT_NE(beside.find("[5, 5.7]"), std::string::npos) << beside;
  EXPECT_EQ(beside.find("larger than the mesh's parts"), std::string::npos) << beside;
  const std::string corner = warningOn({ 0.9, 0.9, 0.9 }, 1e-6);
  EXPECT_NE(corner.find("covers only a part of the mesh's bounds"), std::string::npos) << corner;
  EXPECT_EQ(corner.find("larger than the mesh's parts"), std::string::npos) << corner;
}

// A part smaller than a voxel beside a large one: the large one has voxels
// inside, the small one none (so no surface), and it vanished without a word
// (the warning came only when nothing at all was inside). The premise is read
// from the output: no voxel within a voxel of the small box is negative.
TEST(MeshToSdfWarnings, PartsSmallerThanAVoxelVanish)
{
  TriangleMesh m = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 6.0f, 6.0f, 6.0f });
  const TriangleMesh small = makeBoxMesh({ 10.0f, 3.0f, 3.0f }, { 10.1f, 3.1f, 3.1f });
  const auto n = static_cast<std::uint32_t>(m.points.size());
  m.points.insert(m.points.end(), small.points.begin(), small.points.end());
  for (auto t : small.triangles) m.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  // negative voxels within one voxel of the small box, and deep inside voxels anywhere
  auto run = [&](std::int64_t res, std::int64_t& nearSmall) {
    const GridGeometry g = fitGridToMesh(m, res, 2.0);
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    MeshToSdfOptions o;
    o.device = Device::Cpu;
    const MeshToSdfStats st = meshToSdf(m, FloatGridView{ out.data(), g }, o);
    nearSmall = 0;
    for (std::int64_t k = 0; k < g.dims[2]; ++k)
      for (std::int64_t j = 0; j < g.dims[1]; ++j)
        for (std::int64_t i = 0; i < g.dims[0]; ++i)
        {
          const double p[3] = { g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1],
            g.origin[2] + k * g.spacing[2] };
          const double lo[3] = { 10.0, 3.0, 3.0 }, hi[3] = { 10.1, 3.1, 3.1 };
          bool near = true;
          for (int a = 0; a < 3; ++a) near = near && p[a] > lo[a] - g.spacing[a] && p[a] < hi[a] + g.spacing[a];
          nearSmall += near && out[static_cast<std::size_t>(g.index(i, j, k))] < 0.0f;
        }
    EXPECT_GT(deepInside(out), 0) << res; // the large box is there
    return st;
  };
  std::int64_t nearSmall = -1;
  const MeshToSdfStats coarse = run(24, nearSmall);
  ASSERT_EQ(nearSmall, 0); // the premise: the small box left no inside voxel
  EXPECT_TRUE(mentions(coarse, "1 of 2 parts of the mesh")) << (coarse.warnings.empty() ? "" : coarse.warnings[0]);
  EXPECT_TRUE(mentions(coarse, "more voxels"));
  // the option it names helps: at 0.05-voxel spacing the small box has voxels inside
  const MeshToSdfStats fine = run(256, nearSmall);
  EXPECT_GT(nearSmall, 0);
  EXPECT_TRUE(fine.warnings.empty()) << fine.warnings[0];
  // into a dictionary volume too
  const GridGeometry g = fitGridToMesh(m, 24, 2.0);
  DictionaryVolume vol(volumeOptionsOn(g));
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(mentions(meshToSdf(m, vol, o), "1 of 2 parts of the mesh"));
}

// A small part far from a large one sets the mesh's bounds, and the fitted
// grid puts a grid point on those bounds: in double arithmetic that point fell
// a hair inside the part (29.000000000000004 voxels against a bound at 29), so
// the part counted as holding a voxel centre, and `lvdif mesh-to-sdf` of a
// 10-unit cube with a 0.05-unit cube 20 units away (--dims 32) lost the small
// cube without a word. The oracle is the output: wherever no voxel within a
// voxel of the small box is negative, the warning names it.
TEST(MeshToSdfWarnings, PartsOnTheFittedBoundsVanishWithAWarning)
{
  int checked = 0;
  for (float at : { 30.0f, 17.0f, 55.5f, 101.25f })
    for (std::int64_t res : { 16, 24, 32, 40, 57 })
    {
      TriangleMesh m = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 10.0f, 10.0f, 10.0f });
      const float lo[3] = { at, at, at }, hi[3] = { at + 0.05f, at + 0.05f, at + 0.05f };
      const TriangleMesh small = makeBoxMesh({ lo[0], lo[1], lo[2] }, { hi[0], hi[1], hi[2] });
      const auto n = static_cast<std::uint32_t>(m.points.size());
      m.points.insert(m.points.end(), small.points.begin(), small.points.end());
      for (auto t : small.triangles) m.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
      const GridGeometry g = fitGridToMesh(m, res, 2.0);
      std::vector<float> out(static_cast<std::size_t>(g.count()));
      MeshToSdfOptions o;
      o.device = Device::Cpu;
      const MeshToSdfStats st = meshToSdf(m, FloatGridView{ out.data(), g }, o);
      std::int64_t nearSmall = 0;
      for (std::int64_t k = 0; k < g.dims[2]; ++k)
        for (std::int64_t j = 0; j < g.dims[1]; ++j)
          for (std::int64_t i = 0; i < g.dims[0]; ++i)
          {
            const double p[3] = { g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1],
              g.origin[2] + k * g.spacing[2] };
            bool near = true;
            for (int a = 0; a < 3; ++a) near = near && p[a] > lo[a] - g.spacing[a] && p[a] < hi[a] + g.spacing[a];
            nearSmall += near && out[static_cast<std::size_t>(g.index(i, j, k))] < 0.0f;
          }
      // (not the case under test: the small box has a voxel inside, or the large one none)
      if (nearSmall > 0 || deepInside(out) == 0) continue;
      ++checked;
      EXPECT_TRUE(mentions(st, "1 of 2 parts of the mesh"))
        << "small box at " << at << ", --dims " << res << ": " << (st.warnings.empty() ? "no warning" : st.warnings[0]);
    }
  EXPECT_GE(checked, 15); // the premise held in most of the cases
}

// On CUDA the parts are found on a thread of their own while the GPU computes
// the distances (partsBesideGpu): the same warning, into a float grid and a
// dictionary volume, on a fresh prepared mesh each time and on one reused
// (whose parts are found already).
TEST(MeshToSdfWarnings, PartsSmallerThanAVoxelVanishOnCuda)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  TriangleMesh m = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 6.0f, 6.0f, 6.0f });
  const TriangleMesh small = makeBoxMesh({ 10.0f, 3.0f, 3.0f }, { 10.1f, 3.1f, 3.1f });
  const auto n = static_cast<std::uint32_t>(m.points.size());
  m.points.insert(m.points.end(), small.points.begin(), small.points.end());
  for (auto t : small.triangles) m.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  const GridGeometry g = fitGridToMesh(m, 24, 2.0);
  MeshToSdfOptions o;
  o.device = Device::Cuda;
  for (SignMode sign : { SignMode::WindingNumber, SignMode::PseudoNormal })
  {
    o.sign = sign;
    const MeshToSdfPrepared reused = prepareMeshToSdf(m, o.sign);
    for (int call = 0; call < 2; ++call)
    {
      std::vector<float> out(static_cast<std::size_t>(g.count()));
      const MeshToSdfStats grid = meshToSdf(prepareMeshToSdf(m, o.sign), FloatGridView{ out.data(), g }, o);
      EXPECT_EQ(grid.device, Device::Cuda);
      EXPECT_GT(deepInside(out), 0);
      EXPECT_TRUE(mentions(grid, "1 of 2 parts of the mesh")) << call;
      EXPECT_TRUE(mentions(meshToSdf(reused, FloatGridView{ out.data(), g }, o), "1 of 2 parts of the mesh")) << call;
      DictionaryVolume vol(volumeOptionsOn(g));
      const MeshToSdfStats volume = meshToSdf(reused, vol, o);
      EXPECT_EQ(volume.device, Device::Cuda);
      EXPECT_TRUE(mentions(volume, "1 of 2 parts of the mesh")) << call;
    }
  }
}

// The parts are found by a union-find on all threads: many small parts and a
// long strip, their vertices shuffled through the vertex array so that the
// threads link the same sets concurrently, with unused vertices between them.
// The count the warning gives is that of the construction: every small part
// and the strip vanish, the large box does not.
TEST(MeshToSdfWarnings, PartsAreCountedOnAllThreads)
{
  TriangleMesh parts = makeBoxMesh({ 0.0f, 0.0f, 0.0f }, { 6.0f, 6.0f, 6.0f });
  constexpr int smallBoxes = 1500, strip = 1000;
  for (int b = 0; b < smallBoxes; ++b)
  {
    const float x = 8.0f + 0.2f * static_cast<float>(b % 30), y = 0.2f * static_cast<float>(b / 30 % 25),
                z = 1.0f + 0.1f * static_cast<float>(b / 750);
    const TriangleMesh box = makeBoxMesh({ x, y, z }, { x + 0.01f, y + 0.01f, z + 0.01f });
    const auto n = static_cast<std::uint32_t>(parts.points.size());
    parts.points.insert(parts.points.end(), box.points.begin(), box.points.end());
    for (auto t : box.triangles) parts.triangles.push_back({ t[0] + n, t[1] + n, t[2] + n });
  }
  // a strip of triangles (i, i+1, i+2) along a small helix: one part
  const auto first = static_cast<std::uint32_t>(parts.points.size());
  for (int i = 0; i < strip + 2; ++i)
  {
    const float a = 0.05f * static_cast<float>(i);
    parts.points.push_back({ 3.0f + 0.02f * std::cos(a), 8.0f + 0.02f * std::sin(a), 3.0f + 0.00004f * i });
  }
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(strip); ++i) // consistently oriented
    parts.triangles.push_back(i % 2 ? std::array<std::uint32_t, 3>{ first + i + 1, first + i, first + i + 2 }
                                    : std::array<std::uint32_t, 3>{ first + i, first + i + 1, first + i + 2 });
  // shuffle the vertex ids (a fixed permutation) and leave unused vertices between them
  const std::size_t nv = parts.points.size();
  std::vector<std::uint32_t> newId(nv);
  std::iota(newId.begin(), newId.end(), 0u);
  std::mt19937 rng(7);
  std::shuffle(newId.begin(), newId.end(), rng);
  TriangleMesh m;
  m.points.assign(2 * nv, { 3.0f, 3.0f, 3.0f }); // unused, inside the large box
  for (std::size_t v = 0; v < nv; ++v) m.points[2 * std::size_t{ newId[v] }] = parts.points[v];
  for (auto t : parts.triangles) m.triangles.push_back({ 2 * newId[t[0]], 2 * newId[t[1]], 2 * newId[t[2]] });
  const int before = omp_get_max_threads();
  omp_set_num_threads(8);
  const Result r = runFloat(m, 24, SignMode::WindingNumber);
  omp_set_num_threads(before);
  EXPECT_GT(r.inside, 0);
  EXPECT_TRUE(mentions(r.stats, std::to_string(smallBoxes + 1) + " of " + std::to_string(smallBoxes + 2) +
                                  " parts of the mesh"))
    << ::testing::PrintToString(r.stats.warnings);
}

TEST(MeshToSdfWarnings, NoneForAClosedMeshOrAPiece)
{
  const TriangleMesh sphere = makeSphereMesh(0, 0, 0, 1, 10, 20);
  for (SignMode s : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Normal })
  {
    const Result r = runFloat(sphere, 24, s);
    EXPECT_GT(r.inside, 0);
    EXPECT_TRUE(r.stats.warnings.empty()) << toString(s);
  }
  // a piece of a grid that has nothing inside is not the user's whole field
  const TriangleMesh m = sheet(6);
  const GridGeometry g = fitGridToMesh(m, 24, 2.0);
  VoxelBox piece;
  piece.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] / 2 };
  std::vector<float> out(static_cast<std::size_t>(piece.voxelCount()));
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(meshToSdf(m, g, piece, out.data(), o).warnings.empty());
}

// A band of at most 1 voxel saturates every inside voxel at -band, so none is
// "deeper than 1 voxel": the closed sphere got the warning that meshing gives
// no surface (CLI --band 1, vtkMeshToSDF BandWidth 0.5) although it does.
TEST(MeshToSdfWarnings, NoneForAClosedMeshWithANarrowBand)
{
  const TriangleMesh sphere = makeSphereMesh(0, 0, 0, 1, 16, 32);
  for (float band : { 1.0f, 0.5f, 0.25f })
  {
    const GridGeometry g = fitGridToMesh(sphere, 24, 2.0);
    // the oracle: voxel centres more than 1 voxel inside the analytic sphere
    // (radius 1 less the tessellation's sagitta) exist, and are negative
    const double h = g.spacing[0], r = 1.0 - 0.03;
    std::int64_t deep = 0;
    for (std::int64_t z = 0; z < g.dims[2]; ++z)
      for (std::int64_t y = 0; y < g.dims[1]; ++y)
        for (std::int64_t x = 0; x < g.dims[0]; ++x)
        {
          const double p[3] = { g.origin[0] + h * x, g.origin[1] + h * y, g.origin[2] + h * z };
          deep += std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) < r - h;
        }
    ASSERT_GT(deep, 0);
    VolumeOptions vo = volumeOptionsOn(g);
    vo.bandWidth = band;
    vo.chunkEdge = 16;
    DictionaryVolume vol(vo);
    MeshToSdfOptions o;
    o.device = Device::Cpu;
    const MeshToSdfStats s = meshToSdf(sphere, vol, o);
    EXPECT_TRUE(s.warnings.empty()) << "band " << band << ": " << s.warnings[0];
    EXPECT_LT(vol.sdf(g.dims[0] / 2, g.dims[1] / 2, g.dims[2] / 2), 0.0f);
    // the float grid with the same band
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    o.bandWidth = band;
    const MeshToSdfStats f = meshToSdf(sphere, FloatGridView{ out.data(), g }, o);
    EXPECT_TRUE(f.warnings.empty()) << "band " << band << ": " << f.warnings[0];
  }
  // voxels larger than the parts still get the warning with a narrow band
  const TriangleMesh boxes = twoSmallBoxes();
  const GridGeometry g = fitGridToMesh(boxes, 8, 2.0);
  VolumeOptions vo = volumeOptionsOn(g);
  vo.bandWidth = 0.5f;
  DictionaryVolume vol(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  EXPECT_TRUE(mentions(meshToSdf(boxes, vol, o), "more voxels"));
}

namespace
{
double area2(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t)
{
  const auto& a = m.points[t[0]];
  const auto& b = m.points[t[1]];
  const auto& c = m.points[t[2]];
  const double u[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
  const double v[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return x * x + y * y + z * z;
}

/// The number in the warning right before `what` ("123 of ..." / "45 faces are cancelled").
long long countBefore(const std::string& w, const std::string& what)
{
  const std::size_t at = w.find(what);
  if (at == std::string::npos || at == 0) return -1;
  std::size_t b = at;
  while (b > 0 && w[b - 1] >= '0' && w[b - 1] <= '9') --b;
  return b == at ? -1 : std::stoll(w.substr(b, at - b));
}

/// Brute force over the faces of non-zero area, by their corners' positions
/// (std::map, no welding of the code under test): faces beyond the first of
/// each set of three corners, those cancelled by a copy of opposite
/// orientation (group size - |net|) and those doubling one in the same
/// orientation (|net| - 1); and edges of non-zero net multiplicity.
struct DuplicateOracle
{
  long long copies = 0, opposed = 0, stacked = 0, boundaryEdges = 0;
};
DuplicateOracle duplicateOracle(const TriangleMesh& m)
{
  using P = std::array<float, 3>;
  std::map<std::array<P, 3>, std::vector<int>> groups; // sorted corners -> +-1 per face
  std::map<std::pair<P, P>, int> edges;
  for (const auto& t : m.triangles)
  {
    if (area2(m, t) == 0) continue;
    const std::array<P, 3> c{ m.points[t[0]], m.points[t[1]], m.points[t[2]] };
    std::array<P, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    // +1 when the face runs its sorted corners in cyclic order
    int parity = -1;
    for (int k = 0; k < 3; ++k) parity = c[k] == sorted[0] && c[(k + 1) % 3] == sorted[1] ? 1 : parity;
    groups[sorted].push_back(parity);
    for (int k = 0; k < 3; ++k)
    {
      const P a = c[k], b = c[(k + 1) % 3];
      edges[{ std::min(a, b), std::max(a, b) }] += a < b ? 1 : -1;
    }
  }
  DuplicateOracle o;
  for (const auto& [key, dirs] : groups)
  {
    const long long size = static_cast<long long>(dirs.size());
    const long long net = std::abs(std::accumulate(dirs.begin(), dirs.end(), 0LL));
    o.copies += size - 1;
    o.opposed += size - net;
    o.stacked += std::max(0LL, net - 1);
  }
  for (const auto& [e, mult] : edges) o.boundaryEdges += mult != 0;
  return o;
}

/// makeBoxMesh's box with copies of its faces `which` (reversed or not).
TriangleMesh boxWithCopies(const std::vector<int>& which, bool reversed)
{
  TriangleMesh m = makeBoxMesh({ 0.1f, 0.2f, 0.3f }, { 1.1f, 0.9f, 1.25f });
  for (int t : which)
  {
    auto f = m.triangles[static_cast<std::size_t>(t)];
    if (reversed) std::swap(f[1], f[2]);
    m.triangles.push_back(f);
  }
  return m;
}

/// Grid points strictly inside the box [lo, hi] (by their coordinates):
/// the voxels a field of the box has inside.
std::int64_t pointsInsideBox(const GridGeometry& g, const Vec3f& lo, const Vec3f& hi)
{
  std::int64_t n[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
    for (std::int64_t i = 0; i < g.dims[a]; ++i)
    {
      const double x = g.origin[a] + g.spacing[a] * static_cast<double>(i);
      n[a] += x > lo[a] + 1e-6 && x < hi[a] - 1e-6;
    }
  return n[0] * n[1] * n[2];
}
} // namespace

// A closed box with two of its faces (4 triangles) duplicated in the same
// orientation: the copies' edges do not cancel, so the CLI said "8 boundary
// edges" as of an open mesh, and no warning named the duplicates. Now one
// warning, in every sign mode, counts them, says the mesh is closed once
// each is kept once and names the option that keeps them once; the field is
// the box's (grid points inside it, counted from their coordinates).
TEST(MeshToSdfWarnings, DuplicatedFacesOfAClosedMeshAreNamedNotCalledOpen)
{
  const TriangleMesh m = boxWithCopies({ 0, 1, 2, 3 }, false); // the z = lo and z = hi quads
  const DuplicateOracle d = duplicateOracle(m);
  ASSERT_EQ(d.copies, 4);
  ASSERT_EQ(d.stacked, 4);
  ASSERT_EQ(d.boundaryEdges, 8); // the premise: each copied quad's 4 outer edges
  const GridGeometry g = fitGridToMesh(m, 48, 2.0);
  const std::int64_t inside = pointsInsideBox(g, { 0.1f, 0.2f, 0.3f }, { 1.1f, 0.9f, 1.25f });
  for (const SignMode s : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Normal })
  {
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    MeshToSdfOptions o;
    o.sign = s;
    o.device = Device::Cpu;
    const MeshToSdfStats st = meshToSdf(m, FloatGridView{ out.data(), g }, o);
    EXPECT_EQ(static_cast<long long>(st.boundaryEdges), d.boundaryEdges);
    std::int64_t negative = 0;
    for (float v : out) negative += v < 0;
    EXPECT_EQ(negative, inside) << toString(s); // the box's field, as the warning says
    ASSERT_EQ(st.warnings.size(), 1u) << toString(s);
    const std::string& w = st.warnings[0];
    EXPECT_EQ(countBefore(w, " of the mesh's 16 faces are exact duplicates"), d.copies) << w;
    EXPECT_EQ(countBefore(w, " doubled in the same orientation"), d.stacked) << w;
    EXPECT_NE(w.find("closed once each is kept once"), std::string::npos) << w;
    EXPECT_NE(w.find("8 edges of non-zero net multiplicity"), std::string::npos) << w; // the CLI's summary's words
    EXPECT_EQ(w.find("open ("), std::string::npos) << w;
    EXPECT_NE(w.find("--reorient"), std::string::npos) << w;
  }
  // the option it names keeps each copy once: no boundary left, no warning
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  o.reorientFaces = true;
  EXPECT_TRUE(meshToSdf(m, FloatGridView{ out.data(), g }, o).warnings.empty());
  // and the box itself warns of nothing
  EXPECT_TRUE(runFloat(makeBoxMesh({ 0.1f, 0.2f, 0.3f }, { 1.1f, 0.9f, 1.25f }), 48, SignMode::WindingNumber).stats.warnings.empty());
}

// A closed box whose every face has a reversed copy: the winding number is 0
// everywhere, so nothing is inside; the warning said "the voxels ... are
// larger than the mesh's parts" (use more voxels: no help at any resolution).
// Now it names the cancelled duplicates and says the mesh is closed once
// each is kept once; never "open" nor "more voxels".
TEST(MeshToSdfWarnings, ABoxWhoseFacesAllCancelIsNotBlamedOnTheVoxels)
{
  const TriangleMesh m = boxWithCopies({ 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 }, true);
  const DuplicateOracle d = duplicateOracle(m);
  ASSERT_EQ(d.copies, 12);
  ASSERT_EQ(d.opposed, 24);
  ASSERT_EQ(d.boundaryEdges, 0);
  for (const std::int64_t res : { 32, 96 })
  {
    const Result r = runFloat(m, res, SignMode::WindingNumber);
    EXPECT_EQ(r.inside, 0); // the premise: w = 0 everywhere
    ASSERT_EQ(r.stats.warnings.size(), 1u);
    const std::string& w = r.stats.warnings[0];
    EXPECT_EQ(countBefore(w, " of the mesh's 24 faces are exact duplicates"), d.copies) << w;
    EXPECT_EQ(countBefore(w, " faces are cancelled by exact duplicates of opposite orientation"), d.opposed) << w;
    EXPECT_NE(w.find("closed once each is kept once"), std::string::npos) << w;
    EXPECT_NE(w.find("remove the duplicated faces"), std::string::npos) << w;
    EXPECT_EQ(w.find("larger than the mesh's parts"), std::string::npos) << w;
    EXPECT_EQ(w.find("more voxels"), std::string::npos) << w;
    EXPECT_EQ(w.find("open ("), std::string::npos) << w;
  }
}

TEST(MeshToSdfWarnings, ReversedFacesNameReorient)
{
  const TriangleMesh clean = oracle::bumpySphere();
  const TriangleMesh patched = signquality::damaged(clean, "patch10");
  // the oracle: faces whose corners the damage put in reverse order (of
  // non-zero area: degenerate faces are skipped by the preparation)
  long long reversed = 0;
  for (std::size_t t = 0; t < clean.triangles.size(); ++t)
    reversed += patched.triangles[t] != clean.triangles[t] && area2(clean, clean.triangles[t]) > 0;
  ASSERT_GT(reversed, 0);

  const Result given = runFloat(patched, 48, SignMode::WindingNumber);
  ASSERT_EQ(given.stats.warnings.size(), 1u);
  const std::string& w = given.stats.warnings[0];
  EXPECT_NE(w.find("--reorient"), std::string::npos) << w;
  EXPECT_NE(w.find("ReorientFaces"), std::string::npos) << w;
  EXPECT_EQ(countBefore(w, " of " + std::to_string(given.stats.triangles) + " faces"), reversed) << w;

  // what it says holds: the field as given has voxels outside that lie deep
  // inside the re-oriented solid (extra surfaces), and the option it names
  // removes them and the warning
  const GridGeometry g = fitGridToMesh(patched, 48, 2.0);
  std::vector<float> asGiven(static_cast<std::size_t>(g.count())), fixed(asGiven.size());
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  meshToSdf(patched, FloatGridView{ asGiven.data(), g }, o);
  o.reorientFaces = true;
  EXPECT_TRUE(meshToSdf(patched, FloatGridView{ fixed.data(), g }, o).warnings.empty());
  std::int64_t carved = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i) carved += fixed[i] < -1.0f && asGiven[i] > 0.0f;
  EXPECT_GT(carved, 0);

  // into a dictionary volume too; and never for a consistent mesh, nor for
  // signs that do not run the orientation pass
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 16;
  DictionaryVolume vol(vo);
  o.reorientFaces = false;
  EXPECT_TRUE(mentions(meshToSdf(patched, vol, o), "run against their neighbours"));
  EXPECT_TRUE(runFloat(clean, 48, SignMode::WindingNumber).stats.warnings.empty());
  EXPECT_TRUE(runFloat(patched, 48, SignMode::Unsigned).stats.warnings.empty());
}

TEST(MeshToSdfWarnings, DuplicatesOfOppositeOrientation)
{
  const TriangleMesh clean = oracle::bumpySphere();
  const TriangleMesh dup = signquality::damaged(clean, "duprev20");
  // the oracle: every appended copy in reverse order cancels its original
  long long opposed = 0;
  ASSERT_GT(dup.triangles.size(), clean.triangles.size());
  for (std::size_t t = clean.triangles.size(); t < dup.triangles.size(); ++t)
  {
    const auto& f = dup.triangles[t];
    const bool reversedCopy = std::find(clean.triangles.begin(), clean.triangles.end(), f) == clean.triangles.end();
    opposed += reversedCopy && area2(dup, f) > 0 ? 2 : 0;
  }
  ASSERT_GT(opposed, 0);
  const Result r = runFloat(dup, 32, SignMode::WindingNumber);
  ASSERT_EQ(r.stats.warnings.size(), 1u);
  EXPECT_EQ(countBefore(r.stats.warnings[0], " faces are cancelled by exact duplicates"), opposed) << r.stats.warnings[0];
  EXPECT_NE(r.stats.warnings[0].find("--reorient"), std::string::npos);
  // same-orientation duplicates leave the solid as it was, but are named too
  // (their edges counted as boundary edges, and they gave no word at all)
  const TriangleMesh dup20 = signquality::damaged(clean, "dup20");
  const DuplicateOracle d = duplicateOracle(dup20);
  ASSERT_GT(d.stacked, 0);
  const Result same = runFloat(dup20, 32, SignMode::WindingNumber);
  ASSERT_EQ(same.stats.warnings.size(), 1u);
  EXPECT_EQ(countBefore(same.stats.warnings[0], " doubled in the same orientation"), d.stacked) << same.stats.warnings[0];
  EXPECT_EQ(countBefore(same.stats.warnings[0], " faces are cancelled"), -1) << same.stats.warnings[0];
  EXPECT_EQ(same.inside, runFloat(clean, 32, SignMode::WindingNumber).inside);
}

TEST(MeshToSdfWarnings, PseudoNormalAndNormalNameTheReorientedWindingSign)
{
  const TriangleMesh clean = oracle::bumpySphere();
  const TriangleMesh patched = signquality::damaged(clean, "patch10");
  // the oracle: edges (corners welded by position) of exactly two faces that
  // run them the same way
  std::map<std::array<float, 3>, std::uint32_t> weld;
  auto id = [&](std::uint32_t v) { return weld.emplace(patched.points[v], std::uint32_t(weld.size())).first->second; };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<int>> uses; // (lo, hi) -> +1 lo->hi, -1 hi->lo
  for (const auto& t : patched.triangles)
  {
    if (area2(patched, t) == 0) continue;
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = id(t[k]), b = id(t[(k + 1) % 3]);
      uses[{ std::min(a, b), std::max(a, b) }].push_back(a < b ? 1 : -1);
    }
  }
  long long seams = 0;
  for (const auto& [edge, dirs] : uses) seams += dirs.size() == 2 && dirs[0] == dirs[1];
  ASSERT_GT(seams, 0);

  for (const SignMode s : { SignMode::PseudoNormal, SignMode::Normal })
  {
    const Result r = runFloat(patched, 48, s);
    ASSERT_EQ(r.stats.warnings.size(), 1u) << toString(s);
    const std::string& w = r.stats.warnings[0];
    EXPECT_EQ(countBefore(w, " edges join faces of opposite orientation"), seams) << w;
    EXPECT_NE(w.find("winding-number"), std::string::npos) << w;
    EXPECT_NE(w.find("--reorient"), std::string::npos) << w;
    EXPECT_EQ(w.find("sign voxel filters"), std::string::npos) << w; // none ran
    EXPECT_TRUE(runFloat(clean, 48, s).stats.warnings.empty()) << toString(s);
  }
  // with the sign voxel filters (they may repair part of the damage) the
  // warning says so, and still counts the same seams
  const Result svf = runFloat(patched, 48, SignMode::Normal, 0xF);
  ASSERT_EQ(svf.stats.warnings.size(), 1u);
  EXPECT_NE(svf.stats.warnings[0].find("sign voxel filters"), std::string::npos) << svf.stats.warnings[0];
  EXPECT_EQ(countBefore(svf.stats.warnings[0], " edges join faces of opposite orientation"), seams);
  // what it says holds: the pseudo-normal sign of the damaged mesh differs
  // from the undamaged mesh's on voxels away from the surface, and the
  // option it names gives the undamaged mesh's signs there
  const GridGeometry g = fitGridToMesh(clean, 48, 2.0);
  std::vector<float> pn(static_cast<std::size_t>(g.count())), ref(pn.size()), fixed(pn.size());
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  o.sign = SignMode::PseudoNormal;
  meshToSdf(patched, FloatGridView{ pn.data(), g }, o);
  o.sign = SignMode::WindingNumber;
  meshToSdf(clean, FloatGridView{ ref.data(), g }, o);
  o.reorientFaces = true;
  meshToSdf(patched, FloatGridView{ fixed.data(), g }, o);
  std::int64_t wrongPn = 0, wrongFixed = 0;
  for (std::size_t i = 0; i < ref.size(); ++i)
  {
    if (std::fabs(ref[i]) <= 1.0f) continue;
    wrongPn += std::signbit(pn[i]) != std::signbit(ref[i]);
    wrongFixed += std::signbit(fixed[i]) != std::signbit(ref[i]);
  }
  EXPECT_GT(wrongPn, 0);
  EXPECT_EQ(wrongFixed, 0);
}

// A volume that cannot fit its memory limit ran until a chunk's expansion met
// the limit ("expanding chunk ... holds 2.00 GiB of its 2.00 GiB limit", after
// minutes at 4096^3). Now it is refused before any work, naming the limit and
// the options; the oracle of "never refuse what fits" is the conversion itself:
// the bound is at most what it took, and a limit of exactly that converts.
TEST(MeshToSdfMemory, RefusesWhatCannotFitBeforeAnyWorkAndNeverWhatFits)
{
  const lvdif::TriangleMesh sphere = lvdif::makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 24, 48);
  lvdif::VolumeOptions vo = lvdif::volumeOptionsOn(lvdif::fitGridToMesh(sphere, 160, 2));
  vo.chunkEdge = 16;
  lvdif::MeshToSdfOptions o;
  o.device = lvdif::Device::Cpu;
  lvdif::DictionaryVolume unlimited(vo);
  const std::uint64_t least = lvdif::meshToSdfLeastMemory(sphere, unlimited, o);
  lvdif::meshToSdf(sphere, unlimited, o);
  const std::uint64_t used = unlimited.memoryBytes();
  EXPECT_LE(least, used);
  EXPECT_GT(least, lvdif::DictionaryVolume::tableBytes(vo) + (used - lvdif::DictionaryVolume::tableBytes(vo)) / 4);
  ASSERT_GT(lvdif::DictionaryVolume::denseBytes(vo), used); // the estimate runs

  vo.memoryLimit = used; // fits exactly: converted, the same volume
  lvdif::DictionaryVolume fits(vo);
  EXPECT_NO_THROW(lvdif::meshToSdf(sphere, fits, o));
  EXPECT_EQ(fits.memoryBytes(), used);

  vo.memoryLimit = least - 1;
  lvdif::DictionaryVolume tooSmall(vo);
  try
  {
    lvdif::meshToSdf(sphere, tooSmall, o);
    ADD_FAILURE() << "a volume over its limit was converted";
  }
  catch (const lvdif::Error& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(e.code(), lvdif::ErrorCode::OutOfMemory);
    EXPECT_NE(what.find("needs at least " + lvdif::formatBytes(least)), std::string::npos) << what;
    EXPECT_NE(what.find("LVDIF_MEMORY_LIMIT"), std::string::npos) << what;
    EXPECT_NE(what.find("lvdif-editor --mesh-resolution"), std::string::npos) << what;
  }
  EXPECT_EQ(tooSmall.expandedChunkCount(), 0); // refused before any work

  // between the bound and the need: past the estimate, the conversion's own
  // guard stops it inside its parallel loop, as one error (it once aborted)
  ASSERT_LT(least + 2 * 16 * 16 * 16 * sizeof(lvdif::Voxel), used);
  vo.memoryLimit = used - 2 * 16 * 16 * 16 * sizeof(lvdif::Voxel);
  lvdif::DictionaryVolume between(vo);
  try
  {
    lvdif::meshToSdf(sphere, between, o);
    ADD_FAILURE() << "a volume over its limit was converted";
  }
  catch (const lvdif::Error& e)
  {
    EXPECT_EQ(e.code(), lvdif::ErrorCode::OutOfMemory) << e.what();
    EXPECT_EQ(std::string(e.what()).find("needs at least"), std::string::npos) << "refused by the estimate: " << e.what();
  }
}



// The bound counted only the chunks the surface passes through: about half of
// what a fine grid takes (the chunks within the band beside them are expanded
// too), so a unit mesh at spacing 0.001 under a 2 GiB limit ran until the
// limit was full and then failed. It now counts the chunks of voxels within
// band - 1 of the surface as well: a limit just below the bound is refused
// before any chunk is expanded, naming the grid, the bound and the limit, and
// a limit of what the conversion took (the oracle: the conversion itself)
// still converts, on a box and a sphere, chunks of 8 to 32.
TEST(MeshToSdfMemory, TheBoundCountsTheBandAroundTheSurface)
{
  struct Case
  {
    lvdif::TriangleMesh mesh;
    std::int64_t res;
    int edge;
  };
  const std::vector<Case> cases = {
    { makeBoxMesh({ 0.1f, 0.2f, 0.3f }, { 1.1f, 0.9f, 1.25f }), 160, 8 },
    { makeBoxMesh({ 0.1f, 0.2f, 0.3f }, { 1.1f, 0.9f, 1.25f }), 160, 16 },
    { lvdif::makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 24, 48), 160, 32 },
    { lvdif::makeSphereMesh(0.1f, -0.2f, 0.05f, 1.0f, 24, 48), 96, 8 },
  };
  for (const Case& c : cases)
  {
    lvdif::VolumeOptions vo = lvdif::volumeOptionsOn(lvdif::fitGridToMesh(c.mesh, c.res, 2));
    vo.chunkEdge = c.edge;
    lvdif::MeshToSdfOptions o;
    o.device = lvdif::Device::Cpu;
    lvdif::DictionaryVolume unlimited(vo);
    const std::uint64_t least = lvdif::meshToSdfLeastMemory(c.mesh, unlimited, o);
    lvdif::meshToSdf(c.mesh, unlimited, o);
    const std::uint64_t used = unlimited.memoryBytes();
    const std::uint64_t table = lvdif::DictionaryVolume::tableBytes(vo);
    const std::string name = std::to_string(c.res) + " edge " + std::to_string(c.edge);
    EXPECT_LE(least, used) << name; // never refuses what fits
    EXPECT_GE(least - table, 3 * (used - table) / 4) << name << ": the band's chunks counted";
    ASSERT_GT(lvdif::DictionaryVolume::denseBytes(vo), used); // the estimate runs

    vo.memoryLimit = used; // fits exactly: converted
    lvdif::DictionaryVolume fits(vo);
    EXPECT_NO_THROW(lvdif::meshToSdf(c.mesh, fits, o)) << name;

    vo.memoryLimit = least - 1; // cannot fit: refused up front
    lvdif::DictionaryVolume tooSmall(vo);
    try
    {
      lvdif::meshToSdf(c.mesh, tooSmall, o);
      ADD_FAILURE() << name << ": a volume over its limit was converted";
    }
    catch (const lvdif::Error& e)
    {
      const std::string what = e.what();
      EXPECT_EQ(e.code(), lvdif::ErrorCode::OutOfMemory);
      const std::string grid = std::to_string(vo.dims[0]) + " x " + std::to_string(vo.dims[1]) + " x " + std::to_string(vo.dims[2]);
      EXPECT_NE(what.find("a " + grid + " volume"), std::string::npos) << what;
      EXPECT_NE(what.find("needs at least " + lvdif::formatBytes(least)), std::string::npos) << what;
      EXPECT_NE(what.find("limit of " + lvdif::formatBytes(least - 1)), std::string::npos) << what;
    }
    EXPECT_EQ(tooSmall.expandedChunkCount(), 0) << name << ": refused before any work";
  }
}
