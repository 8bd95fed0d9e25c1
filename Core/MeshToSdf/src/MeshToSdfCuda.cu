// CUDA path of mesh to SDF, host side: the same double-precision algorithms as
// the CPU (MeshToSdf.cpp distanceRow, MeshToSdfWinding.cpp signRow; kernels in
// MeshToSdfCudaKernels.cuh), run over the requested extent one slab of z
// layers at a time so device memory stays bounded (the slab buffer is at most
// 256 MiB, plus the mesh and BVHs). Here: the sessions (float slabs whose
// sign pass runs in parts, each copied back while the next runs;
// dictionary-volume groups encoded on the GPU) over the prepared mesh's device
// copy (MeshToSdfCudaMesh.cu).
#include "MeshToSdfCuda.h"
#include "MeshToSdfCudaFar.cuh"
#include "MeshToSdfCudaKernels.cuh"
#include "MeshToSdfCudaDipole.cuh"
#include "MeshToSdfCudaMemory.cuh"
#include "MeshToSdfCudaMesh.cuh"

#include "lvdif/CudaCheck.cuh"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

using namespace detail::meshtosdf;

namespace
{
/// A CUDA event pair timing kernels without synchronising at each launch.
struct EventTimer
{
  cudaEvent_t a = nullptr, b = nullptr;
  EventTimer()
  {
    LVDIF_CUDA_CHECK(cudaEventCreate(&this->a));
    LVDIF_CUDA_CHECK(cudaEventCreate(&this->b));
  }
  ~EventTimer()
  {
    cudaEventDestroy(this->a);
    cudaEventDestroy(this->b);
  }
  double seconds() const
  {
    float ms = 0;
    LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, this->a, this->b));
    return 1e-3 * ms;
  }
};

/// Events without timing, one per part of the sign pass (or staging slot of the keys).
struct PartEvents
{
  static constexpr int Max = 4;
  cudaEvent_t e[Max] = {};
  PartEvents()
  {
    for (cudaEvent_t& x : this->e) LVDIF_CUDA_CHECK(cudaEventCreateWithFlags(&x, cudaEventDisableTiming));
  }
  ~PartEvents()
  {
    for (cudaEvent_t x : this->e) cudaEventDestroy(x);
  }
  cudaEvent_t operator[](int i) const { return this->e[i]; }
};

std::atomic<std::int64_t> piecesCopied{ 0 }, piecesPageable{ 0 };

