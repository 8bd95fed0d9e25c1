// The sharp features' regions on the GPU (MeshToSdfCuda.h,
// sharpRegionVoxelsOnDevice): step 2 of the Normal sign of solids, the twin
// of the CPU's sharpRegionVoxels. One CUDA block per brick, each thread a few
// of its voxels: the same tests (MeshToSdfSharpTests.h), then the exact
// nearest triangle on the mesh tree (MeshToSdfCudaNearest.cuh), as the Normal
// path's own kernels find it. On a non-blocking stream, with stream-ordered
// memory, so that it runs beside a session's kernels without waiting for them.
#include "MeshToSdfCuda.h"
#include "MeshToSdfCudaMesh.cuh"
#include "MeshToSdfCudaNearest.cuh"
#include "MeshToSdfSharpFeatures.h"
#include "lvdif/CudaCheck.cuh"

#include <algorithm>
#include <atomic>
#include <tuple>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

namespace
{
constexpr int SharpThreads = 128; // per block (one brick)

struct SharpFeatureDev
{
  V3 a, b;
  int edge;
  int limitFirst, limitCount, normalFirst, normalCount;
};

struct SharpBrickDev
{
  long long lo[3], hi[3];
  V3 near[3]; // the closest triangle to the brick's centre
  int feature;
};

struct SharpHit
{
  int brick;
  int voxel; // x + 8 (y + 8 z) within the brick
  float value;
};

struct SharpParams
{
  double origin[3], spacing[3];
  double diagonal, toOut, band;
  const SharpFeatureDev* features;
  const V3* limits;
  const V3* normals;
  const SharpBrickDev* bricks;
  SharpHit* hits;
  unsigned long long* count;
  unsigned long long capacity;
};

__global__ void __launch_bounds__(SharpThreads) sharpRegionKernel(DevBvh bvh, SharpParams P)
{
  const SharpBrickDev& b = P.bricks[blockIdx.x];
  const SharpFeatureDev& fd = P.features[b.feature];
  SharpFeatureView f;
  f.a = fd.a;
  f.b = fd.b;
  f.edge = fd.edge != 0;
  f.limits = P.limits + fd.limitFirst;
  f.limitCount = fd.limitCount;
  f.normals = P.normals + fd.normalFirst;
  f.normalCount = fd.normalCount;
  constexpr int Edge = SharpBrickEdge;
  for (int v = static_cast<int>(threadIdx.x); v < Edge * Edge * Edge; v += SharpThreads)
  {
    const long long i = b.lo[0] + v % Edge, j = b.lo[1] + (v / Edge) % Edge, k = b.lo[2] + v / (Edge * Edge);
    if (i > b.hi[0] || j > b.hi[1] || k > b.hi[2]) continue;
    const V3 p{ P.origin[0] + static_cast<double>(i) * P.spacing[0], P.origin[1] + static_cast<double>(j) * P.spacing[1],
      P.origin[2] + static_cast<double>(k) * P.spacing[2] };
    V3 d;
    double tol = 0;
    if (!sharpVoxelMayBeInRegion(f, p, b.near[0], b.near[1], b.near[2], P.diagonal, d, tol)) continue;
    int slot = -1;
    const NearestResult r = nearestDev(bvh, p, -1, 1e300, slot);
    if (slot < 0 || !sharpVoxelInRegion(d, tol, r.dist2)) continue;
    const float value = storedValue(normalSign(p, r.closest.point, bvh.leaf[slot].n), r.dist2, P.toOut, P.band);
    const unsigned long long at = atomicAdd(P.count, 1ull);
    if (at < P.capacity) P.hits[at] = { static_cast<int>(blockIdx.x), v, value };
  }
}

/// Device memory of one call, stream-ordered (cudaMallocAsync/cudaFreeAsync:
/// neither waits for the session's kernels, as cudaFree would).
class StreamBuffers
{
public:
  explicit StreamBuffers(cudaStream_t s)
    : S(s)
  {
  }
  ~StreamBuffers()
  {
    for (void* p : this->Ptrs) cudaFreeAsync(p, this->S);
    cudaStreamSynchronize(this->S);
  }
  StreamBuffers(const StreamBuffers&) = delete;
  StreamBuffers& operator=(const StreamBuffers&) = delete;
  template <typename T>
  T* alloc(std::size_t n)
  {
    void* p = nullptr;
    LVDIF_CUDA_CHECK(cudaMallocAsync(&p, std::max<std::size_t>(n, 1) * sizeof(T), this->S));
    this->Ptrs.push_back(p);
    return static_cast<T*>(p);
  }
  template <typename T>
  T* upload(const std::vector<T>& v)
  {
    T* d = this->alloc<T>(v.size());
    if (!v.empty()) LVDIF_CUDA_CHECK(cudaMemcpyAsync(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice, this->S));
    return d;
  }

private:
  cudaStream_t S;
  std::vector<void*> Ptrs;
};
std::atomic<bool> failForTests{ false };
} // namespace

