// Mesh to SDF distances against a brute-force double/long-double oracle,
// exact equality of the faithful (paper) mode, grids, outputs, bad input.
#include "ErrorTestUtil.h"
#include "MeshToSdfOracle.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace lvdif;

namespace
{
GridGeometry oddGrid()
{
  GridGeometry g;
  g.dims = { 23, 17, 19 };
  g.origin = { -1.6, -1.5, -1.7 };
  g.spacing = { 0.15, 0.19, 0.18 };
  return g;
}

std::vector<float> run(const TriangleMesh& m, const GridGeometry& g, MeshToSdfOptions o)
{
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  o.device = Device::Cpu;
  meshToSdf(m, FloatGridView{ out.data(), g }, o);
  return out;
}
} // namespace

TEST(MeshToSdf, DistancesMatchBruteForceOracle)
{
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const TriangleMesh m = oracle::randomSoup(40, seed);
    const GridGeometry g = oddGrid();
    MeshToSdfOptions o;
    o.sign = SignMode::Unsigned;
    o.unit = DistanceUnit::World;
    const std::vector<float> d = run(m, g, o);
    double worst = 0;
    for (std::int64_t k = 0; k < g.dims[2]; ++k)
      for (std::int64_t j = 0; j < g.dims[1]; ++j)
        for (std::int64_t i = 0; i < g.dims[0]; ++i)
        {
          const oracle::P p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1],
            g.origin[2] + k * g.spacing[2] };
          const double ref = oracle::distance(m, p);
          worst = std::max(worst, std::fabs(d[g.index(i, j, k)] - ref) / std::max(ref, 1e-3));
        }
    EXPECT_LT(worst, 1e-6) << "seed " << seed; // float rounding of the stored value
  }
}

TEST(MeshToSdf, AllAcceleratorsGiveTheSameFloats)
{
  // Normal signs too: equidistant triangles resolve to the lowest index everywhere
  for (unsigned seed : { 4u, 5u, 6u })
  {
    const TriangleMesh m = seed == 6u ? makeSphereMesh(0.1f, 0, 0, 1.1f, 8, 12) : oracle::randomSoup(60, seed);
    const GridGeometry g = oddGrid();
    MeshToSdfOptions o;
    o.sign = seed == 4u ? SignMode::Unsigned : SignMode::Normal;
    o.accel = MeshToSdfAccel::BruteForce;
    const std::vector<float> ref = run(m, g, o);
    o.accel = MeshToSdfAccel::Bvh;
    EXPECT_EQ(run(m, g, o), ref);
    o.accel = MeshToSdfAccel::Faithful;
    for (int cells : { 1, 3, 8, 16 })
    {
      for (double scale : { 1.0, 2.0 })
      {
        o.faithfulCellsPerAxis = cells;
        o.faithfulScale = scale;
        EXPECT_EQ(run(m, g, o), ref) << "faithful M=" << cells << " scale " << scale;
      }
    }
  }
}

TEST(MeshToSdf, FaithfulExactOnSphereFarOutside)
{
  // voxels far from the mesh are where the original's single-list lookup
  // missed the nearest triangle
  const TriangleMesh m = makeSphereMesh(0.2f, -0.1f, 0.05f, 0.7f, 12, 24);
  GridGeometry g;
  g.dims = { 20, 21, 22 };
  g.origin = { -3, -3, -3 };
  g.spacing = { 0.3, 0.3, 0.3 };
  MeshToSdfOptions o;
  o.sign = SignMode::PseudoNormal;
  o.accel = MeshToSdfAccel::BruteForce;
  const std::vector<float> ref = run(m, g, o);
  o.accel = MeshToSdfAccel::Faithful;
  EXPECT_EQ(run(m, g, o), ref);
}

TEST(MeshToSdf, SubExtentEqualsTheSameVoxelsOfTheWhole)
{
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 10, 20);
  const GridGeometry g = oddGrid();
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  const std::vector<float> whole = run(m, g, o);
  VoxelBox box;
  box.lo = { 3, 5, 2 };
  box.hi = { 20, 9, 15 };
  std::vector<float> part(static_cast<std::size_t>(box.voxelCount()));
  meshToSdf(m, g, box, part.data(), o);
  std::size_t n = 0;
  for (std::int64_t k = box.lo[2]; k <= box.hi[2]; ++k)
    for (std::int64_t j = box.lo[1]; j <= box.hi[1]; ++j)
      for (std::int64_t i = box.lo[0]; i <= box.hi[0]; ++i)
      {
        ASSERT_EQ(part[n++], whole[g.index(i, j, k)]);
      }
}

