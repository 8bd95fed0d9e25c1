// The solid check (MeshToSdfSolid.h) and the PseudoNormal sign of solids by
// the winding path: which meshes are proven to bound a solid, which are not
// (each condition broken on its own), and that the field of a solid is the
// pseudo-normal path's, voxel for voxel, on the CPU and on CUDA.
#include "MeshToSdfFarCases.h"
#include "MeshToSdfOracle.h"
#include "../src/MeshToSdfCuda.h"
#include "../src/MeshToSdfInternal.h"
#include "../src/MeshToSdfSharpFeatures.h"
#include "../src/MeshToSdfSolid.h"
#include "lvdif/Cuda.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace lvdif;

namespace
{
/// A cube of n x n quads per side (flat sides: many coplanar neighbours and
/// coplanar triangles two or more apart), outward.
TriangleMesh gridCube(int n, float lo, float hi)
{
  TriangleMesh m;
  const float s = (hi - lo) / static_cast<float>(n);
  // the six sides as (axis of the normal, direction), points welded by position
  for (int axis = 0; axis < 3; ++axis)
    for (int dir = 0; dir < 2; ++dir)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = static_cast<std::uint32_t>(m.points.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
        {
          Vec3f p{};
          p[axis] = dir ? hi : lo;
          p[u] = lo + s * static_cast<float>(i);
          p[v] = lo + s * static_cast<float>(j);
          if (i == n) p[u] = hi;
          if (j == n) p[v] = hi;
          m.points.push_back(p);
        }
      auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (n + 1) + i); };
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          // (u, v, axis) is right-handed: u x v = +axis, so counter-clockwise
          // in (u, v) faces +axis; the low side turns around
          std::array<std::uint32_t, 3> a{ id(i, j), id(i + 1, j), id(i + 1, j + 1) };
          std::array<std::uint32_t, 3> b{ id(i, j), id(i + 1, j + 1), id(i, j + 1) };
          if (!dir)
          {
            std::swap(a[1], a[2]);
            std::swap(b[1], b[2]);
          }
          m.triangles.push_back(a);
          m.triangles.push_back(b);
        }
    }
  return m;
}

TriangleMesh reversed(TriangleMesh m)
{
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

TriangleMesh tetrahedron(Vec3f a, Vec3f b, Vec3f c, Vec3f d)
{
  // outward whatever the order of the corners: orient each face away from the fourth point
  TriangleMesh m;
  m.points = { a, b, c, d };
  const std::array<std::array<std::uint32_t, 4>, 4> faces{ { { 0, 1, 2, 3 }, { 0, 1, 3, 2 }, { 0, 2, 3, 1 }, { 1, 2, 3, 0 } } };
  for (const auto& f : faces)
  {
    const oracle::P p0 = oracle::pt(m.points[f[0]]), p1 = oracle::pt(m.points[f[1]]), p2 = oracle::pt(m.points[f[2]]);
    const oracle::P o = oracle::pt(m.points[f[3]]);
    const double side = oracle::dot(oracle::cross(oracle::sub(p1, p0), oracle::sub(p2, p0)), oracle::sub(o, p0));
    m.triangles.push_back(side < 0 ? std::array<std::uint32_t, 3>{ f[0], f[1], f[2] }
                                   : std::array<std::uint32_t, 3>{ f[0], f[2], f[1] });
  }
  return m;
}

detail::meshtosdf::SolidBoundary solidOf(const TriangleMesh& m)
{
  const MeshToSdfPrepared p = prepareMeshToSdf(m, SignMode::PseudoNormal);
  return p.impl().solidBoundary();
}

/// Voxels of two fields that differ: those on the surface (opposite signs at
/// distance 0 up to rounding: a face's plane through the voxel, as where the
/// grid meets a box's side, whose sign no path can know) apart.
struct FieldDifference
{
  std::int64_t differ = 0, onSurface = 0;
};
FieldDifference differences(const std::vector<float>& x, const std::vector<float>& y)
{
  FieldDifference d;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    if (std::memcmp(&x[i], &y[i], sizeof(float)) == 0) continue;
    if (x[i] == -y[i] && std::fabs(x[i]) < 1e-6f)
      ++d.onSurface;
    else
      ++d.differ;
  }
  return d;
}