class CudaSession : public Session
{
public:
  CudaSession(const CudaMesh& mesh, const GridGeometry& grid, const MeshToSdfOptions& options, double toOut,
    double band, MeshToSdfStats& stats, std::function<void()> ensureWinding)
    : Options(options)
    , Mesh(mesh)
    , HasWinding(options.sign == SignMode::WindingNumber)
    , Variant(options.reorientFaces ? 1 : 0)
    , EnsureWinding(std::move(ensureWinding))
    , Stats(stats)
  {
    require(!this->HasWinding || mesh.hasWinding(this->Variant == 1) || this->EnsureWinding,
      "mesh to SDF: the device mesh has no winding structures");
    require(!(options.sign == SignMode::Normal || options.sign == SignMode::PseudoNormal) || mesh.hasNormals(),
      "mesh to SDF: the device mesh has no triangle normals");
    this->Counters = this->Arena.alloc<unsigned long long>(3);
    if (this->HasWinding)
    {
      // the rays of at most this many scan lines at a time (no slab has more lines than the grid)
      this->RayRows = std::max<long long>(1, std::min<long long>(1ll << 17, grid.dims[1] * grid.dims[2]));
      this->RayHits = this->Arena.alloc<Hit>(static_cast<std::size_t>(this->RayRows * RowHits));
      this->RayMeta = this->Arena.alloc<int4>(static_cast<std::size_t>(this->RayRows));
    }
    for (int a = 0; a < 3; ++a)
    {
      this->P.origin[a] = grid.origin[a];
      this->P.spacing[a] = grid.spacing[a];
    }
    this->P.toOut = toOut;
    this->P.band = band;
    this->P.bandWorld = std::isfinite(band) ? band / toOut : 1e300;
    this->P.reach = this->P.bandWorld < 1e299 ? this->P.bandWorld + 4 * grid.spacing[0] : 1e300;
    this->P.sign = options.sign == SignMode::Normal ? 0 : options.sign == SignMode::PseudoNormal ? 1
      : options.sign == SignMode::WindingNumber ? 2 : 3;
    this->P.useVertexNormals = options.useVertexNormals ? 1 : 0;
    this->P.bounded = (this->P.sign >= 2 && this->P.bandWorld < 1e299) ? 1 : 0;
    LVDIF_CUDA_CHECK(cudaMemset(this->Counters, 0, 3 * sizeof(unsigned long long)));
    // far blocks: as makeEngine decides them for the CPU (the GPU always runs the BVH)
    this->FarOn = options.farBlocks && (this->P.sign == 0 || this->P.sign == 1) && !options.useVertexNormals &&
      this->P.bandWorld < 1e299;
    if (this->FarOn)
    {
      this->FarBig = farScale(mesh.prepared(), grid);
      this->FarMargin = farMargin(this->FarBig, static_cast<double>(mesh.prepared().tris.size()));
      this->FarDecided = this->Arena.alloc<unsigned long long>(1);
      this->FarWork = this->Arena.alloc<unsigned long long>(2);
      LVDIF_CUDA_CHECK(cudaMemset(this->FarDecided, 0, sizeof(unsigned long long)));
    }
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  ~CudaSession() override
  {
    if (this->BoundsSeconds > 0) trace("winding sign on the GPU, dictionary volume: the correction's block bounds", this->BoundsSeconds);
    if (this->RaysSeconds > 0) trace("winding sign on the GPU, dictionary volume: the scan lines' rays", this->RaysSeconds);
    if (this->LocalCounts && tracePhasesActive())
      std::fprintf(stderr, "[mesh to SDF] winding sign on the GPU: local step: %llu blocks of 4^3 expanded, %llu failed, %llu voxels decided by their intervals\n",
        this->LocalTotals[0], this->LocalTotals[1], this->LocalTotals[2]);
    if (this->FarOn)
    {
      trace("distance pass on the GPU: far blocks (farBlockKernel)", this->FarBlockSeconds);
      trace("distance pass on the GPU: far halves, cells and voxels (farCellKernel)", this->FarHalfSeconds);
      trace("distance pass on the GPU: the per-voxel kernel on what the far blocks leave", this->FarRestSeconds);
    }
    // never free buffers under running kernels, nor give back staging that a copy still fills
    if (this->Launched || this->Pieces > 0) cudaDeviceSynchronize();
    pinnedPool().give(this->Staging);
  }

  void compute(const VoxelBox& extent, float* out, MeshToSdfStats& stats, Interrupter& interrupter) override
  {
    const long long nx = extent.hi[0] - extent.lo[0] + 1, ny = extent.hi[1] - extent.lo[1] + 1;
    const long long nz = extent.hi[2] - extent.lo[2] + 1;
    const std::uint64_t layerBytes = static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny) * sizeof(float);
    const long long slabLayers =
      std::max<long long>(1, std::min<long long>(nz, static_cast<long long>(this->Options.cudaSlabBytes / layerBytes)));
    this->reserveSlab(static_cast<std::size_t>(slabLayers * nx * ny), stats);
    for (long long z0 = extent.lo[2]; z0 <= extent.hi[2]; z0 += slabLayers)
    {
      interrupter.checkInterrupt();
      const long long z1 = std::min<long long>(extent.hi[2], z0 + slabLayers - 1);
      VoxelBox slab = extent;
      slab.lo[2] = z0;
      slab.hi[2] = z1;
      const long long rows = ny * (z1 - z0 + 1);
      // the sign pass in parts: part p is copied back while part p + 1 runs
      const int parts = this->HasWinding && rows >= 4 * 4096 ? 4 : 1;
      this->launchSlab(slab, parts);
      float* slabOut = out + (z0 - extent.lo[2]) * nx * ny;
      for (int p = 0; p < parts; ++p)
      {
        const long long r0 = rows * p / parts, r1 = rows * (p + 1) / parts;
        LVDIF_CUDA_CHECK(cudaEventSynchronize(this->PartDone[p]));
        const double t0 = now();
        LVDIF_CUDA_CHECK(cudaMemcpyAsync(slabOut + r0 * nx, this->Slab + r0 * nx,
          static_cast<std::size_t>((r1 - r0) * nx) * sizeof(float), cudaMemcpyDeviceToHost, this->Copy.s));
        LVDIF_CUDA_CHECK(cudaStreamSynchronize(this->Copy.s));
        stats.writeSeconds += now() - t0;
      }
      LVDIF_CUDA_CHECK(cudaEventSynchronize(this->SignDone.b));
      stats.distanceSeconds += this->DistanceDone.seconds();
      this->addFarSplit();
      if (this->HasWinding) stats.signSeconds += this->SignDone.seconds();
      interrupter.progress(static_cast<double>(z1 - extent.lo[2] + 1) / static_cast<double>(nz));
    }
    this->readCounters(stats);
  }