TEST(MeshToSdf, VoxelUnitsAndBand)
{
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 10, 20);
  const GridGeometry g = oddGrid();
  MeshToSdfOptions o;
  o.unit = DistanceUnit::World;
  const std::vector<float> world = run(m, g, o);
  o.unit = DistanceUnit::Voxel;
  o.bandWidth = 2.0f;
  const std::vector<float> vox = run(m, g, o);
  const double h = 0.15; // smallest spacing
  for (std::size_t i = 0; i < world.size(); ++i)
  {
    const double expect = std::max(-2.0, std::min(2.0, world[i] / h));
    ASSERT_NEAR(vox[i], expect, 1e-5) << i;
  }
}

TEST(MeshToSdf, DictionaryVolumeMatchesFloatPath)
{
  // a clean sphere, and one with every 7th face reversed (the winding
  // correction's per-block bounds then run); the float buffer of the sparse
  // route as large as the whole chunk layer, and as small as one row of chunks
  TriangleMesh reversed = makeSphereMesh(0, 0, 0, 1.0f, 16, 32);
  for (std::size_t t = 0; t < reversed.triangles.size(); t += 7) std::swap(reversed.triangles[t][1], reversed.triangles[t][2]);
  const TriangleMesh meshes[] = { makeSphereMesh(0, 0, 0, 1.0f, 16, 32), reversed };
  for (const TriangleMesh& m : meshes)
    for (std::uint64_t bandBytes : { std::uint64_t{ 32 } << 20, std::uint64_t{ 1 } })
    {
      SCOPED_TRACE(&m == &meshes[0] ? "clean sphere" : "sphere, every 7th face reversed");
      SCOPED_TRACE(bandBytes);
      VolumeOptions vo;
      vo.dims = { 45, 40, 37 }; // not multiples of the chunk edge
      vo.chunkEdge = 8;
      vo.origin = { -1.5, -1.4, -1.3 };
      vo.spacing = { 0.07, 0.07, 0.07 };
      vo.bandWidth = 3.0f;
      DictionaryVolume vol(vo);
      MeshToSdfOptions o;
      o.device = Device::Cpu;
      o.cpuBandBytes = bandBytes;
      const MeshToSdfStats st = meshToSdf(m, vol, o);
      EXPECT_EQ(st.triangles, m.triangles.size());
      const GridGeometry g = gridOf(vo);
      o.bandWidth = 3.0f;
      const std::vector<float> ref = run(m, g, o);
      for (std::int64_t z = 0; z < g.dims[2]; ++z)
        for (std::int64_t y = 0; y < g.dims[1]; ++y)
          for (std::int64_t x = 0; x < g.dims[0]; ++x)
          {
            ASSERT_EQ(vol.get(x, y, z).sdf, vol.encode(ref[g.index(x, y, z)])) << x << " " << y << " " << z;
          }
      // a chunk is expanded exactly when its keys differ (equal keys from
      // different floats collapse too)
      for (std::int64_t id = 0; id < vol.chunkCount(); ++id)
      {
        const VoxelBox cb = vol.chunkBox(id);
        const SdfKey first = vol.get(cb.lo[0], cb.lo[1], cb.lo[2]).sdf;
        bool same = true;
        for (std::int64_t z = cb.lo[2]; z <= cb.hi[2]; ++z)
          for (std::int64_t y = cb.lo[1]; y <= cb.hi[1]; ++y)
            for (std::int64_t x = cb.lo[0]; x <= cb.hi[0]; ++x) same = same && vol.get(x, y, z).sdf == first;
        EXPECT_EQ(vol.isUniform(id), same) << "chunk " << id;
      }
      // far chunks are saturated and stay uniform
      EXPECT_LT(vol.expandedChunkCount(), vol.chunkCount());
      EXPECT_GT(vol.expandedChunkCount(), 0);
      EXPECT_FALSE(vol.takeDirtyChunks().empty());
    }
}

