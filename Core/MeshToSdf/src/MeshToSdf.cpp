// Mesh to SDF driver: validation, grid fitting, the per-row distance and sign
// passes (OpenMP over rows), output into a float extent or a dictionary
// volume slab by slab. Algorithms: MeshToSdf.h; structures: MeshToSdfInternal.h.
#include "lvdif/MeshToSdf.h"

#include "MeshToSdfCuda.h"
#include "MeshToSdfFarBlocks.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfNearest.h"
#include "lvdif/Memory.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <sstream>
#include <utility>

namespace lvdif
{

using namespace detail::meshtosdf;

namespace
{
void validateGrid(const GridGeometry& g)
{
  for (int a = 0; a < 3; ++a)
  {
    require(g.dims[a] >= 1 && g.dims[a] <= DictionaryVolume::MaxDimension,
      "mesh to SDF: grid dimension " + std::to_string(g.dims[a]) + " out of range [1, " +
        std::to_string(DictionaryVolume::MaxDimension) + "]");
    require(std::isfinite(g.origin[a]), "mesh to SDF: grid origin is not finite");
    require(std::isfinite(g.spacing[a]) && g.spacing[a] > 0, "mesh to SDF: grid spacing must be positive and finite");
  }
}

struct Engine
{
  const PreparedMesh* mesh = nullptr;
  const NearestIndex* index = nullptr;
  const WindingSigner* winding = nullptr;
  std::unique_ptr<FaithfulGrid> grid;
  GridGeometry geom;
  MeshToSdfOptions opts;
  bool far = false;       // far blocks (Normal/PseudoNormal, finite band, CPU BVH; MeshToSdfOptions::farBlocks)
  const Bvh* farBvh = nullptr;                 // their tree and node cones
  const std::vector<FarCone>* farCones = nullptr;
  bool bandCells = false; // the same blocks by distance alone (WindingNumber/Unsigned, finite band, CPU BVH)
  double toOut = 1;       // world distance -> output units
  double band = 0;        // output units (may be infinite)
  double bandWorld2 = 0;  // squared band in world units, for bounded queries

  V3 position(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return { this->geom.origin[0] + i * this->geom.spacing[0], this->geom.origin[1] + j * this->geom.spacing[1],
      this->geom.origin[2] + k * this->geom.spacing[2] };
  }

  NearestResult nearest(V3 p, std::int32_t hint) const
  {
    switch (this->opts.accel)
    {
      case MeshToSdfAccel::Faithful: return this->grid->nearest(p);
      case MeshToSdfAccel::BruteForce:
      {
        NearestResult best;
        best.dist2 = 1e300;
        for (std::size_t t = 0; t < this->mesh->tris.size(); ++t)
        {
          const Tri& tri = this->mesh->tris[t];
          const Closest c = closestPointOnTriangle(p, tri.v[0], tri.v[1], tri.v[2]);
          const V3 d = c.point - p;
          const double d2 = dot(d, d);
          if (d2 < best.dist2)
          {
            best = { d2, static_cast<std::int32_t>(t), c };
          }
        }
        return best;
      }
      default:
      {
        // only the winding-number and unsigned modes may stop at the band:
        // the others need the closest triangle for its normal
        const bool bounded = this->opts.sign == SignMode::WindingNumber || this->opts.sign == SignMode::Unsigned;
        return this->index->nearest(p, hint, bounded ? this->bandWorld2 : 1e300);
      }
    }
  }

  /// -1 inside, +1 outside, from the closest triangle (Normal / PseudoNormal).
  float localSign(V3 p, const NearestResult& r) const
  {
    const Tri& t = this->mesh->tris[r.tri];
    V3 n;
    if (this->opts.sign == SignMode::PseudoNormal)
    {
      n = featureNormal(t, r.closest.feature);
    }
    else if (this->opts.useVertexNormals && dot(t.nv[0], t.nv[0]) > 0)
    {
      const double b0 = 1 - r.closest.b1 - r.closest.b2;
      n = b0 * t.nv[0] + r.closest.b1 * t.nv[1] + r.closest.b2 * t.nv[2];
    }
    else
    {
      n = t.n;
    }
    return dot(p - r.closest.point, n) < 0 ? -1.0f : 1.0f;
  }

  void distanceBricks(const VoxelBox& box, float* out, const FarCells& far, Interrupter& intr, double progressBase,
    double progressSpan) const;

