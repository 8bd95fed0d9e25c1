// CUDA mesh to SDF against the CPU path (itself tested against brute-force
// oracles): distances within float rounding, signs equal except on voxels
// lying on the surface (|d| < 1e-3 voxel). Skipped without a CUDA device.
#include "MeshToSdfDamagedMeshes.h"
#include "MeshToSdfFarCases.h"
#include "MeshToSdfOracle.h"
#include "lvdif/Cuda.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/SdfDictionary.h"
#include "../src/MeshToSdfCuda.h"
#include "../src/MeshToSdfInternal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
TriangleMesh holedFlipped()
{
  TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 24, 48);
  std::vector<std::array<std::uint32_t, 3>> kept;
  std::mt19937 rng(3);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    if (t < 48 * 3 || t % 41 == 7) continue; // holes
    auto tri = m.triangles[t];
    if (rng() % 7 == 0) std::swap(tri[1], tri[2]);
    kept.push_back(tri);
  }
  m.triangles = kept;
  return m;
}

void compare(const TriangleMesh& m, const GridGeometry& g, const VoxelBox& box, MeshToSdfOptions o, const std::string& what)
{
  std::vector<float> cpu(static_cast<std::size_t>(box.voxelCount())), gpu(cpu.size());
  o.device = Device::Cpu;
  meshToSdf(m, g, box, cpu.data(), o);
  o.device = Device::Cuda;
  const MeshToSdfStats st = meshToSdf(m, g, box, gpu.data(), o);
  ASSERT_EQ(st.device, Device::Cuda) << what;
  EXPECT_GT(st.devicePeakBytes, 0u);
  std::int64_t badDistance = 0, badSign = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i)
  {
    const float a = cpu[i], b = gpu[i];
    if (std::fabs(std::fabs(a) - std::fabs(b)) > 1e-5f * std::max(1.0f, std::fabs(a))) ++badDistance;
    if (std::fabs(a) > 1e-3f && (a < 0) != (b < 0)) ++badSign;
  }
  EXPECT_EQ(badDistance, 0) << what;
  // Algorithm 1's sign follows whichever of several near-equidistant
  // triangles wins, so it agrees only because both sides round alike: the
  // .cu is built with --fmad=false and the CPU files with -ffp-contract=off.
  EXPECT_EQ(badSign, 0) << what;
  std::printf("[ cpu vs cuda ] %s: %lld distance, %lld sign differences of %zu voxels\n", what.c_str(),
    static_cast<long long>(badDistance), static_cast<long long>(badSign), cpu.size());
}
} // namespace

TEST(MeshToSdfCuda, MatchesCpuOnEverySignMode)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh m = holedFlipped();
  const GridGeometry g = fitGridToMesh(m, 70, 3);
  VoxelBox all;
  all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  for (SignMode s : { SignMode::Normal, SignMode::PseudoNormal, SignMode::WindingNumber, SignMode::Unsigned })
  {
    for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
    {
      MeshToSdfOptions o;
      o.sign = s;
      o.bandWidth = band;
      o.cudaSlabBytes = 70 * 70 * 4 * 9; // several slabs
      compare(m, g, all, o, std::string(toString(s)) + " band " + std::to_string(band));
    }
  }
  // the Normal sign with the mesh's vertex normals (the corner normals' copy on the device)
  TriangleMesh withNormals = m;
  withNormals.normals.resize(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i)
  {
    const Vec3f& p = m.points[i];
    withNormals.normals[i] = { p[0] + 0.3f * p[1], p[1] - 0.2f * p[2], p[2] + 0.1f }; // not the face normals
  }
  MeshToSdfOptions o;
  o.sign = SignMode::Normal;
  o.useVertexNormals = true;
  o.bandWidth = 3;
  compare(withNormals, g, all, o, "Normal with vertex normals");
}

