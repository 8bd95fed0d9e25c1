// Merging chunk meshes: points with bit-identical coordinates are the same
// vertex (chunk-boundary vertices are computed identically from both sides).
#include "lvdif/ChunkedMarchingCubes.h"

#include "lvdif/Error.h"

#include <cstring>
#include <unordered_map>

namespace lvdif
{
namespace
{
struct Key
{
  std::uint32_t v[3];
  bool operator==(const Key& o) const { return v[0] == o.v[0] && v[1] == o.v[1] && v[2] == o.v[2]; }
};
struct KeyHash
{
  std::size_t operator()(const Key& k) const
  {
    std::uint64_t h = k.v[0] * 0x9E3779B97F4A7C15ull;
    h ^= (k.v[1] + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (k.v[2] + 0x165667B19E3779F9ull) * 0x85EBCA77C2B2AE63ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};
} // namespace

TriangleMesh mergeChunkMeshes(const std::vector<ChunkMesh>& meshes, MergeBy by)
{
  TriangleMesh out;
  std::size_t np = 0, nt = 0;
  bool normals = true;
  for (const ChunkMesh& m : meshes)
  {
    np += m.points.size();
    nt += m.triangles.size();
    normals &= m.normals.size() == m.points.size();
  }
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  index.reserve(np);
  out.points.reserve(np);
  out.triangles.reserve(nt);
  std::vector<std::uint32_t> remap;
  for (const ChunkMesh& m : meshes)
  {
    require(by == MergeBy::Position || m.edgeIds.size() == m.points.size(),
      "mergeChunkMeshes: a chunk mesh has no edge ids");
    remap.resize(m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
      Key k;
      if (by == MergeBy::Position)
        std::memcpy(k.v, m.points[i].data(), sizeof(k.v));
      else
      {
        k.v[0] = static_cast<std::uint32_t>(m.edgeIds[i]);
        k.v[1] = static_cast<std::uint32_t>(m.edgeIds[i] >> 32);
        k.v[2] = 0;
      }
      auto it = index.emplace(k, static_cast<std::uint32_t>(out.points.size()));
      if (it.second)
      {
        out.points.push_back(m.points[i]);
        if (normals) out.normals.push_back(m.normals[i]);
      }
      remap[i] = it.first->second;
    }
    for (const auto& t : m.triangles) out.triangles.push_back({ remap[t[0]], remap[t[1]], remap[t[2]] });
  }
  return out;
}

} // namespace lvdif
