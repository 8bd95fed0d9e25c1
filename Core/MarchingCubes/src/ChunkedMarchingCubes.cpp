// Chunk layout, range skipping, input gathering and incremental bookkeeping of
// the chunked marching cubes; the per-chunk kernel is in MarchingCubesCpu.cpp.
#include "MarchingCubesImpl.h"

#include "lvdif/Error.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <string>

namespace lvdif
{

std::uint64_t ChunkMesh::memoryBytes() const
{
  return points.size() * sizeof(Vec3f) + edgeIds.size() * sizeof(std::uint64_t) + normals.size() * sizeof(Vec3f) + colors.size() * sizeof(Rgba) +
    triangles.size() * sizeof(triangles[0]) + cornerColors.size() * sizeof(cornerColors[0]) +
    triangleCells.size() * sizeof(std::int64_t);
}

void ChunkedMarchingCubes::Impl::init(const Index3& dims, const MarchingCubesOptions& options)
{
  require(options.chunkEdge >= 16 && options.chunkEdge <= 256,
    "marching cubes: chunk edge " + std::to_string(options.chunkEdge) + " outside 16..256");
  require(options.isoValue == options.isoValue, "marching cubes: iso value is NaN");
  for (int a = 0; a < 3; ++a)
  {
    require(dims[a] >= 2, "marching cubes: the volume needs at least 2 points per axis");
    require(Spacing[a] > 0, "marching cubes: spacing must be positive");
  }
  Options = options;
  Dims = dims;
  VoxelBox all;
  for (int a = 0; a < 3; ++a)
  {
    require(options.gridOffset[a] >= 0, "marching cubes: negative grid offset");
    Cells[a] = dims[a] - 1;
    all.hi[a] = Cells[a] - 1;
    InvSpacing[a] = static_cast<float>(1.0 / Spacing[a]);
  }
  Region = options.cellRegion.empty() ? all : options.cellRegion.intersect(all);
  require(!Region.empty(), "marching cubes: the cell region lies outside the grid");
  const std::int64_t E = options.chunkEdge;
  for (int a = 0; a < 3; ++a)
  {
    const Index3& off = options.gridOffset;
    First[a] = (Region.lo[a] + off[a]) / E;
    Counts[a] = (Region.hi[a] + off[a]) / E - First[a] + 1;
  }
  Total = Counts[0] * Counts[1] * Counts[2];
  if (options.triangleTable)
    Tables = std::make_shared<const MarchingCubesTables>(marchingCubesTablesWith(*options.triangleTable));
  else
    Tables = std::shared_ptr<const MarchingCubesTables>(&marchingCubesTables(), [](const MarchingCubesTables*) {});
  Options.device = resolveDevice(options.device);
  if (Options.device == Device::Cuda) Cuda = makeMarchingCubesCudaState(*Tables);
  // level 1: the grid subsampled by 2 (coarse point c = full point 2c)
  bool coarse = true;
  for (int a = 0; a < 3; ++a) coarse = coarse && dims[a] >= 3 && options.gridOffset[a] % 2 == 0;
  if (coarse)
  {
    auto c = std::make_shared<Impl>();
    c->Options = Options;
    c->Options.cornerColors = false;
    c->Options.device = Device::Cpu;
    c->Tables = Tables;
    c->Counts = Counts;
    c->First = First;
    c->Total = Total;
    c->Origin = Origin;
    for (int a = 0; a < 3; ++a)
    {
      c->Options.gridOffset[a] = options.gridOffset[a] / 2;
      c->Dims[a] = (dims[a] - 1) / 2 + 1;
      c->Cells[a] = c->Dims[a] - 1;
      c->Spacing[a] = 2.0 * Spacing[a];
      c->InvSpacing[a] = static_cast<float>(1.0 / c->Spacing[a]);
    }
    Coarse = c;
  }
}

VoxelBox ChunkedMarchingCubes::Impl::coarseCells(std::int64_t id) const
{
  const VoxelBox f = cells(id);
  VoxelBox b;
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = (f.lo[a] + 1) / 2; // the first even point in the chunk's cells
    b.hi[a] = std::min<std::int64_t>(f.hi[a] / 2, Coarse->Dims[a] - 2);
  }
  return b;
}