// Device::Auto runs WindingNumber on the GPU for meshes with reversed faces
// too (the kernel takes the CPU's construction): the same field as the CPU.
TEST(MeshToSdfCuda, AutoKeepsReversedFacesOnTheGpu)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  TriangleMesh flipped = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 24, 48);
  for (std::size_t t = 0; t < flipped.triangles.size(); t += 9) std::swap(flipped.triangles[t][1], flipped.triangles[t][2]);
  const GridGeometry g = fitGridToMesh(flipped, 24, 2);
  VoxelBox all;
  all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  std::vector<float> a(static_cast<std::size_t>(all.voxelCount())), b(a.size());
  MeshToSdfOptions o;
  o.sign = SignMode::WindingNumber;
  o.device = Device::Auto;
  EXPECT_EQ(meshToSdf(flipped, g, all, a.data(), o).device, Device::Cuda);
  o.device = Device::Cpu;
  EXPECT_EQ(meshToSdf(flipped, g, all, b.data(), o).device, Device::Cpu);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  // the re-oriented mesh too, with the CPU's re-oriented structures
  o.reorientFaces = true;
  EXPECT_EQ(meshToSdf(flipped, g, all, b.data(), o).device, Device::Cpu);
  o.device = Device::Auto;
  EXPECT_EQ(meshToSdf(flipped, g, all, a.data(), o).device, Device::Cuda);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

// The damaged meshes (reversed patches, scattered reversals, duplicates half
// reversed, holes, fins, an intersecting pair, combinations): CUDA = CPU bit
// for bit on the whole volume (distances and signs), with and without a
// band, over several slabs; and the brute-force winding number on a sample
// of the far voxels.
namespace
{
void damagedMeshesMatchCpu(const char* lists)
{
  for (const auto& [name, m] : oracle::damagedMeshes())
  {
    const GridGeometry g = fitGridToMesh(m, 64, 2);
    VoxelBox all;
    all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
    const MeshToSdfPrepared prepared = prepareMeshToSdf(m);
    // the mesh as given, then re-oriented (reorientFaces: no oracle, which sums M as given)
    for (const bool reorient : { false, true })
    for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
    {
      std::vector<float> cpu(static_cast<std::size_t>(g.count())), gpu(cpu.size());
      MeshToSdfOptions o;
      o.sign = SignMode::WindingNumber;
      o.reorientFaces = reorient;
      o.bandWidth = band;
      o.device = Device::Cpu;
      meshToSdf(prepared, g, all, cpu.data(), o);
      o.device = Device::Auto;
      o.cudaSlabBytes = static_cast<std::uint64_t>(g.dims[0] * g.dims[1]) * 4 * 11; // several slabs
      const MeshToSdfStats st = meshToSdf(prepared, g, all, gpu.data(), o);
      ASSERT_EQ(st.device, Device::Cuda) << name;
      std::int64_t sign = 0, dist = 0, inside = 0;
      for (std::size_t i = 0; i < cpu.size(); ++i)
      {
        sign += std::signbit(cpu[i]) != std::signbit(gpu[i]);
        dist += std::fabs(cpu[i]) != std::fabs(gpu[i]);
        inside += std::signbit(gpu[i]);
      }
      std::int64_t far = 0, wrong = 0;
      for (std::size_t i = 0; std::isinf(band) && !reorient && i < gpu.size(); i += 397)
      {
        if (!(std::fabs(gpu[i]) > 1.0f)) continue;
        const std::int64_t x = static_cast<std::int64_t>(i) % g.dims[0], y = (static_cast<std::int64_t>(i) / g.dims[0]) % g.dims[1],
                           z = static_cast<std::int64_t>(i) / (g.dims[0] * g.dims[1]);
        const double w = oracle::winding(m, { g.origin[0] + x * g.spacing[0], g.origin[1] + y * g.spacing[1], g.origin[2] + z * g.spacing[2] });
        ++far;
        wrong += (std::fabs(w) >= 0.5) != std::signbit(gpu[i]);
      }
      std::printf("[ cpu vs cuda ] %-14s%s band %g%s: %lld sign, %lld distance differences of %zu voxels (%lld inside); "
                  "%lld refined, %lld canonical on the GPU; oracle: %lld wrong of %lld far\n",
        name.c_str(), reorient ? " re-oriented" : "", static_cast<double>(band), lists, static_cast<long long>(sign), static_cast<long long>(dist), cpu.size(),
        static_cast<long long>(inside), static_cast<long long>(st.windingEvaluations),
        static_cast<long long>(st.windingFullSums), static_cast<long long>(wrong), static_cast<long long>(far));
      EXPECT_EQ(sign, 0) << name << " band " << band;
      EXPECT_EQ(dist, 0) << name << " band " << band;
      EXPECT_EQ(std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(float)), 0) << name << " band " << band;
      EXPECT_EQ(wrong, 0) << name;
      if (std::isinf(band) && !reorient) EXPECT_GT(far, 300) << name;
      EXPECT_GT(inside, g.count() / 50) << name;
    }
  }
}
} // namespace

