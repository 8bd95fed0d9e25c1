// Far blocks (MeshToSdfOptions::farBlocks) against the per-voxel path: the
// Normal and PseudoNormal fields must be the same floats bit for bit on every
// mesh (clean, sharp, open, flipped, duplicated, non-manifold, intersecting,
// soups, slivers), on cubic and non-cubic grids, sub-extents and dictionary
// volumes, with several bands; and the per-voxel path itself equals the
// brute-force accelerator (no index, no far blocks) on a smaller grid.
#include "MeshToSdfFarCases.h"
#include "../src/MeshToSdfNearestRow.h" // nearestRowUseAvx2
#include "lvdif/DictionaryVolume.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
struct FarRun
{
  std::vector<float> out;
  MeshToSdfStats stats;
};

FarRun run(const MeshToSdfPrepared& m, const GridGeometry& g, const VoxelBox& box, MeshToSdfOptions o, bool far)
{
  o.device = Device::Cpu;
  o.farBlocks = far;
  FarRun r;
  r.out.assign(static_cast<std::size_t>(box.voxelCount()), 0.0f);
  r.stats = meshToSdf(m, g, box, r.out.data(), o);
  return r;
}

std::int64_t bitDifferences(const std::vector<float>& a, const std::vector<float>& b)
{
  std::int64_t bad = 0;
  for (std::size_t i = 0; i < a.size(); ++i) bad += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return bad;
}

VoxelBox whole(const GridGeometry& g)
{
  VoxelBox b;
  b.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  return b;
}

struct Grid
{
  const char* name;
  GridGeometry g;
  VoxelBox box;
};

/// The grids every far-block test runs on: a cubic one fitted to the mesh
/// (at least 41 x 34 x 39), a non-cubic one (other counts per axis,
/// anisotropic spacing, origin off the mesh's bounds) and a sub-extent of the
/// cubic one whose blocks do not start at the grid's.
std::vector<Grid> testGrids(const TriangleMesh& mesh, std::int64_t resolution)
{
  GridGeometry cubic = fitGridToMesh(mesh, resolution, 6);
  cubic.dims = { std::max<std::int64_t>(cubic.dims[0], 41), std::max<std::int64_t>(cubic.dims[1], 34),
    std::max<std::int64_t>(cubic.dims[2], 39) };
  GridGeometry odd;
  odd.dims = { 37, 21, 29 };
  odd.origin = { -1.71, -1.43, -1.52 };
  odd.spacing = { 0.093, 0.141, 0.117 };
  VoxelBox sub;
  sub.lo = { 3, 5, 7 };
  sub.hi = { 40, 33, 38 };
  return { Grid{ "cubic", cubic, whole(cubic) }, Grid{ "non-cubic", odd, whole(odd) }, Grid{ "sub-extent", cubic, sub } };
}
} // namespace