void ChunkedMarchingCubes::Impl::gatherCoarseInto(std::int64_t id, ChunkInput& in) const
{
  const Impl& C = *Coarse;
  in.view = nullptr;
  in.viewColors = nullptr;
  in.level = 1;
  in.chunkId = id;
  in.cells = coarseCells(id);
  Index3 hi;
  for (int a = 0; a < 3; ++a)
  {
    in.lo[a] = std::max<std::int64_t>(in.cells.lo[a] - 1, 0);
    hi[a] = std::min<std::int64_t>(in.cells.hi[a] + 2, C.Dims[a] - 1);
    in.size[a] = hi[a] - in.lo[a] + 1;
  }
  const std::size_t n = static_cast<std::size_t>(in.size[0] * in.size[1] * in.size[2]);
  const bool colors = wantsColors();
  in.voxels.clear();
  in.sdfTable = nullptr;
  in.isoKey = 0;
  in.colorKeys.clear();
  in.palette.clear();
  in.values.resize(n);
  in.colors.resize(colors ? n : 0);
  std::size_t o = 0;
  if (Volume)
  {
    const DictionaryVolume& v = *Volume;
    const float* table = v.sdfDictionary().table();
    const Rgba* palette = v.colors().colors().data();
    for (std::int64_t z = in.lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = in.lo[1]; y <= hi[1]; ++y)
        for (std::int64_t x = in.lo[0]; x <= hi[0]; ++x, ++o)
        {
          const Voxel w = v.get(2 * x, 2 * y, 2 * z);
          in.values[o] = table[w.sdf];
          if (colors) in.colors[o] = palette[w.color];
        }
  }
  else
  {
    for (std::int64_t z = in.lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = in.lo[1]; y <= hi[1]; ++y)
        for (std::int64_t x = in.lo[0]; x <= hi[0]; ++x, ++o)
        {
          const std::int64_t g = Grid.geometry.index(2 * x, 2 * y, 2 * z);
          in.values[o] = Grid.data[g];
          if (colors) in.colors[o] = GridColors[g];
        }
  }
}

VoxelBox ChunkedMarchingCubes::Impl::cells(std::int64_t id) const
{
  const Index3 c = globalCoord(id);
  VoxelBox b;
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = c[a] * Options.chunkEdge - Options.gridOffset[a];
    b.hi[a] = b.lo[a] + Options.chunkEdge - 1;
  }
  return b.intersect(Region);
}

VoxelBox ChunkedMarchingCubes::Impl::points(std::int64_t id) const
{
  VoxelBox b = cells(id);
  for (int a = 0; a < 3; ++a) b.hi[a] += 1;
  return b;
}

void ChunkedMarchingCubes::Impl::rangeOfPoints(std::int64_t id, float& lo, float& hi) const
{
  const VoxelBox b = points(id);
  float l = std::numeric_limits<float>::infinity(), h = -l;
  for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
    for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
    {
      const float* row = Grid.data + Grid.geometry.index(b.lo[0], y, z);
      const std::int64_t n = b.hi[0] - b.lo[0] + 1;
      // simd reduction: plain std::min/max over floats is not vectorized (NaN rules)
#pragma omp simd reduction(min : l) reduction(max : h)
      for (std::int64_t i = 0; i < n; ++i)
      {
        l = row[i] < l ? row[i] : l;
        h = row[i] > h ? row[i] : h;
      }
    }
  lo = l;
  hi = h;
}

bool ChunkedMarchingCubes::Impl::empty(std::int64_t id) const
{
  const float iso = Options.isoValue;
  if (!Volume)
  {
    return MinValue[id] >= iso || MaxValue[id] < iso;
  }
  // the storage chunks this chunk reads; their exact key ranges bound its values
  SdfKey lo = std::numeric_limits<SdfKey>::max(), hi = 0;
  Volume->forEachChunkInBox(points(id), [&](std::int64_t s) {
    const auto r = Volume->chunkRange(s);
    lo = std::min(lo, r.first);
    hi = std::max(hi, r.second);
  });
  return Volume->decode(lo) >= iso || Volume->decode(hi) < iso;
}