  /// Distances (and the local sign) of one row; out holds output units.
  /// With a finite band and no normal-based sign, the distance being
  /// 1-Lipschitz lets far voxels skip the query: each query past the band
  /// looks a margin beyond it, and the following voxels stay saturated while
  /// the lower bound (previous distance - steps) is still past the band.
  /// rowTris (nx entries): on entry the nearest triangles of the row below
  /// when belowValid (they seed the bounds), on exit this row's.
  /// far (optional): the far cells of this row (FarCell voxels each from i0)
  /// and their masks; farBit: the row's bit in them (2 y + 4 z inside the
  /// cell): a voxel whose bit farBit + x is set is +-band without a query.
  void distanceRow(std::int64_t j, std::int64_t k, std::int64_t i0, std::int64_t i1, float* out,
    std::int32_t* rowTris, bool belowValid, const std::int8_t* far = nullptr, const std::uint8_t* farMask = nullptr,
    int farBit = 0) const
  {
    auto isFar = [&](std::int64_t i) {
      return far && ((farMask[(i - i0) / FarCell] >> (farBit + ((i - i0) & 1))) & 1) != 0;
    };
    const bool bounded = this->opts.accel == MeshToSdfAccel::Bvh &&
      (this->opts.sign == SignMode::WindingNumber || this->opts.sign == SignMode::Unsigned) &&
      this->bandWorld2 < 1e299;
    const double h = this->geom.spacing[0];
    const double bandWorld = std::sqrt(this->bandWorld2);
    const double reach = bandWorld + 4 * h;
    double lower = -1; // lower bound of the current voxel's world distance
    std::int32_t hint = -1;
    // the BVH takes the voxels RowPoints at a time (one shared traversal,
    // seeded by the row below) where they need their nearest triangle: every
    // voxel without a band, and after a voxel within the band with one; past
    // the band one bounded query at a time finds the next voxel to query
    const bool packets = this->opts.accel == MeshToSdfAccel::Bvh;
    bool withinBand = false; // the last voxel queried was
    for (std::int64_t i = i0; i <= i1;)
    {
      if (isFar(i))
      {
        out[i - i0] = static_cast<float>(far[(i - i0) / FarCell]) * static_cast<float>(this->band);
        rowTris[i - i0] = -1;
        lower -= h; // keeps the bound of the voxels after the cell valid
        withinBand = false;
        ++i;
        continue;
      }
      NearestResult res[NearestIndex::RowPoints];
      V3 ps[NearestIndex::RowPoints];
      int count = 1;
      if (packets && (!bounded || withinBand))
      {
        count = static_cast<int>(std::min<std::int64_t>(NearestIndex::RowPoints, i1 - i + 1));
        for (int q = 1; far && q < count; ++q)
          if (isFar(i + q)) count = q;
        for (int q = 0; q < count; ++q) ps[q] = this->position(i + q, j, k);
        this->index->nearestRow(ps, count, hint, belowValid ? rowTris + (i - i0) : nullptr, res);
      }
      else
      {
        lower -= h;
        if (bounded && lower >= bandWorld)
        {
          out[i - i0] = static_cast<float>(this->band);
          rowTris[i - i0] = -1;
          ++i;
          continue;
        }
        ps[0] = this->position(i, j, k);
        res[0] = bounded ? this->index->nearest(ps[0], hint, reach * reach) : this->nearest(ps[0], hint);
      }
      for (int q = 0; q < count; ++q, ++i)
      {
        const NearestResult& r = res[q];
        rowTris[i - i0] = r.tri;
        double d = r.tri < 0 ? this->band : std::sqrt(r.dist2) * this->toOut;
        lower = r.tri < 0 ? reach : std::sqrt(r.dist2);
        d = std::min(d, this->band);
        float s = 1.0f;
        if (r.tri >= 0)
        {
          hint = r.tri;
          if (this->opts.sign == SignMode::Normal || this->opts.sign == SignMode::PseudoNormal)
          {
            s = this->localSign(ps[q], r);
          }
        }
        out[i - i0] = s * static_cast<float>(d);
      }
      withinBand = lower < bandWorld;
    }
  }
};

/// On CUDA the winding structures are left to openCuda, which builds them
/// (if not prepared yet) while the GPU computes distances.
std::unique_ptr<Engine> makeEngine(const MeshToSdfPrepared& prepared, const GridGeometry& geom,
  const MeshToSdfOptions& opts, float band, Device device, MeshToSdfStats& stats)
{
  validateGrid(geom);
  require(opts.faithfulCellsPerAxis >= 1 && opts.faithfulCellsPerAxis <= 256,
    "mesh to SDF: faithfulCellsPerAxis must be in [1, 256]");
  require(opts.faithfulScale >= 1 && opts.faithfulScale <= 16, "mesh to SDF: faithfulScale must be in [1, 16]");
  require(band > 0, "mesh to SDF: band width must be positive");
  const double t0 = now();
  auto e = std::make_unique<Engine>();
  MeshToSdfPrepared::Impl& impl = prepared.impl();
  e->mesh = &impl.mesh;
  e->geom = geom;
  e->opts = opts;
  const double unit = std::min(geom.spacing[0], std::min(geom.spacing[1], geom.spacing[2]));
  e->toOut = opts.unit == DistanceUnit::Voxel ? 1.0 / unit : 1.0;
  e->band = band;
  const double bw = static_cast<double>(band) / e->toOut;
  e->bandWorld2 = std::isfinite(bw) ? bw * bw * (1 + 1e-9) : 1e300;
  double lazy = 0; // only what this call had to build (timed inside)
  // the records' pseudo-normals: read only by these signs (CPU and GPU alike)
  if (opts.sign == SignMode::Normal || opts.sign == SignMode::PseudoNormal) impl.pseudoNormals(lazy);
  if (device == Device::Cpu && opts.accel == MeshToSdfAccel::Bvh)
  {
    e->index = &impl.nearestIndex(lazy);
  }
  e->far = opts.farBlocks && e->index != nullptr && e->bandWorld2 < 1e299 && !opts.useVertexNormals &&
    (opts.sign == SignMode::Normal || opts.sign == SignMode::PseudoNormal);
  if (e->far) e->farBvh = &impl.farTree(e->farCones, lazy);
  e->bandCells = opts.farBlocks && e->index != nullptr && e->bandWorld2 < 1e299 &&
    (opts.sign == SignMode::WindingNumber || opts.sign == SignMode::Unsigned);
  if (opts.sign == SignMode::WindingNumber && device == Device::Cpu)
  {
    e->winding = &impl.windingSigner(lazy);
  }
  if (opts.accel == MeshToSdfAccel::Faithful)
  {
    const std::uint64_t cells = static_cast<std::uint64_t>(opts.faithfulCellsPerAxis) *
      opts.faithfulCellsPerAxis * opts.faithfulCellsPerAxis;
    requireMemory(cells * 48, "mesh to SDF: faithful cell lists");
    e->grid = std::make_unique<FaithfulGrid>(
      e->mesh->tris, e->mesh->lo, e->mesh->hi, opts.faithfulCellsPerAxis, opts.faithfulScale);
  }
  stats.triangles = e->mesh->tris.size();
  stats.degenerateSkipped = e->mesh->degenerate;
  stats.boundaryEdges = e->mesh->boundaryEdges;
  stats.buildSeconds += now() - t0;
  return e;
}

/// Says (with --trace) which winding construction the GPU runs.
void traceWindingPath(const WindingSigner& w)
{
  const DipoleTree* s = w.cpuCorrection();
  const std::string what = !w.gpuTakesCpuClosure()
    ? "winding sign on the GPU: cone over the boundary (the older construction)"
    : s ? "winding sign on the GPU: the CPU's closure, correction s over " + std::to_string(s->size()) +
          " faces (caps, reversed, removed) in the dipole tree"
        : std::string("winding sign on the GPU: closed mesh, crossings only");
  trace(what.c_str(), 0);
}

/// The CUDA session of a call, on the prepared mesh's device copy (uploaded
/// on first use; the upload counts as build time). Winding structures not
/// built yet (the one-call API) are built and uploaded by the session right
/// after it queues the first distance kernel, overlapping it; that host time
/// is added to the build time too.
std::unique_ptr<detail::meshtosdf_cuda::Session> openCuda(const MeshToSdfPrepared& prepared, const Engine& e,
  const MeshToSdfOptions& opts, MeshToSdfStats& stats)
{
  const double t0 = now();
  double unused = 0;
  MeshToSdfPrepared::Impl& impl = prepared.impl();
  const bool winding = opts.sign == SignMode::WindingNumber;
  const bool normals = opts.sign == SignMode::Normal || opts.sign == SignMode::PseudoNormal;
  const bool built = impl.hasWindingSigner();
  const detail::meshtosdf_cuda::DeviceMesh& dm = impl.deviceMesh(winding && built, normals, unused, winding && !built);
  std::function<void()> ensure;
  if (winding && built) traceWindingPath(impl.windingSigner(unused));
  if (winding)
  {
    ensure = [&impl, &stats]() {
      const double t1 = now();
      double s = 0;
      impl.deviceMesh(true, false, s);
      stats.buildSeconds += now() - t1;
      trace("winding structures built and uploaded, overlapping the distance kernel", now() - t1);
      traceWindingPath(impl.windingSigner(s));
    };
  }
  auto session = detail::meshtosdf_cuda::openSession(dm, e.geom, opts, e.toOut, e.band, stats, std::move(ensure));
  stats.buildSeconds += now() - t0;
  trace("upload and session", now() - t0);
  return session;
}

/// The device of a call. Auto prefers CUDA for every mesh: the CUDA sign
/// kernel takes the CPU's winding construction (orientation pass, local caps,
/// the dipole tree over caps, reversed and removed faces) and decides every
/// voxel as the CPU does (MeshToSdfCudaDipole.cuh). Only reorientFaces stays
/// on the CPU.
Device chooseDevice(const MeshToSdfOptions& options)
{
  const Device d = resolveDevice(options.device);
  if (d != Device::Cuda || options.sign != SignMode::WindingNumber) return d;
  if (options.reorientFaces) return Device::Cpu; // not on CUDA (documented at the option)
  return d;
}

/// Runs fn(row) for every (j, k) row of the box on OpenMP threads; progress
/// from thread 0, cancellation per row; rethrows the first exception.
template <typename F>
void forRows(const VoxelBox& box, Interrupter& intr, double progressBase, double progressSpan, F&& fn, int chunk = 2)
{
  const std::int64_t ny = box.hi[1] - box.lo[1] + 1, nz = box.hi[2] - box.lo[2] + 1;
  const std::int64_t rows = ny * nz;
  std::atomic<std::int64_t> done{ 0 };
  std::atomic<bool> stop{ false };
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, chunk)
  for (std::int64_t r = 0; r < rows; ++r)
  {
    if (stop.load(std::memory_order_relaxed)) continue;
    try
    {
      fn(box.lo[1] + r % ny, box.lo[2] + r / ny, r);
      const std::int64_t n = done.fetch_add(1) + 1;
      if (omp_get_thread_num() == 0)
      {
        if (intr.wasInterrupted()) stop = true;
        intr.progress(progressBase + progressSpan * static_cast<double>(n) / static_cast<double>(rows));
      }
    }
    catch (...)
    {
#pragma omp critical(lvdif_mesh_to_sdf_failure)
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  }
  if (failure) std::rethrow_exception(failure);
  // thread 0 may not have run the last row: the span's end is reported here
  if (!stop.load()) intr.progress(progressBase + progressSpan);
  intr.checkInterrupt();
}

/// Bricks of BrickX x Brick x Brick voxels within the band. 8 x 4 x 4
/// measured fastest on the bunny and the armadillo at 512 (4^3: more bricks,
/// each with a query and a list; 8^3: lists too long for each voxel; 2 or 16
/// along x: slower or no better).
constexpr std::int64_t BrickX = 8, Brick = 4;

/// The distance pass of a banded box (WindingNumber, Unsigned: the sign comes
/// later) brick by brick (from the box's first voxel): the voxels of a brick that the far cells left get
/// NearestIndex::nearestBrick bounded at the band (the same values as the
/// rows' queries: a voxel with no triangle within the band is +band either
/// way), on OpenMP threads; progress from thread 0, cancellation per brick.
void Engine::distanceBricks(const VoxelBox& box, float* out, const FarCells& far, Interrupter& intr,
  double progressBase, double progressSpan) const
{
  constexpr std::int64_t BX = BrickX, B = Brick;
  const std::int64_t n[3] = { box.hi[0] - box.lo[0] + 1, box.hi[1] - box.lo[1] + 1, box.hi[2] - box.lo[2] + 1 };
  const std::int64_t nb[3] = { (n[0] + BX - 1) / BX, (n[1] + B - 1) / B, (n[2] + B - 1) / B };
  const std::int64_t bricks = nb[0] * nb[1] * nb[2];
  const bool anyFar = !far.sign.empty();
  static_assert(FarCell == 2, "cells of 2^3 voxels: one bit each");
  auto cellOf = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::size_t>((x >> 1) + far.count[0] * ((y >> 1) + far.count[1] * (z >> 1)));
  };
  auto isFar = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return ((far.mask[cellOf(x, y, z)] >> ((x & 1) + 2 * (y & 1) + 4 * (z & 1))) & 1) != 0;
  };
  // the far voxels first, row by row (in brick order their stores would stride across the buffer)
  if (anyFar)
  {
#pragma omp parallel for schedule(static)
    for (std::int64_t r = 0; r < n[1] * n[2]; ++r)
    {
      const std::int64_t y = r % n[1], z = r / n[1];
      const std::size_t c0 = cellOf(0, y, z);
      const int rowBit = static_cast<int>(2 * (y & 1) + 4 * (z & 1));
      float* row = out + n[0] * r;
      for (std::int64_t cx = 0; 2 * cx < n[0]; ++cx)
      {
        // this row's two bits of the cell
        const int bits = (far.mask[c0 + static_cast<std::size_t>(cx)] >> rowBit) & 3;
        if (bits == 0) continue;
        const float v = static_cast<float>(far.sign[c0 + static_cast<std::size_t>(cx)]) * static_cast<float>(this->band);
        if (bits & 1) row[2 * cx] = v;
        if ((bits & 2) && 2 * cx + 1 < n[0]) row[2 * cx + 1] = v;
      }
    }
  }
  std::atomic<std::int64_t> done{ 0 };
  std::atomic<bool> stop{ false };
  std::exception_ptr failure;
#pragma omp parallel
  {
    NearestIndex::BrickScratch scratch;
    std::vector<V3> ps;
    std::vector<std::int64_t> at;
    std::vector<NearestResult> res;
    std::int32_t hint = -1;
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t b = 0; b < bricks; ++b)
    {
      if (stop.load(std::memory_order_relaxed)) continue;
      try
      {
        const std::int64_t o[3] = { BX * (b % nb[0]), B * ((b / nb[0]) % nb[1]), B * (b / (nb[0] * nb[1])) };
        ps.clear();
        at.clear();
        const std::int64_t x1 = std::min(n[0], o[0] + BX), y1 = std::min(n[1], o[1] + B), z1 = std::min(n[2], o[2] + B);
        // the far voxels are written (above); a brick of whole far cells has nothing else
        bool allFar = anyFar;
        for (std::int64_t z = o[2]; z < z1 && allFar; z += FarCell)
          for (std::int64_t y = o[1]; y < y1 && allFar; y += FarCell)
            for (std::int64_t x = o[0]; x < x1 && allFar; x += FarCell)
              allFar = far.mask[cellOf(x, y, z)] == 0xff;
        for (std::int64_t z = o[2]; z < z1 && !allFar; ++z)
          for (std::int64_t y = o[1]; y < y1; ++y)
            for (std::int64_t x = o[0]; x < x1; ++x)
            {
              if (anyFar && isFar(x, y, z)) continue;
              ps.push_back(this->position(box.lo[0] + x, box.lo[1] + y, box.lo[2] + z));
              at.push_back(x + n[0] * (y + n[1] * z));
            }
        if (!ps.empty())
        {
          res.resize(ps.size());
          this->index->nearestBrick(ps.data(), static_cast<int>(ps.size()), this->bandWorld2, hint, res.data(), scratch);
          for (std::size_t q = 0; q < ps.size(); ++q)
          {
            const NearestResult& r = res[q];
            double d = r.tri < 0 ? this->band : std::sqrt(r.dist2) * this->toOut;
            d = std::min(d, this->band);
            if (r.tri >= 0) hint = r.tri;
            out[at[q]] = static_cast<float>(d);
          }
        }
        const std::int64_t k = done.fetch_add(1) + 1;
        if (omp_get_thread_num() == 0 && (k & 255) == 0)
        {
          if (intr.wasInterrupted()) stop = true;
          intr.progress(progressBase + progressSpan * static_cast<double>(k) / static_cast<double>(bricks));
        }
      }
      catch (...)
      {
#pragma omp critical(lvdif_mesh_to_sdf_failure)
        if (!failure) failure = std::current_exception();
        stop = true;
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (!stop.load()) intr.progress(progressBase + progressSpan);
  intr.checkInterrupt();
}

/// The distance and sign passes over one box of voxels into out (box layout).
void computeBox(const Engine& e, const VoxelBox& box, float* out, MeshToSdfStats& stats, Interrupter& intr,
  double progressBase, double progressSpan)
{
  const std::int64_t nx = box.hi[0] - box.lo[0] + 1, ny = box.hi[1] - box.lo[1] + 1;
  const bool winding = e.opts.sign == SignMode::WindingNumber;
  double t0 = now();
  // per thread: the nearest triangles of its last row; rows come in chunks of
  // 8 consecutive ones, so most rows find the row below in their buffer
  const int threads = omp_get_max_threads();
  requireMemory(static_cast<std::uint64_t>(threads) * static_cast<std::uint64_t>(nx) * 4, "mesh to SDF: row hints");
  std::vector<std::int32_t> rowTris(static_cast<std::size_t>(threads * nx), -1);
  std::vector<std::int64_t> lastRow(static_cast<std::size_t>(threads), -2);
  FarCells far;
  if (e.far)
  {
    const double tf = now();
    stats.farVoxels += classifyFarCells(
      *e.index, *e.farBvh, *e.farCones, *e.mesh, e.geom, box, static_cast<double>(e.band) / e.toOut,
      e.opts.sign == SignMode::PseudoNormal, far);
    trace("far blocks of a box", now() - tf);
  }
  else if (e.bandCells)
  {
    const double tf = now();
    stats.farVoxels += classifyBandCells(*e.index, *e.mesh, e.geom, box, static_cast<double>(e.band) / e.toOut, far);
    trace("blocks past the band of a box", now() - tf);
  }
  if (e.bandCells)
    e.distanceBricks(box, out, far, intr, progressBase, winding ? progressSpan * 0.5 : progressSpan);
  else
    forRows(box, intr, progressBase, winding ? progressSpan * 0.5 : progressSpan,
    [&](std::int64_t j, std::int64_t k, std::int64_t r) {
      const int t = std::min(omp_get_thread_num(), threads - 1);
      const bool below = lastRow[static_cast<std::size_t>(t)] == r - 1 && j > box.lo[1];
      const std::int64_t farAt = far.count[0] * ((j - box.lo[1]) / FarCell + far.count[1] * ((k - box.lo[2]) / FarCell));
      const bool anyFar = !far.sign.empty();
      e.distanceRow(j, k, box.lo[0], box.hi[0], out + r * nx, rowTris.data() + t * nx, below,
        anyFar ? far.sign.data() + farAt : nullptr, anyFar ? far.mask.data() + farAt : nullptr,
        static_cast<int>(2 * ((j - box.lo[1]) & 1) + 4 * ((k - box.lo[2]) & 1)));
      lastRow[static_cast<std::size_t>(t)] = r;
    }, 8);
  stats.distanceSeconds += now() - t0;
  if (!winding) return;
  t0 = now();
  // The correction s (reversed, removed, capped faces) bounded once per
  // group of 16^3 voxels, where that fails per block of 4^3, and where that
  // fails per 2^3 (each starting from the larger block's cut): away from
  // those faces a block's bound decides all its voxels, where row segments
  // of 16 (a ball of radius 7.5 voxels) would reach a face; the rows then
  // refine only what is left.
  constexpr std::int64_t Block = 2; // the finer blocks; the coarse ones are 2 x 2 x 2 of them
  const bool reorient = e.opts.reorientFaces;
  const std::int64_t bx = (nx + Block - 1) / Block, by = (ny + Block - 1) / Block,
                     bz = (box.hi[2] - box.lo[2] + Block) / Block;
  std::vector<double> blockLo, blockHi;
  if (e.winding->hasCorrection(reorient))
  {
    blockLo.assign(static_cast<std::size_t>(bx * by * bz), 1.0);
    blockHi.assign(blockLo.size(), 0.0);
    const std::int64_t cx = (bx + 1) / 2, cy = (by + 1) / 2;
    // the ball about the voxels [v0, v0 + edge)^3 of the box (clipped)
    auto ball = [&](std::int64_t x0, std::int64_t y0, std::int64_t z0, std::int64_t edge, V3& centre) {
      const V3 p0 = e.position(x0, y0, z0);
      const V3 p1 = e.position(std::min(x0 + edge - 1, box.hi[0]), std::min(y0 + edge - 1, box.hi[1]),
        std::min(z0 + edge - 1, box.hi[2]));
      centre = 0.5 * (p0 + p1);
      const double half = 0.5 * norm(p1 - p0);
      // rho also covers the rounding of the voxel positions as the rows compute them
      return half + 1e-9 * (half + std::fabs(centre.x) + std::fabs(centre.y) + std::fabs(centre.z));
    };
    // the coarse blocks in groups of 4 x 4 x 4 (16^3 voxels): one ball first
    // (far from the corrected faces it bounds them all), then each coarse
    // block from the group's cut
    const std::int64_t gx = (cx + 3) / 4, gy = (cy + 3) / 4, groups = gx * gy * ((((bz + 1) / 2) + 3) / 4);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t grp = 0; grp < groups; ++grp)
    {
      const std::int64_t ox = 4 * (grp % gx), oy = 4 * ((grp / gx) % gy), oz = 4 * (grp / (gx * gy)); // first coarse block
      std::vector<std::int32_t> groupCut;
      V3 centre;
      double rho = ball(box.lo[0] + 2 * Block * ox, box.lo[1] + 2 * Block * oy, box.lo[2] + 2 * Block * oz, 8 * Block, centre);
      double glo = 0, ghi = 0;
      std::int64_t leafTris = 0;
      const bool groupWhole = e.winding->boundCorrection(centre, rho, glo, ghi, leafTris, reorient, &groupCut);
      for (std::int64_t q = 0; q < 64; ++q)
      {
        const std::int64_t qx = ox + (q & 3), qy = oy + ((q >> 2) & 3), qz = oz + (q >> 4);
        if (qx >= cx || qy >= cy || qz >= (bz + 1) / 2) continue;
        const std::int64_t fx = 2 * qx, fy = 2 * qy, fz = 2 * qz; // first fine block
        std::vector<std::int32_t> cut;
        double lo = glo, hi = ghi;
        bool whole = groupWhole;
        if (!whole)
        {
          cut = groupCut;
          rho = ball(box.lo[0] + Block * fx, box.lo[1] + Block * fy, box.lo[2] + Block * fz, 2 * Block, centre);
          whole = e.winding->boundCorrection(centre, rho, lo, hi, leafTris, reorient, &cut);
        }
        for (std::int64_t d = 0; d < 8; ++d)
        {
          const std::int64_t ix = fx + (d & 1), iy = fy + ((d >> 1) & 1), iz = fz + (d >> 2);
          if (ix >= bx || iy >= by || iz >= bz) continue;
          const std::size_t f = static_cast<std::size_t>(ix + bx * (iy + by * iz));
          if (whole)
          {
            blockLo[f] = lo;
            blockHi[f] = hi;
            continue;
          }
          std::vector<std::int32_t> sub = cut;
          rho = ball(box.lo[0] + Block * ix, box.lo[1] + Block * iy, box.lo[2] + Block * iz, Block, centre);
          double l = 0, u = 0;
          if (e.winding->boundCorrection(centre, rho, l, u, leafTris, reorient, &sub))
          {
            blockLo[f] = l;
            blockHi[f] = u;
          }
        }
      }
    }
  }
  trace("winding: block bounds of the correction s", now() - t0);
  const double tr = now();
  std::atomic<std::int64_t> evals{ 0 }, exact{ 0 }, fullSums{ 0 };
  forRows(box, intr, progressBase + 0.5 * progressSpan, 0.5 * progressSpan,
    [&](std::int64_t j, std::int64_t k, std::int64_t r) {
      std::int64_t ev = 0, ex = 0, fs = 0;
      thread_local std::vector<double> priorLo, priorHi;
      const double* pl = nullptr;
      const double* ph = nullptr;
      if (!blockLo.empty())
      {
        priorLo.resize(static_cast<std::size_t>(nx));
        priorHi.resize(static_cast<std::size_t>(nx));
        const std::int64_t row = bx * ((j - box.lo[1]) / Block + by * ((k - box.lo[2]) / Block));
        for (std::int64_t i = 0; i < nx; ++i)
        {
          priorLo[static_cast<std::size_t>(i)] = blockLo[static_cast<std::size_t>(row + i / Block)];
          priorHi[static_cast<std::size_t>(i)] = blockHi[static_cast<std::size_t>(row + i / Block)];
        }
        pl = priorLo.data();
        ph = priorHi.data();
      }
      e.winding->signRow(e.position(box.lo[0], j, k), e.geom.spacing[0], nx, out + r * nx, ev, ex, &fs, reorient,
        pl, ph);
      evals += ev;
      exact += ex;
      fullSums += fs;
    });
  (void)ny;
  trace("winding: rows (crossings, voxels refined one by one)", now() - tr);
  stats.windingEvaluations += evals.load();
  stats.windingExact += exact.load();
  stats.windingFullSums += fullSums.load();
  stats.signSeconds += now() - t0;
}

/// Stores one chunk's keys (the CPU and GPU paths): a uniform chunk over a
/// uniform one is filled, anything else expanded and written (colours kept).
/// `uniform` is whether the keys of the chunk's voxels inside the volume are
/// all equal: when they are not, the chunk cannot collapse, so only a
/// uniform key over varied colours tries.
template <typename KeyAt>
void storeChunk(DictionaryVolume& volume, std::int64_t id, bool uniform, SdfKey first, KeyAt&& keyAt)
{
  if (uniform && volume.isUniform(id))
  {
    volume.fillChunk(id, Voxel{ first, volume.uniformValue(id).color });
    return;
  }
  const VoxelBox cb = volume.chunkBox(id);
  Voxel* data = volume.expandChunk(id);
  const std::int64_t nx = cb.hi[0] - cb.lo[0] + 1;
  for (std::int64_t z = cb.lo[2]; z <= cb.hi[2]; ++z)
    for (std::int64_t y = cb.lo[1]; y <= cb.hi[1]; ++y)
    {
      const std::int64_t l0 = volume.localIndex(cb.lo[0], y, z); // x is the fastest local index
      Voxel* row = data + l0;
      if (uniform)
        for (std::int64_t i = 0; i < nx; ++i) row[i].sdf = first;
      else
        for (std::int64_t i = 0; i < nx; ++i) row[i].sdf = keyAt(cb.lo[0] + i, y, z, l0 + i);
    }
  volume.markDirty(id);
  if (uniform) volume.tryCollapseChunk(id);
}

/// The chunks of a region (MeshToSdfOptions::chunkRegion; the CPU's whole-volume route passes
/// every chunk), one band of them at a time: whole x rows of the region, as many rows of chunks
/// along y as fit in `bandBytes` (at least one), one chunk layer along z, computed as float boxes
/// by `compute` and encoded on the host (the CUDA route's keys equal the host's encode). The
/// buffer stays bounded whatever the grid, where a whole chunk layer would be nx * ny * chunkEdge
/// floats (532 MB at 2048^2 x 32). Boxes start on chunk boundaries, as the whole-volume CUDA
/// route's do, so the 4-voxel winding blocks fall where they fall in the whole grid and every
/// voxel gets the value of a whole-volume run.
void volumeRegion(DictionaryVolume& volume, const VoxelBox& region, std::uint64_t bandBytes, MeshToSdfStats& stats,
  Interrupter& intr, const std::function<void(const VoxelBox&, float*, double, double)>& compute)
{
  const std::int64_t edge = volume.chunkEdge();
  const Index3& cc = volume.chunkCounts();
  const Index3& dims = volume.dims();
  VoxelBox all;
  all.hi = { cc[0] - 1, cc[1] - 1, cc[2] - 1 };
  const VoxelBox rc = region.intersect(all);
  require(!rc.empty(), "mesh to SDF: the chunk region holds no chunk of the volume");
  const std::int64_t x0 = rc.lo[0] * edge, x1 = std::min(dims[0], (rc.hi[0] + 1) * edge) - 1;
  const std::uint64_t rowFloats = checkedMultiply(
    checkedMultiply(static_cast<std::uint64_t>(x1 - x0 + 1), static_cast<std::uint64_t>(edge), "band"),
    static_cast<std::uint64_t>(edge), "band");
  const std::int64_t rows = rc.hi[1] - rc.lo[1] + 1;
  const std::int64_t rowsPerBand = static_cast<std::int64_t>(std::max<std::uint64_t>(1,
    std::min<std::uint64_t>(static_cast<std::uint64_t>(rows), bandBytes / (rowFloats * sizeof(float)))));
  const std::uint64_t bufferFloats = checkedMultiply(rowFloats, static_cast<std::uint64_t>(rowsPerBand), "band");
  requireMemory(bufferFloats * sizeof(float), "mesh to SDF: region band buffer");
  std::vector<float> buffer(static_cast<std::size_t>(bufferFloats));
  const std::int64_t bandsPerLayer = (rows + rowsPerBand - 1) / rowsPerBand;
  const std::int64_t bands = bandsPerLayer * (rc.hi[2] - rc.lo[2] + 1);
  for (std::int64_t b = 0; b < bands; ++b)
  {
    const std::int64_t cz = rc.lo[2] + b / bandsPerLayer, cy0 = rc.lo[1] + (b % bandsPerLayer) * rowsPerBand;
    const std::int64_t cy1 = std::min(rc.hi[1] + 1, cy0 + rowsPerBand); // exclusive
    VoxelBox box;
    box.lo = { x0, cy0 * edge, cz * edge };
    box.hi = { x1, std::min(dims[1], cy1 * edge) - 1, std::min(dims[2], (cz + 1) * edge) - 1 };
    compute(box, buffer.data(), static_cast<double>(b) / static_cast<double>(bands), 1.0 / static_cast<double>(bands));
    const double t0 = now();
    const std::int64_t nx = box.hi[0] - box.lo[0] + 1, ny = box.hi[1] - box.lo[1] + 1;
    const std::int64_t ncx = rc.hi[0] - rc.lo[0] + 1, chunksInBand = ncx * (cy1 - cy0);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < chunksInBand; ++c)
    {
      const std::int64_t id = volume.chunkId(rc.lo[0] + c % ncx, cy0 + c / ncx, cz);
      const VoxelBox cb = volume.chunkBox(id);
      auto valueAt = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
        return buffer[static_cast<std::size_t>((x - box.lo[0]) + nx * ((y - box.lo[1]) + ny * (z - box.lo[2])))];
      };
      // equal floats encode to equal keys (encode reads the value only by
      // comparisons and |value|, so +0 and -0 alike; NaN never compares equal
      // and is encoded): the saturated +-band voxels, most of a banded
      // volume, reuse the previous voxel's key instead of encoding again
      float lastValue = valueAt(cb.lo[0], cb.lo[1], cb.lo[2]);
      SdfKey lastKey = volume.encode(lastValue);
      auto keyAt = [&](std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t) {
        const float v = valueAt(x, y, z);
        if (v == lastValue) return lastKey;
        lastValue = v;
        lastKey = volume.encode(v);
        return lastKey;
      };
      const SdfKey first = lastKey;
      const float firstValue = lastValue;
      // a chunk of one float is uniform; otherwise its keys may still be
      bool sameFloat = true;
      for (std::int64_t z = cb.lo[2]; z <= cb.hi[2] && sameFloat; ++z)
        for (std::int64_t y = cb.lo[1]; y <= cb.hi[1] && sameFloat; ++y)
        {
          const float* row = buffer.data() + ((cb.lo[0] - box.lo[0]) + nx * ((y - box.lo[1]) + ny * (z - box.lo[2])));
          const std::int64_t n = cb.hi[0] - cb.lo[0] + 1;
          bool same = true;
          for (std::int64_t i = 0; i < n; ++i) same &= row[i] == firstValue;
          sameFloat = same;
        }
      bool uniform = true;
      for (std::int64_t z = cb.lo[2]; z <= cb.hi[2] && !sameFloat && uniform; ++z)
        for (std::int64_t y = cb.lo[1]; y <= cb.hi[1] && uniform; ++y)
          for (std::int64_t x = cb.lo[0]; x <= cb.hi[0] && uniform; ++x) uniform = keyAt(x, y, z, 0) == first;
      storeChunk(volume, id, uniform, first, keyAt);
    }
    stats.writeSeconds += now() - t0;
    intr.checkInterrupt();
  }
}