std::vector<std::pair<std::string, TriangleMesh>> solids()
{
  std::vector<std::pair<std::string, TriangleMesh>> s;
  s.emplace_back("sphere", makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24));
  s.emplace_back("box", makeBoxMesh({ -0.9f, -0.7f, -0.8f }, { 0.8f, 0.9f, 0.6f }));
  s.emplace_back("cube of 8x8 quads a side", gridCube(8, -0.7f, 0.8f));
  s.emplace_back("tetrahedron", tetrahedron({ -0.8f, -0.6f, -0.7f }, { 0.9f, -0.5f, -0.6f }, { 0.1f, 0.8f, -0.5f }, { 0.0f, 0.1f, 0.9f }));
  s.emplace_back("two spheres apart", oracle::merge(makeSphereMesh(-0.5f, 0, 0, 0.4f, 10, 20), makeSphereMesh(0.5f, 0.05f, 0, 0.4f, 10, 20)));
  // a hollow ball: the cavity's faces point into it
  s.emplace_back("sphere with a cavity", oracle::merge(makeSphereMesh(0, 0, 0, 0.9f, 14, 28), reversed(makeSphereMesh(0.05f, 0, 0, 0.5f, 10, 20))));
  // a ball inside the cavity of a hollow ball
  s.emplace_back("ball in a cavity", oracle::merge(oracle::merge(makeSphereMesh(0, 0, 0, 0.9f, 14, 28),
    reversed(makeSphereMesh(0, 0, 0, 0.6f, 12, 24))), makeSphereMesh(0.02f, 0, 0, 0.3f, 8, 16)));
  return s;
}
} // namespace

TEST(MeshToSdfSolid, SolidsAreRecognised)
{
  for (const auto& [name, mesh] : solids())
  {
    const detail::meshtosdf::SolidBoundary s = solidOf(mesh);
    EXPECT_TRUE(s.solid) << name << ": " << s.why;
  }
}

TEST(MeshToSdfSolid, EachBrokenConditionIsFound)
{
  const TriangleMesh sphere = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  struct Case
  {
    std::string name;
    TriangleMesh mesh;
    std::string why; // a word of the reason
  };
  std::vector<Case> cases;
  cases.push_back({ "facing inwards", reversed(sphere), "faces inwards" });
  cases.push_back({ "nested, both facing out", oracle::merge(makeSphereMesh(0, 0, 0, 0.9f, 14, 28), makeSphereMesh(0.05f, 0, 0, 0.5f, 10, 20)),
    "nested" });
  cases.push_back({ "two spheres overlapping", oracle::merge(makeSphereMesh(-0.3f, 0, 0, 0.5f, 10, 20), makeSphereMesh(0.3f, 0.05f, 0, 0.5f, 10, 20)),
    "meet" });
  {
    // the north pole pushed through the south: its fan crosses the southern faces
    TriangleMesh poked = sphere;
    float top = -1e9f;
    for (const auto& p : poked.points) top = std::max(top, p[2]);
    for (auto& p : poked.points)
      if (p[2] == top) p[2] = -1.5f;
    cases.push_back({ "a pole pushed through", poked, "meet" });
  }
  // a second tetrahedron whose corner lies exactly on the first one's face (touching, no shared vertex)
  cases.push_back({ "a corner touching a face",
    oracle::merge(tetrahedron({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }),
      tetrahedron({ 0.25f, 0.25f, 0.0f }, { 0.2f, 0.3f, -1 }, { 0.8f, 0.1f, -1 }, { 0.1f, 0.7f, -1 })),
    "meet" });
  // two tetrahedra sharing one corner and nothing else: closed, but not a manifold there
  cases.push_back({ "pinched at a vertex",
    oracle::merge(tetrahedron({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }),
      tetrahedron({ 0, 0, 0 }, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, -1 })),
    "fans" });
  // the same two tetrahedra turned so that the second pokes into the first through the shared corner
  cases.push_back({ "sharing a corner, crossing",
    oracle::merge(tetrahedron({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }),
      tetrahedron({ 0, 0, 0 }, { 1, 1, 0.2f }, { 1, 0.2f, 1 }, { -1, -1, -1 })),
    "" });
  for (const farcases::Case& c : farcases::meshes())
    if (c.name != "closed sphere" && c.name != "closed box") cases.push_back({ c.name, c.mesh, "" });
  for (const Case& c : cases)
  {
    const detail::meshtosdf::SolidBoundary s = solidOf(c.mesh);
    EXPECT_FALSE(s.solid) << c.name;
    if (!s.solid && !c.why.empty()) EXPECT_NE(s.why.find(c.why), std::string::npos) << c.name << ": " << s.why;
  }
}

