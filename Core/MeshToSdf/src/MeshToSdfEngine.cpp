// The CPU engine of mesh to SDF (MeshToSdfEngine.h): nearest queries by the
// chosen accelerator, the per-row distance pass, the band bricks, and the
// sign pass, on OpenMP threads with progress and cancellation.
#include "MeshToSdfEngine.h"

#include "MeshToSdfDipoleLocal.h"
#include "MeshToSdfNearest.h"
#include "lvdif/Memory.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <utility>

namespace lvdif
{
namespace detail::meshtosdf
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

double outputScale(const GridGeometry& grid, const MeshToSdfOptions& options)
{
  const double unit = std::min(grid.spacing[0], std::min(grid.spacing[1], grid.spacing[2]));
  return options.unit == DistanceUnit::Voxel ? 1.0 / unit : 1.0;
}

NearestResult Engine::nearest(V3 p, std::int32_t hint) const
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

float Engine::localSign(V3 p, const NearestResult& r) const
{
  const Tri& t = this->mesh->tris[r.tri];
  const V3 n = this->opts.sign == SignMode::PseudoNormal
    ? featureNormal(t, this->mesh->normals[r.tri], r.closest.feature)
    : interpolatedNormal(t, this->opts.useVertexNormals ? this->mesh->cornersOf(r.tri) : nullptr, r.closest.b1,
        r.closest.b2);
  return normalSign(p, r.closest.point, n);
}

void Engine::distanceRow(std::int64_t j, std::int64_t k, std::int64_t i0, std::int64_t i1, float* out,
  std::int32_t* rowTris, bool belowValid, const std::int8_t* far, const std::uint8_t* farMask,
  int farBit) const
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
      lower = r.tri < 0 ? reach : std::sqrt(r.dist2);
      float s = 1.0f;
      if (r.tri >= 0)
      {
        hint = r.tri;
        if (this->opts.sign == SignMode::Normal || this->opts.sign == SignMode::PseudoNormal)
        {
          s = this->localSign(ps[q], r);
        }
      }
      out[i - i0] = r.tri < 0 ? static_cast<float>(this->band) : storedValue(s, r.dist2, this->toOut, this->band);
    }
    withinBand = lower < bandWorld;
  }
}

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
  e->toOut = outputScale(geom, opts);
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