TEST(MeshToSdfCuda, DamagedMeshesMatchCpuBitForBit)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  damagedMeshesMatchCpu("");
}

// The winding decision's work lists (the listed voxels, blocks and voxels
// between passes, the local step's pool of 4^3 blocks, MeshToSdfCudaDipole.cuh)
// cut to 5 entries: what a full list leaves is finished in its thread (the
// blocks beyond the pool go to the 2^3 balls), and the result stays the
// CPU's bit for bit.
TEST(MeshToSdfCuda, DamagedMeshesMatchCpuWithFullWorkLists)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  ::setenv("LVDIF_CUDA_DIPOLE_LIST_CAP", "5", 1);
  damagedMeshesMatchCpu(", lists of 5");
  ::unsetenv("LVDIF_CUDA_DIPOLE_LIST_CAP");
}

// Without the local step (LVDIF_CUDA_DIPOLE_LOCAL=0: the 2^3 balls and the
// voxels one by one, as before it): still the CPU's bit for bit.
TEST(MeshToSdfCuda, DamagedMeshesMatchCpuWithoutTheLocalStep)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  ::setenv("LVDIF_CUDA_DIPOLE_LOCAL", "0", 1);
  damagedMeshesMatchCpu(", no local step");
  ::unsetenv("LVDIF_CUDA_DIPOLE_LOCAL");
}

// The local step decides on the GPU what the balls leave: over the damaged
// meshes the voxels refined one by one (windingEvaluations) at least halve
// with it (the CPU emulation's counts: MeshToSdfDipoleDecide.LocalStepDecidesWhatTheBallsLeave).
TEST(MeshToSdfCuda, LocalStepCutsTheVoxelsRefinedOneByOne)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  std::int64_t refined[2] = { 0, 0 };
  for (const auto& [name, m] : oracle::damagedMeshes())
  {
    const GridGeometry g = fitGridToMesh(m, 64, 2);
    VoxelBox all;
    all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
    const MeshToSdfPrepared prepared = prepareMeshToSdf(m);
    for (int on = 0; on < 2; ++on)
    {
      ::setenv("LVDIF_CUDA_DIPOLE_LOCAL", on ? "1" : "0", 1);
      std::vector<float> gpu(static_cast<std::size_t>(g.count()));
      MeshToSdfOptions o;
      o.sign = SignMode::WindingNumber;
      o.bandWidth = std::numeric_limits<float>::infinity();
      o.device = Device::Auto;
      const MeshToSdfStats st = meshToSdf(prepared, g, all, gpu.data(), o);
      ASSERT_EQ(st.device, Device::Cuda) << name;
      refined[on] += st.windingEvaluations;
      std::printf("[ local step ] %-14s local %s: %lld voxels refined one by one on the GPU\n", name.c_str(), on ? "on " : "off",
        static_cast<long long>(st.windingEvaluations));
    }
  }
  ::unsetenv("LVDIF_CUDA_DIPOLE_LOCAL");
  EXPECT_GT(refined[0], 0);
  EXPECT_LT(2 * refined[1], refined[0]);
}

