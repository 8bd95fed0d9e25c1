// CUDA path of the brush (see lvdif/BrushCuda.h): one thread per voxel of each
// touched chunk, the same per-voxel rule as the CPU (BrushKernel.h). Compiled
// with --fmad=false (Core/CMakeLists.txt) so no multiply-add is contracted and
// the double arithmetic matches the host bit for bit.
#include "lvdif/BrushCuda.h"

#include "BrushKernel.h"
#include "BrushVoxelDevice.cuh"
#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <vector>

namespace lvdif
{
namespace cuda
{
namespace
{

using DeviceBox = detail::edit::DeviceDabBox;

__global__ void dabKernel(std::uint32_t* slots, const std::uint32_t* uniform, const int* expanded,
  const long long* origin, int edge, int shift, long long dx, long long dy, long long dz, const Dab* dabs,
  const DeviceBox* boxes, int nDabs, detail::edit::BrushContext ctx, const float* table, detail::edit::EncodeParams enc,
  unsigned int* changed)
{
  const long long n = static_cast<long long>(edge) * edge * edge;
  const long long local = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
  const int slot = blockIdx.y;
  if (local >= n)
    return;
  const long long m = edge - 1;
  const long long x = origin[3 * slot] + (local & m);
  const long long y = origin[3 * slot + 1] + ((local >> shift) & m);
  const long long z = origin[3 * slot + 2] + (local >> (2 * shift));
  std::uint32_t* p = slots + static_cast<long long>(slot) * n + local;
  const std::uint32_t v = expanded[slot] ? *p : uniform[slot];
  std::uint32_t nv = v;
  if (x < dx && y < dy && z < dz)
  {
    nv = detail::edit::applyDabsToVoxel(v, x, y, z, dabs, boxes, nDabs, ctx, table, enc);
  }
  *p = nv;
  if (nv != v)
    atomicOr(&changed[slot], 1u);
}

// Grow-only device buffers reused across calls (never freed: a static
// destructor could run after the CUDA runtime has shut down).
struct DeviceCache
{
  std::mutex mutex;
  void* slots = nullptr;
  std::size_t slotBytes = 0;
  void* small = nullptr;
  std::size_t smallBytes = 0;
  float* table = nullptr;
  const float* tableSource = nullptr;