/// CUDA: groups of chunk layers as large as cudaSlabBytes allows (at least
/// one), encoded on the GPU (SdfDictionary::encodeWith, the host's own
/// rounding); only the keys of non-uniform chunks come back. For group g the
/// host lists its chunks, queues its keys and group g + 1's kernels, stores the
/// uniform chunks, then the keys piece by piece as they arrive in pinned
/// memory (piece k stored while k + 1 is copied), all while the GPU computes
/// group g + 1.
void volumeOnCuda(detail::meshtosdf_cuda::Session& session, DictionaryVolume& volume, const MeshToSdfOptions& opts,
  MeshToSdfStats& stats, Interrupter& intr)
{
  const Index3 dims = volume.options().dims;
  const std::int64_t edge = volume.chunkEdge();
  const Index3& cc = volume.chunkCounts();
  const std::uint64_t layerBytes = static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(dims[1]) *
    static_cast<std::uint64_t>(edge) * sizeof(float);
  const std::int64_t group = std::max<std::int64_t>(1,
    std::min<std::int64_t>(cc[2], static_cast<std::int64_t>(opts.cudaSlabBytes / layerBytes)));
  const SdfDictionary::EncodeConstants& enc = volume.sdfDictionary().encodeConstants();
  const float band = volume.bandWidth();
  auto boxOf = [&](std::int64_t g0) {
    VoxelBox b;
    b.lo = { 0, 0, g0 * edge };
    b.hi = { dims[0] - 1, dims[1] - 1, std::min(dims[2], (g0 + group) * edge) - 1 };
    return b;
  };
  detail::meshtosdf_cuda::ChunkKeys keys;
  session.launchKeys(boxOf(0), static_cast<int>(edge), enc, band, stats);
  const std::int64_t e3 = edge * edge * edge;
  double listSeconds = 0, waitSeconds = 0, storeSeconds = 0; // the parts of writeSeconds (tracePhases)
  for (std::int64_t g0 = 0; g0 < cc[2]; g0 += group)
  {
    intr.checkInterrupt();
    const double fetch0 = stats.writeSeconds;
    session.fetchKeys(keys, stats); // its time after the kernels' wait counts as write
    listSeconds += stats.writeSeconds - fetch0;
    if (g0 + group < cc[2]) session.launchKeys(boxOf(g0 + group), static_cast<int>(edge), enc, band, stats);
    const double t0 = now();
    const VoxelBox box = boxOf(g0);
    const std::int64_t perLayer = cc[0] * cc[1];
    auto idOf = [&](std::int64_t c) { return volume.chunkId(c % cc[0], (c / cc[0]) % cc[1], g0 + c / perLayer); };
    std::atomic<std::int64_t> mismatches{ 0 }, verified{ 0 };
    // tests: every GPU key against the host's encode of the same float
    auto verify = [&](std::int64_t id, auto&& keyAt) {
      if (keys.floats.empty()) return;
      const VoxelBox cb = volume.chunkBox(id);
      std::int64_t bad = 0, n = 0;
      for (std::int64_t z = cb.lo[2]; z <= cb.hi[2]; ++z)
        for (std::int64_t y = cb.lo[1]; y <= cb.hi[1]; ++y)
          for (std::int64_t x = cb.lo[0]; x <= cb.hi[0]; ++x)
          {
            const SdfKey want =
              volume.encode(keys.floats[static_cast<std::size_t>(x + dims[0] * (y + dims[1] * (z - box.lo[2])))]);
            bad += want != keyAt(volume.localIndex(x, y, z));
            ++n;
          }
      mismatches += bad;
      verified += n;
    };
    // the uniform chunks, while the first pieces of keys are copied
    const std::int64_t chunks = static_cast<std::int64_t>(keys.uniform.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t c = 0; c < chunks; ++c)
    {
      const std::uint32_t u = keys.uniform[static_cast<std::size_t>(c)];
      if (u == detail::meshtosdf_cuda::ChunkKeys::NotUniform) continue;
      const std::int64_t id = idOf(c);
      verify(id, [&](std::int64_t) { return static_cast<SdfKey>(u); });
      storeChunk(volume, id, true, static_cast<SdfKey>(u), [](std::int64_t, std::int64_t, std::int64_t, std::int64_t) {
        return SdfKey(0);
      });
    }
    const double store0 = now() - t0;
    // then the others, one piece of keys at a time
    double storePieces = 0;
    const double waited = session.takeKeys([&](std::size_t first, std::size_t last, const std::uint16_t* pieceKeys) {
      const double s0 = now();
      const std::int64_t n = static_cast<std::int64_t>(last - first);
#pragma omp parallel for schedule(dynamic, 1)
      for (std::int64_t i = 0; i < n; ++i)
      {
        const std::uint16_t* k = pieceKeys + i * e3;
        const std::int64_t id = idOf(keys.listed[first + static_cast<std::size_t>(i)]);
        verify(id, [&](std::int64_t l) { return static_cast<SdfKey>(k[l]); });
        storeChunk(volume, id, false, SdfKey(0),
          [&](std::int64_t, std::int64_t, std::int64_t, std::int64_t l) { return static_cast<SdfKey>(k[l]); });
      }
      storePieces += now() - s0;
    });
    stats.keyMismatches += mismatches.load();
    stats.keysVerified += verified.load();
    stats.writeSeconds += now() - t0;
    waitSeconds += waited;
    storeSeconds += store0 + storePieces;
    intr.progress(static_cast<double>(std::min(cc[2], g0 + group)) / static_cast<double>(cc[2]));
  }
  // the GPU waits only for the listing (the keys kernel runs before the next
  // group's); copies and stores overlap the next group's kernels
  trace("write: list the chunks and queue their keys (GPU idle meanwhile)", listSeconds);
  trace("write: wait for the keys' pieces (copies overlap the next group)", waitSeconds);
  trace("write: store into the volume (overlaps the next group and the copies)", storeSeconds);
}