TEST(MeshToSdfFarBlocks, SameFloatsAsPerVoxelOnEveryMeshGridAndBand)
{
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::PseudoNormal);
    const std::vector<Grid> grids = testGrids(c.mesh, 44);
    const GridGeometry& cubic = grids[0].g;
    for (const Grid& gr : grids)
    {
      for (SignMode s : { SignMode::Normal, SignMode::PseudoNormal })
      {
        for (float band : { 1.5f, 4.0f, std::numeric_limits<float>::infinity() })
        {
          for (DistanceUnit unit : { DistanceUnit::Voxel, DistanceUnit::World })
          {
            if (unit == DistanceUnit::World && std::string(gr.name) != "cubic") continue;
            MeshToSdfOptions o;
            o.sign = s;
            o.solidsByWinding = false; // the far blocks' own path, on solids too
            o.bandWidth = unit == DistanceUnit::World ? band * 0.1f : band;
            o.unit = unit;
            const FarRun fast = run(prepared, gr.g, gr.box, o, true), slow = run(prepared, gr.g, gr.box, o, false);
            const std::string what = c.name + ", " + gr.name + ", " + toString(s) + ", band " + std::to_string(band) +
              (unit == DistanceUnit::World ? " world" : " voxels");
            EXPECT_EQ(bitDifferences(fast.out, slow.out), 0) << what;
            EXPECT_EQ(slow.stats.farVoxels, 0) << what;
            if (!std::isfinite(band)) EXPECT_EQ(fast.stats.farVoxels, 0) << what;
            std::int64_t saturated = 0;
            for (float v : slow.out) saturated += std::fabs(v) == o.bandWidth;
            EXPECT_LE(fast.stats.farVoxels, saturated) << what;
            // the shortcut must actually work where the surface allows it
            if (std::isfinite(band) && band < 2 && c.name == "closed sphere" && std::string(gr.name) == "cubic")
              EXPECT_GT(fast.stats.farVoxels, saturated / 3) << what;
            // with pseudo-normals the voxel level and the per-feature planes decide most of the saturated
            // voxels off corners and fins too (before them: 23 % of the box's, 3 % of the fin's)
            if (s == SignMode::PseudoNormal && band == 1.5f && unit == DistanceUnit::Voxel &&
              std::string(gr.name) == "cubic" &&
              (c.name == "closed sphere" || c.name == "closed box" || c.name == "non-manifold boxes + fin"))
              EXPECT_GT(fast.stats.farVoxels, saturated * 8 / 10) << what;
            if (s == SignMode::PseudoNormal && band == 1.5f && unit == DistanceUnit::Voxel)
              std::printf("[ far blocks ] %s, %s: %lld of %lld saturated voxels by far blocks\n", c.name.c_str(),
                gr.name, static_cast<long long>(fast.stats.farVoxels), static_cast<long long>(saturated));
          }
        }
      }
    }
    // vertex normals (Normal mode): no far blocks, same result
    MeshToSdfOptions o;
    o.sign = SignMode::Normal;
    o.useVertexNormals = true;
    o.bandWidth = 2;
    const FarRun fast = run(prepared, cubic, whole(cubic), o, true), slow = run(prepared, cubic, whole(cubic), o, false);
    EXPECT_EQ(bitDifferences(fast.out, slow.out), 0) << c.name;
    EXPECT_EQ(fast.stats.farVoxels, 0) << c.name;
  }
}

TEST(MeshToSdfFarBlocks, PerVoxelPathEqualsBruteForce)
{
  // the reference of the test above, against the brute-force accelerator
  // (every triangle for every voxel; far blocks apply to the BVH only)
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::PseudoNormal);
    const GridGeometry g = fitGridToMesh(c.mesh, 20, 6);
    for (SignMode s : { SignMode::Normal, SignMode::PseudoNormal, SignMode::WindingNumber, SignMode::Unsigned })
    {
      MeshToSdfOptions o;
      o.sign = s;
      o.solidsByWinding = false; // the far blocks' own path, on solids too
      o.bandWidth = 1.5f;
      const FarRun fast = run(prepared, g, whole(g), o, true);
      o.accel = MeshToSdfAccel::BruteForce;
      const FarRun brute = run(prepared, g, whole(g), o, true);
      EXPECT_EQ(brute.stats.farVoxels, 0) << c.name;
      EXPECT_EQ(bitDifferences(fast.out, brute.out), 0) << c.name << ", " << toString(s);
    }
  }
}

TEST(MeshToSdfFarBlocks, DictionaryVolumeSameKeys)
{
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::PseudoNormal);
    const GridGeometry g = fitGridToMesh(c.mesh, 70, 8);
    VolumeOptions vo = volumeOptionsOn(g);
    vo.chunkEdge = 16;
    vo.bandWidth = 3;
    for (SignMode s : { SignMode::Normal, SignMode::PseudoNormal })
    {
      DictionaryVolume a(vo), b(vo);
      MeshToSdfOptions o;
      o.sign = s;
      o.solidsByWinding = false; // the far blocks' own path, on solids too
      o.device = Device::Cpu;
      const MeshToSdfStats st = meshToSdf(prepared, a, o);
      o.farBlocks = false;
      meshToSdf(prepared, b, o);
      std::int64_t bad = 0;
      for (std::int64_t z = 0; z < g.dims[2]; ++z)
        for (std::int64_t y = 0; y < g.dims[1]; ++y)
          for (std::int64_t x = 0; x < g.dims[0]; ++x) bad += a.get(x, y, z).sdf != b.get(x, y, z).sdf;
      EXPECT_EQ(bad, 0) << c.name << ", " << toString(s);
      if (c.name == "closed sphere") EXPECT_GT(st.farVoxels, g.count() / 2) << toString(s);
    }
  }
}