  void reserve(void*& ptr, std::size_t& have, std::size_t want)
  {
    if (want <= have)
      return;
    if (ptr)
      LVDIF_CUDA_CHECK(cudaFree(ptr));
    ptr = nullptr;
    have = 0;
    LVDIF_CUDA_CHECK(cudaMalloc(&ptr, want));
    have = want;
  }
};

DeviceCache& cache()
{
  static DeviceCache* c = new DeviceCache();
  return *c;
}

std::size_t alignUp(std::size_t x)
{
  return (x + 255) & ~std::size_t(255);
}

} // namespace

EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer)
{
  if (!available())
    throw Error(ErrorCode::Unsupported, "no CUDA device is available for the brush");
  // (Smooth, Grab and Pinch are refused by planDabs: they read neighbours, CPU only.)
  const detail::edit::DabPlan plan = detail::edit::planDabs(volume, dabs, settings);
  EditResult result;
  if (plan.chunks.empty())
    return result;

  const int edge = volume.chunkEdge();
  int shift = 0;
  while ((1 << shift) < edge)
    ++shift;
  const std::size_t n = static_cast<std::size_t>(edge) * edge * edge;
  const std::size_t chunkBytes = n * sizeof(std::uint32_t);
  const std::size_t nChunks = plan.chunks.size();
  const std::size_t budget = std::min<std::size_t>(freeMemory() / 2, std::size_t(1) << 30);
  const std::size_t batch = std::max<std::size_t>(1, std::min<std::size_t>({ nChunks, budget / chunkBytes, 65535 }));
  const int nDabs = static_cast<int>(plan.dabs.size());

  std::vector<DeviceBox> boxes(plan.boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k)
    for (int a = 0; a < 3; ++a)
    {
      boxes[k].lo[a] = plan.boxes[k].lo[a];
      boxes[k].hi[a] = plan.boxes[k].hi[a];
    }

  DeviceCache& dc = cache();
  std::lock_guard<std::mutex> lock(dc.mutex);
  // layout of the small buffer: dabs | boxes | uniform | expanded | origin | changed | soft paint's mix table
  const std::size_t oDabs = 0;
  const std::size_t oBoxes = alignUp(oDabs + sizeof(Dab) * plan.dabs.size());
  const std::size_t oUniform = alignUp(oBoxes + sizeof(DeviceBox) * boxes.size());
  const std::size_t oExpanded = alignUp(oUniform + sizeof(std::uint32_t) * batch);
  const std::size_t oOrigin = alignUp(oExpanded + sizeof(int) * batch);
  const std::size_t oChanged = alignUp(oOrigin + sizeof(long long) * 3 * batch);
  const std::size_t oMixFrom = alignUp(oChanged + sizeof(unsigned int) * batch);
  const std::size_t oMixTo = alignUp(oMixFrom + sizeof(std::uint16_t) * plan.mixFrom.size());
  const std::size_t smallTotal = alignUp(oMixTo + sizeof(std::uint16_t) * plan.mixTo.size());
  dc.reserve(dc.small, dc.smallBytes, smallTotal);
  dc.reserve(dc.slots, dc.slotBytes, batch * chunkBytes);
  if (!dc.table)
    LVDIF_CUDA_CHECK(cudaMalloc(&dc.table, sizeof(float) * SdfDictionary::KeyCount));
  const float* hostTable = volume.sdfDictionary().table();
  if (dc.tableSource != hostTable)
  {
    LVDIF_CUDA_CHECK(cudaMemcpy(dc.table, hostTable, sizeof(float) * SdfDictionary::KeyCount, cudaMemcpyHostToDevice));
    dc.tableSource = hostTable;
  }
  char* small = static_cast<char*>(dc.small);
  std::uint32_t* slots = static_cast<std::uint32_t*>(dc.slots);
  if (nDabs > 0)
  {
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oDabs, plan.dabs.data(), sizeof(Dab) * plan.dabs.size(), cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oBoxes, boxes.data(), sizeof(DeviceBox) * boxes.size(), cudaMemcpyHostToDevice));
  }
  detail::edit::BrushContext ctx = plan.ctx;
  if (!plan.mixFrom.empty())
  {
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oMixFrom, plan.mixFrom.data(), sizeof(std::uint16_t) * plan.mixFrom.size(),
      cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(
      cudaMemcpy(small + oMixTo, plan.mixTo.data(), sizeof(std::uint16_t) * plan.mixTo.size(), cudaMemcpyHostToDevice));
    ctx.mixFrom = reinterpret_cast<const std::uint16_t*>(small + oMixFrom);
    ctx.mixTo = reinterpret_cast<const std::uint16_t*>(small + oMixTo);
  }
  const detail::edit::EncodeParams enc = detail::edit::EncodeParams::of(volume.sdfDictionary(), volume.bandWidth());
  const Index3& dims = volume.dims();

  std::vector<std::uint32_t> uniform(batch);
  std::vector<int> expanded(batch);
  std::vector<long long> origin(3 * batch);
  std::vector<unsigned int> changed(batch);
  for (std::size_t first = 0; first < nChunks; first += batch)
  {
    const std::size_t count = std::min(batch, nChunks - first);
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::int64_t id = plan.chunks[first + i];
      const Voxel* d = volume.chunkData(id);
      expanded[i] = d != nullptr;
      Voxel u = volume.uniformValue(id);
      std::memcpy(&uniform[i], &u, sizeof(std::uint32_t));
      const Index3 c = volume.chunkCoord(id);
      for (int a = 0; a < 3; ++a)
        origin[3 * i + static_cast<std::size_t>(a)] = c[a] * edge;
      if (d)
        LVDIF_CUDA_CHECK(cudaMemcpy(slots + i * n, d, chunkBytes, cudaMemcpyHostToDevice));
    }
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oUniform, uniform.data(), sizeof(std::uint32_t) * count, cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oExpanded, expanded.data(), sizeof(int) * count, cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemcpy(small + oOrigin, origin.data(), sizeof(long long) * 3 * count, cudaMemcpyHostToDevice));
    LVDIF_CUDA_CHECK(cudaMemset(small + oChanged, 0, sizeof(unsigned int) * count));
    const dim3 block(256);
    const dim3 grid(static_cast<unsigned>((n + 255) / 256), static_cast<unsigned>(count));
    dabKernel<<<grid, block>>>(slots, reinterpret_cast<const std::uint32_t*>(small + oUniform),
      reinterpret_cast<const int*>(small + oExpanded), reinterpret_cast<const long long*>(small + oOrigin), edge, shift,
      dims[0], dims[1], dims[2], reinterpret_cast<const Dab*>(small + oDabs),
      reinterpret_cast<const DeviceBox*>(small + oBoxes), nDabs, ctx, dc.table, enc,
      reinterpret_cast<unsigned int*>(small + oChanged));
    LVDIF_CUDA_CHECK(cudaGetLastError());
    LVDIF_CUDA_CHECK(cudaMemcpy(changed.data(), small + oChanged, sizeof(unsigned int) * count, cudaMemcpyDeviceToHost));

    // bring back the changed chunks and write their changed voxels on the host
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < count; ++i)
      if (changed[i])
        todo.push_back(i);
    std::vector<std::uint32_t> back(todo.size() * n);
    for (std::size_t t = 0; t < todo.size(); ++t)
      LVDIF_CUDA_CHECK(cudaMemcpy(back.data() + t * n, slots + todo[t] * n, chunkBytes, cudaMemcpyDeviceToHost));
    std::vector<std::int64_t> perChunk(todo.size(), 0);
    std::vector<VoxelBox> boxes2(todo.size());
    const std::int64_t nTodo = static_cast<std::int64_t>(todo.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < nTodo; ++t)
    {
      const std::int64_t id = plan.chunks[first + todo[static_cast<std::size_t>(t)]];
      const VoxelBox b = volume.chunkBox(id);
      const std::uint32_t* src = back.data() + static_cast<std::size_t>(t) * n;
      bool touched = false;
      std::int64_t count2 = 0;
      VoxelBox box;
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          {
            Voxel nv;
            std::memcpy(&nv, src + volume.localIndex(x, y, z), sizeof(Voxel));
            if (nv != volume.get(x, y, z))
            {
              if (!touched)
              {
                touched = true;
                if (observer)
                  observer->beforeChunkWrite(volume, id);
              }
              volume.set(x, y, z, nv);
              ++count2;
              box.include(x, y, z);
            }
          }
      if (touched && !volume.isUniform(id))
        volume.tryCollapseChunk(id);
      perChunk[static_cast<std::size_t>(t)] = count2;
      boxes2[static_cast<std::size_t>(t)] = box;
    }
    for (std::size_t t = 0; t < todo.size(); ++t)
      if (perChunk[t] > 0)
      {
        result.changedChunks.push_back(plan.chunks[first + todo[t]]);
        result.changedChunkBoxes.push_back(boxes2[t]);
        result.changedVoxels += perChunk[t];
        result.changedBox = result.changedBox.unite(boxes2[t]);
      }
  }
  return result;
}

} // namespace cuda
} // namespace lvdif