/// stats.warnings when a signed field over the whole grid has no voxel
/// inside (`inside`: voxels deeper than 1 voxel inside the surface).
void warnIfNothingInside(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const MeshToSdfOptions& options,
  std::int64_t inside, MeshToSdfStats& stats)
{
  if (options.sign == SignMode::Unsigned || inside > 0) return;
  const double h = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
  std::ostringstream w;
  if (mesh.boundaryEdges() > 0)
  {
    w << "mesh to SDF: no voxel is inside the mesh (deeper than 1 voxel): it is open (" << mesh.boundaryEdges()
      << " boundary edges) and encloses no volume at any voxel centre"
      << (options.sign == SignMode::WindingNumber ? " (|winding number| < 1/2 everywhere, as for a single open sheet)"
                                                  : "")
      << ", so the field has no zero crossing and meshing it gives no surface; close the mesh, or use the "
         "pseudo-normal sign (each side of a sheet gets its own sign) or the unsigned distance meshed at a "
         "positive iso-value (a shell around the sheet)";
  }
  else
  {
    w << "mesh to SDF: no voxel centre lies inside the mesh (deeper than 1 voxel): the voxels (spacing " << h
      << ") are larger than the mesh's parts, so the field has no zero crossing and meshing it gives no surface; "
         "use more voxels (a higher resolution / --dims) or less padding";
  }
  stats.warnings.push_back(w.str());
}