TEST(MeshToSdfFarBlocks, WindingAndUnsignedBlocksPastTheBandSameFloats)
{
  // the same blocks by distance alone (the winding sign pass comes after):
  // bit for bit the per-voxel path, on a cubic and a non-cubic grid and a
  // sub-extent, in voxels and world units, and into a dictionary volume
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::WindingNumber);
    const std::vector<Grid> grids = testGrids(c.mesh, 40);
    const GridGeometry& cubic = grids[0].g;
    for (const Grid& gr : grids)
    {
      for (SignMode s : { SignMode::WindingNumber, SignMode::Unsigned })
      {
        for (float band : { 1.5f, 4.0f })
        {
          for (DistanceUnit unit : { DistanceUnit::Voxel, DistanceUnit::World })
          {
            MeshToSdfOptions o;
            o.sign = s;
            o.solidsByWinding = false; // the far blocks' own path, on solids too
            o.bandWidth = unit == DistanceUnit::World ? band * 0.1f : band;
            o.unit = unit;
            const FarRun fast = run(prepared, gr.g, gr.box, o, true), slow = run(prepared, gr.g, gr.box, o, false);
            const std::string what = c.name + ", " + gr.name + ", " + toString(s) + ", band " + std::to_string(band) +
              (unit == DistanceUnit::World ? " world" : " voxels");
            EXPECT_EQ(bitDifferences(fast.out, slow.out), 0) << what;
            EXPECT_EQ(slow.stats.farVoxels, 0) << what;
            std::int64_t saturated = 0;
            for (float v : slow.out) saturated += std::fabs(v) == o.bandWidth;
            EXPECT_LE(fast.stats.farVoxels, saturated) << what;
            if (c.name == "closed sphere" && std::string(gr.name) == "cubic")
              EXPECT_GT(fast.stats.farVoxels, saturated / 2) << what;
          }
        }
      }
    }
    VolumeOptions vo = volumeOptionsOn(cubic);
    vo.chunkEdge = 16;
    vo.bandWidth = 3;
    DictionaryVolume a(vo), b(vo);
    MeshToSdfOptions o;
    o.sign = SignMode::WindingNumber;
    o.device = Device::Cpu;
    const MeshToSdfStats st = meshToSdf(prepared, a, o);
    o.farBlocks = false;
    meshToSdf(prepared, b, o);
    std::int64_t bad = 0;
    for (std::int64_t z = 0; z < cubic.dims[2]; ++z)
      for (std::int64_t y = 0; y < cubic.dims[1]; ++y)
        for (std::int64_t x = 0; x < cubic.dims[0]; ++x) bad += a.get(x, y, z).sdf != b.get(x, y, z).sdf;
    EXPECT_EQ(bad, 0) << c.name << ", dictionary volume";
    if (c.name == "closed sphere") EXPECT_GT(st.farVoxels, cubic.count() / 2) << "dictionary volume";
  }
}