  void launchKeys(const VoxelBox& box, int edge, const SdfDictionary::EncodeConstants& encode, float band,
    MeshToSdfStats& stats) override
  {
    const long long nx = box.hi[0] - box.lo[0] + 1, ny = box.hi[1] - box.lo[1] + 1;
    const long long nz = box.hi[2] - box.lo[2] + 1;
    this->reserveSlab(static_cast<std::size_t>(nx * ny * nz), stats);
    this->KeyBox = box;
    this->Edge = edge;
    this->Encode = encode;
    this->Band = band;
    this->Ccx = static_cast<int>((nx + edge - 1) / edge);
    this->Ccy = static_cast<int>((ny + edge - 1) / edge);
    this->Chunks = static_cast<long long>(this->Ccx) * this->Ccy * ((nz + edge - 1) / edge);
    if (this->Chunks > this->FlagCapacity)
    {
      this->Flags = this->Arena.alloc<unsigned>(static_cast<std::size_t>(this->Chunks));
      this->List = this->Arena.alloc<long long>(static_cast<std::size_t>(this->Chunks));
      this->FlagCapacity = this->Chunks;
    }
    this->launchSlab(box);
    chunkUniformKernel<<<static_cast<unsigned>(this->Chunks), 256>>>(
      this->Slab, nx, ny, nz, edge, this->Ccx, this->Ccy, encode, band, this->Flags);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  void fetchKeys(ChunkKeys& out, MeshToSdfStats& stats) override
  {
    require(this->Pieces == 0, "mesh to SDF: fetchKeys before the last group's takeKeys");
    const long long nx = this->KeyBox.hi[0] - this->KeyBox.lo[0] + 1, ny = this->KeyBox.hi[1] - this->KeyBox.lo[1] + 1;
    const long long nz = this->KeyBox.hi[2] - this->KeyBox.lo[2] + 1;
    out.uniform.resize(static_cast<std::size_t>(this->Chunks));
    LVDIF_CUDA_CHECK(cudaMemcpy(out.uniform.data(), this->Flags, out.uniform.size() * sizeof(unsigned),
      cudaMemcpyDeviceToHost)); // waits for the kernels
    this->Launched = false;
    stats.distanceSeconds += this->DistanceDone.seconds();
    this->addFarSplit();
    if (this->HasWinding)
    {
      stats.signSeconds += this->SignDone.seconds();
      float ms = 0;
      LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, this->SignDone.a, this->SignSplit.a));
      this->BoundsSeconds += 1e-3 * ms;
      this->RaysSeconds += this->SignSplit.seconds();
    }
    const double t0 = now();
    out.listed.clear();
    for (long long c = 0; c < this->Chunks; ++c)
    {
      if (out.uniform[static_cast<std::size_t>(c)] == ChunkKeys::NotUniform) out.listed.push_back(c);
    }
    const std::size_t e3 = static_cast<std::size_t>(this->Edge) * this->Edge * this->Edge;
    const std::size_t keyCount = out.listed.size() * e3;
    this->Listed = out.listed.size();
    if (!out.listed.empty())
    {
      if (keyCount > this->KeyCapacity)
      {
        if (this->Keys) this->Arena.release(this->Keys);
        this->Keys = this->Arena.alloc<unsigned short>(keyCount);
        this->KeyCapacity = keyCount;
      }
      LVDIF_CUDA_CHECK(cudaMemcpy(this->List, out.listed.data(), out.listed.size() * sizeof(long long),
        cudaMemcpyHostToDevice));
      chunkKeysKernel<<<static_cast<unsigned>(out.listed.size()), 256>>>(this->Slab, nx, ny, nz, this->Edge,
        this->Ccx, this->Ccy, this->Encode, this->Band, this->List, this->Keys);
      LVDIF_CUDA_CHECK(cudaGetLastError());
      this->Launched = true;
      LVDIF_CUDA_CHECK(cudaEventRecord(this->KeysReady[0]));
      LVDIF_CUDA_CHECK(cudaStreamWaitEvent(this->Copy.s, this->KeysReady[0], 0));
      // pieces of whole chunks, at most the group's (the staging block then
      // fits every later group of the call, and a small grid pins little)
      this->PieceChunks = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(this->Chunks),
        static_cast<std::size_t>(this->Options.cudaKeyPieceBytes / (e3 * sizeof(std::uint16_t)))));
      const std::size_t need = Slots * this->PieceChunks * e3 * sizeof(std::uint16_t);
      if (this->Staging.bytes < need)
      {
        pinnedPool().give(this->Staging);
        this->Staging = HostBlock();
        this->Staging = pinnedPool().take(need);
      }
      this->Pieces = (this->Listed + this->PieceChunks - 1) / this->PieceChunks;
      // the first pieces start now, under the next group's kernels
      for (std::size_t k = 0; k < Slots && k < this->Pieces; ++k) this->copyPiece(k);
    }
    if (this->Options.cudaVerifyKeys)
    {
      out.floats.resize(static_cast<std::size_t>(nx * ny * nz));
      LVDIF_CUDA_CHECK(cudaMemcpy(out.floats.data(), this->Slab, out.floats.size() * sizeof(float),
        cudaMemcpyDeviceToHost));
    }
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
    stats.writeSeconds += now() - t0;
    this->readCounters(stats);
  }

  double takeKeys(const KeyPieceFn& store) override
  {
    const std::size_t e3 = static_cast<std::size_t>(this->Edge) * this->Edge * this->Edge;
    double waited = 0;
    for (std::size_t k = 0; k < this->Pieces; ++k)
    {
      const std::size_t slot = k % Slots;
      const double t0 = now();
      LVDIF_CUDA_CHECK(cudaEventSynchronize(this->PieceDone[static_cast<int>(slot)]));
      waited += now() - t0;
      const std::size_t first = k * this->PieceChunks, last = std::min(this->Listed, first + this->PieceChunks);
      store(first, last, this->Staging.p + slot * this->PieceChunks * e3);
      // the slot is free again: the piece Slots further on goes into it
      if (k + Slots < this->Pieces) this->copyPiece(k + Slots);
    }
    this->Pieces = 0;
    return waited;
  }

