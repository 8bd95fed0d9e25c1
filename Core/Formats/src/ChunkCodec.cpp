// Chunk codec 1 of the volume file: a lossless transform that makes a chunk
// compress well with zstd.
//
// SDF keys are ordered like distances and a signed distance field is close to
// linear locally, so each key is predicted from its already-coded neighbours
// with the planar predictor a + b - c of lossless JPEG (ITU T.81, predictor 7
// in Annex H: left + up - up-left), which is exact for a linear field, and only
// the residual is stored. Residuals of a quantized smooth field are a few keys,
// so they are zigzag-mapped (small magnitude -> small number) and the low and
// high bytes are stored in separate planes, as Blosc's shuffle filter does for
// typed arrays; colour keys (mostly constant) get two planes of their own.
// Keys wrap modulo 2^16 in both directions, so any input round-trips exactly.
#include "VolumeFileFormat.h"

namespace lvdif
{
namespace detail::volumefile
{

namespace
{
using u16 = std::uint16_t;

inline u16 zigzag(u16 residual)
{
  const std::int16_t r = static_cast<std::int16_t>(residual);
  return static_cast<u16>((static_cast<u16>(r) << 1) ^ static_cast<u16>(r >> 15));
}

inline u16 unzigzag(u16 z)
{
  return static_cast<u16>((z >> 1) ^ static_cast<u16>(-(z & 1)));
}

/// Prediction of the first key of a row: from the rows above in y, else the
/// slab below in z. Rows with y = 0 continue linearly in x.
inline u16 rowStart(const u16* row, int y, int z, int edge)
{
  if (y >= 2)
    return static_cast<u16>(2 * row[-edge] - row[-2 * edge]);
  if (y == 1)
    return row[-edge];
  return z > 0 ? row[-static_cast<std::ptrdiff_t>(edge) * edge] : u16(0);
}
} // namespace

void encodeChunkPlanes(const Voxel* voxels, int edge, std::uint8_t* planes)
{
  const std::int64_t n = static_cast<std::int64_t>(edge) * edge * edge;
  std::vector<u16> keys(static_cast<size_t>(n)), res(static_cast<size_t>(n));
  for (std::int64_t i = 0; i < n; ++i)
  {
    keys[i] = voxels[i].sdf;
  }
  for (int z = 0; z < edge; ++z)
    for (int y = 0; y < edge; ++y)
    {
      const std::int64_t at = (static_cast<std::int64_t>(z) * edge + y) * edge;
      const u16* r = keys.data() + at;
      u16* out = res.data() + at;
      out[0] = static_cast<u16>(r[0] - rowStart(r, y, z, edge));
      if (y > 0)
      {
        const u16* up = r - edge;
        for (int x = 1; x < edge; ++x) // planar predictor a + b - c
          out[x] = static_cast<u16>(r[x] - r[x - 1] - up[x] + up[x - 1]);
      }
      else
      {
        out[1] = static_cast<u16>(r[1] - r[0]);
        for (int x = 2; x < edge; ++x) // linear extrapolation along x
          out[x] = static_cast<u16>(r[x] - 2 * r[x - 1] + r[x - 2]);
      }
    }
  std::uint8_t *lo = planes, *hi = planes + n, *clo = planes + 2 * n, *chi = planes + 3 * n;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const u16 z = zigzag(res[i]);
    lo[i] = static_cast<std::uint8_t>(z & 0xff);
    hi[i] = static_cast<std::uint8_t>(z >> 8);
    clo[i] = static_cast<std::uint8_t>(voxels[i].color & 0xff);
    chi[i] = static_cast<std::uint8_t>(voxels[i].color >> 8);
  }
}

void decodeChunkPlanes(const std::uint8_t* planes, int edge, Voxel* voxels)
{
  const std::int64_t n = static_cast<std::int64_t>(edge) * edge * edge;
  std::vector<u16> keys(static_cast<size_t>(n));
  const std::uint8_t *lo = planes, *hi = planes + n, *clo = planes + 2 * n, *chi = planes + 3 * n;
  for (std::int64_t i = 0; i < n; ++i)
  {
    keys[i] = unzigzag(static_cast<u16>(lo[i] | (hi[i] << 8))); // residuals, replaced row by row
  }
  for (int z = 0; z < edge; ++z)
    for (int y = 0; y < edge; ++y)
    {
      u16* r = keys.data() + (static_cast<std::int64_t>(z) * edge + y) * edge;
      r[0] = static_cast<u16>(r[0] + rowStart(r, y, z, edge));
      if (y > 0)
      {
        const u16* up = r - edge;
        for (int x = 1; x < edge; ++x)
          r[x] = static_cast<u16>(r[x] + r[x - 1] + up[x] - up[x - 1]);
      }
      else
      {
        r[1] = static_cast<u16>(r[1] + r[0]);
        for (int x = 2; x < edge; ++x)
          r[x] = static_cast<u16>(r[x] + 2 * r[x - 1] - r[x - 2]);
      }
    }
  for (std::int64_t i = 0; i < n; ++i)
  {
    voxels[i].sdf = keys[i];
    voxels[i].color = static_cast<ColorKey>(clo[i] | (chi[i] << 8));
  }
}

} // namespace detail::volumefile
} // namespace lvdif