TEST(MeshToSdfFarBlocks, BandBricksEqualBruteForce)
{
  // the voxels within the band go through bricks (8 x 4 x 4) with one candidate
  // list each (NearestIndex::nearestBrick): bit for bit the brute-force
  // accelerator (every triangle for every voxel) on open, flipped, duplicated,
  // non-manifold and intersecting meshes and soups, on the non-cubic grid
  // (37 x 21 x 29: partial bricks on every axis, anisotropic spacing) and a
  // sub-extent whose bricks start off the grid's, with bands that cut
  // through bricks: a third of a voxel, 2.7 voxels, and one wider than the
  // grid (nothing far: every brick is exact), in voxels and world units
  for (const farcases::Case& c : farcases::meshes())
  {
    const MeshToSdfPrepared prepared = prepareMeshToSdf(c.mesh, SignMode::WindingNumber);
    const std::vector<Grid> grids = testGrids(c.mesh, 24);
    for (const Grid& gr : { grids[1], grids[2] })
    {
      for (float band : { 0.3f, 2.7f, 40.0f })
      {
        const SignMode s = std::string(gr.name) == "non-cubic" ? SignMode::WindingNumber : SignMode::Unsigned;
        const DistanceUnit unit = band == 2.7f ? DistanceUnit::World : DistanceUnit::Voxel;
        MeshToSdfOptions o;
        o.sign = s;
        o.solidsByWinding = false; // the far blocks' own path, on solids too
        o.unit = unit;
        o.bandWidth = unit == DistanceUnit::World ? band * 0.1f : band;
        // the candidate scan four lanes at a time, and eight where the CPU has AVX2
        const bool avx2 = detail::meshtosdf::nearestRowUseAvx2;
        detail::meshtosdf::nearestRowUseAvx2 = false;
        const FarRun bricks4 = run(prepared, gr.g, gr.box, o, true);
        detail::meshtosdf::nearestRowUseAvx2 = avx2;
        const FarRun bricks = run(prepared, gr.g, gr.box, o, true);
        o.accel = MeshToSdfAccel::BruteForce;
        const FarRun brute = run(prepared, gr.g, gr.box, o, true);
        const std::string what = c.name + ", " + gr.name + ", " + toString(s) + ", band " + std::to_string(band) +
          (unit == DistanceUnit::World ? " world" : " voxels");
        EXPECT_EQ(bitDifferences(bricks.out, brute.out), 0) << what;
        EXPECT_EQ(bitDifferences(bricks4.out, brute.out), 0) << what << ", four lanes";
        std::int64_t within = 0;
        for (float v : brute.out) within += std::fabs(v) < o.bandWidth;
        EXPECT_GT(within, 0) << what; // the band holds voxels that the bricks computed
      }
    }
  }
}

TEST(MeshToSdfFarBlocks, BandBricksOnACoarseGridOfADenseMeshEqualBruteForce)
{
  // a coarse grid (12 voxels across) on a dense mesh, band 8 voxels: the band
  // holds nearly every voxel and the bricks' candidate lists would hold
  // thousands of triangles, so the bricks go point by point
  // (NearestIndex::BrickListMax): bit for bit the brute-force accelerator, in
  // both modes, with the AVX2 and the four-lane scans
  const TriangleMesh mesh = farcases::denseMesh();
  const MeshToSdfPrepared prepared = prepareMeshToSdf(mesh, SignMode::WindingNumber);
  const GridGeometry g = fitGridToMesh(mesh, 12, 2);
  for (SignMode s : { SignMode::WindingNumber, SignMode::Unsigned })
  {
    MeshToSdfOptions o;
    o.sign = s;
    o.solidsByWinding = false; // the far blocks' own path, on solids too
    o.bandWidth = 8;
    const bool avx2 = detail::meshtosdf::nearestRowUseAvx2;
    detail::meshtosdf::nearestRowUseAvx2 = false;
    const FarRun bricks4 = run(prepared, g, whole(g), o, true);
    detail::meshtosdf::nearestRowUseAvx2 = avx2;
    const FarRun bricks = run(prepared, g, whole(g), o, true);
    o.accel = MeshToSdfAccel::BruteForce;
    const FarRun brute = run(prepared, g, whole(g), o, true);
    EXPECT_EQ(bitDifferences(bricks.out, brute.out), 0) << toString(s);
    EXPECT_EQ(bitDifferences(bricks4.out, brute.out), 0) << toString(s) << ", four lanes";
    std::int64_t within = 0;
    for (float v : brute.out) within += std::fabs(v) < o.bandWidth;
    EXPECT_GT(within, g.count() / 2) << toString(s);
  }
}