TEST(MeshToSdfCuda, ClosedAndIntersectingMeshesAndSubExtent)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh m =
    oracle::merge(makeSphereMesh(-0.35f, 0, 0, 0.8f, 16, 32), makeSphereMesh(0.4f, 0.1f, 0.05f, 0.75f, 16, 32));
  const GridGeometry g = fitGridToMesh(m, 80, 2);
  VoxelBox box;
  box.lo = { 5, 7, 3 };
  box.hi = { g.dims[0] - 4, g.dims[1] - 9, g.dims[2] - 2 };
  MeshToSdfOptions o;
  o.bandWidth = 5.0f;
  compare(m, g, box, o, "two spheres, sub-extent");
  // random soup, unsigned, brute-force comparison of the GPU result
  const TriangleMesh soup = oracle::randomSoup(80, 9);
  GridGeometry gs;
  gs.dims = { 21, 19, 17 };
  gs.origin = { -1.6, -1.5, -1.7 };
  gs.spacing = { 0.16, 0.17, 0.2 };
  std::vector<float> gpu(static_cast<std::size_t>(gs.count()));
  o.sign = SignMode::Unsigned;
  o.bandWidth = std::numeric_limits<float>::infinity();
  o.unit = DistanceUnit::World;
  o.device = Device::Cuda;
  meshToSdf(soup, FloatGridView{ gpu.data(), gs }, o);
  for (std::int64_t k = 0; k < gs.dims[2]; ++k)
    for (std::int64_t j = 0; j < gs.dims[1]; ++j)
      for (std::int64_t i = 0; i < gs.dims[0]; ++i)
      {
        const double ref = oracle::distance(
          soup, { gs.origin[0] + i * gs.spacing[0], gs.origin[1] + j * gs.spacing[1], gs.origin[2] + k * gs.spacing[2] });
        ASSERT_NEAR(gpu[gs.index(i, j, k)], ref, 1e-6 * std::max(1.0, ref));
      }
}

TEST(MeshToSdfCuda, AmbiguousScanLinesMatchCpu)
{
  // An open box with its side and bottom faces on grid planes: scan lines
  // lying in those faces or through their edges are ambiguous, so the
  // warp-cooperative per-voxel fallback of the sign kernel runs (and must
  // give the CPU's signs). The open top is off the grid planes: in the plane
  // of a hole the winding number is exactly 1/2, a knife edge for any sign.
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  TriangleMesh m;
  m.points = { { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 }, { -1, -1, 1.1f }, { 1, -1, 1.1f },
    { 1, 1, 1.1f }, { -1, 1, 1.1f } };
  m.triangles = { { 0, 2, 1 }, { 0, 3, 2 }, { 0, 1, 5 }, { 0, 5, 4 }, { 1, 2, 6 }, { 1, 6, 5 }, { 2, 3, 7 },
    { 2, 7, 6 }, { 3, 0, 4 }, { 3, 4, 7 } }; // the top (z = 1.1) is left open
  GridGeometry g;
  g.dims = { 17, 17, 17 };
  g.origin = { -2, -2, -2 };
  g.spacing = { 0.25, 0.25, 0.25 };
  VoxelBox all;
  all.hi = { 16, 16, 16 };
  MeshToSdfOptions o;
  o.sign = SignMode::WindingNumber;
  for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
  {
    o.bandWidth = band;
    compare(m, g, all, o, "open box on grid planes, band " + std::to_string(band));
    std::vector<float> gpu(static_cast<std::size_t>(g.count()));
    o.device = Device::Cuda;
    const MeshToSdfStats st = meshToSdf(m, FloatGridView{ gpu.data(), g }, o);
    EXPECT_GT(st.windingExact, 0) << "no ambiguous scan line: the fallback was not exercised";
  }
}