namespace
{
/// Runs fn(state, i) for every i in [0, count) on the OpenMP threads
/// (`chunk` items at a time), state = makeState() once per thread; progress
/// and the cancellation check from thread 0 every `progressEvery` items (a
/// power of two); rethrows the first exception. Thread 0 need not run the
/// last item: the span's end is reported here.
template <typename MakeState, typename F>
void forEachOnThreads(std::int64_t count, [[maybe_unused]] int chunk, std::int64_t progressEvery, Interrupter& intr,
  double progressBase, double progressSpan, MakeState&& makeState, F&& fn)
{
  std::atomic<std::int64_t> done{ 0 };
  std::atomic<bool> stop{ false };
  std::exception_ptr failure;
#pragma omp parallel
  {
    auto state = makeState();
#pragma omp for schedule(dynamic, chunk)
    for (std::int64_t i = 0; i < count; ++i)
    {
      if (stop.load(std::memory_order_relaxed)) continue;
      try
      {
        fn(state, i);
        const std::int64_t n = done.fetch_add(1) + 1;
        if (omp_get_thread_num() == 0 && (n & (progressEvery - 1)) == 0)
        {
          if (intr.wasInterrupted()) stop = true;
          intr.progress(progressBase + progressSpan * static_cast<double>(n) / static_cast<double>(count));
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

/// fn(j, k, r) for every (j, k) row r of the box on the OpenMP threads
/// (forEachOnThreads: progress and cancellation per row).
template <typename F>
void forRows(const VoxelBox& box, Interrupter& intr, double progressBase, double progressSpan, F&& fn, int chunk = 2)
{
  const std::int64_t ny = box.hi[1] - box.lo[1] + 1, nz = box.hi[2] - box.lo[2] + 1;
  forEachOnThreads(ny * nz, chunk, 1, intr, progressBase, progressSpan, [] { return 0; },
    [&](int&, std::int64_t r) { fn(box.lo[1] + r % ny, box.lo[2] + r / ny, r); });
}

/// Bricks of BrickX x Brick x Brick voxels within the band. 8 x 4 x 4
/// measured fastest on the bunny and the armadillo at 512 (4^3: more bricks,
/// each with a query and a list; 8^3: lists too long for each voxel; 2 or 16
/// along x: slower or no better).
constexpr std::int64_t BrickX = 8, Brick = 4;
} // namespace

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
  // the far voxels first, row by row (in brick order their stores would stride across the buffer)
  bool wholeCells = anyFar;
  if (anyFar)
  {
    // classifyBandCells marks whole cells (mask 0xff) with sign +1, so every
    // far voxel is +band: then every row is filled with +band at once (a
    // plain fill, no per-cell mask test: the mask walk below was ~6 % of the
    // call's instructions on the armadillo at 512) and the bricks overwrite
    // the voxels that are not far (each one is written, see below). Checked
    // here, cheaply (one byte per 8 voxels), so any other cells keep the walk.
    unsigned char odd = 0;
    const std::size_t cells = far.mask.size();
    for (std::size_t c = 0; c < cells; ++c)
    {
      const unsigned char m = far.mask[c];
      odd |= static_cast<unsigned char>((m != 0 && m != 0xff) | (far.sign[c] != (m != 0 ? 1 : 0)));
    }
    wholeCells = odd == 0;
  }
  if (wholeCells)
  {
    const float v = static_cast<float>(this->band); // static_cast<float>(+1) * band, as below
#pragma omp parallel for schedule(static)
    for (std::int64_t r = 0; r < n[1] * n[2]; ++r) std::fill(out + n[0] * r, out + n[0] * (r + 1), v);
  }
  else if (anyFar)
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
  struct PerThread
  {
    NearestIndex::BrickScratch scratch;
    // one brick's voxels that are not far (fixed arrays: a brick holds BX * B * B)
    V3 ps[BX * B * B];
    std::int64_t at[BX * B * B];
    NearestResult res[BX * B * B];
    std::int32_t hint = -1; // the last nearest triangle: the next brick's seed
  };
  forEachOnThreads(bricks, 16, 256, intr, progressBase, progressSpan, [] { return std::make_unique<PerThread>(); },
    [&](std::unique_ptr<PerThread>& stp, std::int64_t b) {
      PerThread& st = *stp;
      const std::int64_t o[3] = { BX * (b % nb[0]), B * ((b / nb[0]) % nb[1]), B * (b / (nb[0] * nb[1])) };
      const std::int64_t x1 = std::min(n[0], o[0] + BX), y1 = std::min(n[1], o[1] + B), z1 = std::min(n[2], o[2] + B);
      // the far voxels are written (above); a brick of whole far cells has nothing else
      bool allFar = anyFar;
      for (std::int64_t z = o[2]; z < z1 && allFar; z += FarCell)
        for (std::int64_t y = o[1]; y < y1 && allFar; y += FarCell)
          for (std::int64_t x = o[0]; x < x1 && allFar; x += FarCell)
            allFar = far.mask[cellOf(x, y, z)] == 0xff;
      if (allFar) return;
      // the brick's voxel coordinates, each as position() computes it, and per
      // row (y, z) its far voxels as bits (x - o[0]; o[0] is even, so a
      // cell's two bits of the row land on bits 2 cx, 2 cx + 1): the loops
      // below then look neither at the cells nor at the grid per voxel
      double xs[BX], ys[B], zs[B];
      for (std::int64_t x = o[0]; x < x1; ++x) xs[x - o[0]] = this->position(box.lo[0] + x, 0, 0).x;
      for (std::int64_t y = o[1]; y < y1; ++y) ys[y - o[1]] = this->position(0, box.lo[1] + y, 0).y;
      for (std::int64_t z = o[2]; z < z1; ++z) zs[z - o[2]] = this->position(0, 0, box.lo[2] + z).z;
      auto farBits = [&](std::int64_t y, std::int64_t z) {
        unsigned bits = 0;
        if (!anyFar) return bits;
        const int rowBit = static_cast<int>(2 * (y & 1) + 4 * (z & 1));
        for (std::int64_t x = o[0]; x < x1; x += FarCell)
          bits |= ((static_cast<unsigned>(far.mask[cellOf(x, y, z)]) >> rowBit) & 3u) << (x - o[0]);
        return bits;
      };
      // serpentine order (x back and forth, y back and forth per layer):
      // nearestBrick seeds each voxel with its predecessor's triangle, and
      // here the predecessor is always a neighbour (in x, y, z order a row's
      // first voxel was seeded from 7 voxels away), so fewer candidates pass
      // the first bounds. Only the order of the queries changes: each voxel's
      // answer is its own bounded nearest (ties to the lowest index), the
      // same float whatever the seed.
      int m = 0;
      bool yUp = true, xUp = true;
      for (std::int64_t z = o[2]; z < z1; ++z, yUp = !yUp)
        for (std::int64_t yi = o[1]; yi < y1; ++yi, xUp = !xUp)
        {
          const std::int64_t y = yUp ? yi : o[1] + y1 - 1 - yi;
          const unsigned fb = farBits(y, z);
          const double py = ys[y - o[1]], pz = zs[z - o[2]];
          const std::int64_t row = n[0] * (y + n[1] * z);
          for (std::int64_t xi = o[0]; xi < x1; ++xi)
          {
            const std::int64_t x = xUp ? xi : o[0] + x1 - 1 - xi;
            if ((fb >> (x - o[0])) & 1u) continue;
            st.ps[m] = V3{ xs[x - o[0]], py, pz };
            st.at[m] = x + row;
            ++m;
          }
        }
      if (m > 0)
      {
        this->index->nearestBrick(st.ps, m, this->bandWorld2, st.hint, st.res, st.scratch);
        for (int q = 0; q < m; ++q)
        {
          const NearestResult& r = st.res[q];
          double d = r.tri < 0 ? this->band : std::sqrt(r.dist2) * this->toOut;
          d = std::min(d, this->band);
          if (r.tri >= 0) st.hint = r.tri;
          out[st.at[q]] = static_cast<float>(d);
        }
      }
    });
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
  // group of 16^3 voxels, where that fails per block of 4^3 (from the
  // group's cut): away from those faces a block's bound decides all its
  // voxels, where row segments of 16 (a ball of radius 7.5 voxels) would
  // reach a face. Where the 4^3 ball fails, its voxels get intervals one by
  // one from a local expansion about the block (boundCorrectionAt); the rows
  // then refine only what is left.
  constexpr std::int64_t Block = 2; // the bounds' unit; the coarse blocks are 2 x 2 x 2 of them
  const bool reorient = e.opts.reorientFaces;
  const std::int64_t bx = (nx + Block - 1) / Block, by = (ny + Block - 1) / Block,
                     bz = (box.hi[2] - box.lo[2] + Block) / Block;
  std::vector<double> blockLo, blockHi;
  // voxels bounded one by one by a block's local expansion: per fine block
  // an entry of the pool of 2^3 voxel intervals (lo[8], hi[8]; lo > hi:
  // none), -1 where the block has none (4 bytes per 2^3 block; the pool
  // grows with the blocks near the corrected faces only)
  std::vector<std::int32_t> voxelSlot;
  std::vector<double> voxelPool;
  std::mutex voxelPoolLock;
  LocalBoundsCounts localCounts; // summed under voxelPoolLock, traced
  if (e.winding->hasCorrection(reorient))
  {
    blockLo.assign(static_cast<std::size_t>(bx * by * bz), 1.0);
    blockHi.assign(blockLo.size(), 0.0);
    voxelSlot.assign(blockLo.size(), -1);
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
    // the voxels [v0, v0 + edge)^3 of the box (clipped) bounded one by one by
    // a local expansion about their ball (WindingSigner::boundCorrectionAt),
    // at the positions signRow gives them; their intervals go to the pools
    auto boundVoxels = [&](std::int64_t x0, std::int64_t y0, std::int64_t z0, std::int64_t edge,
                         const std::vector<std::int32_t>* start) {
      V3 centre;
      const double rho = ball(x0, y0, z0, edge, centre);
      thread_local std::vector<V3> pts;
      thread_local std::vector<std::int64_t> at; // fine block * 8 + voxel within it
      thread_local std::vector<double> lo, hi;
      pts.clear();
      at.clear();
      const double h = e.geom.spacing[0];
      for (std::int64_t z = z0; z < std::min(z0 + edge, box.hi[2] + 1); ++z)
        for (std::int64_t y = y0; y < std::min(y0 + edge, box.hi[1] + 1); ++y)
        {
          const V3 rowStart = e.position(box.lo[0], y, z);
          for (std::int64_t x = x0; x < std::min(x0 + edge, box.hi[0] + 1); ++x)
          {
            const std::int64_t i = x - box.lo[0], jy = y - box.lo[1], kz = z - box.lo[2];
            pts.push_back(rowStart + V3{ static_cast<double>(i) * h, 0, 0 });
            const std::int64_t f = i / Block + bx * (jy / Block + by * (kz / Block));
            at.push_back(8 * f + (i % Block) + 2 * (jy % Block) + 4 * (kz % Block));
          }
        }
      const int n = static_cast<int>(pts.size());
      lo.resize(pts.size());
      hi.resize(pts.size());
      LocalBoundsCounts counts;
      e.winding->boundCorrectionAt(centre, rho, pts.data(), n, lo.data(), hi.data(), reorient, start, &counts);
      const std::lock_guard<std::mutex> lock(voxelPoolLock); // one append per 4^3 block
      localCounts.add(counts);
      for (int v = 0; v < n; ++v)
      {
        const std::size_t f = static_cast<std::size_t>(at[static_cast<std::size_t>(v)] / 8);
        const std::int64_t sub = at[static_cast<std::size_t>(v)] % 8;
        if (voxelSlot[f] < 0)
        {
          voxelSlot[f] = static_cast<std::int32_t>(voxelPool.size() / 16);
          voxelPool.resize(voxelPool.size() + 16);
          std::fill(voxelPool.end() - 16, voxelPool.end() - 8, 1.0); // lo > hi: none
          std::fill(voxelPool.end() - 8, voxelPool.end(), 0.0);
        }
        const std::size_t base = 16 * static_cast<std::size_t>(voxelSlot[f]);
        voxelPool[base + static_cast<std::size_t>(sub)] = lo[static_cast<std::size_t>(v)];
        voxelPool[base + 8 + static_cast<std::size_t>(sub)] = hi[static_cast<std::size_t>(v)];
      }
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
        double lo = glo, hi = ghi;
        if (!groupWhole)
        {
          std::vector<std::int32_t> cut = groupCut;
          rho = ball(box.lo[0] + Block * fx, box.lo[1] + Block * fy, box.lo[2] + Block * fz, 2 * Block, centre);
          if (!e.winding->boundCorrection(centre, rho, lo, hi, leafTris, reorient, &cut))
          {
            // no ball decides the coarse block: its voxels one by one from
            // one local expansion (measured on the damaged armadillos at
            // 128^3: cheaper than balls about its 2^3 blocks and the rows'
            // refinements they left; the 2^3 balls first, or a local
            // expansion per 2^3 block, were slower)
            boundVoxels(box.lo[0] + Block * fx, box.lo[1] + Block * fy, box.lo[2] + Block * fz, 2 * Block, &cut);
            continue;
          }
        }
        for (std::int64_t d = 0; d < 8; ++d)
        {
          const std::int64_t ix = fx + (d & 1), iy = fy + ((d >> 1) & 1), iz = fz + (d >> 2);
          if (ix >= bx || iy >= by || iz >= bz) continue;
          const std::size_t f = static_cast<std::size_t>(ix + bx * (iy + by * iz));
          blockLo[f] = lo;
          blockHi[f] = hi;
        }
      }
    }
  }
  trace("winding: block bounds of the correction s", now() - t0);
  if (tracePhasesActive() && !voxelSlot.empty())
    std::fprintf(stderr,
      "[mesh to SDF] winding: local bounds: %lld triangles expanded about a block's centre, %lld exact solid "
      "angles (triangle x voxel)\n",
      static_cast<long long>(localCounts.triangleTaylors), static_cast<long long>(localCounts.exactSolidAngles));
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
        const std::int64_t subRow = 2 * ((j - box.lo[1]) % Block) + 4 * ((k - box.lo[2]) % Block);
        for (std::int64_t i = 0; i < nx; ++i)
        {
          const std::size_t f = static_cast<std::size_t>(row + i / Block);
          if (voxelSlot[f] >= 0)
          {
            const std::size_t at = 16 * static_cast<std::size_t>(voxelSlot[f]) + static_cast<std::size_t>(i % Block + subRow);
            priorLo[static_cast<std::size_t>(i)] = voxelPool[at];
            priorHi[static_cast<std::size_t>(i)] = voxelPool[at + 8];
            continue;
          }
          priorLo[static_cast<std::size_t>(i)] = blockLo[f];
          priorHi[static_cast<std::size_t>(i)] = blockHi[f];
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

} // namespace detail::meshtosdf
} // namespace lvdif
