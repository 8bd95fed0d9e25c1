// What a mesh-to-SDF conversion into a dictionary volume certainly needs,
// checked before any work (MeshToSdf.h: meshToSdfLeastMemory).
#include "MeshToSdfInternal.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

namespace lvdif
{

std::uint64_t meshToSdfLeastMemory(const TriangleMesh& mesh, const DictionaryVolume& volume,
  const MeshToSdfOptions& options)
{
  const VolumeOptions& vo = volume.options();
  const std::uint64_t table = DictionaryVolume::tableBytes(vo);
  // voxels near the surface are unsaturated only with a band of at least the
  // nearest voxel centre's distance (sqrt(3)/2), and an unsigned field may be
  // one saturated value elsewhere: then only the table is certain
  const float band = volume.bandWidth();
  if (options.sign == SignMode::Unsigned || (band > 0 && band < 1)) return table;
  const GridGeometry grid = gridOf(vo);
  const Index3& counts = volume.chunkCounts();
  const std::int64_t edge = vo.chunkEdge;
  const std::uint64_t chunkBytes = static_cast<std::uint64_t>(edge * edge * edge) * sizeof(Voxel);
  const VoxelBox& region = options.chunkRegion; // in chunks
  std::vector<std::uint64_t> seen(static_cast<std::size_t>((counts[0] * counts[1] * counts[2] + 63) / 64), 0);
  std::uint64_t touched = 0;
  // the chunk of the voxel nearest to a point of the surface holds a voxel
  // within sqrt(3)/2 voxel of it, below the band: it is expanded
  auto mark = [&](const double v[3]) {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a)
    {
      const double i = std::floor(v[a] + 0.5);
      if (!(i >= 0 && i <= static_cast<double>(grid.dims[a] - 1))) return;
      c[a] = static_cast<std::int64_t>(i) / edge;
      if (!region.empty() && (c[a] < region.lo[a] || c[a] > region.hi[a])) return;
    }
    const std::uint64_t id = static_cast<std::uint64_t>(c[0] + counts[0] * (c[1] + counts[1] * c[2]));
    std::uint64_t& word = seen[id / 64];
    const std::uint64_t bit = std::uint64_t(1) << (id % 64);
    touched += (word & bit) ? 0 : 1;
    word |= bit;
  };
  // Every voxel within band - 1 of the surface holds a distance a whole voxel
  // below the band, so its chunk is expanded too: not only the chunks the
  // surface passes through (the bound was about half of what a fine grid took,
  // so a unit mesh at spacing 0.001 under a 2 GiB limit ran until the limit
  // was full). Around each point, the voxels nearest to the points `reach`
  // away in the 26 directions of the cube's faces, edges and corners: each is
  // within reach + sqrt(3)/2 = band - 1 of the surface.
  const double reach = static_cast<double>(band) - 1.0 - 0.5 * std::sqrt(3.0);
  std::vector<std::array<double, 3>> around;
  if (reach > 0)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const double l = std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
          around.push_back({ reach * dx / l, reach * dy / l, reach * dz / l });
        }
  double last[3] = { -1.0, -1.0, -1.0 }; // the voxel of the last point marked around (small triangles share it)
  auto markAround = [&](const double v[3]) {
    const double k[3] = { std::floor(v[0] + 0.5), std::floor(v[1] + 0.5), std::floor(v[2] + 0.5) };
    if (k[0] == last[0] && k[1] == last[1] && k[2] == last[2]) return;
    for (int a = 0; a < 3; ++a) last[a] = k[a];
    mark(v);
    for (const auto& d : around)
    {
      const double w[3] = { v[0] + d[0], v[1] + d[1], v[2] + d[2] };
      mark(w);
    }
  };
  // points on each triangle (of non-zero area) at most half a chunk apart: a
  // lower bound of the chunks its surface passes through (at most 4096 steps
  // a side, so a few huge triangles cost little)
  for (const auto& t : mesh.triangles)
  {
    double p[3][3];
    bool finite = true;
    for (int k = 0; k < 3; ++k)
    {
      if (t[k] >= mesh.points.size()) return table; // validate() names it
      for (int a = 0; a < 3; ++a)
      {
        p[k][a] = (static_cast<double>(mesh.points[t[k]][a]) - grid.origin[a]) / grid.spacing[a];
        finite = finite && std::isfinite(p[k][a]);
      }
    }
    if (!finite) return table;
    const double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue; // degenerate: skipped by the conversion
    double longest = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double* a = p[k];
      const double* b = p[(k + 1) % 3];
      longest = std::max(longest, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                            (a[2] - b[2]) * (a[2] - b[2])));
    }
    const int steps = static_cast<int>(std::min(4096.0, std::max(1.0, std::ceil(longest / (0.5 * edge)))));
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; i + j <= steps; ++j)
      {
        const double u = double(i) / steps, w = double(j) / steps;
        const double v[3] = { p[0][0] + u * e1[0] + w * e2[0], p[0][1] + u * e1[1] + w * e2[1],
          p[0][2] + u * e1[2] + w * e2[2] };
        markAround(v);
      }
  }
  return table + touched * chunkBytes;
}

namespace detail::meshtosdf
{

void requireVolumeFits(const TriangleMesh& mesh, const DictionaryVolume& volume, const MeshToSdfOptions& options)
{
  // Refused before any work when the volume certainly cannot fit its memory
  // limit (a 4096^3 conversion ran for minutes until "expanding chunk ... holds
  // 2.00 GiB of its 2.00 GiB limit"); skipped where even a dense volume fits.
  const VolumeOptions& vo = volume.options();
  if (DictionaryVolume::denseBytes(vo) > volume.memoryLimit())
  {
    const std::uint64_t least = meshToSdfLeastMemory(mesh, volume, options);
    if (least > volume.memoryLimit())
    {
      std::ostringstream m;
      m << "mesh to SDF: a " << vo.dims[0] << " x " << vo.dims[1] << " x " << vo.dims[2]
        << " volume of this mesh needs at least " << formatBytes(least)
        << " (its chunk table and the chunks its surface passes through), more than its memory limit of "
        << formatBytes(volume.memoryLimit())
        << " (LVDIF_MEMORY_LIMIT, or 90% of the available memory): use fewer voxels (lvdif mesh-to-sdf --dims, "
           "lvdif-editor --mesh-resolution, vtkMeshToSDF's MaxDimension) or raise LVDIF_MEMORY_LIMIT";
      throw Error(ErrorCode::OutOfMemory, m.str());
    }
  }
}

} // namespace detail::meshtosdf
} // namespace lvdif