TEST(MeshToSdfSolid, FoldedNeighboursAndCoplanarOverlapsMeet)
{
  // a box whose top is pushed below its bottom: turned inside out
  TriangleMesh dent = makeBoxMesh({ -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f });
  for (auto& p : dent.points)
    if (p[2] > 0) p[2] = -0.7f;
  EXPECT_FALSE(solidOf(dent).solid);
  // a thin box flattened to zero thickness: top and bottom coincide
  TriangleMesh flat = makeBoxMesh({ -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f });
  for (auto& p : flat.points) p[2] = 0.0f;
  EXPECT_FALSE(solidOf(flat).solid); // the sides vanish, top and bottom lie on each other
  TriangleMesh sliver = makeBoxMesh({ -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f });
  for (auto& p : sliver.points) p[2] = p[2] > 0 ? 1e-13f : 0.0f; // within the allowance: counts as meeting
  EXPECT_FALSE(solidOf(sliver).solid);
}

/// The field of a solid by the winding path equals the pseudo-normal path's:
/// the same distances, and the same signs except on the surface itself
/// (distance 0 up to rounding), banded and not.
TEST(MeshToSdfSolid, SolidFieldEqualsThePseudoNormalPath)
{
  std::vector<Device> devices{ Device::Cpu };
  if (cuda::available()) devices.push_back(Device::Cuda);
  for (const auto& [name, mesh] : solids())
    for (Device device : devices)
      for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
      {
        const GridGeometry g = fitGridToMesh(mesh, 37, 3);
        std::vector<float> byWinding(static_cast<std::size_t>(g.count())), byNormals(byWinding.size());
        MeshToSdfOptions o;
        o.sign = SignMode::PseudoNormal;
        o.bandWidth = band;
        o.device = device;
        const MeshToSdfStats a = meshToSdf(mesh, FloatGridView{ byWinding.data(), g }, o);
        o.solidsByWinding = false;
        const MeshToSdfStats b = meshToSdf(mesh, FloatGridView{ byNormals.data(), g }, o);
        EXPECT_TRUE(a.signByWinding) << name;
        EXPECT_FALSE(b.signByWinding) << name;
        // on the surface the winding path takes the exact crossings' sign
        const FieldDifference d = differences(byWinding, byNormals);
        EXPECT_EQ(d.differ, 0) << name << (device == Device::Cuda ? " on CUDA" : " on the CPU") << ", band " << band
                               << " (" << d.onSurface << " voxels on the surface)";
        EXPECT_GT(std::count_if(byWinding.begin(), byWinding.end(), [](float v) { return v < 0; }), 0) << name;
      }
}

/// A ball whose every fourth vertex of alternate rings is pushed out: sharp
/// spikes (vertices and edges whose faces' normals are more than 90 degrees
/// apart) among smooth ones.
TriangleMesh spikyBall()
{
  TriangleMesh m = makeSphereMesh(0.02f, -0.01f, 0.03f, 0.6f, 10, 20);
  for (std::size_t i = 0; i < m.points.size(); i += 7)
    for (int a = 0; a < 3; ++a) m.points[i][a] = 0.02f + 1.6f * (m.points[i][a] - 0.02f);
  return m;
}