private:
  /// Adds the far kernels' and the per-voxel kernel's shares of the last
  /// slab's distance pass (--trace; the events are done once DistanceDone is).
  void addFarSplit()
  {
    if (!this->FarOn) return;
    float ms = 0;
    LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, this->DistanceDone.a, this->FarSplit.a));
    this->FarBlockSeconds += 1e-3 * ms;
    this->FarHalfSeconds += this->FarSplit.seconds();
    LVDIF_CUDA_CHECK(cudaEventElapsedTime(&ms, this->FarSplit.b, this->DistanceDone.b));
    this->FarRestSeconds += 1e-3 * ms;
  }

  /// Queues the copy of listed piece k into its staging slot (on Copy, after the keys kernel).
  void copyPiece(std::size_t k)
  {
    const std::size_t e3 = static_cast<std::size_t>(this->Edge) * this->Edge * this->Edge;
    const std::size_t first = k * this->PieceChunks, last = std::min(this->Listed, first + this->PieceChunks);
    const int slot = static_cast<int>(k % Slots);
    LVDIF_CUDA_CHECK(cudaMemcpyAsync(this->Staging.p + static_cast<std::size_t>(slot) * this->PieceChunks * e3,
      this->Keys + first * e3, (last - first) * e3 * sizeof(std::uint16_t), cudaMemcpyDeviceToHost, this->Copy.s));
    LVDIF_CUDA_CHECK(cudaEventRecord(this->PieceDone[slot], this->Copy.s));
    ++piecesCopied;
    if (!this->Staging.pinned) ++piecesPageable;
  }

  void reserveSlab(std::size_t floats, MeshToSdfStats& stats)
  {
    if (floats > this->SlabCapacity)
    {
      if (this->Slab) this->Arena.release(this->Slab);
      this->Slab = this->Arena.alloc<float>(floats);
      this->SlabCapacity = floats;
    }
    stats.devicePeakBytes = std::max(stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
  }

  /// A work list's capacity: n, or LVDIF_CUDA_DIPOLE_LIST_CAP when set (the
  /// tests make the lists overflow, so that the work a full list leaves in
  /// its thread is checked too).
  static long long listCapacity(long long n)
  {
    const char* e = std::getenv("LVDIF_CUDA_DIPOLE_LIST_CAP");
    return e ? std::max(1LL, std::atoll(e)) : n;
  }

  /// Queues the distance and sign kernels of one slab (box layout in Slab).
  /// parts: the sign kernel in that many launches over consecutive rows,
  /// PartDone[p] recorded after launch p (after the distance kernel when
  /// there is no sign pass).
  void launchSlab(const VoxelBox& box, int parts = 1)
  {
    Params P = this->P;
    for (int a = 0; a < 3; ++a)
    {
      P.lo[a] = box.lo[a];
      P.hi[a] = box.hi[a];
    }
    const long long rows = (box.hi[1] - box.lo[1] + 1) * (box.hi[2] - box.lo[2] + 1);
    LVDIF_CUDA_CHECK(cudaEventRecord(this->DistanceDone.a));
    if (this->FarOn) this->launchFar(P);
    this->reserveDistanceLists(distanceRuns(P));
    launchDistance(this->Mesh.meshBvh(), P, this->Slab, this->Distance);
    LVDIF_CUDA_CHECK(cudaEventRecord(this->DistanceDone.b));
    if (this->HasWinding && !this->Mesh.hasWinding(this->Variant == 1))
    {
      // built and uploaded on the host while the distance kernel runs
      this->EnsureWinding();
      require(this->Mesh.hasWinding(this->Variant == 1), "mesh to SDF: the device mesh has no winding structures");
      this->Stats.devicePeakBytes = std::max(this->Stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
    }
    LVDIF_CUDA_CHECK(cudaEventRecord(this->SignDone.a));
    // the correction s: bounded per block of voxels first (MeshToSdfCudaDipole.cuh)
    const bool dipole = this->HasWinding && this->Mesh.D[this->Variant].count > 0;
    long long bx = 0, by = 0;
    if (dipole)
    {
      // the levels of blocks coarse to fine, the finest first in Bounds:
      // far from the corrected faces one coarse bound serves many voxels
      long long count[DipoleLevels], total = 0;
      for (int l = 0; l < DipoleLevels; ++l)
      {
        const long long e = DipoleEdges[l];
        count[l] = ((box.hi[0] - box.lo[0] + e) / e) * ((box.hi[1] - box.lo[1] + e) / e) * ((box.hi[2] - box.lo[2] + e) / e);
        total += count[l];
      }
      if (total > this->BoundCapacity)
      {
        if (this->Bounds) this->Arena.release(this->Bounds);
        if (this->BlockLists) this->Arena.release(this->BlockLists);
        if (this->BlockPending) this->Arena.release(this->BlockPending);
        this->Bounds = this->Arena.alloc<double>(static_cast<std::size_t>(2 * total));
        // the blocks without a bound of every level but the finest
        this->BlockLists = this->Arena.alloc<long long>(static_cast<std::size_t>(total - count[DipoleLevels - 1]));
        // blocks between passes (an eighth of the finest level's, twice: in
        // and out; beyond that a block's passes go on in its thread)
        this->PendingCap = listCapacity(count[DipoleLevels - 1] / 8 + 1024);
        this->BlockPending = this->Arena.alloc<DipolePending>(static_cast<std::size_t>(2 * this->PendingCap));
        this->BoundCapacity = total;
      }
      if (!this->ListCounts) this->ListCounts = this->Arena.alloc<unsigned long long>(ListCountSlots);
      // the local step (dipoleLocalKernel): per 4^3 block a slot, and the
      // intervals of the failed ones' voxels (a quarter of the level's
      // blocks; beyond that their 2^3 blocks are bounded as before)
      DipoleLocalLists local;
      if (localStepOn())
      {
        const long long blocks4 = count[LocalLevel];
        if (blocks4 > this->LocalSlotCapacity)
        {
          if (this->LocalSlot) this->Arena.release(this->LocalSlot);
          if (this->LocalPool) this->Arena.release(this->LocalPool);
          this->LocalSlot = this->Arena.alloc<int>(static_cast<std::size_t>(blocks4));
          this->LocalCap = listCapacity(blocks4 / 4 + 1024);
          this->LocalPool = this->Arena.alloc<double>(static_cast<std::size_t>(2 * DipoleLocalVoxels * this->LocalCap));
          this->LocalSlotCapacity = blocks4;
        }
        if (!this->LocalNear)
        {
          // the near-triangle lists of the blocks in flight: DipoleLocalNearCap x 32 per warp (one block each) of a fixed grid
          int device = 0, sms = 0;
          LVDIF_CUDA_CHECK(cudaGetDevice(&device));
          LVDIF_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
          // as many CUDA blocks as the SMs hold at once (its registers set that: 3 of 128 threads
          // at its 168 on sm_90): the walks wait on the tree's loads, so every resident warp counts
          int perSm = 0;
          LVDIF_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, dipoleLocalKernel, LocalThreads, 0));
          this->LocalGrid = std::max(1, std::max(1, perSm) * sms);
          this->LocalNear = this->Arena.alloc<int>(static_cast<std::size_t>(this->LocalGrid) * (LocalThreads / 32) * 32 * DipoleLocalNearCap);
        }
        if (!this->LocalCounts)
        {
          this->LocalCounts = this->Arena.alloc<unsigned long long>(3);
          LVDIF_CUDA_CHECK(cudaMemset(this->LocalCounts, 0, 3 * sizeof(unsigned long long)));
        }
        LVDIF_CUDA_CHECK(cudaMemsetAsync(this->LocalSlot, 0xff, static_cast<std::size_t>(blocks4) * sizeof(int))); // -1: none
        local.pool = this->LocalPool;
        local.slot = this->LocalSlot;
        local.cap = this->LocalCap;
        local.counts = this->LocalCounts;
      }
      // the voxels the blocks leave undecided, listed per part of the sign pass
      // (a quarter of the part's voxels; beyond that they are refined in place)
      const long long queueCap = listCapacity((rows / parts + 1) * (box.hi[0] - box.lo[0] + 1) / 4 + 1024);
      if (queueCap > this->QueueCapacity)
      {
        if (this->Queue) this->Arena.release(this->Queue);
        this->Queue = this->Arena.alloc<unsigned long long>(static_cast<std::size_t>(queueCap));
        this->QueueCapacity = queueCap;
      }
      this->Stats.devicePeakBytes = std::max(this->Stats.devicePeakBytes, this->Mesh.bytes() + this->Arena.bytes());
      LVDIF_CUDA_CHECK(cudaMemsetAsync(this->ListCounts, 0, ListCountSlots * sizeof(unsigned long long)));
      const double* parent = nullptr;
      long long offset = total, listOffset = 0, pbx = 0, pby = 0;
      for (int l = 0; l < DipoleLevels; ++l)
      {
        const long long e = DipoleEdges[l];
        const int ratio = l ? DipoleEdges[l - 1] / DipoleEdges[l] : 1;
        offset -= count[l];
        double* level = this->Bounds + 2 * offset; // the finest level at offset 0
        bx = (box.hi[0] - box.lo[0] + e) / e;
        by = (box.hi[1] - box.lo[1] + e) / e;
        const long long bz = (box.hi[2] - box.lo[2] + e) / e;
        // the lists of this level: its blocks without a bound (none for the
        // finest), and the blocks between passes (counts per level and pass)
        unsigned long long* passCounts = this->ListCounts + DipoleLevels + l * DipoleBlockPasses;
        auto lists = [&](int pass) {
          DipoleBlockLists L;
          if (l + 1 < DipoleLevels)
          {
            L.fail = this->BlockLists + listOffset;
            L.failCount = this->ListCounts + l;
          }
          if (pass + 1 < DipoleBlockPasses)
          {
            L.next = this->BlockPending + (pass % 2) * this->PendingCap;
            L.nextCount = passCounts + pass;
            L.nextCap = this->PendingCap;
          }
          return L;
        };
        const long long most = std::min<long long>((count[l] + 127) / 128, 2048); // grid-stride kernels
        dipoleBlockKernel<<<static_cast<unsigned>((count[l] + 127) / 128), 128>>>(this->Mesh.D[this->Variant], P, static_cast<int>(e), bx,
          by, count[l], parent, ratio, level, lists(0));
        LVDIF_CUDA_CHECK(cudaGetLastError());
        if (l)
        {
          // the blocks inside the parents without a bound, full warps of them
          dipoleListedBlockKernel<<<static_cast<unsigned>(most), 128>>>(this->Mesh.D[this->Variant], P, static_cast<int>(e), bx, by, bz, pbx,
            pby, ratio, this->BlockLists + listOffset - count[l - 1], this->ListCounts + l - 1,
            l == LocalLevel + 1 ? local.cap : 0, level, lists(0));
          LVDIF_CUDA_CHECK(cudaGetLastError());
        }
        for (int pass = 1; pass < DipoleBlockPasses; ++pass)
        {
          dipoleBlockPassKernel<<<static_cast<unsigned>(most), 128>>>(this->Mesh.D[this->Variant], P, static_cast<int>(e), bx, by, pass,
            this->BlockPending + ((pass - 1) % 2) * this->PendingCap, passCounts + pass - 1, this->PendingCap, level,
            lists(pass));
          LVDIF_CUDA_CHECK(cudaGetLastError());
        }
        if (l == LocalLevel && local.slot)
        {
          // the blocks of this level left without a bound: their voxels' intervals from one local expansion each
          local.bx = bx;
          local.by = by;
          dipoleLocalKernel<<<static_cast<unsigned>(this->LocalGrid), LocalThreads>>>(this->Mesh.D[this->Variant], P,
            this->BlockLists + listOffset, this->ListCounts + l, local, this->LocalNear);
          LVDIF_CUDA_CHECK(cudaGetLastError());
        }
        listOffset += count[l];
        pbx = bx;
        pby = by;
        parent = level;
      }
      this->QueueCap = queueCap;
      this->Local = local;
    }
    if (this->HasWinding) LVDIF_CUDA_CHECK(cudaEventRecord(this->SignSplit.a)); // the block bounds end here
    for (int p = 0; p < parts; ++p)
    {
      // the scan lines' rays first (one thread per line), then the sign
      // kernel, in pieces of at most RayRows lines (the rays' buffers)
      const long long r0 = rows * p / parts, r1 = rows * (p + 1) / parts;
      for (long long c0 = r0; this->HasWinding && c0 < r1; c0 += this->RayRows)
      {
        const long long c1 = std::min(r1, c0 + this->RayRows);
        rowRayKernel<<<static_cast<unsigned>((c1 - c0 + 127) / 128), 128>>>(
          this->Mesh.W[this->Variant], P, c0, c1, this->RayHits, this->RayMeta);
        LVDIF_CUDA_CHECK(cudaGetLastError());
        if (p == 0 && c0 == r0) LVDIF_CUDA_CHECK(cudaEventRecord(this->SignSplit.b)); // (--trace: the first rays)
        const unsigned grid = static_cast<unsigned>((c1 - c0 + SignWarps - 1) / SignWarps);
        if (dipole)
        {
          // the queue: the voxels the rows leave, each refined by a warp (dipoleRefineKernel)
          unsigned long long* queueCount = this->ListCounts + DipoleLevels * (1 + DipoleBlockPasses);
          LVDIF_CUDA_CHECK(cudaMemsetAsync(queueCount, 0, sizeof(unsigned long long)));
          signDipoleKernel<<<grid, 32 * SignWarps>>>(this->Mesh.W[this->Variant], this->Mesh.D[this->Variant], P, c0, c1, this->RayMeta,
            this->RayHits, this->Bounds, bx, by, this->Slab, this->Counters, this->Queue, queueCount, this->QueueCap, this->Local);
          LVDIF_CUDA_CHECK(cudaGetLastError());
          dipoleRefineKernel<<<2048, 128>>>(this->Mesh.D[this->Variant], P, this->Queue, queueCount, this->QueueCap, this->Slab,
            this->Counters);
          LVDIF_CUDA_CHECK(cudaGetLastError());
        }
        else
        {
          signKernel<<<grid, 32 * SignWarps>>>(
            this->Mesh.W[this->Variant], P, c0, c1, this->RayMeta, this->RayHits, this->Slab, this->Counters, this->Counters + 1);
        }
        LVDIF_CUDA_CHECK(cudaGetLastError());
      }
      LVDIF_CUDA_CHECK(cudaEventRecord(this->PartDone[p]));
    }
    LVDIF_CUDA_CHECK(cudaEventRecord(this->SignDone.b));
    this->Launched = true;
  }

  /// Room for the run list of a slab of `runs` runs (DistanceLists).
  void reserveDistanceLists(long long runs)
  {
    if (!this->Distance.work)
    {
      this->Distance.work = this->Arena.alloc<unsigned long long>(2);
      int device = 0, sms = 0, perSm = 0;
      LVDIF_CUDA_CHECK(cudaGetDevice(&device));
      LVDIF_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
      LVDIF_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, distanceRunKernel, 128, 0));
      this->Distance.runGrid = std::max(1, sms * std::max(1, perSm));
    }
    if (runs > this->Distance.capacity)
    {
      if (this->Distance.list) this->Arena.release(this->Distance.list);
      this->Distance.list = this->Arena.alloc<long long>(static_cast<std::size_t>(runs));
      this->Distance.capacity = runs;
    }
  }

  /// The far cells of the slab in P (which then points the distance kernel at them).
  void launchFar(Params& P)
  {
    long long count[3], blocks = 1;
    for (int a = 0; a < 3; ++a)
    {
      const long long n = P.hi[a] - P.lo[a] + 1;
      count[a] = (n + FarCell - 1) / FarCell;
      blocks *= (n + FarBlock - 1) / FarBlock;
    }
    const long long cells = count[0] * count[1] * count[2];
    if (cells > this->FarCapacity)
    {
      if (this->Far) this->Arena.release(this->Far);
      if (this->FarMask) this->Arena.release(this->FarMask);
      this->Far = this->Arena.alloc<signed char>(static_cast<std::size_t>(cells));
      this->FarMask = this->Arena.alloc<unsigned char>(static_cast<std::size_t>(cells));
      this->FarCapacity = cells;
    }
    // the blocks' states (candidate lists) for their halves, and the list of
    // those left undecided
    if (blocks > this->FarStateCapacity)
    {
      if (this->FarStates) this->Arena.release(this->FarStates);
      if (this->FarList) this->Arena.release(this->FarList);
      this->FarStates = this->Arena.alloc<FarState>(static_cast<std::size_t>(blocks));
      this->FarList = this->Arena.alloc<long long>(static_cast<std::size_t>(blocks));
      this->FarStateCapacity = blocks;
    }
    if (this->FarCellGrid == 0)
    {
      // enough CUDA blocks of farCellKernel to fill the GPU (they take the listed blocks in turn)
      int device = 0, sms = 0, perSm = 0;
      LVDIF_CUDA_CHECK(cudaGetDevice(&device));
      LVDIF_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
      LVDIF_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, farCellKernel, FarCellThreads, 0));
      this->FarCellGrid = std::max(1, sms * std::max(1, perSm));
    }
    LVDIF_CUDA_CHECK(cudaMemsetAsync(this->Far, 0, static_cast<std::size_t>(cells)));
    LVDIF_CUDA_CHECK(cudaMemsetAsync(this->FarMask, 0, static_cast<std::size_t>(cells)));
    LVDIF_CUDA_CHECK(cudaMemsetAsync(this->FarWork, 0, 2 * sizeof(unsigned long long)));
    long long m[3], tiles[3];
    for (int a = 0; a < 3; ++a) m[a] = (P.hi[a] - P.lo[a] + FarBlock) / FarBlock;
    farTiles(m, tiles);
    const long long threads = 32 * tiles[0] * tiles[1] * tiles[2];
    farBlockKernel<<<static_cast<unsigned>((threads + 127) / 128), 128>>>(this->Mesh.meshBvh(), this->Mesh.cones(), P,
      this->FarMargin, this->FarBig, this->Far, this->FarMask, this->FarStates, this->FarList, this->FarWork,
      this->FarDecided);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    LVDIF_CUDA_CHECK(cudaEventRecord(this->FarSplit.a));
    farCellKernel<<<static_cast<unsigned>(std::min<long long>(blocks, this->FarCellGrid)), FarCellThreads>>>(
      this->Mesh.meshBvh(), this->Mesh.cones(), P, this->FarMargin, this->FarBig, this->Far, this->FarMask,
      this->FarStates, this->FarList, this->FarWork, this->FarDecided);
    LVDIF_CUDA_CHECK(cudaGetLastError());
    LVDIF_CUDA_CHECK(cudaEventRecord(this->FarSplit.b));
    P.far = this->Far;
    P.farMask = this->FarMask;
    P.farCount[0] = count[0];
    P.farCount[1] = count[1];
  }

  void readCounters(MeshToSdfStats& stats)
  {
    if (this->FarOn)
    {
      unsigned long long far = 0;
      LVDIF_CUDA_CHECK(cudaMemcpy(&far, this->FarDecided, sizeof(far), cudaMemcpyDeviceToHost));
      LVDIF_CUDA_CHECK(cudaMemset(this->FarDecided, 0, sizeof(far)));
      stats.farVoxels += static_cast<std::int64_t>(far);
    }
    unsigned long long host[3] = { 0, 0, 0 };
    LVDIF_CUDA_CHECK(cudaMemcpy(host, this->Counters, sizeof(host), cudaMemcpyDeviceToHost));
    LVDIF_CUDA_CHECK(cudaMemset(this->Counters, 0, sizeof(host)));
    stats.windingEvaluations += static_cast<std::int64_t>(host[0]);
    stats.windingExact += static_cast<std::int64_t>(host[1]);
    stats.windingFullSums += static_cast<std::int64_t>(host[2]);
    if (this->LocalCounts)
    {
      unsigned long long local[3] = { 0, 0, 0 };
      LVDIF_CUDA_CHECK(cudaMemcpy(local, this->LocalCounts, sizeof(local), cudaMemcpyDeviceToHost));
      LVDIF_CUDA_CHECK(cudaMemset(this->LocalCounts, 0, sizeof(local)));
      for (int i = 0; i < 3; ++i) this->LocalTotals[i] += local[i];
    }
  }

  /// The local step is on unless LVDIF_CUDA_DIPOLE_LOCAL=0 (the benches time both).
  static bool localStepOn()
  {
    const char* e = std::getenv("LVDIF_CUDA_DIPOLE_LOCAL");
    return !(e && e[0] == '0');
  }

  MeshToSdfOptions Options;
  const CudaMesh& Mesh;
  bool HasWinding;
  int Variant; // which winding structures of the device copy: 0 M as given, 1 M+ (reorientFaces)
  std::function<void()> EnsureWinding;
  MeshToSdfStats& Stats;
  bool Launched = false;
  DeviceArena Arena;
  Params P;
  EventTimer DistanceDone, SignDone;
  EventTimer SignSplit; // a: after the block bounds, b: after the first rays of a slab (volume path: --trace)
  double BoundsSeconds = 0, RaysSeconds = 0;
  EventTimer FarSplit; // a: after farBlockKernel, b: after farCellKernel (--trace)
  double FarBlockSeconds = 0, FarHalfSeconds = 0, FarRestSeconds = 0;
  PartEvents PartDone;
  Stream Copy; // device -> host copies, beside the kernels of the legacy stream
  unsigned long long* Counters = nullptr;
  // the scan lines' rays (rowRayKernel), RayRows lines at a time
  long long RayRows = 1;
  Hit* RayHits = nullptr;
  int4* RayMeta = nullptr;
  // far blocks (Normal/PseudoNormal with a band): per FarCell^3 cell of the
  // slab the side and the mask of its decided voxels; per block its state
  bool FarOn = false;
  double FarBig = 0, FarMargin = 0;
  signed char* Far = nullptr;
  unsigned char* FarMask = nullptr;
  long long FarCapacity = 0;
  FarState* FarStates = nullptr;
  long long* FarList = nullptr; // the blocks farBlockKernel leaves undecided
  unsigned long long* FarWork = nullptr; // their count, the next one farCellKernel takes
  long long FarStateCapacity = 0;
  int FarCellGrid = 0; // CUDA blocks of farCellKernel
  unsigned long long* FarDecided = nullptr;
  DistanceLists Distance; // the distance pass's runs that need queries
  float* Slab = nullptr;
  std::size_t SlabCapacity = 0;
  double* Bounds = nullptr; // per block of the slab: s's bound (lo, hi), lo > hi: none
  long long BoundCapacity = 0;
  // the work lists of the winding decision (MeshToSdfCudaDipole.cuh)
  static constexpr int ListCountSlots = DipoleLevels * (1 + DipoleBlockPasses) + 1; // the levels' lists, their passes, the queue
  long long* BlockLists = nullptr;          // per level but the finest: its blocks without a bound
  DipolePending* BlockPending = nullptr;    // blocks between passes (in, out)
  long long PendingCap = 0;
  unsigned long long* ListCounts = nullptr; // per level, per level and pass, then the voxels' per pass
  unsigned long long* Queue = nullptr;      // the voxels of a part the blocks left undecided (dipoleListVoxel)
  long long QueueCapacity = 0, QueueCap = 0;
  // the local step (dipoleLocalKernel) on the failed blocks of level LocalLevel
  static constexpr int LocalLevel = 1;
  static_assert(DipoleEdges[LocalLevel] == DipoleLocalEdge && LocalLevel + 1 < DipoleLevels, "the local step's blocks");
  DipoleLocalLists Local; // the last slab's (the sign kernel reads it)
  static constexpr int LocalThreads = 32 * LocalWarpsPerBlock; // dipoleLocalKernel's CUDA block (4 warps, a block of voxels each)
  int LocalGrid = 0;                       // its CUDA blocks (a grid-stride loop)
  int* LocalNear = nullptr;                // its warps' near-triangle lists
  int* LocalSlot = nullptr;
  double* LocalPool = nullptr;
  long long LocalSlotCapacity = 0, LocalCap = 0;
  unsigned long long* LocalCounts = nullptr; // blocks expanded, blocks failed, voxels decided (since the last readCounters)
  unsigned long long LocalTotals[3] = { 0, 0, 0 };
  // the group of chunk layers of the last launchKeys
  VoxelBox KeyBox;
  int Edge = 32, Ccx = 0, Ccy = 0;
  long long Chunks = 0, FlagCapacity = 0;
  SdfDictionary::EncodeConstants Encode;
  float Band = 0;
  unsigned* Flags = nullptr;
  long long* List = nullptr;
  unsigned short* Keys = nullptr;
  std::size_t KeyCapacity = 0;
  // the keys' way back: Slots staging slots of PieceChunks chunks each
  static constexpr std::size_t Slots = 3;
  static_assert(Slots <= PartEvents::Max, "one event per slot");
  HostBlock Staging;
  std::size_t PieceChunks = 1, Listed = 0, Pieces = 0; // Pieces > 0: takeKeys pending
  PartEvents PieceDone; // per slot: its copy done
  PartEvents KeysReady; // [0]: the keys kernel of the last fetchKeys done
};
} // namespace