TEST(MeshToSdfCuda, DictionaryVolumeMatchesCpu)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh m = holedFlipped();
  const GridGeometry g = fitGridToMesh(m, 75, 2); // not a multiple of the chunk edge: partial chunks
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 16;
  vo.bandWidth = 4.0f;
  DictionaryVolume a(vo), b(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  meshToSdf(m, a, o);
  o.device = Device::Cuda;
  o.cudaVerifyKeys = true;
  o.cudaSlabBytes = static_cast<std::uint64_t>(g.dims[0] * g.dims[1]) * 16 * 4 * 2; // groups of 2 chunk layers
  const MeshToSdfPrepared prepared = prepareMeshToSdf(m);
  for (int pass = 0; pass < 2; ++pass) // the second pass writes over expanded chunks
  {
    const MeshToSdfStats st = meshToSdf(prepared, b, o);
    ASSERT_EQ(st.device, Device::Cuda);
    // every GPU-encoded key of every slab against the host's encode of the same float
    EXPECT_EQ(st.keysVerified, g.count());
    EXPECT_EQ(st.keyMismatches, 0);
    std::int64_t diff = 0, structure = 0;
    for (std::int64_t c = 0; c < a.chunkCount(); ++c) structure += a.isUniform(c) != b.isUniform(c);
    for (std::int64_t z = 0; z < g.dims[2]; ++z)
      for (std::int64_t y = 0; y < g.dims[1]; ++y)
        for (std::int64_t x = 0; x < g.dims[0]; ++x) diff += a.get(x, y, z).sdf != b.get(x, y, z).sdf;
    EXPECT_EQ(diff, 0) << "pass " << pass; // the same floats and the same rounding: equal keys
    EXPECT_EQ(structure, 0) << "pass " << pass;
    std::printf("[ cpu vs cuda ] dictionary volume pass %d: %lld key and %lld chunk differences, %lld keys "
                "verified, %lld expanded chunks\n",
      pass, static_cast<long long>(diff), static_cast<long long>(structure),
      static_cast<long long>(st.keysVerified), static_cast<long long>(b.expandedChunkCount()));
  }
}

TEST(MeshToSdfCuda, ScanLinesWithManyCrossingsMatchCpu)
{
  // five nested spheres: a scan line through the middle crosses 10 times,
  // more than the ray pre-pass keeps per line (its warp casts it again);
  // closed (crossings only) and with holes (the correction s), several slabs
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  for (const bool holes : { false, true })
  {
    TriangleMesh m;
    for (int s = 0; s < 5; ++s)
    {
      const TriangleMesh sphere = makeSphereMesh(0.03f, -0.02f, 0.01f, 1.0f - 0.19f * static_cast<float>(s), 20, 40);
      const std::uint32_t base = static_cast<std::uint32_t>(m.points.size());
      m.points.insert(m.points.end(), sphere.points.begin(), sphere.points.end());
      for (std::size_t t = 0; t < sphere.triangles.size(); ++t)
      {
        if (holes && t % 37 == 5) continue;
        auto tri = sphere.triangles[t];
        for (auto& v : tri) v += base;
        m.triangles.push_back(tri);
      }
    }
    const GridGeometry g = fitGridToMesh(m, 56, 2);
    VoxelBox all;
    all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
    const MeshToSdfPrepared prepared = prepareMeshToSdf(m);
    for (float band : { 3.0f, std::numeric_limits<float>::infinity() })
    {
      std::vector<float> cpu(static_cast<std::size_t>(g.count())), gpu(cpu.size());
      MeshToSdfOptions o;
      o.bandWidth = band;
      o.device = Device::Cpu;
      meshToSdf(prepared, g, all, cpu.data(), o);
      o.device = Device::Cuda;
      o.cudaSlabBytes = static_cast<std::uint64_t>(g.dims[0] * g.dims[1]) * 4 * 9; // several slabs
      const MeshToSdfStats st = meshToSdf(prepared, g, all, gpu.data(), o);
      ASSERT_EQ(st.device, Device::Cuda);
      std::int64_t inside = 0;
      for (float v : gpu) inside += std::signbit(v);
      EXPECT_GT(inside, g.count() / 20);
      EXPECT_EQ(std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(float)), 0)
        << (holes ? "holes" : "closed") << " band " << band;
      std::printf("[ cpu vs cuda ] nested spheres%s band %g: %s, %lld inside\n", holes ? " with holes" : "",
        static_cast<double>(band), std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(float)) ? "DIFFER" : "equal",
        static_cast<long long>(inside));
    }
  }
}