/// The Normal sign of a solid by the winding path and the sharp features'
/// regions (MeshToSdfSharpFeatures.h) stores the Normal path's floats, on the
/// CPU and CUDA, banded and not, on grids of unequal spacings, into float
/// grids and dictionary volumes. The Normal field differs from the winding
/// field on sharp meshes (else this test could not fail): that difference is
/// what the regions must recompute.
TEST(MeshToSdfSolid, NormalFieldOfSolidsEqualsTheNormalPath)
{
  std::vector<Device> devices{ Device::Cpu };
  if (cuda::available()) devices.push_back(Device::Cuda);
  auto meshes = solids();
  meshes.emplace_back("spiky ball", spikyBall());
  meshes.emplace_back("needle", tetrahedron({ -0.2f, -0.15f, -0.9f }, { 0.25f, -0.1f, -0.85f }, { 0.0f, 0.2f, -0.8f }, { 0.05f, 0.02f, 0.9f }));
  std::int64_t sharpSeen = 0, normalDiffersFromWinding = 0;
  for (const auto& [name, mesh] : meshes)
    for (Device device : devices)
      for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
        for (bool anisotropic : { false, true })
        {
          GridGeometry g = fitGridToMesh(mesh, 31, 3);
          if (anisotropic)
          {
            const double s = g.spacing[0];
            g.spacing = { s, 1.37 * s, 0.71 * s };
            g.dims = { g.dims[0], static_cast<std::int64_t>(g.dims[1] / 1.37) + 1, static_cast<std::int64_t>(g.dims[2] / 0.71) + 1 };
          }
          std::vector<float> byWinding(static_cast<std::size_t>(g.count())), byNormal(byWinding.size()),
            winding(byWinding.size());
          MeshToSdfOptions o;
          o.sign = SignMode::Normal;
          o.bandWidth = band;
          o.device = device;
          const MeshToSdfStats a = meshToSdf(mesh, FloatGridView{ byWinding.data(), g }, o);
          o.solidsByWinding = false;
          const MeshToSdfStats b = meshToSdf(mesh, FloatGridView{ byNormal.data(), g }, o);
          o.sign = SignMode::WindingNumber;
          meshToSdf(mesh, FloatGridView{ winding.data(), g }, o);
          const std::string where = name + (device == Device::Cuda ? " on CUDA" : " on the CPU") + ", band " +
            std::to_string(band) + (anisotropic ? ", unequal spacings" : "");
          EXPECT_TRUE(a.signByWinding) << where << ": " << solidOf(mesh).why;
          EXPECT_FALSE(b.signByWinding) << where;
          sharpSeen += a.sharpVoxels;
          for (std::size_t i = 0; i < byWinding.size(); ++i)
            normalDiffersFromWinding += (byNormal[i] < 0) != (winding[i] < 0) && std::fabs(byNormal[i]) > 1e-3f;
          const FieldDifference d = differences(byWinding, byNormal);
          EXPECT_EQ(d.differ, 0) << where << " (" << d.onSurface << " voxels on the surface, " << a.sharpVoxels
                                 << " recomputed)";
          if (band == 3.0f && !anisotropic)
          {
            // the dictionary volume: the same keys as the Normal path's
            VolumeOptions vo;
            vo.dims = g.dims;
            vo.origin = g.origin;
            vo.spacing = g.spacing;
            vo.bandWidth = band;
            DictionaryVolume viaWinding(vo), viaNormal(vo);
            o.sign = SignMode::Normal;
            o.solidsByWinding = true;
            const MeshToSdfStats c = meshToSdf(mesh, viaWinding, o);
            o.solidsByWinding = false;
            meshToSdf(mesh, viaNormal, o);
            EXPECT_TRUE(c.signByWinding) << where;
            std::int64_t keysDiffer = 0;
            for (std::int64_t z = 0; z < g.dims[2]; ++z)
              for (std::int64_t y = 0; y < g.dims[1]; ++y)
                for (std::int64_t x = 0; x < g.dims[0]; ++x)
                {
                  const float p = viaWinding.sdf(x, y, z), q = viaNormal.sdf(x, y, z);
                  keysDiffer += viaWinding.get(x, y, z) != viaNormal.get(x, y, z) && !(p == -q && std::fabs(p) < 1e-2f);
                }
            EXPECT_EQ(keysDiffer, 0) << where << ", dictionary volume";
          }
        }
  EXPECT_GT(sharpSeen, 0);
  EXPECT_GT(normalDiffersFromWinding, 0);
}