TEST(MeshToSdf, FitGridToMesh)
{
  const TriangleMesh m = makeBoxMesh({ 0, 0, 0 }, { 4, 2, 1 });
  const GridGeometry g = fitGridToMesh(m, 101, 2.5);
  EXPECT_EQ(g.dims[0], 101);
  EXPECT_LT(g.dims[1], 101);
  EXPECT_LT(g.dims[2], g.dims[1]);
  EXPECT_DOUBLE_EQ(g.spacing[0], g.spacing[1]);
  EXPECT_DOUBLE_EQ(g.spacing[0], g.spacing[2]);
  for (int a = 0; a < 3; ++a)
  {
    const double hi = a == 0 ? 4 : (a == 1 ? 2 : 1);
    // at least 2.5 voxels of margin on both sides
    EXPECT_LE(g.origin[a] + 2.5 * g.spacing[a], 1e-9) << a;
    EXPECT_GE(g.origin[a] + (g.dims[a] - 1 - 2.5) * g.spacing[a], hi - 1e-9) << a;
  }
  EXPECT_NEAR(g.origin[0] + 2.5 * g.spacing[0], 0, 1e-9);
}

TEST(MeshToSdf, FitGridGivesAFlatMeshOneCellAtZeroPadding)
{
  // a flat sheet (z = 0.5) without padding: its axis got 1 point, a volume
  // nothing can mesh (not even the unsigned shell around the sheet) and no
  // editor can open; now 2 points (MinCanvasDimension), the sheet midway
  TriangleMesh sheet;
  sheet.points = { { 0, 0, 0.5f }, { 3, 0, 0.5f }, { 0, 2, 0.5f } };
  sheet.triangles = { { 0, 1, 2 } };
  const GridGeometry g = fitGridToMesh(sheet, 16, 0);
  EXPECT_EQ(g.dims[0], 16);
  EXPECT_EQ(g.dims[2], DictionaryVolume::MinCanvasDimension);
  EXPECT_NEAR(g.origin[2] + 0.5 * g.spacing[2], 0.5, 1e-9);
  EXPECT_EQ(fitGridToMesh(sheet, 16, 1).dims[2], 3); // padding alone already gives the cell
}

TEST(MeshToSdf, DegenerateTrianglesAreSkippedAndCounted)
{
  TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 8, 16);
  const TriangleMesh clean = m;
  m.points.push_back({ 0.3f, 0.3f, 0.3f });
  const std::uint32_t last = static_cast<std::uint32_t>(m.points.size() - 1);
  m.triangles.push_back({ last, last, 0 });      // repeated index
  m.triangles.push_back({ 0, 0, 0 });             // a point
  const GridGeometry g = oddGrid();
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  std::vector<float> a(static_cast<std::size_t>(g.count())), b(a.size());
  const MeshToSdfStats st = meshToSdf(m, FloatGridView{ a.data(), g }, o);
  meshToSdf(clean, FloatGridView{ b.data(), g }, o);
  EXPECT_EQ(st.degenerateSkipped, 2u);
  EXPECT_EQ(a, b);
}