ChunkedMarchingCubes::ChunkedMarchingCubes(const DictionaryVolume& volume, const MarchingCubesOptions& options)
  : P(new Impl)
{
  P->Volume = &volume;
  P->Origin = volume.options().origin;
  P->Spacing = volume.options().spacing;
  P->init(volume.dims(), options);
  P->IsoKey = volume.sdfDictionary().keysBelow(P->Options.isoValue);
}

ChunkedMarchingCubes::ChunkedMarchingCubes(const FloatGridView& grid, const Rgba* colors,
  const MarchingCubesOptions& options)
  : P(new Impl)
{
  require(grid.data != nullptr, "marching cubes: the float grid has no data");
  P->Grid = grid;
  P->GridColors = colors;
  P->Origin = grid.geometry.origin;
  P->Spacing = grid.geometry.spacing;
  P->init(grid.geometry.dims, options);
  P->MinValue.resize(static_cast<std::size_t>(P->Total));
  P->MaxValue.resize(static_cast<std::size_t>(P->Total));
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t id = 0; id < P->Total; ++id)
  {
    P->rangeOfPoints(id, P->MinValue[id], P->MaxValue[id]);
  }
}

ChunkedMarchingCubes::~ChunkedMarchingCubes() = default;

const MarchingCubesOptions& ChunkedMarchingCubes::options() const { return P->Options; }
const Index3& ChunkedMarchingCubes::pointDims() const { return P->Dims; }
const Index3& ChunkedMarchingCubes::chunkCounts() const { return P->Counts; }
std::int64_t ChunkedMarchingCubes::chunkCount() const { return P->Total; }
VoxelBox ChunkedMarchingCubes::chunkCells(std::int64_t id) const { return P->cells(id); }
Index3 ChunkedMarchingCubes::chunkCoord(std::int64_t id) const { return P->globalCoord(id); }
bool ChunkedMarchingCubes::chunkIsEmpty(std::int64_t id) const { return P->empty(id); }