/// Step 2 of the sharp regions on the GPU gives the CPU's voxels and floats
/// on the same bricks (grids of equal and unequal
/// spacings, a band and none). Only with a GPU.
TEST(MeshToSdfSolid, SharpRegionsOnTheGpuEqualTheCpu)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  auto meshes = solids();
  meshes.emplace_back("spiky ball", spikyBall());
  meshes.emplace_back("needle", tetrahedron({ -0.2f, -0.15f, -0.9f }, { 0.25f, -0.1f, -0.85f }, { 0.0f, 0.2f, -0.8f }, { 0.05f, 0.02f, 0.9f }));
  std::int64_t compared = 0;
  for (const auto& [name, mesh] : meshes)
    for (double band : { 3.0, 1e30 })
      for (bool anisotropic : { false, true })
      {
        GridGeometry g = fitGridToMesh(mesh, 40, 3);
        if (anisotropic) g.spacing = { g.spacing[0], 1.37 * g.spacing[1], 0.71 * g.spacing[2] };
        const MeshToSdfPrepared p = prepareMeshToSdf(mesh, SignMode::Normal);
        MeshToSdfPrepared::Impl& impl = p.impl();
        if (!impl.solidBoundary().solid) continue;
        const detail::meshtosdf::SharpFeatures& sharp = impl.sharpFeatures();
        VoxelBox whole;
        whole.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
        if (!detail::meshtosdf::sharpFeaturesInside(sharp, g, whole)) continue;
        Interrupter never;
        const auto bvh = impl.meshBvh();
        const auto bricks = detail::meshtosdf::sharpRegionBricks(sharp, *bvh, g, whole, never);
        const double toOut = 1.0 / g.spacing[0];
        auto cpu = detail::meshtosdf::sharpRegionVoxels(impl.mesh, sharp, *bvh, bricks, g, whole, toOut, band, never);
        double unused = 0;
        auto gpu = detail::meshtosdf_cuda::sharpRegionVoxelsOnDevice(
          impl.deviceMesh(false, false, unused), sharp, bricks, g, whole, toOut, band);
        // the CPU's threads append in any order: compare as sorted lists
        auto inOrder = [](std::vector<detail::meshtosdf::SharpVoxel>& v) {
          std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) {
            return std::tie(x.k, x.j, x.i, x.value) < std::tie(y.k, y.j, y.i, y.value);
          });
        };
        inOrder(cpu);
        inOrder(gpu);
        const std::string where = name + ", band " + std::to_string(band) + (anisotropic ? ", unequal spacings" : "");
        ASSERT_EQ(cpu.size(), gpu.size()) << where;
        std::int64_t differ = 0;
        for (std::size_t n = 0; n < cpu.size(); ++n)
          differ += cpu[n].i != gpu[n].i || cpu[n].j != gpu[n].j || cpu[n].k != gpu[n].k ||
            std::memcmp(&cpu[n].value, &gpu[n].value, sizeof(float)) != 0;
        EXPECT_EQ(differ, 0) << where << " (" << cpu.size() << " voxels)";
        compared += static_cast<std::int64_t>(cpu.size());
      }
  EXPECT_GT(compared, 0);
}

/// A GPU whose step 2 fails leaves it to the CPU: the same floats, and a
/// warning that says so (the call does not fail).
TEST(MeshToSdfSolid, SharpRegionsFallBackToTheCpuWhenTheGpuFails)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh mesh = spikyBall();
  const GridGeometry g = fitGridToMesh(mesh, 40, 3);
  std::vector<float> onGpu(static_cast<std::size_t>(g.count())), fellBack(onGpu.size());
  MeshToSdfOptions o;
  o.sign = SignMode::Normal;
  o.bandWidth = 3;
  o.device = Device::Cuda;
  const MeshToSdfStats a = meshToSdf(mesh, FloatGridView{ onGpu.data(), g }, o);
  ASSERT_TRUE(a.signByWinding);
  ASSERT_GT(a.sharpVoxels, 0);
  for (const std::string& w : a.warnings) EXPECT_EQ(w.find("sharp features' regions"), std::string::npos) << w;
  detail::meshtosdf_cuda::failSharpRegionsOnDevice(true);
  MeshToSdfStats b;
  try
  {
    b = meshToSdf(mesh, FloatGridView{ fellBack.data(), g }, o);
  }
  catch (...)
  {
    detail::meshtosdf_cuda::failSharpRegionsOnDevice(false);
    throw;
  }
  detail::meshtosdf_cuda::failSharpRegionsOnDevice(false);
  EXPECT_EQ(b.sharpVoxels, a.sharpVoxels);
  EXPECT_EQ(differences(onGpu, fellBack).differ, 0);
  bool warned = false;
  for (const std::string& w : b.warnings)
    warned = warned || (w.find("computed on the CPU") != std::string::npos && w.find("on purpose") != std::string::npos);
  EXPECT_TRUE(warned) << "no warning of the CPU fallback";
}