// A closed box whose top and front faces are polygons with 7 more corners on
// their shared edge: the reader's ears of collinear corners have zero area
// and are skipped, but they still close their edges, so the box has no
// boundary (the skipped ears left it with 4 boundary edges). Exactly
// collinear at size 1, and collinear only after rounding to float at 1e20
// (corners 1e6 off the edge in the file, well under the float spacing there).
TEST(MeshToSdf, ZeroAreaEarsOfPolygonsLeaveAClosedMeshClosed)
{
  for (const double size : { 1.0, 1e20 })
  {
    SCOPED_TRACE(size);
    const double o = size; // the box spans [o, o + size] on every axis
    const double bulge = size > 1 ? 1e6 : 0.0;
    std::vector<std::array<double, 3>> v;
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) v.push_back({ o + x * size, o + y * size, o + z * size }); // 1 + x + 2y + 4z
    for (int k = 1; k < 8; ++k) v.push_back({ o + k * size / 8, o - bulge, o + size }); // 9 .. 15 (OBJ ids)
    // outward faces; the top's corners run along the shared edge one way, the front's the other
    const std::vector<std::vector<int>> faces = { { 5, 9, 10, 11, 12, 13, 14, 15, 6, 8, 7 },
      { 1, 2, 6, 15, 14, 13, 12, 11, 10, 9, 5 }, { 1, 3, 4, 2 }, { 3, 7, 8, 4 }, { 1, 5, 7, 3 }, { 2, 4, 8, 6 } };
    std::string obj;
    char line[128];
    for (const auto& p : v)
    {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
      obj += line;
    }
    std::map<std::pair<int, int>, int> directed; // the oracle: the file's polygon edges pair up
    for (const auto& f : faces)
    {
      obj += "f";
      for (std::size_t i = 0; i < f.size(); ++i)
      {
        obj += " " + std::to_string(f[i]);
        ++directed[{ f[i], f[(i + 1) % f.size()] }];
      }
      obj += "\n";
    }
    for (const auto& e : directed) ASSERT_EQ(directed.count({ e.first.second, e.first.first }), 1u);
    MemorySource src(obj.data(), obj.size());
    const TriangleMesh m = readMesh(src, MeshFormat::Obj, "box.obj");
    const MeshToSdfPrepared prepared = prepareMeshToSdf(m, SignMode::WindingNumber);
    EXPECT_GT(prepared.degenerateSkipped(), 0u); // the guard: there are zero-area ears
    EXPECT_EQ(prepared.boundaryEdges(), 0u);
  }
}

TEST(MeshToSdf, BadInputIsRefused)
{
  const GridGeometry g = oddGrid();
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  // each refused with InvalidArgument (errorMessageOf fails the test otherwise)
  auto refusal = [&](const TriangleMesh& m, const GridGeometry& gg) {
    return errortest::errorMessageOf(
      [&] { meshToSdf(m, gg, VoxelBox{ { 0, 0, 0 }, { 0, 0, 0 } }, out.data(), o); }, ErrorCode::InvalidArgument);
  };
  const TriangleMesh sphere = makeSphereMesh(0, 0, 0, 1.0f, 4, 6);
  refusal(TriangleMesh{}, g);
  TriangleMesh nan = sphere;
  nan.points[1][2] = std::numeric_limits<float>::quiet_NaN();
  refusal(nan, g);
  // a coordinate beyond +-1e30 (a float still) is the mesh's error with its bounds, also on an
  // explicit grid (it was checked only for NaN and infinity here, and the distances overflowed)
  TriangleMesh far = sphere;
  far.points[1][2] = 3e38f;
  const std::string farRefused = refusal(far, g);
  EXPECT_NE(farRefused.find("mesh coordinates span"), std::string::npos) << farRefused;
  TriangleMesh badIndex = sphere;
  badIndex.triangles[0][1] = 999;
  refusal(badIndex, g);
  TriangleMesh allDegenerate;
  allDegenerate.points = { { 0, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 } };
  allDegenerate.triangles = { { 0, 1, 2 } };
  // one sentence, the count in the right number ("no triangle of non-zero area (1 degenerate triangles)")
  EXPECT_EQ(refusal(allDegenerate, g), "the mesh's only triangle has zero area (its corners coincide or lie on one line), "
                                       "so there is no surface to convert: check the file's points and faces");
  allDegenerate.triangles = { { 0, 1, 2 }, { 2, 1, 0 }, { 0, 0, 1 } };
  EXPECT_EQ(refusal(allDegenerate, g), "all 3 triangles of the mesh have zero area (the corners of each coincide or lie "
                                       "on one line), so there is no surface to convert: check the file's points and faces");
  GridGeometry huge = g;
  huge.dims = { 1 << 22, 4, 4 };
  refusal(sphere, huge);
  GridGeometry zeroSpacing = g;
  zeroSpacing.spacing[1] = 0;
  refusal(sphere, zeroSpacing);
  // extent outside the grid
  EXPECT_THROW(meshToSdf(sphere, g, VoxelBox{ { 0, 0, 0 }, { 23, 0, 0 } }, out.data(), o), Error);
  // fitted grids: zero-size bounds, absurd dims
  TriangleMesh point;
  point.points = { { 1, 1, 1 } };
  point.triangles = { { 0, 0, 0 } };
  EXPECT_THROW(fitGridToMesh(point, 64, 1), Error);
  EXPECT_THROW(fitGridToMesh(sphere, std::int64_t(1) << 40, 1), Error);
  EXPECT_THROW(fitGridToMesh(sphere, 8, 4), Error);
  // a dictionary volume of absurd size is refused by its constructor, before allocating
  VolumeOptions vo;
  vo.dims = { 1 << 20, 1 << 20, 1 << 20 };
  EXPECT_THROW(DictionaryVolume v(vo), Error);
}