std::unique_ptr<ChunkedMarchingCubes::ChunkInput> ChunkedMarchingCubes::gather(std::int64_t id) const
{
  require(id >= 0 && id < P->Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
  if (P->empty(id))
  {
    return nullptr;
  }
  auto in = std::make_unique<ChunkInput>();
  P->gatherInto(id, *in);
  return in;
}

bool ChunkedMarchingCubes::gather(std::int64_t id, ChunkInput& into) const
{
  require(id >= 0 && id < P->Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
  if (P->empty(id)) return false;
  P->gatherInto(id, into);
  return true;
}

bool ChunkedMarchingCubes::gather(std::int64_t id, ChunkInput& into, int level) const
{
  if (level == 0) return this->gather(id, into);
  require(level == 1, "marching cubes: level of detail " + std::to_string(level) + " is not 0 or 1");
  require(id >= 0 && id < P->Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
  require(P->Coarse != nullptr,
    "marching cubes: the coarse level needs 3 or more points per axis and an even grid offset");
  const VoxelBox cc = P->coarseCells(id);
  if (cc.empty()) return false;
  // the full chunk's range bounds the coarse points it holds
  const VoxelBox full = P->points(id);
  bool within = true;
  for (int a = 0; a < 3; ++a) within = within && 2 * (cc.hi[a] + 1) <= full.hi[a];
  if (within && P->empty(id)) return false;
  P->gatherCoarseInto(id, into);
  // no cut cell: nothing to mesh
  const float iso = P->Options.isoValue;
  bool above = false, below = false;
  for (std::int64_t z = cc.lo[2]; z <= cc.hi[2] + 1; ++z)
    for (std::int64_t y = cc.lo[1]; y <= cc.hi[1] + 1; ++y)
    {
      const float* row = into.values.data() + into.local(cc.lo[0], y, z);
      for (std::int64_t i = 0; i <= cc.hi[0] + 1 - cc.lo[0]; ++i) (row[i] >= iso ? above : below) = true;
      if (above && below) return true;
    }
  return false;
}

ChunkMesh ChunkedMarchingCubes::extractChunkCoarse(std::int64_t id) const
{
  thread_local ChunkInput in;
  if (this->gather(id, in, 1)) return this->mesh(in);
  ChunkMesh m;
  m.chunkId = id;
  m.level = 1;
  m.chunkCoord = P->globalCoord(id);
  m.cells = P->cells(id);
  return m;
}

void ChunkedMarchingCubes::Impl::gatherInto(std::int64_t id, ChunkInput& input) const
{
  const Impl* P = this;
  ChunkInput* in = &input;
  in->level = 0;
  in->view = nullptr;
  in->viewColors = nullptr;
  in->chunkId = id;
  in->cells = P->cells(id);
  Index3 hi;
  for (int a = 0; a < 3; ++a)
  {
    // the chunk's points plus one more on each side for the gradient stencil
    in->lo[a] = std::max<std::int64_t>(in->cells.lo[a] - 1, 0);
    hi[a] = std::min<std::int64_t>(in->cells.hi[a] + 2, P->Dims[a] - 1);
    in->size[a] = hi[a] - in->lo[a] + 1;
  }
  const std::size_t n = static_cast<std::size_t>(in->size[0] * in->size[1] * in->size[2]);
  // On the CPU a dictionary volume's voxels are copied as they are (a memcpy per
  // row) and decoded only where the mesher reads them: colours through a
  // palette copy; the GPU path wants values (and colours) decoded.
  const bool raw = P->Volume && !P->Cuda;
  // resize keeps the capacity of a reused input (no page faults, no zeroing)
  in->values.resize(raw ? 0 : n);
  in->voxels.resize(raw ? n : 0);
  in->sdfTable = raw ? P->Volume->sdfDictionary().table() : nullptr;
  in->isoKey = raw ? P->IsoKey : 0;
  const bool colors = P->wantsColors() && !raw, keys = P->wantsCornerColors() && !raw;
  in->colors.resize(colors ? n : 0);
  in->colorKeys.resize(keys ? n : 0);
  if (raw && P->wantsColors())
    in->palette = P->Volume->colors().colors();
  else
    in->palette.clear();
  const std::int64_t nx = in->size[0];
  if (P->Volume)
  {
    const DictionaryVolume& v = *P->Volume;
    const float* table = v.sdfDictionary().table();
    const Rgba* palette = v.colors().colors().data();
    const std::int64_t E = v.chunkEdge();
    // Storage chunks that are "quiet": all their values, and all those of their
    // 26 neighbours, on one side of iso. No cell with a corner in a quiet chunk
    // is cut, and no point of a cut cell nor of its gradient stencil (both
    // within 2 voxels of a point on the other side, which lies outside the
    // neighbourhood, E >= 16 away) is inside one: only the side of their
    // points is read, so they are filled with one value of that side and
    // their colours are not decoded (left stale: never read).
    Index3 q0, q1, qn;
    for (int a = 0; a < 3; ++a)
    {
      q0[a] = in->lo[a] / E;
      q1[a] = hi[a] / E;
      qn[a] = q1[a] - q0[a] + 1;
    }
    std::vector<std::int8_t>& side = in->sideScratch;
    std::vector<float>& quiet = in->quietScratch; // NaN = decode
    const Index3 rn{ qn[0] + 2, qn[1] + 2, qn[2] + 2 };
    side.assign(static_cast<std::size_t>(rn[0] * rn[1] * rn[2]), 0);
    const Index3& cc = v.chunkCounts();
    for (std::int64_t k = 0; k < rn[2]; ++k)
      for (std::int64_t j = 0; j < rn[1]; ++j)
        for (std::int64_t i = 0; i < rn[0]; ++i)
        {
          const std::int64_t cx = q0[0] + i - 1, cy = q0[1] + j - 1, cz = q0[2] + k - 1;
          std::int8_t sd = 2; // outside the volume: agrees with anything
          if (cx >= 0 && cy >= 0 && cz >= 0 && cx < cc[0] && cy < cc[1] && cz < cc[2])
          {
            const auto r = v.chunkRange(v.chunkId(cx, cy, cz));
            sd = table[r.first] >= P->Options.isoValue ? 1 : (table[r.second] < P->Options.isoValue ? -1 : 0);
          }
          side[static_cast<std::size_t>(i + rn[0] * (j + rn[1] * k))] = sd;
        }
    quiet.assign(static_cast<std::size_t>(qn[0] * qn[1] * qn[2]), std::numeric_limits<float>::quiet_NaN());
    for (std::int64_t k = 0; k < qn[2]; ++k)
      for (std::int64_t j = 0; j < qn[1]; ++j)
        for (std::int64_t i = 0; i < qn[0]; ++i)
        {
          const std::int8_t me = side[static_cast<std::size_t>((i + 1) + rn[0] * ((j + 1) + rn[1] * (k + 1)))];
          if (me == 0) continue;
          bool same = true;
          for (std::int64_t dk = 0; dk < 3 && same; ++dk)
            for (std::int64_t dj = 0; dj < 3 && same; ++dj)
              for (std::int64_t di = 0; di < 3 && same; ++di)
              {
                const std::int8_t o = side[static_cast<std::size_t>((i + di) + rn[0] * ((j + dj) + rn[1] * (k + dk)))];
                same = o == me || o == 2;
              }
          if (same)
          {
            const std::int64_t s = v.chunkId(q0[0] + i, q0[1] + j, q0[2] + k);
            quiet[static_cast<std::size_t>(i + qn[0] * (j + qn[1] * k))] = table[v.chunkRange(s).first];
          }
        }
    for (std::int64_t z = in->lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = in->lo[1]; y <= hi[1]; ++y)
      {
        std::int64_t o = in->local(in->lo[0], y, z);
        const std::size_t qrow = static_cast<std::size_t>(qn[0] * ((y / E - q0[1]) + qn[1] * (z / E - q0[2])));
        // walk the row storage chunk by storage chunk
        for (std::int64_t x = in->lo[0]; x <= hi[0];)
        {
          const std::int64_t end = std::min(hi[0], (x / E + 1) * E - 1);
          const std::int64_t s = v.chunkOf(x, y, z);
          const Voxel* d = v.chunkData(s);
          const float qv = quiet[qrow + static_cast<std::size_t>(x / E - q0[0])];
          if (raw)
          {
            const std::int64_t m = end - x + 1;
            Voxel* out = in->voxels.data() + o;
            if (qv == qv)
              std::fill_n(out, m, Voxel{ v.chunkRange(s).first, 0 }); // only its side is read
            else if (d)
              std::memcpy(out, d + v.localIndex(x, y, z), static_cast<std::size_t>(m) * sizeof(Voxel));
            else
              std::fill_n(out, m, v.uniformValue(s));
          }
          else if (qv == qv)
          {
            std::fill(in->values.begin() + o, in->values.begin() + o + (end - x + 1), qv);
          }
          else if (d)
          {
            const Voxel* row = d + v.localIndex(x, y, z);
            const std::int64_t m = end - x + 1;
            float* val = in->values.data() + o;
            for (std::int64_t i = 0; i < m; ++i) val[i] = table[row[i].sdf];
            if (keys)
            {
              ColorKey* k = in->colorKeys.data() + o;
              for (std::int64_t i = 0; i < m; ++i) k[i] = row[i].color;
            }
            if (colors)
            {
              Rgba* c = in->colors.data() + o;
              for (std::int64_t i = 0; i < m; ++i) c[i] = palette[row[i].color];
            }
          }
          else
          {
            const Voxel u = v.uniformValue(s);
            const std::int64_t m = end - x + 1;
            std::fill_n(in->values.data() + o, m, table[u.sdf]);
            if (colors) std::fill_n(in->colors.data() + o, m, palette[u.color]);
            if (keys) std::fill_n(in->colorKeys.data() + o, m, u.color);
          }
          o += end - x + 1;
          x = end + 1;
        }
      }
  }
  else
  {
    for (std::int64_t z = in->lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = in->lo[1]; y <= hi[1]; ++y)
      {
        const std::int64_t g = P->Grid.geometry.index(in->lo[0], y, z);
        std::copy(P->Grid.data + g, P->Grid.data + g + nx, in->values.begin() + in->local(in->lo[0], y, z));
        if (colors)
        {
          std::copy(P->GridColors + g, P->GridColors + g + nx, in->colors.begin() + in->local(in->lo[0], y, z));
        }
      }
  }
}

ChunkMesh ChunkedMarchingCubes::mesh(const ChunkInput& input) const
{
  if (input.level == 1)
  {
    // the coarse grid's mesh (CPU kernel), named in full-resolution terms
    ChunkMesh m = meshChunkCpu(*P->Coarse, input);
    m.level = 1;
    m.cells = P->cells(input.chunkId);
    const Index3& cd = P->Coarse->Dims;
    for (std::uint64_t& e : m.edgeIds)
    {
      const std::int64_t lin = static_cast<std::int64_t>(e / 3);
      const std::int64_t x = lin % cd[0], y = (lin / cd[0]) % cd[1], z = lin / (cd[0] * cd[1]);
      e = 3 * static_cast<std::uint64_t>(2 * x + P->Dims[0] * (2 * y + P->Dims[1] * 2 * z)) + e % 3;
    }
    return m;
  }
  return P->Cuda ? meshChunkCuda(*P, input) : meshChunkCpu(*P, input);
}

ChunkMesh ChunkedMarchingCubes::extractChunk(std::int64_t id) const
{
  if (!P->Volume)
  {
    // float grid: mesh the caller's array in place (no copy)
    require(id >= 0 && id < P->Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
    ChunkInput view;
    view.chunkId = id;
    view.cells = P->cells(id);
    view.size = P->Dims;
    view.view = P->Grid.data;
    view.viewColors = P->wantsColors() ? P->GridColors : nullptr;
    if (!P->empty(id)) return this->mesh(view);
    ChunkMesh m;
    m.chunkId = id;
    m.chunkCoord = P->globalCoord(id);
    m.cells = view.cells;
    return m;
  }
  require(id >= 0 && id < P->Total, "marching cubes: chunk id " + std::to_string(id) + " out of range");
  if (P->empty(id))
  {
    ChunkMesh m;
    m.chunkId = id;
    m.chunkCoord = P->globalCoord(id);
    m.cells = P->cells(id);
    return m;
  }
  // one decoded copy per thread, reused from chunk to chunk
  thread_local ChunkInput in;
  P->gatherInto(id, in);
  return this->mesh(in);
}

bool ChunkedMarchingCubes::onDevice() const
{
  return P->Cuda != nullptr;
}

void ChunkedMarchingCubes::extractChunksFromDevice(const DeviceVolumeView& volume, const std::vector<std::int64_t>& ids,
  PackedChunkMeshes& out) const
{
  require(P->Cuda && P->Volume, "marching cubes from a device volume needs the CUDA mesher of a dictionary volume");
  require(volume.valid() && volume.dims[0] == P->Dims[0] && volume.dims[1] == P->Dims[1] && volume.dims[2] == P->Dims[2],
    "marching cubes: the device volume is not the mesher's volume");
  packChunksFromDeviceVolumeCuda(*P, volume, ids, out);
}

std::vector<ChunkMesh> ChunkedMarchingCubes::extractChunks(const std::vector<std::int64_t>& ids,
  Interrupter& interrupter) const
{
  interrupter.start("marching cubes");
  if (P->Cuda && !P->Volume)
  {
    // float grid on the GPU: batches of chunks over the grid's device copy
    std::vector<ChunkMesh> meshes = meshChunksCuda(*P, ids, interrupter);
    interrupter.progress(1.0);
    interrupter.end();
    return meshes;
  }
  std::vector<ChunkMesh> out(ids.size());
  std::atomic<bool> cancelled{ false };
  std::atomic<std::int64_t> done{ 0 };
  const std::int64_t n = static_cast<std::int64_t>(ids.size());
  // progress about 1024 times a run, and after every chunk of a small one: every
  // 64th chunk left a run of one batch (vtkChunkedMarchingCubes meshes a sparse
  // volume 64 chunks at a time) with no progress between 0 and 1, so ParaView's
  // bar jumped and its cancel, asked from a progress event, never came
  const std::int64_t progressStep = std::max<std::int64_t>(1, n / 1024);
  Error firstError(ErrorCode::InvalidArgument, "");
  std::atomic<bool> failed{ false };
  // the GPU path meshes one chunk at a time (its kernels fill the device)
#pragma omp parallel for schedule(dynamic, 1) if (!P->Cuda)
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (cancelled.load(std::memory_order_relaxed) || failed.load(std::memory_order_relaxed)) continue;
    try
    {
      out[i] = this->extractChunk(ids[i]);
    }
    catch (const Error& e)
    {
#pragma omp critical(lvdif_mc_error)
      {
        if (!failed.exchange(true)) firstError = e;
      }
    }
    const std::int64_t d = ++done;
    if (interrupter.wasInterrupted()) cancelled = true;
    if (d % progressStep == 0)
    {
#pragma omp critical(lvdif_mc_progress)
      interrupter.progress(static_cast<double>(d) / static_cast<double>(n));
    }
  }
  if (failed) throw firstError;
  if (cancelled) interrupter.checkInterrupt();
  interrupter.progress(1.0);
  interrupter.end();
  return out;
}

std::vector<ChunkMesh> ChunkedMarchingCubes::extractAll(Interrupter& interrupter) const
{
  // test emptiness first (cheap, serial) so the parallel loop only sees real work
  std::vector<std::int64_t> ids;
  for (std::int64_t id = 0; id < P->Total; ++id)
  {
    if (!P->empty(id)) ids.push_back(id);
  }
  std::vector<ChunkMesh> all = this->extractChunks(ids, interrupter);
  all.erase(std::remove_if(all.begin(), all.end(), [](const ChunkMesh& m) { return m.empty(); }), all.end());
  return all;
}

void ChunkedMarchingCubes::extractAllPacked(PackedChunkMeshes& out, Interrupter& interrupter) const
{
  if (P->Cuda && !P->Volume)
  {
    std::vector<std::int64_t> ids;
    for (std::int64_t id = 0; id < P->Total; ++id)
    {
      if (!P->empty(id)) ids.push_back(id);
    }
    interrupter.start("marching cubes");
    packChunksCuda(*P, ids, out, interrupter);
    interrupter.progress(1.0);
    interrupter.end();
    return;
  }
  packChunkMeshes(*P, this->extractAll(interrupter), out);
}

std::vector<std::int64_t> ChunkedMarchingCubes::chunksAffectedBy(const VoxelBox& changed) const
{
  std::vector<std::int64_t> ids;
  if (changed.empty()) return ids;
  Index3 lo, hi;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t c0 = std::max<std::int64_t>(changed.lo[a] - 2, P->Region.lo[a]);
    const std::int64_t c1 = std::min<std::int64_t>(changed.hi[a] + 1, P->Region.hi[a]);
    if (c1 < c0) return ids;
    const std::int64_t off = P->Options.gridOffset[a];
    lo[a] = (c0 + off) / P->Options.chunkEdge - P->First[a];
    hi[a] = (c1 + off) / P->Options.chunkEdge - P->First[a];
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        ids.push_back(x + P->Counts[0] * (y + P->Counts[1] * z));
  return ids;
}

std::vector<std::int64_t> ChunkedMarchingCubes::chunksAffectedByStorageChunks(
  const std::vector<std::int64_t>& storageIds) const
{
  require(P->Volume != nullptr, "marching cubes: storage chunks exist only for a dictionary volume");
  std::vector<char> mark(static_cast<std::size_t>(P->Total), 0);
  for (std::int64_t s : storageIds)
  {
    for (std::int64_t id : this->chunksAffectedBy(P->Volume->chunkBox(s))) mark[id] = 1;
  }
  std::vector<std::int64_t> ids;
  for (std::int64_t id = 0; id < P->Total; ++id)
    if (mark[id]) ids.push_back(id);
  return ids;
}

void ChunkedMarchingCubes::invalidate(const VoxelBox& changed)
{
  if (P->Volume) return; // chunkRange of the volume is always exact
  if (P->Cuda) dropMarchingCubesCudaGrid(*P->Cuda);
  for (std::int64_t id : this->chunksAffectedBy(changed))
  {
    P->rangeOfPoints(id, P->MinValue[id], P->MaxValue[id]);
  }
}

} // namespace lvdif
