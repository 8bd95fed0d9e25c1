// Storing a mesh-to-SDF pass into a dictionary volume (MeshToSdfVolumeStore.h).
#include "MeshToSdfVolumeStore.h"

#include "MeshToSdfInternal.h"
#include "lvdif/Memory.h"
#include "lvdif/ParallelFailure.h"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
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

} // namespace

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
    ParallelFailure failure;
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
          std::int64_t i = 0;
#if defined(__SSE2__) || defined(_M_X64)
          // four at a time: this scan reads every voxel of the grid, and the
          // scalar loop (not vectorized by the compiler) was 2-3 % of the
          // banded call's CPU time. cmpeq_ps is the ordered == of the loop
          // below (+0 == -0, NaN never equal): the same answer
          const __m128 f4 = _mm_set1_ps(firstValue);
          __m128 eq = _mm_cmpeq_ps(f4, f4);
          for (; i + 4 <= n; i += 4) eq = _mm_and_ps(eq, _mm_cmpeq_ps(_mm_loadu_ps(row + i), f4));
          same = _mm_movemask_ps(eq) == 0xf; // a NaN first value: never equal, as below
#endif
          for (; i < n; ++i) same &= row[i] == firstValue;
          sameFloat = same;
        }
      bool uniform = true;
      for (std::int64_t z = cb.lo[2]; z <= cb.hi[2] && !sameFloat && uniform; ++z)
        for (std::int64_t y = cb.lo[1]; y <= cb.hi[1] && uniform; ++y)
          for (std::int64_t x = cb.lo[0]; x <= cb.hi[0] && uniform; ++x) uniform = keyAt(x, y, z, 0) == first;
      failure.run([&] { storeChunk(volume, id, uniform, first, keyAt); });
    }
    failure.rethrow();
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
void volumeOnCuda(meshtosdf_cuda::Session& session, DictionaryVolume& volume, const MeshToSdfOptions& opts,
  MeshToSdfStats& stats, Interrupter& intr, const std::function<void()>& beforeEachGroup)
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
  meshtosdf_cuda::ChunkKeys keys;
  session.launchKeys(boxOf(0), static_cast<int>(edge), enc, band, stats);
  const std::int64_t e3 = edge * edge * edge;
  double listSeconds = 0, waitSeconds = 0, storeSeconds = 0; // the parts of writeSeconds (tracePhases)
  for (std::int64_t g0 = 0; g0 < cc[2]; g0 += group)
  {
    intr.checkInterrupt();
    beforeEachGroup();
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
    ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t c = 0; c < chunks; ++c)
    {
      const std::uint32_t u = keys.uniform[static_cast<std::size_t>(c)];
      if (u == meshtosdf_cuda::ChunkKeys::NotUniform) continue;
      const std::int64_t id = idOf(c);
      verify(id, [&](std::int64_t) { return static_cast<SdfKey>(u); });
      failure.run([&] {
        storeChunk(volume, id, true, static_cast<SdfKey>(u),
          [](std::int64_t, std::int64_t, std::int64_t, std::int64_t) { return SdfKey(0); });
      });
    }
    failure.rethrow();
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
        failure.run([&] {
          storeChunk(volume, id, false, SdfKey(0),
            [&](std::int64_t, std::int64_t, std::int64_t, std::int64_t l) { return static_cast<SdfKey>(k[l]); });
        });
      }
      storePieces += now() - s0;
    });
    failure.rethrow();
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

} // namespace detail::meshtosdf
} // namespace lvdif
