// The prepared mesh's device copy (MeshToSdfCudaMesh.cuh): uploads of the
// mesh tree (its leaf copies gathered on the device from the welded mesh),
// of the closures' trees, the normals and node cones, and of the winding
// structures.
#include "MeshToSdfCudaMesh.cuh"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

namespace
{
// The host tree's nodes are uploaded as they are (no converted copy of
// every node): both records have the same layout.
static_assert(sizeof(GpuNode) == sizeof(Bvh::Node) && offsetof(GpuNode, lo) == offsetof(Bvh::Node, lo) &&
    offsetof(GpuNode, hi) == offsetof(Bvh::Node, hi) && offsetof(GpuNode, left) == offsetof(Bvh::Node, left) &&
    offsetof(GpuNode, right) == offsetof(Bvh::Node, right) && offsetof(GpuNode, first) == offsetof(Bvh::Node, first) &&
    offsetof(GpuNode, count) == offsetof(Bvh::Node, count),
  "GpuNode must mirror Bvh::Node");

std::vector<GpuTri> compactTris(const TriList& tris)
{
  std::vector<GpuTri> out(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
  {
    for (int k = 0; k < 3; ++k) out[i].v[k] = tris[i].v[k];
    out[i].n = tris[i].n;
  }
  return out;
}

/// A closure's tree: its nodes, order and leaf copies (leafCopies, built on
/// the host), into the reserved buffers of `into` where they fit.
DevBvh uploadBvh(DeviceArena& arena, cudaStream_t stream, const Bvh& b, const DevBvh& into = DevBvh(),
  std::size_t cap = 0)
{
  DevBvh d;
  d.leaf = arena.uploadOn(stream, leafCopies(b), const_cast<GpuTri*>(into.leaf), cap);
  d.nodes = reinterpret_cast<const GpuNode*>(arena.uploadOn(stream, b.nodes(),
    reinterpret_cast<Bvh::Node*>(const_cast<GpuNode*>(into.nodes)), 2 * cap));
  d.order = arena.uploadOn(stream, b.order(), const_cast<int*>(into.order), cap);
  return d;
}

/// The mesh tree's leaf copies from the welded mesh: leaf[i] = triangle
/// order[i]'s corners points[welded[t][k]] (the input's floats, exact in
/// double) and its unit normal by the records' own expression (faceCross,
/// unitFaceNormal; no FMA contraction): the bits of leafCopies on the host.
__global__ void gatherLeavesKernel(const unsigned* welded, const float* points, const int* order, long long n,
  GpuTri* leaf)
{
  for (long long i = blockIdx.x * static_cast<long long>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<long long>(gridDim.x) * blockDim.x)
  {
    const long long t = order[i];
    GpuTri l;
    for (int k = 0; k < 3; ++k)
    {
      const long long p = welded[3 * t + k];
      l.v[k] = V3{ points[3 * p], points[3 * p + 1], points[3 * p + 2] };
    }
    const V3 c = faceCross(l.v);
    l.n = unitFaceNormal(c, norm(c));
    leaf[i] = l;
  }
}


/// The mesh's own tree: its nodes and order, and its leaf copies gathered on
/// the device from the welded mesh (12 bytes per triangle and per vertex go
/// up instead of 96 per triangle: for 13.3M triangles 240 MB instead of
/// 1.2 GB, which took 43-150 ms through the pinned halves on H200 hosts).
DevBvh uploadMeshTree(DeviceArena& arena, cudaStream_t stream, const PreparedMesh& mesh, const Bvh& b)
{
  require(&b.tris() == &mesh.tris && mesh.points.size() == mesh.vertices,
    "mesh to SDF: the device copy needs the mesh's own tree and welded points");
  DevBvh d;
  d.nodes = reinterpret_cast<const GpuNode*>(arena.uploadOn(stream, b.nodes()));
  d.order = arena.uploadOn(stream, b.order());
  GpuTri* leaf = arena.alloc<GpuTri>(b.order().size());
  {
    DeviceArena scratch; // freed once the gather is done
    const unsigned* welded = reinterpret_cast<const unsigned*>(scratch.uploadOn(stream, mesh.welded));
    const float* points = reinterpret_cast<const float*>(scratch.uploadOn(stream, mesh.points));
    const long long n = static_cast<long long>(b.order().size());
    const unsigned blocks = static_cast<unsigned>(std::min<long long>((n + 255) / 256, 65536));
    gatherLeavesKernel<<<std::max(blocks, 1u), 256, 0, stream>>>(welded, points, d.order, n, leaf);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    LVDIF_CUDA_CHECK(cudaStreamSynchronize(stream));
  }
  d.leaf = leaf;
  return d;
}

} // namespace

CudaMesh::CudaMesh(
  const PreparedMesh& mesh, const Bvh& bvh, const WindingSigner* winding, bool normals, bool windingLater)
  : Mesh(mesh)
  , MeshBvh(bvh)
{
  const double t0 = now();
  this->Dbvh = uploadMeshTree(this->Arena, this->Upload.s, mesh, bvh);
  trace("upload: the mesh tree, its leaves gathered on the device", now() - t0);
  if (normals) this->addNormals();
  if (winding)
  {
    this->addWinding(*winding, false);
  }
  else if (windingLater && !mesh.boundary.empty())
  {
    // (a closed mesh is its own closure: addWinding reuses the mesh's tree)
    this->ClosedCap = mesh.tris.size() + mesh.boundary.size();
    this->EdgeCap = mesh.boundary.size();
    this->Reserved.leaf = this->Arena.alloc<GpuTri>(this->ClosedCap);
    this->Reserved.nodes = this->Arena.alloc<GpuNode>(2 * this->ClosedCap);
    this->Reserved.order = this->Arena.alloc<int>(this->ClosedCap);
    this->ReservedSlot = this->Arena.alloc<int>(mesh.tris.size());
    this->ReservedCone = this->Arena.alloc<GpuTri>(this->EdgeCap);
    this->ReservedClusters = this->Arena.alloc<WindingSigner::Cluster>(this->EdgeCap);
    // the correction's faces: caps (fewer than the boundary edges of what they
    // close) and F, R (chosen only when they and the caps of M+ are fewer than
    // the boundary edges of M); its nodes: at most one per face
    this->ReservedDipoleTris = this->Arena.alloc<WeightedTri>(this->EdgeCap);
    this->ReservedDipoleNodes = this->Arena.alloc<DipoleNode>(this->EdgeCap + 2);
  }
  LVDIF_CUDA_CHECK(cudaDeviceSynchronize());
}

void CudaMesh::addNormals()
{
  if (this->hasNormals()) return;
  // with the normal cones of the tree's nodes (far blocks), published before the records
  const double t0 = now();
  const std::vector<FarCone> cones = farCones(this->MeshBvh, this->Mesh);
  trace("far blocks: the node cones of the mesh BVH (host)", now() - t0);
  this->Cones = this->Arena.uploadOn(this->Upload.s, cones);
  this->Normals = this->Arena.uploadOn(this->Upload.s, this->Mesh.normals);
  if (!this->Mesh.cornerNormals.empty()) this->Corners = this->Arena.uploadOn(this->Upload.s, this->Mesh.cornerNormals);
  this->Full.store(this->Arena.uploadOn(this->Upload.s, this->Mesh.tris), std::memory_order_release);
}

DevBvh CudaMesh::meshBvh() const
{
  DevBvh b = this->Dbvh;
  b.tris = this->Full.load(std::memory_order_acquire);
  if (b.tris)
  {
    b.normals = this->Normals;
    b.corners = this->Corners;
  }
  return b;
}

void CudaMesh::addWinding(const WindingSigner& winding, bool reoriented)
{
  const int v = reoriented ? 1 : 0;
  if (this->hasWinding(reoriented)) return;
  require(!reoriented || winding.gpuTakesCpuClosure(true),
    "mesh to SDF: the re-oriented winding structures have a cone closure, which the GPU does not take");
  const cudaStream_t st = this->Upload.s;
  // the reserved buffers (windingLater) are for the one-call route's first
  // variant, M as given; the re-oriented one is allocated as it comes
  const bool reserved = !reoriented;
  WindingDev& w = this->W[v];
  DipoleDev& d = this->D[v];
  w.allTris = static_cast<int>(this->MeshBvh.order().size());
  w.meshLeaf = this->Dbvh.leaf;
  if (!this->Slot)
  {
    std::vector<int> slot(this->MeshBvh.order().size());
    for (std::size_t i = 0; i < slot.size(); ++i) slot[static_cast<std::size_t>(this->MeshBvh.order()[i])] = static_cast<int>(i);
    this->Slot = this->Arena.uploadOn(st, slot, reserved ? this->ReservedSlot : nullptr,
      reserved && this->ReservedSlot ? slot.size() : 0);
  }
  w.meshSlot = this->Slot;
  if (winding.gpuTakesCpuClosure(reoriented))
  {
    // the CPU's closure (M+ or M closed by local caps) and its correction s
    const WindingSigner::Closure& c = winding.cpuClosure(reoriented);
    // a closed mesh's closure shares the mesh's tree (the same object): its copy is already here
    w.closed = c.bvh.get() == &this->MeshBvh
      ? this->Dbvh
      : uploadBvh(this->Arena, st, *c.bvh, reserved ? this->Reserved : DevBvh(), reserved ? this->ClosedCap : 0);
    w.meshTris = static_cast<int>(c.meshTris);
    if (const DipoleTree* s = winding.cpuCorrection(reoriented))
    {
      d.tris = this->Arena.uploadOn(st, s->tris(), reserved ? this->ReservedDipoleTris : nullptr, reserved ? this->EdgeCap : 0);
      d.nodes = this->Arena.uploadOn(st, s->nodes(), reserved ? this->ReservedDipoleNodes : nullptr,
        reserved ? this->EdgeCap + 2 : 0);
      d.count = static_cast<int>(s->tris().size());
      d.rootMass = s->nodes().empty() ? 0.0 : s->nodes()[0].mass;
    }
    this->Winding[v].store(true, std::memory_order_release);
    return;
  }
  w.closed = uploadBvh(this->Arena, st, winding.closedBvh(), this->Reserved, this->ClosedCap);
  w.meshTris = static_cast<int>(winding.meshTriangles());
  w.cone = this->Arena.uploadOn(st, compactTris(winding.cone()), this->ReservedCone, this->EdgeCap);
  w.coneCount = static_cast<int>(winding.cone().size());
  w.clusters = this->Arena.uploadOn(st, winding.clusters(), this->ReservedClusters, this->EdgeCap);
  w.clusterCount = static_cast<int>(winding.clusters().size());
  this->Winding[v].store(true, std::memory_order_release);
}

std::unique_ptr<DeviceMesh> uploadMesh(
  const PreparedMesh& mesh, const Bvh& bvh, const WindingSigner* winding, bool normals, bool windingLater)
{
  return std::make_unique<CudaMesh>(mesh, bvh, winding, normals, windingLater);
}

std::vector<LeafTri> meshLeavesOnDevice(const PreparedMesh& mesh, const Bvh& bvh)
{
  DeviceArena arena;
  const Stream stream;
  const DevBvh d = uploadMeshTree(arena, stream.s, mesh, bvh);
  std::vector<LeafTri> host(bvh.order().size());
  LVDIF_CUDA_CHECK(cudaMemcpy(host.data(), d.leaf, host.size() * sizeof(LeafTri), cudaMemcpyDeviceToHost));
  return host;
}

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