TEST(MeshToSdfCuda, DictionaryVolumeKeysInPiecesPinnedAndPageable)
{
  // the keys come back in pieces through a few staging slots: many pieces
  // per group (more than the slots), a last piece shorter than the others,
  // and the pageable fallback; every run equals the CPU's volume key for key
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const TriangleMesh m = holedFlipped();
  const GridGeometry g = fitGridToMesh(m, 75, 2);
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 16;
  vo.bandWidth = 4.0f;
  DictionaryVolume cpu(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  meshToSdf(m, cpu, o);
  const MeshToSdfPrepared prepared = prepareMeshToSdf(m);
  o.device = Device::Cuda;
  o.cudaSlabBytes = static_cast<std::uint64_t>(g.dims[0] * g.dims[1]) * 16 * 4 * 2; // groups of 2 chunk layers
  const std::uint64_t chunkKeyBytes = 16 * 16 * 16 * 2;
  struct Case
  {
    std::uint64_t pieceBytes;
    bool pageable;
  };
  for (const Case c : { Case{ 3 * chunkKeyBytes + 1, false }, Case{ chunkKeyBytes / 2, false },
         Case{ 5 * chunkKeyBytes, true }, Case{ o.cudaKeyPieceBytes, true } })
  {
    o.cudaKeyPieceBytes = c.pieceBytes;
    detail::meshtosdf_cuda::refusePinnedKeys(c.pageable);
    const detail::meshtosdf_cuda::KeyCopyCounts before = detail::meshtosdf_cuda::keyCopyCounts();
    DictionaryVolume gpu(vo);
    const MeshToSdfStats st = meshToSdf(prepared, gpu, o);
    detail::meshtosdf_cuda::refusePinnedKeys(false);
    const detail::meshtosdf_cuda::KeyCopyCounts after = detail::meshtosdf_cuda::keyCopyCounts();
    ASSERT_EQ(st.device, Device::Cuda);
    const std::int64_t pieces = after.pieces - before.pieces, pageable = after.pageable - before.pageable;
    const std::int64_t perPiece = std::max<std::int64_t>(1, static_cast<std::int64_t>(c.pieceBytes / chunkKeyBytes));
    // at least the expanded chunks over the piece size, per group rounded up
    EXPECT_GE(pieces * perPiece, gpu.expandedChunkCount()) << c.pieceBytes;
    if (perPiece <= 3) EXPECT_GT(pieces, 3 * (g.dims[2] / 32 + 1)) << "more pieces than slots per group";
    EXPECT_EQ(pageable, c.pageable ? pieces : 0) << c.pieceBytes;
    std::int64_t diff = 0, structure = 0;
    for (std::int64_t ch = 0; ch < cpu.chunkCount(); ++ch) structure += cpu.isUniform(ch) != gpu.isUniform(ch);
    for (std::int64_t z = 0; z < g.dims[2]; ++z)
      for (std::int64_t y = 0; y < g.dims[1]; ++y)
        for (std::int64_t x = 0; x < g.dims[0]; ++x) diff += cpu.get(x, y, z).sdf != gpu.get(x, y, z).sdf;
    EXPECT_EQ(diff, 0) << c.pieceBytes << (c.pageable ? " pageable" : " pinned");
    EXPECT_EQ(structure, 0) << c.pieceBytes;
    std::printf("[ cpu vs cuda ] keys in pieces of %llu bytes (%s): %lld pieces, %lld key differences, %lld "
                "expanded chunks\n",
      static_cast<unsigned long long>(c.pieceBytes), c.pageable ? "pageable" : "pinned",
      static_cast<long long>(pieces), static_cast<long long>(diff), static_cast<long long>(gpu.expandedChunkCount()));
  }
}

TEST(MeshToSdfCuda, DeviceEncodeMatchesHostEncode)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  const SdfDictionary& d = defaultSdfDictionary();
  std::vector<float> v;
  for (std::uint64_t bits = 0; bits < (1ull << 32); bits += 251) // every 251st float bit pattern (NaN, inf too)
  {
    const std::uint32_t b32 = static_cast<std::uint32_t>(bits);
    float f;
    std::memcpy(&f, &b32, sizeof(f));
    v.push_back(f);
  }
  for (int i = -12000; i <= 12000; ++i) // around every half step of Group A and the gap to Group B
  {
    const float c = static_cast<float>(i * 0.0005);
    v.push_back(c);
    v.push_back(std::nextafter(c, 1e9f));
    v.push_back(std::nextafter(c, -1e9f));
  }
  for (float band : { 4.0f, 8.0f, std::numeric_limits<float>::infinity() })
  {
    const std::vector<std::uint16_t> gpu = detail::meshtosdf_cuda::encodeOnDevice(d.encodeConstants(), band, v);
    std::int64_t bad = 0;
    for (std::size_t i = 0; i < v.size(); ++i) bad += gpu[i] != d.encodeClamped(v[i], band);
    EXPECT_EQ(bad, 0) << "band " << band;
  }
}