TEST(MeshToSdf, CancelStopsWithCancelled)
{
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 8, 16);
  const GridGeometry g = oddGrid();
  std::vector<float> out(static_cast<std::size_t>(g.count()));
  CancelFlagInterrupter intr;
  intr.cancel();
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  errortest::errorMessageOf([&] { meshToSdf(m, FloatGridView{ out.data(), g }, o, intr); }, ErrorCode::Cancelled);
}

namespace
{
/// Cancels from its n-th poll on (1-based).
struct CancelAtPoll : Interrupter
{
  explicit CancelAtPoll(int n)
    : At(n)
  {
  }
  bool wasInterrupted() const override { return ++this->Polls >= this->At; }
  int At;
  mutable std::atomic<int> Polls{ 0 };
};
} // namespace

TEST(MeshToSdf, ACancelDuringTheBuildStopsAtTheNextPhaseAndLosesNothing)
{
  // Ctrl-C while a large mesh's structures were built (seconds for 832k
  // triangles on two cores) waited for the whole build: no phase polled.
  // Cancel at every poll in turn: some cancels must fall between two phases
  // of the preparation, of the nearest index and of the solid check (told
  // by the phase trace), and after each, the same prepared mesh must give
  // the uncancelled field bit for bit (a stopped build publishes nothing).
  const TriangleMesh m = makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 24, 48);
  const GridGeometry g = fitGridToMesh(m, 12, 2);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  o.sign = SignMode::Normal;
  std::vector<float> reference(static_cast<std::size_t>(g.count())), out(reference.size());
  meshToSdf(m, FloatGridView{ reference.data(), g }, o);
  auto between = [](const std::string& log, const char* done, const char* next) {
    return log.find(done) != std::string::npos && log.find(next) == std::string::npos;
  };
  bool inPrepare = false, inIndex = false, inCheck = false, finished = false;
  int cancels = 0;
  for (int n = 1; n < 1000 && !finished; ++n)
  {
    // the one-call API (it prepares) ...
    MeshToSdfOptions traced = o;
    traced.tracePhases = true;
    CancelAtPoll c(n);
    testing::internal::CaptureStderr();
    bool cancelled = false;
    try
    {
      meshToSdf(m, FloatGridView{ out.data(), g }, traced, c);
    }
    catch (const Error& e)
    {
      cancelled = e.code() == ErrorCode::Cancelled;
      if (!cancelled) ADD_FAILURE() << e.what();
    }
    const std::string log = testing::internal::GetCapturedStderr();
    if (!cancelled)
    {
      finished = true;
      EXPECT_EQ(std::memcmp(out.data(), reference.data(), out.size() * sizeof(float)), 0);
      break;
    }
    ++cancels;
    inPrepare = inPrepare || between(log, "prepare: validate and weld", "prepare: triangle records");
    inIndex = inIndex || between(log, "nearest index: binary tree", "nearest index: slabs");
    inCheck = inCheck || between(log, "solid check: edges and fans", "solid check: no triangles meet");
    // ... and a prepared mesh, cancelled at the same poll, then asked again
    const MeshToSdfPrepared prepared = prepareMeshToSdf(m, SignMode::Normal);
    CancelAtPoll again(n);
    try
    {
      meshToSdf(prepared, FloatGridView{ out.data(), g }, o, again);
    }
    catch (const Error& e)
    {
      EXPECT_EQ(e.code(), ErrorCode::Cancelled) << e.what();
    }
    std::fill(out.begin(), out.end(), 0.0f);
    meshToSdf(prepared, FloatGridView{ out.data(), g }, o);
    EXPECT_EQ(std::memcmp(out.data(), reference.data(), out.size() * sizeof(float)), 0) << "after a cancel at poll " << n;
  }
  EXPECT_TRUE(finished);
  EXPECT_GT(cancels, 3);
  EXPECT_TRUE(inPrepare) << "no cancel between the preparation's phases";
  EXPECT_TRUE(inIndex) << "no cancel between the nearest index's phases";
  EXPECT_TRUE(inCheck) << "no cancel between the solid check's phases";
}

