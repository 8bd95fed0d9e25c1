// PackedChunkMeshes: many chunk meshes in one host block (see
// ChunkedMarchingCubes.h); its storage, accessors and the CPU packing.
#include "MarchingCubesImpl.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <cstring>

namespace lvdif
{
namespace
{
std::uint64_t align256(std::uint64_t x) { return (x + 255) & ~std::uint64_t(255); }
} // namespace

void PackedChunkMeshes::Storage::reserve(std::uint64_t v, std::uint64_t t, std::uint64_t keepV, std::uint64_t keepT,
  bool pageLocked, bool nrm, bool col, bool cel, bool key)
{
  const bool sameLayout = block && pinned == pageLocked && normalsOn == nrm && colorsOn == col && cellsOn == cel &&
    keysOn == key;
  if (sameLayout && v <= vcap && t <= tcap) return;
  if (!sameLayout) keepV = keepT = 0;
  // grow by half again so that a slowly growing result does not reallocate every time
  if (sameLayout)
  {
    v = std::max(v, vcap + vcap / 2);
    t = std::max(t, tcap + tcap / 2);
  }
  v = std::max<std::uint64_t>(v, 1);
  t = std::max<std::uint64_t>(t, 1);
  std::uint64_t off[7], bytes = 0;
  const std::uint64_t sizes[7] = { v * sizeof(Vec3f), v * sizeof(std::uint64_t), nrm ? v * sizeof(Vec3f) : 0,
    col ? v * sizeof(Rgba) : 0, t * sizeof(std::array<std::uint32_t, 3>), cel ? t * sizeof(std::int64_t) : 0,
    key ? t * sizeof(std::array<ColorKey, 8>) : 0 };
  for (int i = 0; i < 7; ++i)
  {
    off[i] = bytes;
    bytes = align256(bytes + sizes[i]);
  }
  requireMemory(bytes, "packed marching cubes meshes");
  std::shared_ptr<std::uint8_t> nb;
  if (pageLocked)
    nb = allocatePageLocked(bytes);
  else
    nb = std::shared_ptr<std::uint8_t>(new std::uint8_t[bytes], std::default_delete<std::uint8_t[]>());
  std::uint8_t* b = nb.get();
  auto at = [&](int i) { return sizes[i] ? b + off[i] : nullptr; };
  Storage n;
  n.block = nb;
  n.pinned = pageLocked;
  n.normalsOn = nrm;
  n.colorsOn = col;
  n.cellsOn = cel;
  n.keysOn = key;
  n.vcap = v;
  n.tcap = t;
  n.points = reinterpret_cast<Vec3f*>(at(0));
  n.edgeIds = reinterpret_cast<std::uint64_t*>(at(1));
  n.normals = reinterpret_cast<Vec3f*>(at(2));
  n.colors = reinterpret_cast<Rgba*>(at(3));
  n.tris = reinterpret_cast<std::array<std::uint32_t, 3>*>(at(4));
  n.cells = reinterpret_cast<std::int64_t*>(at(5));
  n.keys = reinterpret_cast<std::array<ColorKey, 8>*>(at(6));
  auto keep = [](auto* dst, const auto* src, std::uint64_t count) {
    if (dst && src && count) std::memcpy(dst, src, count * sizeof(*src));
  };
  keep(n.points, points, keepV);
  keep(n.edgeIds, edgeIds, keepV);
  keep(n.normals, normals, keepV);
  keep(n.colors, colors, keepV);
  keep(n.tris, tris, keepT);
  keep(n.cells, cells, keepT);
  keep(n.keys, keys, keepT);
  *this = std::move(n);
}

const Vec3f* PackedChunkMeshes::points() const { return storage && vertexCount() ? storage->points : nullptr; }
const std::uint64_t* PackedChunkMeshes::edgeIds() const { return storage && vertexCount() ? storage->edgeIds : nullptr; }
const Vec3f* PackedChunkMeshes::normals() const { return storage && vertexCount() ? storage->normals : nullptr; }
const Rgba* PackedChunkMeshes::colors() const { return storage && vertexCount() ? storage->colors : nullptr; }
const std::array<std::uint32_t, 3>* PackedChunkMeshes::triangles() const
{
  return storage && triangleCount() ? storage->tris : nullptr;
}
const std::int64_t* PackedChunkMeshes::triangleCells() const
{
  return storage && triangleCount() ? storage->cells : nullptr;
}
const std::array<ColorKey, 8>* PackedChunkMeshes::cornerColors() const
{
  return storage && triangleCount() ? storage->keys : nullptr;
}
bool PackedChunkMeshes::pageLocked() const { return storage && storage->pinned; }

ChunkMesh PackedChunkMeshes::chunk(std::size_t i) const
{
  require(i < chunkIds.size(), "packed meshes: chunk index out of range");
  ChunkMesh m;
  m.chunkId = chunkIds[i];
  m.chunkCoord = chunkCoords[i];
  m.cells = chunkCells[i];
  const std::uint64_t v0 = vertexStart[i], v1 = vertexStart[i + 1], t0 = triangleStart[i], t1 = triangleStart[i + 1];
  if (t1 == t0) return m;
  const Storage& s = *storage;
  m.points.assign(s.points + v0, s.points + v1);
  m.edgeIds.assign(s.edgeIds + v0, s.edgeIds + v1);
  if (s.normals) m.normals.assign(s.normals + v0, s.normals + v1);
  if (s.colors) m.colors.assign(s.colors + v0, s.colors + v1);
  m.triangles.assign(s.tris + t0, s.tris + t1);
  if (s.cells) m.triangleCells.assign(s.cells + t0, s.cells + t1);
  if (s.keys) m.cornerColors.assign(s.keys + t0, s.keys + t1);
  return m;
}

void packChunkMeshes(const ChunkedMarchingCubes::Impl& impl, const std::vector<ChunkMesh>& meshes,
  PackedChunkMeshes& out)
{
  const std::size_t n = meshes.size();
  out.chunkIds.resize(n);
  out.chunkCoords.resize(n);
  out.chunkCells.resize(n);
  out.vertexStart.assign(n + 1, 0);
  out.triangleStart.assign(n + 1, 0);
  bool nrm = false, col = false, cel = false, key = false;
  for (std::size_t i = 0; i < n; ++i)
  {
    const ChunkMesh& m = meshes[i];
    out.chunkIds[i] = m.chunkId;
    out.chunkCoords[i] = m.chunkCoord;
    out.chunkCells[i] = m.cells;
    out.vertexStart[i + 1] = out.vertexStart[i] + m.points.size();
    out.triangleStart[i + 1] = out.triangleStart[i] + m.triangles.size();
    nrm |= !m.normals.empty();
    col |= !m.colors.empty();
    cel |= !m.triangleCells.empty();
    key |= !m.cornerColors.empty();
  }
  (void)impl;
  if (!out.storage || out.storage.use_count() > 1) out.storage = std::make_shared<PackedChunkMeshes::Storage>();
  out.storage->reserve(out.vertexCount(), out.triangleCount(), 0, 0, false, nrm, col, cel, key);
  PackedChunkMeshes::Storage& s = *out.storage;
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i)
  {
    const ChunkMesh& m = meshes[i];
    const std::uint64_t v0 = out.vertexStart[i], t0 = out.triangleStart[i];
    std::copy(m.points.begin(), m.points.end(), s.points + v0);
    std::copy(m.edgeIds.begin(), m.edgeIds.end(), s.edgeIds + v0);
    if (s.normals) std::copy(m.normals.begin(), m.normals.end(), s.normals + v0);
    if (s.colors) std::copy(m.colors.begin(), m.colors.end(), s.colors + v0);
    std::copy(m.triangles.begin(), m.triangles.end(), s.tris + t0);
    if (s.cells) std::copy(m.triangleCells.begin(), m.triangleCells.end(), s.cells + t0);
    if (s.keys) std::copy(m.cornerColors.begin(), m.cornerColors.end(), s.keys + t0);
  }
}

} // namespace lvdif