bool wholeGrid(const GridGeometry& grid, const VoxelBox& extent)
{
  for (int a = 0; a < 3; ++a)
    if (extent.lo[a] != 0 || extent.hi[a] != grid.dims[a] - 1) return false;
  return true;
}

} // namespace

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent,
  float* out, const MeshToSdfOptions& options, Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  validateGrid(grid);
  require(out != nullptr, "mesh to SDF: output pointer is null");
  require(!extent.empty(), "mesh to SDF: the requested extent is empty");
  for (int a = 0; a < 3; ++a)
  {
    require(extent.lo[a] >= 0 && extent.hi[a] < grid.dims[a], "mesh to SDF: the extent lies outside the grid");
  }
  MeshToSdfStats stats;
  interrupter.start("mesh to SDF");
  stats.device = chooseDevice(options);
  auto engine = makeEngine(mesh, grid, options, options.bandWidth, stats.device, stats);
  if (stats.device == Device::Cuda)
  {
    openCuda(mesh, *engine, options, stats)->compute(extent, out, stats, interrupter);
  }
  else
  {
    computeBox(*engine, extent, out, stats, interrupter, 0.0, 1.0);
  }
  if (options.svfFilters != 0)
  {
    const double t0 = now();
    FloatGridView view;
    view.data = out;
    view.geometry.dims = { extent.hi[0] - extent.lo[0] + 1, extent.hi[1] - extent.lo[1] + 1,
      extent.hi[2] - extent.lo[2] + 1 };
    SignVoxelFilterParams p = options.svf;
    p.filters = options.svfFilters;
    if (p.device == Device::Auto) p.device = options.device; // "--device cpu" holds for the filters too
    stats.svfFlips = signVoxelFilter(view, p, interrupter).totalFlips();
    stats.svfSeconds = now() - t0;
  }
  if (wholeGrid(grid, extent) && options.sign != SignMode::Unsigned)
  {
    // a piece of a larger grid may rightly have nothing inside: whole grids
    // only. Inside voxels within 1 voxel of the surface do not count: a
    // curved open sheet has a film of them (|w| just above 1/2), and
    // meshing them gives slivers at best
    const double h = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
    const float deep = options.unit == DistanceUnit::World ? static_cast<float>(-h) : -1.0f;
    std::int64_t inside = 0;
    const std::int64_t n = extent.voxelCount();
#pragma omp parallel for reduction(+ : inside)
    for (std::int64_t i = 0; i < n; ++i) inside += out[i] < deep;
    warnIfNothingInside(mesh, grid, options, inside, stats);
  }
  interrupter.end();
  return stats;
}

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  VoxelBox all;
  all.hi = { out.geometry.dims[0] - 1, out.geometry.dims[1] - 1, out.geometry.dims[2] - 1 };
  return meshToSdf(mesh, out.geometry, all, out.data, options, interrupter);
}

MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, DictionaryVolume& volume, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  const GridGeometry grid = gridOf(volume.options());
  MeshToSdfOptions opts = options;
  opts.unit = DistanceUnit::Voxel;
  MeshToSdfStats stats;
  interrupter.start("mesh to SDF");
  stats.device = chooseDevice(options);
  auto engine = makeEngine(mesh, grid, opts, volume.bandWidth(), stats.device, stats);
  const bool region = !options.chunkRegion.empty();
  require(!region || options.svfFilters == 0,
    "mesh to SDF: a chunk region cannot be combined with the sign voxel filters (they need the whole volume)");
  if (region)
  {
    std::unique_ptr<detail::meshtosdf_cuda::Session> cuda;
    if (stats.device == Device::Cuda) cuda = openCuda(mesh, *engine, opts, stats);
    volumeRegion(volume, options.chunkRegion, opts.cpuBandBytes, stats, interrupter,
      [&](const VoxelBox& box, float* out, double p0, double dp) {
        if (cuda)
          cuda->compute(box, out, stats, interrupter);
        else
          computeBox(*engine, box, out, stats, interrupter, p0, dp);
      });
  }
  else if (stats.device == Device::Cuda)
  {
    volumeOnCuda(*openCuda(mesh, *engine, opts, stats), volume, opts, stats, interrupter);
  }
  else
  {
    VoxelBox everyChunk;
    everyChunk.hi = { volume.chunkCounts()[0] - 1, volume.chunkCounts()[1] - 1, volume.chunkCounts()[2] - 1 };
    volumeRegion(volume, everyChunk, opts.cpuBandBytes, stats, interrupter,
      [&](const VoxelBox& box, float* out, double p0, double dp) {
        computeBox(*engine, box, out, stats, interrupter, p0, dp);
      });
  }
  if (options.svfFilters != 0)
  {
    const double t0 = now();
    SignVoxelFilterParams p = options.svf;
    p.filters = options.svfFilters;
    if (p.device == Device::Auto) p.device = options.device; // "--device cpu" holds for the filters too
    stats.svfFlips = signVoxelFilter(volume, p, interrupter).totalFlips();
    stats.svfSeconds = now() - t0;
  }
  if (options.sign != SignMode::Unsigned && !region) // a region may rightly have nothing inside
  {
    // voxels deeper than 1 voxel inside (as for float grids): uniform chunks
    // by their value, the others voxel by voxel until the first one
    const SdfKey zero = volume.sdfDictionary().encode(-1.0f);
    std::int64_t inside = 0;
    for (std::int64_t c = 0; c < volume.chunkCount() && inside == 0; ++c)
    {
      if (volume.isUniform(c))
      {
        inside += volume.uniformValue(c).sdf < zero;
        continue;
      }
      const VoxelBox b = volume.chunkBox(c);
      for (std::int64_t z = b.lo[2]; z <= b.hi[2] && inside == 0; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1] && inside == 0; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0] && inside == 0; ++x) inside += volume.get(x, y, z).sdf < zero;
    }
    warnIfNothingInside(mesh, grid, options, inside, stats);
  }
  interrupter.end();
  return stats;
}