/// A mesh that is not a solid's boundary keeps the pseudo-normal path, and
/// its field is unchanged by the option.
TEST(MeshToSdfSolid, OthersKeepThePseudoNormalPath)
{
  for (const farcases::Case& c : farcases::meshes())
  {
    if (c.name == "closed sphere" || c.name == "closed box") continue;
    const GridGeometry g = fitGridToMesh(c.mesh, 24, 3);
    std::vector<float> on(static_cast<std::size_t>(g.count())), off(on.size());
    MeshToSdfOptions o;
    o.sign = SignMode::PseudoNormal;
    o.bandWidth = 3;
    o.device = Device::Cpu;
    const MeshToSdfStats a = meshToSdf(c.mesh, FloatGridView{ on.data(), g }, o);
    o.solidsByWinding = false;
    meshToSdf(c.mesh, FloatGridView{ off.data(), g }, o);
    EXPECT_FALSE(a.signByWinding) << c.name;
    EXPECT_EQ(std::memcmp(on.data(), off.data(), on.size() * sizeof(float)), 0) << c.name;
  }
}

/// A closed mesh whose faces point inwards makes the normal and pseudo-normal
/// signs inside out, silently before: a warning names the parts and the way
/// out; a mesh facing out, or with a cavity facing in, gets none.
TEST(MeshToSdfSolid, PartsFacingInwardsAreWarnedAbout)
{
  const TriangleMesh sphere = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  const TriangleMesh twoInward = oracle::merge(reversed(makeSphereMesh(-0.5f, 0, 0, 0.4f, 10, 20)),
    reversed(makeSphereMesh(0.5f, 0.05f, 0, 0.4f, 10, 20)));
  const TriangleMesh oneInward = oracle::merge(makeSphereMesh(-0.5f, 0, 0, 0.4f, 10, 20),
    reversed(makeSphereMesh(0.5f, 0.05f, 0, 0.4f, 10, 20)));
  auto warningsOf = [](const TriangleMesh& m, SignMode sign) {
    const GridGeometry g = fitGridToMesh(m, 24, 3);
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    MeshToSdfOptions o;
    o.sign = sign;
    o.bandWidth = 3;
    o.device = Device::Cpu;
    const MeshToSdfStats st = meshToSdf(m, FloatGridView{ out.data(), g }, o);
    std::string all;
    for (const std::string& w : st.warnings) all += w + "\n";
    return all;
  };
  for (SignMode sign : { SignMode::PseudoNormal, SignMode::Normal })
  {
    const std::string name = sign == SignMode::Normal ? "normal" : "pseudo-normal";
    const std::string reversedSphere = warningsOf(reversed(sphere), sign);
    EXPECT_NE(reversedSphere.find("1 of the mesh's 1 connected parts face inwards"), std::string::npos) << reversedSphere;
    EXPECT_NE(reversedSphere.find("the " + name + " sign is inside out"), std::string::npos) << reversedSphere;
    EXPECT_NE(warningsOf(twoInward, sign).find("2 of the mesh's 2 connected parts face inwards"), std::string::npos);
    EXPECT_NE(warningsOf(oneInward, sign).find("1 of the mesh's 2 connected parts face inwards"), std::string::npos);
    EXPECT_EQ(warningsOf(sphere, sign).find("face inwards"), std::string::npos);
    for (const auto& [solidName, mesh] : solids())
      EXPECT_EQ(warningsOf(mesh, sign).find("face inwards"), std::string::npos) << solidName;
  }
  // the winding sign is right either way: no such warning
  EXPECT_EQ(warningsOf(reversed(sphere), SignMode::WindingNumber).find("face inwards"), std::string::npos);
}