namespace
{
/// Records each stage's name and the last fraction reported in it.
struct StageRecorder : Interrupter
{
  std::vector<std::pair<std::string, double>> stages;
  void start(const char* name) override { stages.emplace_back(name, -1.0); }
  void progress(double f) override
  {
    ASSERT_FALSE(stages.empty()) << "progress before any stage";
    stages.back().second = f;
  }
};
} // namespace

TEST(MeshToSdf, EveryStageReportsItsEndBeforeTheNextBegins)
{
  // progress comes from OpenMP thread 0, which need not run the last row: the
  // CLI printed "mesh to SDF: done" only when it did (a CI failure)
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 12, 24);
  const GridGeometry g = fitGridToMesh(m, 40, 3);
  for (SignMode sign : { SignMode::WindingNumber, SignMode::Normal })
  {
    MeshToSdfOptions o;
    o.device = Device::Cpu;
    o.sign = sign;
    o.svfFilters = SvfAll;
    std::vector<float> out(static_cast<std::size_t>(g.count()));
    StageRecorder grid;
    meshToSdf(m, FloatGridView{ out.data(), g }, o, grid);
    VolumeOptions vo = volumeOptionsOn(g);
    DictionaryVolume volume(vo);
    StageRecorder vol;
    meshToSdf(m, volume, o, vol);
    for (const StageRecorder* r : { &grid, &vol })
    {
      ASSERT_GE(r->stages.size(), 2u) << "mesh to SDF, then the sign voxel filters";
      EXPECT_EQ(r->stages.front().first, "mesh to SDF");
      for (const auto& [name, last] : r->stages) EXPECT_EQ(last, 1.0) << name << ", sign " << toString(sign);
    }
  }
}

TEST(MeshToSdf, PreparedMeshEqualsOneCallAndIsNeverStale)
{
  // a holed sphere (open: boundary cone) checked against the oracle, then the
  // prepared path against it bit for bit, before and after editing the mesh;
  // prepared for Unsigned, the pseudo-normals are built by the first
  // PseudoNormal call (after the winding structures), and must be those of
  // the one-call path, which prepares them at once
  TriangleMesh m = makeSphereMesh(0.1f, 0.0f, -0.05f, 1.0f, 12, 24);
  m.triangles.erase(m.triangles.begin(), m.triangles.begin() + 24);
  const GridGeometry g = fitGridToMesh(m, 24, 2);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  o.bandWidth = 4.0f;
  const MeshToSdfPrepared prepared = prepareMeshToSdf(m, SignMode::Unsigned);
  EXPECT_EQ(prepared.triangles(), m.triangles.size());
  EXPECT_GT(prepared.boundaryEdges(), 0u);
  std::vector<float> one(static_cast<std::size_t>(g.count())), prep(one.size());
  for (SignMode s : { SignMode::WindingNumber, SignMode::PseudoNormal, SignMode::Normal, SignMode::Unsigned })
  {
    o.sign = s;
    meshToSdf(m, FloatGridView{ one.data(), g }, o);
    meshToSdf(prepared, FloatGridView{ prep.data(), g }, o);
    EXPECT_EQ(one, prep) << toString(s);
  }
  for (std::int64_t k = 0; k < g.dims[2]; k += 3)
    for (std::int64_t j = 0; j < g.dims[1]; j += 3)
      for (std::int64_t i = 0; i < g.dims[0]; i += 3)
      {
        const double ref = std::min(4.0, oracle::distance(m, { g.origin[0] + i * g.spacing[0],
          g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] }) / g.spacing[0]);
        ASSERT_NEAR(std::fabs(prep[g.index(i, j, k)]), ref, 1e-4);
      }
  const std::vector<float> before = prep;
  for (auto& p : m.points) p[1] += 0.3f; // edit the mesh: the prepared copy must not see it
  meshToSdf(prepared, FloatGridView{ prep.data(), g }, o);
  EXPECT_EQ(prep, before);
  meshToSdf(m, FloatGridView{ one.data(), g }, o);
  EXPECT_NE(one, before);
}