TEST(MeshToSdfCuda, MeshTreeLeavesGatheredOnTheDeviceEqualTheHostCopies)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  using namespace detail::meshtosdf;
  std::vector<std::pair<std::string, TriangleMesh>> meshes = oracle::damagedMeshes();
  meshes.emplace_back("holed and flipped", holedFlipped());
  // a soup: every corner its own point (duplicated positions weld), a
  // degenerate triangle skipped, signed zeros and far coordinates
  TriangleMesh soup;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int t = 0; t < 3000; ++t)
  {
    const float big = t % 5 == 0 ? 1e6f : 1.0f;
    for (int k = 0; k < 3; ++k)
      soup.points.push_back({ t % 7 == 0 ? -0.0f : u(rng) * big, u(rng), t % 11 == 0 ? 0.0f : u(rng) });
    const std::uint32_t b = static_cast<std::uint32_t>(3 * t);
    soup.triangles.push_back({ b, b + 1, t % 13 == 0 ? b + 1 : b + 2 });
    if (t % 3 == 0) soup.triangles.push_back({ b, b + 2, b + 1 }); // the reversed copy, sharing the points
  }
  meshes.emplace_back("soup", soup);
  for (const auto& [name, mesh] : meshes)
  {
    const PreparedMesh pm = prepareMesh(mesh, false);
    const Bvh bvh(pm.tris);
    const LargeVector<LeafTri> host = leafCopies(bvh);
    const std::vector<LeafTri> device = detail::meshtosdf_cuda::meshLeavesOnDevice(pm, bvh);
    ASSERT_EQ(device.size(), host.size()) << name;
    std::int64_t differ = 0;
    for (std::size_t i = 0; i < host.size(); ++i) differ += std::memcmp(&device[i], &host[i], sizeof(LeafTri)) != 0;
    EXPECT_EQ(differ, 0) << name << ": " << host.size() << " leaves";
  }
}

TEST(MeshToSdfCuda, PreparedMeshIsReusedAcrossCallsAndDevices)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  TriangleMesh m = holedFlipped();
  const GridGeometry g = fitGridToMesh(m, 48, 2);
  MeshToSdfOptions o;
  o.bandWidth = 3.0f;
  o.sign = SignMode::Unsigned;
  const MeshToSdfPrepared prepared = prepareMeshToSdf(m, SignMode::Unsigned); // winding made on first use
  std::vector<float> first(static_cast<std::size_t>(g.count())), again(first.size()), cpu(first.size());
  for (SignMode s : { SignMode::Unsigned, SignMode::WindingNumber, SignMode::PseudoNormal })
  {
    o.sign = s;
    o.device = Device::Cuda;
    meshToSdf(prepared, FloatGridView{ first.data(), g }, o);
    meshToSdf(prepared, FloatGridView{ again.data(), g }, o);
    o.device = Device::Cpu;
    meshToSdf(m, FloatGridView{ cpu.data(), g }, o); // the one-call CPU path
    EXPECT_EQ(first, again) << toString(s);
    EXPECT_EQ(first, cpu) << toString(s);
  }
  // the prepared mesh owns its data: editing the mesh afterwards changes nothing
  for (auto& p : m.points) p[0] += 0.25f;
  o.device = Device::Cuda;
  meshToSdf(prepared, FloatGridView{ again.data(), g }, o);
  EXPECT_EQ(first, again);
}