void failSharpRegionsOnDevice(bool fail)
{
  failForTests.store(fail);
}

std::vector<SharpVoxel> sharpRegionVoxelsOnDevice(const DeviceMesh& device, const SharpFeatures& sharp,
  const std::vector<SharpBrick>& bricks, const GridGeometry& grid, const VoxelBox& extent, double toOut, double band)
{
  std::vector<SharpVoxel> out;
  if (bricks.empty()) return out;
  if (failForTests.load())
    throw Error(ErrorCode::DeviceFailure, "CUDA: sharp features' regions: failed on purpose (failSharpRegionsOnDevice)");
  const auto& mesh = static_cast<const CudaMesh&>(device);
  const PreparedMesh& prepared = mesh.prepared();
  std::vector<SharpFeatureDev> features;
  std::vector<V3> limits, normals;
  for (const SharpFeature& f : sharp.features)
  {
    features.push_back({ f.a, f.b, f.edge ? 1 : 0, static_cast<int>(limits.size()), static_cast<int>(f.limits.size()),
      static_cast<int>(normals.size()), static_cast<int>(f.normals.size()) });
    limits.insert(limits.end(), f.limits.begin(), f.limits.end());
    normals.insert(normals.end(), f.normals.begin(), f.normals.end());
  }
  std::vector<SharpBrickDev> boxes(bricks.size());
  for (std::size_t n = 0; n < bricks.size(); ++n)
  {
    const VoxelBox box = sharpBrickBox(bricks[n], grid, extent);
    SharpBrickDev& b = boxes[n];
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] = box.lo[a];
      b.hi[a] = box.hi[a];
    }
    const Tri& near = prepared.tris[static_cast<std::size_t>(bricks[n].nearest)];
    for (int c = 0; c < 3; ++c) b.near[c] = near.v[c];
    b.feature = bricks[n].feature;
  }
  require(bricks.size() < 0x7fffffffu, "mesh to SDF: too many bricks in the sharp features' regions");

  Stream stream;
  StreamBuffers buffers(stream.s);
  SharpParams P{};
  for (int a = 0; a < 3; ++a)
  {
    P.origin[a] = grid.origin[a];
    P.spacing[a] = grid.spacing[a];
  }
  P.diagonal = sharpVoxelDiagonal(grid);
  P.toOut = toOut;
  P.band = band;
  P.features = buffers.upload(features);
  P.limits = buffers.upload(limits);
  P.normals = buffers.upload(normals);
  P.bricks = buffers.upload(boxes);
  P.count = buffers.alloc<unsigned long long>(1);
  // a region holds a small part of its bricks' voxels (about 1 in 60 for the
  // armadillo); a second launch takes the rest if the first overflows
  P.capacity = std::max<unsigned long long>(1ull << 16, bricks.size() * 32ull);
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    P.hits = buffers.alloc<SharpHit>(P.capacity);
    LVDIF_CUDA_CHECK(cudaMemsetAsync(P.count, 0, sizeof(unsigned long long), stream.s));
    sharpRegionKernel<<<static_cast<unsigned>(bricks.size()), SharpThreads, 0, stream.s>>>(mesh.Dbvh, P);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    unsigned long long count = 0;
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(&count, P.count, sizeof count, cudaMemcpyDeviceToHost, stream.s));
    LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream.s));
    if (count > P.capacity)
    {
      P.capacity = count;
      continue;
    }
    std::vector<SharpHit> hits(count);
    if (count > 0)
      LVDIF_CUDA_CHECK(cudaMemcpyAsync(hits.data(), P.hits, count * sizeof(SharpHit), cudaMemcpyDeviceToHost, stream.s));
    LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream.s));
    // one order whatever the blocks did: the CPU's (brick, then voxel)
    std::sort(hits.begin(), hits.end(),
      [](const SharpHit& x, const SharpHit& y) { return std::tie(x.brick, x.voxel) < std::tie(y.brick, y.voxel); });
    out.reserve(hits.size());
    constexpr int Edge = SharpBrickEdge;
    for (const SharpHit& h : hits)
    {
      const SharpBrickDev& b = boxes[static_cast<std::size_t>(h.brick)];
      out.push_back({ b.lo[0] + h.voxel % Edge, b.lo[1] + (h.voxel / Edge) % Edge, b.lo[2] + h.voxel / (Edge * Edge),
        h.value });
    }
    return out;
  }
  throw Error(ErrorCode::DeviceFailure, "mesh to SDF: the sharp features' regions outgrew their count on the GPU");
}

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