std::unique_ptr<Session> openSession(const DeviceMesh& mesh, const GridGeometry& grid,
  const MeshToSdfOptions& options, double toOut, double band, MeshToSdfStats& stats,
  std::function<void()> ensureWinding)
{
  return std::make_unique<CudaSession>(
    static_cast<const CudaMesh&>(mesh), grid, options, toOut, band, stats, std::move(ensureWinding));
}

KeyCopyCounts keyCopyCounts()
{
  KeyCopyCounts c;
  c.pieces = piecesCopied.load();
  c.pageable = piecesPageable.load();
  return c;
}

void refusePinnedKeys(bool refuse)
{
  pinnedPool().refuse(refuse);
}

std::vector<std::uint16_t> encodeOnDevice(
  const SdfDictionary::EncodeConstants& encode, float band, const std::vector<float>& values)
{
  DeviceArena arena;
  const float* in = arena.upload(values);
  unsigned short* out = arena.alloc<unsigned short>(values.size());
  const long long n = static_cast<long long>(values.size());
  encodeKernel<<<static_cast<unsigned>((n + 255) / 256), 256>>>(encode, band, in, n, out);
  LVDIF_CUDA_CHECK(cudaGetLastError());
  std::vector<std::uint16_t> host(values.size());
  LVDIF_CUDA_CHECK(cudaMemcpy(host.data(), out, host.size() * sizeof(unsigned short), cudaMemcpyDeviceToHost));
  return host;
}

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