/// prepareMeshToSdf; the winding structures only when sign is WindingNumber
/// (otherwise built on first use: on CUDA while the GPU computes distances).
/// The pseudo-normals only when `sign` reads them (Normal, PseudoNormal): the
/// others (e.g. the GPU's winding-number path) skip that work; a later call
/// with such a sign builds them then (Impl::pseudoNormals).
/// meshTreeNow (a call that will run on CUDA, whose distance kernel needs
/// the mesh BVH): for a large mesh the tree is built on its own thread as
/// soon as the triangle records are, beside the edge pass (boundary,
/// pseudo-normals) that only the signs need; the same tree as built
/// afterwards. Below TreeBesideEdgePassTriangles the new thread's OpenMP
/// team costs more than the overlap saves (H200 host: the 30k bunny's build
/// 18 -> 27 ms with it; the 832k armadillo's 190 -> 110 ms).
constexpr std::size_t TreeBesideEdgePassTriangles = std::size_t(1) << 18;
static MeshToSdfPrepared prepareInternal(const TriangleMesh& mesh, SignMode sign, bool meshTreeNow = false)
{
  meshTreeNow = meshTreeNow && mesh.triangles.size() >= TreeBesideEdgePassTriangles;
  const bool winding = sign == SignMode::WindingNumber;
  const double t0 = now();
  auto impl = std::make_shared<MeshToSdfPrepared::Impl>();
  // declared after impl: destroyed (joined) first, also when the edge pass throws
  std::future<std::shared_ptr<const Bvh>> tree;
  const bool tracing = tracePhasesActive();
  std::function<void()> startTree;
  if (meshTreeNow)
  {
    startTree = [&tree, &impl, tracing]() {
      const PreparedMesh* m = &impl->mesh;
      // a new thread starts from the default thread count: pass the caller's on
      const int threads = omp_get_max_threads();
      tree = std::async(std::launch::async, [m, tracing, threads]() {
        omp_set_num_threads(threads);
        const PhaseTraceScope scope(tracing);
        const double tb = now();
        auto bvh = std::make_shared<const Bvh>(m->tris);
        trace("mesh BVH (beside the edge pass)", now() - tb);
        return bvh;
      });
    };
  }
  prepareMesh(mesh, impl->mesh, sign == SignMode::Normal || sign == SignMode::PseudoNormal, startTree);
  if (tree.valid()) impl->bvh = tree.get();
  const double t2 = now();
  // the search structures are built on first use: the CPU's NearestIndex by
  // makeEngine, the GPU's Bvh by deviceMesh (each path needs only its own)
  double unused = 0;
  if (winding) impl->windingSigner(unused);
  impl->prepareSeconds = now() - t0;
  trace("prepareMesh", t2 - t0);
  if (winding) trace("winding structures", now() - t2);
  return MeshToSdfPrepared(std::move(impl));
}