/// On CUDA the one-call API checks a closed mesh beside the GPU's pass
/// (SolidCheckBesideGpu): a solid keeps the winding route, anything else is
/// computed again on its sign's own path. Either way the result, the route and
/// the warnings are those of the same call on a prepared mesh whose check ran
/// first (signOfSolids before the pass), into float grids and volumes.
TEST(MeshToSdfSolid, SolidCheckBesideTheGpuGivesTheCheckFirstResult)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh sphere = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  std::vector<std::pair<std::string, TriangleMesh>> meshes = solids();
  meshes.emplace_back("spiky ball", spikyBall());
  meshes.emplace_back("facing inwards", reversed(sphere));
  meshes.emplace_back("two spheres overlapping",
    oracle::merge(makeSphereMesh(-0.3f, 0, 0, 0.5f, 10, 20), makeSphereMesh(0.3f, 0.05f, 0, 0.5f, 10, 20)));
  meshes.emplace_back("nested, both facing out",
    oracle::merge(makeSphereMesh(0, 0, 0, 0.9f, 14, 28), makeSphereMesh(0.05f, 0, 0, 0.5f, 10, 20)));
  int ahead = 0, again = 0;
  for (const auto& [name, mesh] : meshes)
    for (SignMode sign : { SignMode::Normal, SignMode::PseudoNormal })
    {
      const std::string where = name + (sign == SignMode::Normal ? ", normal" : ", pseudo-normal");
      const GridGeometry g = fitGridToMesh(mesh, 40, 3);
      MeshToSdfOptions o;
      o.sign = sign;
      o.bandWidth = 3;
      o.device = Device::Cuda;
      // the check first: a prepared mesh whose check has run
      const MeshToSdfPrepared checkedFirst = prepareMeshToSdf(mesh, sign);
      checkedFirst.impl().solidBoundary();
      std::vector<float> want(static_cast<std::size_t>(g.count())), got(want.size());
      const MeshToSdfStats a = meshToSdf(checkedFirst, FloatGridView{ want.data(), g }, o);
      o.tracePhases = true;
      testing::internal::CaptureStderr();
      const MeshToSdfStats b = meshToSdf(mesh, FloatGridView{ got.data(), g }, o);
      const std::string traced = testing::internal::GetCapturedStderr();
      ASSERT_NE(traced.find("solid check beside the GPU's pass"), std::string::npos) << where << ": not ahead\n" << traced;
      const bool redone = traced.find("the call again on the sign's own path") != std::string::npos;
      ahead += !redone;
      again += redone;
      EXPECT_EQ(redone, !a.signByWinding) << where;
      EXPECT_EQ(a.signByWinding, b.signByWinding) << where;
      EXPECT_EQ(a.sharpVoxels, b.sharpVoxels) << where;
      EXPECT_EQ(a.warnings, b.warnings) << where;
      EXPECT_EQ(differences(want, got).differ, 0) << where << ", float grid";
      // into a volume: the same keys
      VolumeOptions vo = volumeOptionsOn(g);
      vo.chunkEdge = 16;
      DictionaryVolume wantVolume(vo), gotVolume(vo);
      o.tracePhases = false;
      o.cudaSlabBytes = 1; // one chunk layer a group: the check may end (and stop the pass) between groups
      const MeshToSdfStats c = meshToSdf(checkedFirst, wantVolume, o);
      const MeshToSdfStats d = meshToSdf(mesh, gotVolume, o);
      EXPECT_EQ(c.signByWinding, d.signByWinding) << where;
      EXPECT_EQ(c.warnings, d.warnings) << where;
      std::int64_t differ = 0;
      for (std::int64_t k = 0; k < g.dims[2]; ++k)
        for (std::int64_t j = 0; j < g.dims[1]; ++j)
          for (std::int64_t i = 0; i < g.dims[0]; ++i) differ += wantVolume.get(i, j, k).sdf != gotVolume.get(i, j, k).sdf;
      EXPECT_EQ(differ, 0) << where << ", volume";
      // a first pass that stored chunks and stopped leaves none expanded that the own path would not
      EXPECT_EQ(wantVolume.expandedChunkCount(), gotVolume.expandedChunkCount()) << where << ", volume";
    }
  EXPECT_GT(ahead, 0);
  EXPECT_GT(again, 0);
}
