// Mesh to SDF into a dictionary volume restricted to a box of storage chunks
// (MeshToSdfOptions::chunkRegion, what a pvbatch rank computes): the chunks of
// the region get exactly the keys of a whole-volume run, on the CPU and on
// CUDA (against the CPU's whole run), every other chunk stays as it was; a
// region with the sign voxel filters, or outside the volume, is refused.
#include "MeshToSdfOracle.h"
#include "lvdif/Cuda.h"
#include "lvdif/Error.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <string>

using namespace lvdif;

namespace
{
VolumeOptions volumeFor(const GridGeometry& g)
{
  VolumeOptions vo = volumeOptionsOn(g);
  vo.chunkEdge = 8;
  vo.bandWidth = 4.0f;
  return vo;
}

/// Voxels of the region's chunks that differ from `whole`, and voxels outside
/// it that are not the untouched value.
std::pair<std::int64_t, std::int64_t> differences(
  const DictionaryVolume& v, const DictionaryVolume& whole, const VoxelBox& region)
{
  std::int64_t wrong = 0, touched = 0;
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    const Index3 c = v.chunkCoord(id);
    const bool in = region.contains(c[0], c[1], c[2]);
    const VoxelBox b = v.chunkBox(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          if (in)
            wrong += v.get(x, y, z) != whole.get(x, y, z);
          else
            touched += v.get(x, y, z) != v.outsideVoxel();
        }
  }
  return { wrong, touched };
}

void checkRegions(Device device)
{
  const TriangleMesh m = oracle::merge(makeSphereMesh(-0.35f, 0, 0, 0.8f, 16, 32), makeSphereMesh(0.4f, 0.1f, 0.05f, 0.75f, 16, 32));
  const GridGeometry g = fitGridToMesh(m, 45, 2); // not a multiple of the chunk edge: partial chunks
  const VolumeOptions vo = volumeFor(g);
  DictionaryVolume whole(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  meshToSdf(m, whole, o);
  const Index3 cc = whole.chunkCounts();
  o.device = device;
  const VoxelBox regions[] = {
    { { 0, 0, 0 }, { cc[0] - 1, cc[1] - 1, cc[2] / 2 } },             // a slab of layers
    { { 1, 0, 2 }, { cc[0] - 1, cc[1] / 2, cc[2] - 1 } },             // a block, not at the origin
    { { cc[0] - 1, cc[1] - 1, cc[2] - 1 }, { cc[0] - 1, cc[1] - 1, cc[2] - 1 } }, // the last, partial chunk
    { { 2, 1, 1 }, { 2, 1, 1 } },                                     // one chunk (the surface)
  };
  for (const VoxelBox& r : regions)
  {
    DictionaryVolume v(vo);
    o.chunkRegion = r;
    const MeshToSdfStats st = meshToSdf(m, v, o);
    EXPECT_TRUE(st.warnings.empty());
    const auto [wrong, touched] = differences(v, whole, r);
    EXPECT_EQ(wrong, 0) << "region " << r.lo[0] << r.lo[1] << r.lo[2] << ".." << r.hi[0] << r.hi[1] << r.hi[2];
    EXPECT_EQ(touched, 0);
  }
}
}

TEST(MeshToSdfRegion, CpuChunksEqualTheWholeRun)
{
  checkRegions(Device::Cpu);
}

TEST(MeshToSdfRegion, CudaChunksEqualTheCpuWholeRun)
{
  if (!cuda::available()) GTEST_SKIP() << "no CUDA device";
  checkRegions(Device::Cuda);
}

TEST(MeshToSdfRegion, RefusesSignFiltersAndEmptyRegions)
{
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1.0f, 12, 24);
  const VolumeOptions vo = volumeFor(fitGridToMesh(m, 24, 2));
  DictionaryVolume v(vo);
  MeshToSdfOptions o;
  o.device = Device::Cpu;
  o.chunkRegion = { { 0, 0, 0 }, { 0, 0, 0 } };
  o.svfFilters = 15;
  EXPECT_THROW(meshToSdf(m, v, o), Error);
  o.svfFilters = 0;
  o.chunkRegion = { { 50, 0, 0 }, { 60, 0, 0 } };
  EXPECT_THROW(meshToSdf(m, v, o), Error);
}