/// The one-call API: prepare, then the prepared call (preparation counts as build time).
template <typename Out>
MeshToSdfStats prepareAndRun(const TriangleMesh& mesh, Out&& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  const MeshToSdfPrepared prepared = prepareInternal(mesh, options.sign, chooseDevice(options) == Device::Cuda);
  MeshToSdfStats stats = meshToSdf(prepared, std::forward<Out>(out), options, interrupter);
  stats.buildSeconds += prepared.prepareSeconds();
  return stats;
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& options, Interrupter& interrupter)
{
  const PhaseTraceScope tracing(options.tracePhases);
  const MeshToSdfPrepared prepared = prepareInternal(mesh, options.sign, chooseDevice(options) == Device::Cuda);
  MeshToSdfStats stats = meshToSdf(prepared, grid, extent, out, options, interrupter);
  stats.buildSeconds += prepared.prepareSeconds();
  return stats;
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  return prepareAndRun(mesh, out, options, interrupter);
}

MeshToSdfStats meshToSdf(const TriangleMesh& mesh, DictionaryVolume& volume, const MeshToSdfOptions& options,
  Interrupter& interrupter)
{
  return prepareAndRun(mesh, volume, options, interrupter);
}

MeshToSdfPrepared prepareMeshToSdf(const TriangleMesh& mesh, SignMode sign)
{
  return prepareInternal(mesh, sign);
}


} // namespace lvdif