TEST(MeshToSdfCuda, FarBlocksMatchCpuAndThePerVoxelPath)
{
  // far blocks on the GPU (MeshToSdfCudaFar.cuh) against the GPU's per-voxel
  // path (bit for bit) and the CPU's far blocks (the saturated voxels bit for
  // bit, the others as in compare()), into floats over several slabs and into
  // a dictionary volume
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::PseudoNormal);
    const GridGeometry g = fitGridToMesh(c.mesh, 72, 8);
    VoxelBox all;
    all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
    for (SignMode s : { SignMode::Normal, SignMode::PseudoNormal })
    {
      for (float band : { 2.0f, std::numeric_limits<float>::infinity() })
      {
        const std::string what = c.name + ", " + toString(s) + ", band " + std::to_string(band);
        MeshToSdfOptions o;
        o.sign = s;
        o.solidsByWinding = false; // the far blocks' own path, on solids too
        o.bandWidth = band;
        o.cudaSlabBytes = static_cast<std::uint64_t>(g.dims[0] * g.dims[1]) * 4 * 13; // slabs of 13 layers
        std::vector<float> cpu(static_cast<std::size_t>(g.count())), gpu(cpu.size()), perVoxel(cpu.size());
        o.device = Device::Cpu;
        const MeshToSdfStats sc = meshToSdf(prepared, g, all, cpu.data(), o);
        o.device = Device::Cuda;
        const MeshToSdfStats sg = meshToSdf(prepared, g, all, gpu.data(), o);
        ASSERT_EQ(sg.device, Device::Cuda);
        o.farBlocks = false;
        const MeshToSdfStats sp = meshToSdf(prepared, g, all, perVoxel.data(), o);
        EXPECT_EQ(sp.farVoxels, 0) << what;
        std::int64_t bits = 0, saturatedBits = 0, badDistance = 0, badSign = 0;
        for (std::size_t i = 0; i < cpu.size(); ++i)
        {
          bits += std::memcmp(&gpu[i], &perVoxel[i], sizeof(float)) != 0;
          const float a = cpu[i], b = gpu[i];
          if (std::fabs(a) == band || std::fabs(b) == band) saturatedBits += std::memcmp(&a, &b, sizeof(float)) != 0;
          if (std::fabs(std::fabs(a) - std::fabs(b)) > 1e-5f * std::max(1.0f, std::fabs(a))) ++badDistance;
          if (std::fabs(a) > 1e-3f && (a < 0) != (b < 0)) ++badSign;
        }
        EXPECT_EQ(bits, 0) << what;
        EXPECT_EQ(saturatedBits, 0) << what;
        EXPECT_EQ(badDistance, 0) << what;
        EXPECT_EQ(badSign, 0) << what;
        if (!std::isfinite(band)) EXPECT_EQ(sg.farVoxels, 0) << what;
        if (c.name == "closed sphere" && std::isfinite(band))
        {
          EXPECT_GT(sg.farVoxels, g.count() / 2) << what;
        }
        std::printf("[ far blocks cuda ] %s: far voxels gpu %lld cpu %lld; %lld bit differences to the per-voxel GPU "
                    "path, %lld saturated and %lld distance differences to the CPU\n",
          what.c_str(), static_cast<long long>(sg.farVoxels), static_cast<long long>(sc.farVoxels),
          static_cast<long long>(bits), static_cast<long long>(saturatedBits), static_cast<long long>(badDistance));
      }
      // dictionary volume: GPU with far blocks against the CPU without
      VolumeOptions vo = volumeOptionsOn(g);
      vo.chunkEdge = 16;
      vo.bandWidth = 3;
      DictionaryVolume a(vo), b(vo);
      MeshToSdfOptions o;
      o.sign = s;
      o.device = Device::Cuda;
      o.cudaVerifyKeys = true;
      const MeshToSdfStats st = meshToSdf(prepared, a, o);
      EXPECT_EQ(st.keyMismatches, 0);
      o.device = Device::Cpu;
      o.farBlocks = false;
      o.cudaVerifyKeys = false;
      meshToSdf(prepared, b, o);
      std::int64_t bad = 0;
      for (std::int64_t z = 0; z < g.dims[2]; ++z)
        for (std::int64_t y = 0; y < g.dims[1]; ++y)
          for (std::int64_t x = 0; x < g.dims[0]; ++x) bad += a.get(x, y, z).sdf != b.get(x, y, z).sdf;
      EXPECT_EQ(bad, 0) << c.name << ", " << toString(s) << " (volume)";
    }
  }
}
